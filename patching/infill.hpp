#pragma once
// Generalised patches where the quad layout leaves a cut-off (issue 41, thesis Chapter 4): each
// cut-off region of the layout mesh (Coverage::cutOffs) between patch sides and a free-form design
// boundary or a hole's rim becomes a patch of its own with a generalised grid (core/generalised).
// The grid needs a topological disk, so a ring round a hole (the Great Court's between the Reading
// Room and its tangent box) is split into disks first (Section 4.9.1): at its necks, the local
// minima of its width, by sectors about the hole.
//
// Every member of such a patch ends at an anchor on the piece's boundary, which is one of
//  - the design boundary or a hole's rim: a support ring (the anchors of Section 4.3.1);
//  - a side of a quad patch: the neighbour's boundary lamella, taken as a ring beam;
//  - a cut between two pieces of a ring: a ring beam across the neck.
// The piece's report counts the anchors of each kind, so the engineer sees what carries them.
#include "core/generalised/generalised_design.hpp"
#include "core/generalised/grid_optimisation.hpp"
#include "patching/layout.hpp"
#include "patching/patch_graph.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace egg::patching {

struct InfillOptions {
  double minAreaM2 = 1.0;           // smaller cut-offs are left as they are (with that reason)
  double memberSpacingM = 0.0;      // the quad grids' member spacing the infill matches (> 0)
  int minLines = 2, maxLines = 40;  // lines per family of a piece's layout
  generalised::GridOptimisationOptions optimisation;  // `lines` is set per piece
  generalised::GeneralisedDesignOptions design;
  void validate() const;  // throws InvalidInput naming the field
};

// What holds a member end of a generalised patch (see above).
enum class AnchorHold { DesignBoundary, PatchSide, Cut };
// "design_boundary", "patch_side", "cut" (report.json's spelling).
const char* toString(AnchorHold hold);

struct InfillPiece {
  int cutOff = -1;                // index into Coverage::cutOffs
  std::vector<int> layoutFaces;   // layout-mesh faces
  std::vector<int> layoutVertex;  // per piece-mesh vertex: its layout-mesh vertex
  TriMesh mesh;                   // the piece alone (a topological disk when designed)
  double areaM2 = 0.0;
  std::string failure;  // why it has no grid ("" when designed)
  std::optional<generalised::GridOptimisationResult> optimisation;
  std::optional<generalised::GeneralisedDesign> design;
  double precomputeSeconds = 0.0;
  // Anchors (member ends) by what holds them.
  int anchorsOnDesignBoundary = 0, anchorsOnPatchSides = 0, anchorsOnCuts = 0;
  // Per layout member of the design: what holds its start and its end.
  std::vector<std::array<AnchorHold, 2>> memberEndHolds;
};

struct InfillResult {
  std::vector<InfillPiece> pieces;
  double designedAreaM2 = 0.0;  // of the pieces with a grid
  double seconds = 0.0;
};

// Throws InvalidInput for bad options; a piece that cannot take a grid keeps its reason.
InfillResult infillCutOffs(const PatchLayout& layout, const Coverage& coverage,
                           const InfillOptions& options);

}  // namespace egg::patching
