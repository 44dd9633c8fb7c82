#pragma once
// curvature.svg (docs/architecture.md "Outputs"): the analytical sheet of a patching result, beside
// the architect's plan (site_plan.hpp). The design surface projected onto the xy plane (z up, y
// north) with its outline and holes and a Gaussian-curvature colour map; the patch outlines with
// their ids (infeasible patches hatched, with the index of their reason); the injectivity circles
// (Section 3.4.1) and their p_max; the cut-offs (regions no patch covers, Section 3.3.2); a scale
// bar and a legend.
#include "core/mesh/mesh.hpp"
#include "patching/injectivity.hpp"
#include "patching/layout.hpp"
#include "patching/patch_graph.hpp"

#include <Eigen/Dense>
#include <filesystem>
#include <string>
#include <vector>

namespace egg::patching {

struct CurvatureSheetOptions {
  double widthPx = 1000.0;            // width of the map (the legend column comes on top)
  double curvaturePercentile = 98.0;  // the K colour scale is symmetric, +-this percentile of |K|
                                      // over the faces, so noise does not wash it out
  void validate() const;              // throws InvalidInput naming the field
};

// What to draw. Pointers are optional (nullptr = leave it out) and must outlive the call.
struct CurvatureDrawing {
  const TriMesh* surface = nullptr;     // required: outline, holes, K map
  Eigen::VectorXd gaussian;             // per surface vertex [1/m^2]; empty = computeCurvature's
  const PatchLayout* layout = nullptr;  // patch outlines from its sides
  std::vector<std::string>
      patchProblems;  // per layout patch: why it is infeasible ("" = fine); may be empty
  std::vector<SurfacePeak> peaks;  // p_max markers
  std::vector<InjectivityCircle> circles;
  const Coverage* coverage = nullptr;  // cut-offs (faces of layout->mesh); needs `layout`
  std::string title;                   // e.g. the scene name
  CurvatureSheetOptions options;
};

// Writes the plan atomically (core/io/atomic_file.hpp). Element ids: "patch-<i>" (outline polygon,
// with its label "patch-label-<i>"), "circle-<i>", "pmax-<i>", "cutoff-<i>", "scale-bar" (its width
// is the bar's length in px) with "scale-label" (e.g. "10 m"); the root carries data-px-per-m.
// Throws InvalidInput (no surface, sizes that do not match) or WriteError.
void writeCurvatureSheet(const std::filesystem::path& path, const CurvatureDrawing& drawing);

// The SVG text itself (what writeCurvatureSheet writes).
std::string curvatureSheetSvg(const CurvatureDrawing& drawing);

}  // namespace egg::patching
