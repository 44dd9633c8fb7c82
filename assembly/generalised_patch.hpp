#pragma once
// A generalised patch (issue 41, thesis Chapter 4) as the stages after the grid stage take any
// patch: its members and crossings as an EggGrid (u: the family in layer 0) for fabrication and the
// 3D model, and its rods in that order for the simulations. Unlike a quad patch's grid, not every
// u member crosses every v member: `grid.connections` lists only the pairs that cross (memberU,
// memberV), and EggGrid::at() does not apply. Members are never boundary lamellas (every member
// ends at an anchor on the patch's boundary ring, Section 4.3.1), so all of them take notches.
#include "core/egg/grid.hpp"
#include "core/generalised/generalised_design.hpp"
#include "core/rods/joined_network.hpp"
#include "core/rods/rod_network.hpp"
#include "patching/infill.hpp"

#include <vector>

namespace egg::assembly {

// The joined structure (pipeline/joined_simulation.cpp): a generalised member end held on a quad
// patch's side is bolted to that quad's boundary lamella (the ring beam of the piece's report),
// where it lies on it, face to face in the other layer; its anchor is then released. An end in the
// same layer as that lamella cannot lap onto it and keeps its anchor (a bracket on the ring beam's
// support), as do ends on the design boundary, a hole's rim or a cut between pieces.
struct RingBeamJoins {
  std::vector<rods::PatchJoin> bolts;  // patchA: the quad's patch id, patchB: `generalisedIndex`
  std::vector<int> releasedAnchors;    // indices into the generalised network's anchors
  // The same-layer ends as where they would bolt: each is fixed to that lamella by a bracket.
  std::vector<rods::PatchJoin> brackets;
  int sameLayer = 0;       // patch-side ends left anchored: same layer as the lamella
  int unmatched = 0;       // patch-side ends farther than the tolerance from a lamella
  double maxGapM = 0.0;    // largest distance from a bolted end to its lamella
  std::vector<int> quads;  // ascending: the quad patches with an end on their side (either way)
};

struct GeneralisedPatch {
  int patchId = 0;  // numbered after the layout's quad patches: lamellas "P<id>-U<i>", "P<id>-V<j>"
  int piece = -1;   // index into InfillResult::pieces ("G<piece>" in report.json and plan.svg)
  EggGrid grid;     // members u (layer 0) then v (layer 1); connections in the design's order
  // The design's rods in the grid's member order (u then v), its bolts as grid.connections, and
  // two anchors per member: rod r's start at 2r, its end at 2r + 1.
  rods::RodNetwork network;
  std::vector<patching::AnchorHold> anchorHolds;  // per anchor of `network`
  std::vector<int> rodOfMember;                   // per layout member of the design: its rod
  // Family h in layer 0 (the grid's u) and g in layer 1: the choice that bolts more of the ends
  // on the quads' sides to their boundary lamellas (generalisedPatches).
  bool swappedLayers = false;
  // Its ends on the quads' sides as generalisedPatches matched them for that choice (bolts'
  // patchB is 0: the joined run sets its own index of the patch).
  RingBeamJoins ring;
};

// `grids` per layout patch id (nullptr: no grid), `swapped` per patch as layerSwaps gives it.
RingBeamJoins ringBeamJoins(const GeneralisedPatch& patch, int generalisedIndex,
                            const std::vector<const EggGrid*>& grids,
                            const std::vector<char>& swapped, double toleranceM);

// Throws InvalidInput when the piece has no design or its holds do not match its members.
// `swapLayers`: family h in layer 0 and so the grid's u, g in layer 1.
GeneralisedPatch generalisedPatch(const patching::InfillPiece& piece, int pieceIndex, int patchId,
                                  bool swapLayers = false);

// Per piece with a design, in piece order, numbered from `firstPatchId` (piece i is patch
// firstPatchId + i), each with its layers as they bolt more member ends to the quads' boundary
// lamellas (ringBeamJoins with `quadGrids`, `quadSwaps`, `toleranceM`; ties: not swapped). A
// member end in a lamella's own layer needs a bracket; in a quad patch only the family in the
// other layer ends on each side, here both do.
std::vector<GeneralisedPatch> generalisedPatches(const patching::InfillResult& infill,
                                                 int firstPatchId,
                                                 const std::vector<const EggGrid*>& quadGrids,
                                                 const std::vector<char>& quadSwaps,
                                                 double toleranceM);

}  // namespace egg::assembly
