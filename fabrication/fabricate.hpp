#pragma once
// The fabrication stage (Sections 3.5, 3.6.1): from the traced grids to what a workshop needs —
// lamella cut sheets with holes, slots, labels and splices; PTFE sticker sheets; support solids;
// a bill of materials; the bending and torsion stress check and the self-weight.
//   FabricationResult r = fabricate(patches, options);          // pure: geometry and numbers
//   auto files = writeFabricationFiles(r, runDir, outputs);      // cut/, supports/, bom.csv
//   report["fabrication"] = fabricationReport(r, files);
#include "fabrication/assembly_patch.hpp"
#include "fabrication/drawing.hpp"
#include "fabrication/lamella_plan.hpp"
#include "fabrication/nesting.hpp"
#include "fabrication/options.hpp"
#include "fabrication/stickers.hpp"
#include "fabrication/stress.hpp"
#include "fabrication/supports.hpp"

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace egg::fabrication {

struct FabricationResult {
  FabricationOptions options;
  MaterialProperties material;
  std::vector<LamellaPlan> lamellae;  // u then v members, patch by patch
  std::vector<LamellaStress> stress;  // one per lamella
  std::vector<Sticker> stickers;
  std::vector<Support> supports;
  std::vector<TriangleMesh> supportSolids;  // one per support, millimetres
  double groundHeightM = 0.0;
  int anchorsOnSharedSides = 0;   // grid anchors without a support: held by the neighbouring patch
  int narrowedSupportBlocks = 0;  // default blocks narrowed to keep their tops above the ground
  Nesting lamellaNesting, stickerNesting;
  std::vector<Drawing> sheets;                // lamella sheets, or boards (options.stock)
  std::vector<Drawing> stickerSheets;         // PTFE foil sheets
  std::vector<std::string> sheetIds;          // "L01" (sheets) or "B01" (boards), on each sheet
  std::vector<std::string> stickerSheetIds;   // "F01"
  std::vector<std::vector<int>> pieceSheets;  // per lamella, per segment: its sheet (index)
  SheetWidthSuggestion sheetWidthSuggestion;  // sheets only: the width that wastes least
  std::vector<AssemblyPatch> assembly;        // for cut/assembly.pdf
  std::vector<SharedBoundary> shared;         // the shared sides fabricate() was given
  FeatureCounts counts;
  int connections = 0;         // bolts: connections, those merged on a shared lamella once
  int splices = 0;             // all joints, scarfs included
  int scarfJoints = 0;         // glued scarfs among them (fabrication.splice_joint)
  double maxScarfRatio = 0.0;  // the most stressed scarf over its strength
  std::string maxScarfJoint;   // "<lamella> S<k>"
  double totalLengthM = 0.0;   // all strips, overhangs included
  double volumeM3 = 0.0;
  double massKg = 0.0;
  double stickerAreaM2 = 0.0;
  double maxStressRatio = 0.0;
  double maxBendingStressPa = 0.0, maxTorsionStressPa = 0.0;
  std::string maxStressLamella;
  std::vector<FabricationPatch::RingBeamBracket> ringBeamBrackets;  // of all patches
  std::vector<std::string> warnings;  // Section 3.5.2 rules and other things to look at
  std::vector<std::string>
      unspliceable;  // lamellas left out of the cut files: why each cannot be spliced
  double seconds = 0.0;
};

// Validates the options, plans the lamellas (one lamella for each shared side, holding the holes
// of both patches), splices, stickers and supports, nests the parts and checks stresses. A lamella
// that cannot be spliced clear of its holes is left out of the sheets and listed in `unspliceable`
// (a failure of the run, but the rest is cut). Throws InvalidInput (bad option, a part larger than
// the sheet, a support that cannot be built, a shared side that does not match).
FabricationResult fabricate(const std::vector<FabricationPatch>& patches,
                            const FabricationOptions& options,
                            const std::vector<SharedBoundary>& shared = {});

// Which files to write (the scene's outputs "cut_files", "stickers", "supports").
struct FabricationOutputs {
  bool cutFiles = true;  // cut/sheet_NN.svg, .dxf, sheets.pdf, assembly.pdf, cut.zip
  bool stickers = true;  // cut/stickers_NN.svg, cut/stickers_NN.dxf, cut/stickers.pdf
  bool supports = true;  // supports/supports.csv, supports/support_NNN.stl
};

// Writes the files below `dir` (bom.csv always) atomically and returns their paths relative to
// `dir`, in the order written. Throws WriteError naming a file that cannot be written.
std::vector<std::string> writeFabricationFiles(const FabricationResult& result,
                                               const std::filesystem::path& dir,
                                               const FabricationOutputs& outputs = {});

// The bill of materials:
// item,id,count,length_mm,width_mm,thickness_mm,area_m2,volume_m3,mass_kg,note. Rows: one per
// lamella, splices (total, then one splice_joint row per splice with its position), bolts, washers,
// brass sleeves, PTFE stickers, supports, sheets, totals.
std::string bomCsv(const FabricationResult& result);

// report.json "fabrication": lamellae, notches, plain_holes, stickers, supports, sheets, yield,
// max_stress_ratio, mass_kg, files[] and the details behind them (units in the keys), with
// lamella_stress[] ({id, ratio, bending_stress_pa, torsion_stress_pa, from_simulation} per lamella)
// and unspliceable_lamellae[] (why each lamella left out of the cut files cannot be spliced).
nlohmann::json fabricationReport(const FabricationResult& result,
                                 const std::vector<std::string>& files = {});

}  // namespace egg::fabrication
