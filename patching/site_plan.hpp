#pragma once
// plan.svg (docs/architecture.md "Outputs"): the plan an architect reads. The design surface in
// plan (z up, y north) with its outline and holes; the patch outlines with their ids and surface
// areas in plain numbers; the members of every traced grid (U blue, V orange, as in planar.svg);
// the supports; overall dimensions with the holes' positions; the crown's height; cut-offs and
// infeasible patches hatched so that they cannot be mistaken for each other; a scale bar, north
// arrow and legend. Labels never overlap each other or leave the page: a label that finds no free
// place is left out and counted in the legend. The curvature map, K peaks and injectivity circles
// are the second, analytical sheet (curvature_sheet.hpp).
#include "core/mesh/mesh.hpp"
#include "patching/layout.hpp"
#include "patching/patch_graph.hpp"

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace egg::patching {

struct SitePlanMember {
  int patch = -1;
  bool familyU = true;
  bool boundary = false;  // a patch side: drawn heavier
  std::vector<Eigen::Vector3d> points;
};

struct SitePlanSupport {
  std::string id;  // "S001"
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  bool bracket = false;  // a wall bracket rather than a block (fabrication/supports.hpp)
};

// A section line of elevations.svg: constant y (alongX, looking north) or constant x (looking
// west).
struct SitePlanSection {
  std::string name;  // "A"
  bool alongX = true;
  double atM = 0.0;
};

// A generalised patch in a cut-off (patching/infill.hpp): its layout-mesh faces, tinted, with its
// id and surface area.
struct SitePlanGeneralised {
  std::string id;    // "G0"
  int patchId = -1;  // its number in the shop files (lamellas P<patchId>-U<i>), -1: none
  std::vector<int> faces;
  double areaM2 = 0.0;
};

// What to draw. Pointers must outlive the call; only `surface` is required.
struct SitePlanDrawing {
  const TriMesh* surface = nullptr;
  const PatchLayout* layout = nullptr;           // finished (finishLayout): patch outlines
  std::vector<std::string> patchProblems;        // per layout patch, "" = feasible; may be empty
  std::vector<double> patchAreasM2;              // per layout patch, surface area (<= 0: unknown)
  const Coverage* coverage = nullptr;            // cut-offs; needs `layout`
  std::vector<SitePlanGeneralised> generalised;  // needs `layout`
  std::vector<SitePlanMember> members;
  std::vector<SitePlanSupport> supports;
  std::vector<SitePlanSection> sections;
  std::string title;
  double widthPx = 1000.0;  // the map's width, in [200, 20000]
};

// The SVG text. Element ids: "outline", "hole-<i>", "patch-<i>" with "patch-label-<i>",
// "infeasible-<i>", "cutoff-<i>" with "cutoff-label-<i>", "generalised-<id>" with
// "generalised-label-<id>", "members", "support-<id>",
// "section-<name>", "dim-x"/"dim-y" (overall dimensions, their text "dim-x-label"/"dim-y-label"),
// "crown", "scale-bar"/"scale-label"; every placed label carries data-box="x0 y0 x1 y1", the box it
// keeps clear; the root carries data-px-per-m and data-labels-left-out. Throws InvalidInput naming
// what does not fit together.
std::string sitePlanSvg(const SitePlanDrawing& drawing);

}  // namespace egg::patching
