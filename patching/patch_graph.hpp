#pragma once
// The patch graph of a layout (Sections 3.4.3, 3.4.4): which patches share which boundary pieces,
// where T-junctions are, which sides are free (the design boundary), and for each member family
// the chains (or rings) of patches its members run through from side to side: propagation's input.
#include "core/egg/distance_map.hpp"
#include "patching/layout.hpp"

#include <string>
#include <vector>

namespace egg::patching {

// Where a boundary piece lies on one patch: side k, as fractions of that side's length.
struct BoundaryUse {
  int patch = -1;
  int side = -1;
  double from = 0.0,
         to = 1.0;  // fractions along side k (corner k -> k+1) where the segment starts and ends
  bool reversed = false;  // the side runs against the segment's direction
};

// How a boundary segment of the layout is used: by one patch (free: the design boundary), by
// two patches along whole sides (shared), or by two patches one of which it covers only in part.
enum class BoundaryKind { Free, Shared, TJunction };
// "free", "shared", "t_junction" (report.json and patches.json spell them so).
const char* toString(BoundaryKind kind);

struct Boundary {
  int id = -1;  // = segment id
  BoundaryKind kind = BoundaryKind::Free;
  std::vector<BoundaryUse> uses;  // one (free) or two (shared) patches
  double lengthM = 0.0;
};

struct TJunction {
  int corner = -1;
  std::vector<int> patchesThrough;  // patches one of whose sides passes through the corner
  std::vector<int> patchesAt;       // patches that have it as a corner
};

// One node of a chain: a patch's member family. Members enter at the family's start side and
// leave at its end side (familySide in core/egg/patch_maps.hpp).
struct ChainNode {
  int patch = -1;
  Family family = Family::U;
};

struct MemberChain {
  std::vector<ChainNode> nodes;  // in order along the members (a ring: first follows last)
  bool ring = false;
  bool branching = false;  // a T-junction: some node continues into two patches on one side
};

struct PatchGraph {
  std::vector<Boundary> boundaries;
  std::vector<TJunction> tJunctions;
  std::vector<std::pair<int, int>> adjacent;  // patch pairs sharing a boundary piece, a < b
  std::vector<MemberChain> chains;
};

// `usable[p]` false leaves patch p out (it could not be cut or designed).
PatchGraph buildPatchGraph(const PatchLayout& layout, const std::vector<bool>& usable = {});

// Coverage of the design surface (Section 3.3.2): the area of the union of the cut patches over
// the surface area, and the cut-offs, the regions of the layout mesh that no patch covers (cells
// bounded by the layout's sides and the surface boundary).
struct CutOff {
  double areaM2 = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<int> faces;  // layout-mesh faces
};
struct Coverage {
  double coveredAreaM2 = 0.0;
  double surfaceAreaM2 = 0.0;
  double fraction = 0.0;
  std::vector<CutOff> cutOffs;  // largest first
};
// `patchFaces[p]`: the layout-mesh faces of patch p (LayoutPatch::layoutFace; empty if not cut).
Coverage computeCoverage(const PatchLayout& layout,
                         const std::vector<std::vector<int>>& patchFaces);

}  // namespace egg::patching
