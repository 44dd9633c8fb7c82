#pragma once
// Inputs of the fabrication stage (Sections 3.5, 3.6.1): the traced grids of the patches and the
// workshop's options. Lengths on the workshop side are millimetres (cut files are in mm); the
// grid is in metres, as everywhere inside eggshell.
#include "core/egg/grid.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace egg::fabrication {

// One patch handed to fabrication: its grid and, when the simulation ran, the deployed centrelines
// of its members in the grid's member order (all u members, then all v members). Without them the
// stress check reads the traced geodesics (the design), with them the simulated shape.
struct FabricationPatch {
  int patchId = 0;
  const EggGrid* grid = nullptr;
  std::optional<std::vector<std::vector<Eigen::Vector3d>>> deployedCentrelines;  // metres
  // Which sides lie on the design surface's boundary (side 0 = u member 0, 1 = the last v member,
  // 2 = the last u member, 3 = v member 0). A side shared with another patch is held by that
  // patch's lamellas, not by the ground: supports stand only on free sides (Section 3.5.3; Section
  // 2.2: "appropriate support locations are along the boundary"). One patch: all four.
  std::array<bool, 4> freeSides{true, true, true, true};
  // A generalised patch (Chapter 4) holds its members at their ends, not at connections: the ends
  // on the design boundary or a hole's rim stand on supports like a quad patch's anchors (its
  // freeSides are all false: it has no sides in that sense). Quad patches: none.
  struct EndSupport {
    std::string id;  // "P<patch>-U<i>-start", "...-end": the member end it holds
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // metres, on the design surface
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // unit surface normal there
  };
  std::vector<EndSupport> endSupports;
  // A generalised patch whose member ends bolt to quad patches' boundary lamellas (its ring beam
  // on their sides): those patches, which must stand before it is deployed. Quad patches: none.
  std::vector<int> boltedTo;
  // Bolt holes that are not grid connections (connection -1 in the plans): a generalised member's
  // end (its anchor bolt, or its bolt through a quad's boundary lamella), and that bolt's hole in
  // the quad's lamella. `newBolt`: the hole counts a bolt of its own (the member end's hole; not
  // its partner in the quad's lamella).
  struct ExtraHole {
    Family family = Family::U;
    int member = 0;
    double sM = 0.0;  // along the member in the plane (metres from its start)
    std::string id;   // engraved beside it: "P<patch>-U<i>-start" ("-end"), the member end's id
    bool newBolt = true;
  };
  std::vector<ExtraHole> extraHoles;
  // A generalised patch's member ends that lie on a quad's boundary lamella in that lamella's own
  // layer: each butts against it and is fixed by a steel bracket, one bolt through each lamella
  // (both holes are extraHoles, engraved with the end's id). bom.csv lists them.
  struct RingBeamBracket {
    std::string endId;      // "P4-U3-end"
    std::string lamellaId;  // the quad's boundary lamella, "P1-U0"
  };
  std::vector<RingBeamBracket> ringBeamBrackets;
  // Strips cut short at a bracket end (assembly/generalised_fabrication.hpp): `trimMm` less than
  // the usual strip (which reaches an overhang beyond the end point) at its start or its end.
  struct EndTrim {
    Family family = Family::U;
    int member = 0;
    bool atStart = false;
    double trimMm = 0.0;
  };
  std::vector<EndTrim> endTrims;
};

// How pieces are joined into a lamella longer than a piece (FabricationOptions::spliceJoint).
enum class SpliceJoint { Plate, Scarf, PlateOrScarf };
// "plate", "scarf", "plate_or_scarf" (the scene's and bom.csv's spelling).
const char* toString(SpliceJoint joint);

// DXF flavour of the cut files: AutoCAD 2000 (LWPOLYLINE, $INSUNITS) or R12 for old CAM software.
enum class DxfVersion { R2000, R12 };
const char* toString(DxfVersion version);  // "R2000", "R12"

// ISO 216 paper for the PDFs (sheets.pdf, assembly.pdf).
enum class PaperSize { A0, A1, A2, A3, A4 };
const char* toString(PaperSize size);               // "A0" .. "A4"
std::array<double, 2> paperSizeMm(PaperSize size);  // portrait: {short side, long side}

// How sheets.pdf shows a sheet: fitted to one page at a printed 1:n scale, tiled over pages at
// 1:1 (to check parts against the print), or one page of the sheet's own size with hairlines
// (what a laser's print driver takes).
enum class SheetPdf { Fit, Tile, TrueSize };
const char* toString(SheetPdf mode);  // "fit", "tile", "true_size"

// What the lamellas are cut from: sheets (strips nested in rows) or linear stock, boards of the
// lamella's width and stock_length_mm long (a cutting list, cut/boards.csv).
enum class CutStock { Sheet, Boards };
const char* toString(CutStock stock);  // "sheet", "boards"

