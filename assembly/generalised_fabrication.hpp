#pragma once
// What fabrication needs of a generalised patch (issue 41) beyond its grid: a bolt hole at every
// member end, supports under the ends on the design boundary or a hole's rim, the partner holes in
// the quads' boundary lamellas its ends bolt to, and the bracket ends. A member end on a quad's
// boundary lamella in that lamella's own layer cannot lap onto it: its strip stops at the
// lamella's face (its square end a gap clear: (w/2 (1 + |cos|) + gap) / sin back from the
// lamella's centre line, at the angle they meet at) and a steel
// bracket bolts it to the lamella; the rod model keeps the end at the centre line, anchored. Every
// end no quad lamella carries stands on a support, as the simulations anchor it.
#include "assembly/generalised_patch.hpp"
#include "fabrication/options.hpp"

#include <string>
#include <vector>

namespace egg::assembly {

struct GeneralisedFabricationOptions {
  double lamellaWidthM = 0.0;  // > 0
  double endOverhangM = 0.0;   // the strips' overhang beyond their end bolts (>= 0)
  double bracketGapM = 0.01;   // between a trimmed end and the lamella's face
};

// Appends `patch` to `patches` (where the quads' entries already are: their lamellas get the
// partner holes) and returns the bracket ends left untrimmed because cut back, their bolt would
// come within an overhang of a crossing's hole or slot, or of the other end's bolt: "P4-V0-start
// (bolt 414 mm, crossing 33 mm from the end)". They are cut as drawn and overlap the lamella.
// Throws InvalidInput for bad options.
std::vector<std::string> addGeneralisedToFabrication(
    const GeneralisedPatch& patch, const RingBeamJoins& ring,
    const std::vector<const EggGrid*>& quadGrids, const GeneralisedFabricationOptions& options,
    std::vector<fabrication::FabricationPatch>& patches);

}  // namespace egg::assembly
