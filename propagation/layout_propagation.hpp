#pragma once
// Member propagation over a patch layout (Section 3.4.4, Figs. 3.8-3.9): every chain of the patch
// graph (patching/patch_graph.hpp) becomes a ChainProblem (chain_problem.hpp), oriented so that
// members run from the chain's first free side through every patch: a patch entered at its
// family's end side is read backwards (F^-1), and a side whose parameter runs the other way on
// the next patch (BoundaryUse.reversed, familySide) mirrors the map. The solution gives every
// patch of a chain the start parameters x1 of its members, the same members on both sides of
// every shared side (C0). The second family is solved independently (each chain on its own).
//
// A branching chain (a side that meets two smaller patches' sides at a T-junction, Fig. 3.8) is cut
// into sub-chains linked by whole sides, solved one after the other (breadth first over the
// T-junction pieces, the longest first): the corner of a smaller patch inside a side (a T-junction
// of boundary members) is an original there, and a sub-chain whose neighbour across a T-junction
// piece is already solved takes that neighbour's members on the piece as originals and adds no
// member inside it, so both sides carry the same members (forwards or backwards through F, F^-1).
// A chain cut by an infeasible patch is split at it; a lone patch places its own members (2.4.4).
#include "core/egg/planar_quad.hpp"
#include "patching/patch_graph.hpp"
#include "propagation/chain_problem.hpp"
#include "propagation/side_map.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace egg::propagation {

// What propagation reads of one patch's design (patch_sides.hpp builds it from a PatchDesign).
struct PatchSideData {
  bool usable = false;  // designed and feasible
  std::array<PiecewiseLinearMap, 2>
      cladding;  // F_u, F_v: x1 on the family's start side -> x2 on its end side
  std::array<double, 4> sideLengths{};  // metres, side k = corner k -> k+1
  // Smallest distance (metres along the side) between two members' ends: the lamella footprint
  // w / sin(angle) at the smallest angle the family meets its [start, end] side at (2.4.4).
  std::array<std::array<double, 2>, 2> minGapM{};
};

struct PropagationOptions {
  std::optional<int> members;   // per chain, both boundary members included; empty = spacing rule
  double lamellaWidthM = 0.05;  // w
  double spacingFactor =
      8.0;  // spacing rule: intervals = round(longest side of the chain / (factor * w))
  ChainOptions chain;
  void validate() const;
};

// One patch of a propagated chain.
struct PropagatedNode {
  int patch = -1;
  Family family = Family::U;
  bool forward = true;  // enters at the family's start side (F), else at its end side (F^-1)
  // The chain's parameter on the node's two boundaries is 1 - the family's own parameter.
  bool mirrored = false;
};

struct PropagatedChain {
  int graphChain = -1;  // index into PatchGraph::chains
  std::vector<PropagatedNode> nodes;
  bool ring = false;            // boundary n is boundary 0 again (cut open: need not close)
  std::vector<int> boundaries;  // per chain boundary: PatchGraph boundary id, -1 for a free side
  ChainSolution solution;
  // Members' start parameters x1 of node k (increasing, 0 .. 1) from the chain's positions.
  std::vector<double> startParameters(int node) const;
  // Member j of the chain is member memberIndex(node, j) of the node's family (x1 increasing).
  int memberIndex(int node, int member) const;
};

// One end of a member of a patch's family (members indexed by x1 increasing, boundary members
// included): on the family's start side (x1) or its end side (x2).
struct MemberEnd {
  int patch = -1;
  Family family = Family::U;
  int member = -1;
  bool atEnd = false;  // x2
};

// Two member ends that meet on a shared boundary piece: x_b = offset + scale * x_a, in the two
// families' own parameters on the sides the piece lies on.
struct MemberJoint {
  int boundary = -1;  // PatchGraph boundary id
  MemberEnd a, b;
  double offset = 0.0, scale = 1.0;
};

// What a shared boundary piece is: a whole side of both patches, part of a side (a T-junction), or
// the cut that closes a ring of patches (its members need not close, 3.7.1).
enum class PieceKind { WholeSide, TJunction, RingCut };
// "whole side", "t_junction", "ring cut" (report.json's spelling).
const char* toString(PieceKind kind);

// A boundary piece two propagated families share, with the members each puts on it.
struct SharedPiece {
  int boundary = -1;
  int patchA = -1, patchB = -1;
  PieceKind kind = PieceKind::WholeSide;
  int membersA = 0, membersB = 0;
  int chain = -1;           // a ring cut: the ring's index into LayoutPropagation::chains
  std::vector<int> joints;  // indices into LayoutPropagation::joints
};

struct FallbackChain {
  int graphChain = -1;
  std::vector<patching::ChainNode> nodes;
  std::string reason;
};

struct LayoutPropagation {
  std::vector<PropagatedChain> chains;
  std::vector<FallbackChain> fallbacks;  // chains (or pieces) whose patches place their own members
  // Per patch and family (Family as index): x1 of its members, empty = it places its own.
  std::vector<std::array<std::vector<double>, 2>> x1;
  // Per patch and family: (chain, node) in `chains`, or (-1, -1).
  std::vector<std::array<std::pair<int, int>, 2>> nodeOf;
  double evennessBefore = 0.0, evennessAfter = 0.0;  // sums over the propagated chains
  int iterations = 0;                                // SLSQP evaluations, all chains
  int originals = 0;
  std::vector<MemberJoint> joints;  // every pair of member ends that must coincide (C0)
  std::vector<SharedPiece> pieces;
  std::vector<std::string> notes;  // members a piece's two sides could not agree on
  double seconds = 0.0;
};

// Throws InvalidInput on bad options or when `patches` does not match the graph.
LayoutPropagation propagateLayout(const patching::PatchGraph& graph,
                                  const std::vector<PatchSideData>& patches,
                                  const PropagationOptions& options = {});

// Which side (start = false, end = true) of `family` side k is, and whether the family's
// parameter runs against the side (corner k -> k+1); throws for a side of the other family.
std::pair<bool, bool> familySideRole(Family family, int side);

}  // namespace egg::propagation