struct FabricationOptions {
  double lamellaWidthMm = 250.0;  // w, across the strip (scene lamella.width_m)
  double lamellaThicknessMm =
      40.0;  // t, the weak axis the lamella bends about (lamella.thickness_m)
  std::string material = "poplar_plywood";  // core/materials name (lamella.material)
  std::array<double, 2> sheetMm{
      2500.0, 1250.0};            // stock sheet or laser bed; strips run along the first side
  double kerfMm = 0.2;            // width the cutter removes: gap between nested parts
  double marginMm = 10.0;         // unused border around every sheet
  double boltDiameterMm = 8.0;    // hole diameter and slot width
  double minNotchMm = 1.0;        // shorter notches are cut as plain holes (mesh noise, 2.4.5)
  double stockLengthMm = 6000.0;  // longest piece a lamella can be cut from (and at most the
                                  // sheet's first side); longer ones are spliced
  std::optional<double> endOverhangMm;  // strip beyond the end connections; default half the width
  std::optional<double>
      spliceClearanceMm;  // no hole or slot this close to a splice; default the width
  // Where a stock length has no position that clear (slots nearly as long as their spacing), the
  // splice goes to the middle of the widest gap if that keeps this much each side. Default 3.5 d:
  // the new end is then 4 d from the nearest bolt centre, the least end distance of a bolt from an
  // unloaded end in EN 1995-1-1 Table 8.4 (a3,c). Never more than the splice clearance.
  std::optional<double> minSpliceClearanceMm;
  // How pieces are joined into a lamella longer than a piece. "plate": bolted splice plates, in a
  // gap clear of holes and slots (above). "scarf": glued scarf joints of slope 1:scarf_slope
  // (to 1:2 scarf_slope) through the thickness, the pieces cut with their holes and slots and glued
  // before assembly; a scarf may cross holes and slots (only its two feather ends must lie
  // between them), so it also joins strips whose
  // slots leave no gap for a plate (the 8 m notches of a 60 m Yas patch). "plate_or_scarf": plates
  // where a stock length has room for one, scarfs where it has not. Every scarf is checked: the
  // stress over its length against scarf_efficiency x the strength, on the net width where it
  // crosses a hole or slot.
  SpliceJoint spliceJoint = SpliceJoint::Plate;
  double scarfSlope = 12.0;       // 1:12, the usual slope for structural scarfs in plywood and LVL
  double scarfEfficiency = 0.85;  // strength of the glued joint over that of the plain strip
  std::optional<double>
      labelHeightMm;             // engraved text height; default 0.35 w (clamped to 1..30 mm)
  double stickerMarginMm = 2.0;  // PTFE sticker beyond the swept contact area (3.5.1)
  std::optional<std::array<double, 2>> stickerSheetMm;  // PTFE foil sheet; default sheet_mm
  std::optional<double> groundHeightM;   // ground plane z; default 0.1 m below the lowest support
  std::optional<double> supportBlockMm;  // footprint side of a support block; default 3 w
  bool supportsAtBoundaryConnections =
      false;  // a support at every boundary connection (3.5.2 iv), not only at anchors
  DxfVersion dxfVersion = DxfVersion::R2000;
  PaperSize paperSize = PaperSize::A3;  // sheets.pdf and assembly.pdf
  SheetPdf sheetPdf = SheetPdf::Fit;
  CutStock stock = CutStock::Sheet;
  // A router bit's diameter (50-80 mm plywood is routed, not lasered): parts lie at least this
  // far apart so the bit passes between them, and the DXF gains a TOOLPATH layer with the bit's
  // centre path (outlines offset outwards, holes and slots inwards by the radius). Unset: a laser
  // (kerf_mm only).
  std::optional<double> toolDiameterMm;

  // Throws InvalidInput naming the scene field ("fabrication.sheet_mm: ...").
  void validate() const;

  double effectiveEndOverhangMm() const { return endOverhangMm.value_or(lamellaWidthMm / 2.0); }
  double effectiveSpliceClearanceMm() const { return spliceClearanceMm.value_or(lamellaWidthMm); }
  double effectiveMinSpliceClearanceMm() const {
    return std::min(minSpliceClearanceMm.value_or(3.5 * boltDiameterMm),
                    effectiveSpliceClearanceMm());
  }
  double effectiveLabelHeightMm() const;
  // The gap between nested parts: the kerf, or the router bit where one is set.
  double partGapMm() const { return std::max(kerfMm, toolDiameterMm.value_or(0.0)); }
  double scarfLengthMm() const { return scarfSlope * lamellaThicknessMm; }
  std::array<double, 2> effectiveStickerSheetMm() const { return stickerSheetMm.value_or(sheetMm); }
  double effectiveSupportBlockMm() const { return supportBlockMm.value_or(3.0 * lamellaWidthMm); }
};

}  // namespace egg::fabrication
