// The scene's keys of the structure and its checks: lamella, simulation, fabrication, acceptance
// and loads (scene_fields.cpp holds the geometry: surface, patching, grid).
#include "core/io/atomic_file.hpp"
#include "core/materials/materials.hpp"
#include "pipeline/scene_fields.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace egg::pipeline {

using nlohmann::json;

namespace {

// --- lamella, fabrication ---------------------------------------------------------------------

void checkLamella(JsonSection& j, Scene& scene) {
  try {
    materialByName(scene.lamella.material);
  } catch (const InvalidInput& e) {
    j.fail("material", abbreviate(e.what(), 400));
  }
  if (scene.lamella.thicknessM > scene.lamella.widthM)
    j.fail("thickness_m", "must not exceed width_m (a lamella bends about its weak axis)");
}

void readStickerSheet(JsonSection& j, Scene& scene) {
  fabrication::FabricationOptions& f = scene.fabrication.options;
  if (j.has("sticker_sheet_mm")) f.stickerSheetMm = j.pair("sticker_sheet_mm", f.sheetMm, 1.0, 1e5);
}

void checkFabrication(JsonSection& j, Scene& scene) {
  const fabrication::FabricationOptions& f = scene.fabrication.options;
  if (2.0 * f.marginMm >= std::min(f.sheetMm[0], f.sheetMm[1]))
    j.fail("margin_mm", "leaves no room on the sheet");
  // The engraving runs along the lamella: a taller text leaves the part (issue 40: 1000 mm was
  // accepted and engraved off the sheet).
  const double widthMm = 1000.0 * scene.lamella.widthM;
  if (f.labelHeightMm && *f.labelHeightMm > widthMm)
    j.fail("label_height_mm", fmt::format("{:g} mm is taller than the lamella ({:g} mm wide): the "
                                          "engraving would leave the part",
                                          *f.labelHeightMm, widthMm));
}

void readPointLoadConnections(JsonSection& j, Scene& scene) {
  if (!j.has("point_load_connections")) return;
  const json& v = j.raw("point_load_connections");
  if (!v.is_array()) j.fail("point_load_connections", "must be an array of connection names");
  for (const auto& item : v) {
    if (!item.is_string() || item.get<std::string>().empty())
      j.fail("point_load_connections", "each entry must be a name, got " + brief(item));
    scene.loads.pointLoadConnections.push_back(item.get<std::string>());
  }
}

void checkLoads(JsonSection& j, Scene& scene) {
  if (scene.loads.pointLoadKn > 0 && scene.loads.pointLoadConnections.empty())
    j.fail("point_load_kn", "needs point_load_connections");
}

std::string materialNames() {
  std::string names;
  for (const auto& m : materialCatalog()) names += (names.empty() ? "" : ", ") + m.name;
  return names;
}

nlohmann::json materialSchema() {
  nlohmann::json names = nlohmann::json::array();
  for (const auto& m : materialCatalog()) names.push_back(m.name);
  return {{"enum", names}};
}

}  // namespace

void addStructureSections(std::vector<SceneSection>& sections) {
  using namespace field;
  sections.push_back(
      {"lamella",
       "The section and material every member is cut from.",
       {positive("width_m", EGG_AT(lamella.widthM), 10.0, "section width w (strong axis)"),
        positive("thickness_m", EGG_AT(lamella.thicknessM), 10.0,
                 "section thickness t (weak axis), at most the width"),
        {"material", "string",
         "the material (E, G, density, strengths) from the catalogue: " + materialNames(),
         [](JsonSection& j, Scene& s) {
           s.lamella.material = j.text("material", s.lamella.material);
         },
         [](const Scene& s) { return some(s.lamella.material); }, materialSchema()}},
       checkLamella});

  sections.push_back(
      {"simulation",
       "The deployment with discrete elastic rods and sliding bolts (Section 2.5).",
       {boolean("enabled", EGG_AT(simulation.enabled), "simulate the deployed grid"),
        boolean("gravity", EGG_AT(simulation.rods.model.gravity),
                "self-weight from the material's density (3.5.2)"),
        number("friction_mu", EGG_AT(simulation.rods.model.frictionMu), 0.0, 2.0,
               "pseudo-friction coefficient of E_p (2.5)"),
        boolean("notches", EGG_AT(simulation.rods.model.notches),
                "bolts slide in their notches (RMS2 of 2.6.2); false: plain holes"),
        boolean("compare_without_notches", EGG_AT(simulation.rods.compareWithoutNotches),
                "also simulate every patch with plain holes (RMS1 of 2.6.2): a second full run per "
                "patch"),
        choice("supports", EGG_AT(simulation.supports),
               {{SupportChoice::Auto, "auto"},
                {SupportChoice::Anchors, "anchors"},
                {SupportChoice::DesignBoundary, "design_boundary"}},
               "where the grid is held: anchors (corners, curvature extrema, 2.4.6), "
               "design_boundary (also every connection on a side no other patch shares, 3.5.3), "
               "auto: anchors for one patch, design_boundary for several"),
        boolean("hold_shared_sides", EGG_AT(simulation.holdSharedSides),
                "patch by patch with design_boundary supports, also hold the sides shared with a "
                "neighbour (Fig. 3.17)"),
        boolean("join_patches", EGG_AT(simulation.joinPatches),
                "also simulate the whole structure, neighbours bolted along their shared lamellas "
                "(3.5.3)"),
        boolean("fasten_bolts", EGG_AT(simulation.rods.fastenBoltsUnderLoad),
                "under self-weight, bolts tightened at the weightless equilibrium before the grid "
                "carries its weight"),
        number("newton_tolerance", EGG_AT(simulation.rods.solver.tolerance), 1e-16, 1e-2,
               "Newton stops when its decrement falls below this x the energy scale"),
        integer("max_newton_iterations", EGG_AT(simulation.rods.solver.maxIterations), 1, 100000,
                "Newton iterations of a solve (all load steps) before it stops unconverged"),
        number("time_limit_s", EGG_AT(simulation.rods.solver.timeLimitS), 0.1, 1e6,
               "wall-clock hang guard of each solve (the iteration limit, not this, decides "
               "results)")},
       {}});

  sections.push_back(
      {"fabrication",
       "What the workshop cuts (Sections 3.5, 3.6.1); lengths in millimetres.",
       {boolean("enabled", EGG_AT(fabrication.enabled), "write cut files, stickers, supports, BOM"),
        pair("sheet_mm", EGG_AT(fabrication.options.sheetMm), 1.0, 1e5,
             "stock sheet or laser bed; strips run along the first side"),
        positive("bolt_diameter_mm", EGG_AT(fabrication.options.boltDiameterMm), 1000.0,
                 "hole diameter and slot width"),
        number("kerf_mm", EGG_AT(fabrication.options.kerfMm), 0.0, 100.0,
               "width the cutter removes between parts"),
        number("margin_mm", EGG_AT(fabrication.options.marginMm), 0.0, 1e4,
               "unused border of every sheet"),
        number("min_notch_mm", EGG_AT(fabrication.options.minNotchMm), 0.0, 1e4,
               "shorter notches are cut as plain holes (mesh noise, 2.4.5)"),
        positive("stock_length_mm", EGG_AT(fabrication.options.stockLengthMm), 1e6,
                 "longest piece a lamella is cut from; longer lamellas are spliced"),
        optionalNumber("end_overhang_mm", EGG_AT(fabrication.options.endOverhangMm), 0.0, 1e4,
                       "strip beyond the end connections (default: half the width)"),
        optionalNumber("splice_clearance_mm", EGG_AT(fabrication.options.spliceClearanceMm), 0.0,
                       1e5, "no hole or slot this close to a splice (default: the width)"),
        optionalNumber("min_splice_clearance_mm", EGG_AT(fabrication.options.minSpliceClearanceMm),
                       0.0, 1e5,
                       "where no position is that clear, at least this (default 3.5 bolt "
                       "diameters, EN 1995-1-1 8.4)"),
        optionalNumber("label_height_mm", EGG_AT(fabrication.options.labelHeightMm), 0.1, 1000.0,
                       "engraved text height (default 0.35 w, 1..30 mm)"),
        choice("splice_joint", EGG_AT(fabrication.options.spliceJoint),
               {{fabrication::SpliceJoint::Plate, "plate"},
                {fabrication::SpliceJoint::Scarf, "scarf"},
                {fabrication::SpliceJoint::PlateOrScarf, "plate_or_scarf"}},
               "splices as bolted plates, glued scarfs, or plates with scarfs where no plate fits"),
        number("scarf_slope", EGG_AT(fabrication.options.scarfSlope), 4.0, 40.0,
               "scarf run per unit of thickness (1:12)"),
        number("scarf_efficiency", EGG_AT(fabrication.options.scarfEfficiency), 0.01, 1.0,
               "glued joint strength over the plain strip's"),
        number("sticker_margin_mm", EGG_AT(fabrication.options.stickerMarginMm), 0.0, 1000.0,
               "PTFE sticker beyond the swept contact area (3.5.1)"),
        {"sticker_sheet_mm", "two numbers in [1, 100000], optional",
         "PTFE foil sheet (default: sheet_mm)", readStickerSheet,
         [](const Scene& s) {
           const auto& sheet = s.fabrication.options.stickerSheetMm;
           return sheet ? some(*sheet) : std::nullopt;
         },
         pairSchema(1.0, 1e5)},
        optionalNumber("ground_height_m", EGG_AT(fabrication.options.groundHeightM), -1e5, 1e5,
                       "ground plane z of the supports, metres (default: 0.1 m below the lowest)"),
        optionalNumber("support_block_mm", EGG_AT(fabrication.options.supportBlockMm), 1.0, 1e5,
                       "footprint side of a support block (default 3 w)"),
        boolean("supports_at_boundary_connections",
                EGG_AT(fabrication.options.supportsAtBoundaryConnections),
                "a support at every boundary connection (3.5.2 iv), not only at anchors"),
        // Issue 38: what the workshop's software and paper take.
        choice("stock", EGG_AT(fabrication.options.stock),
               {{fabrication::CutStock::Sheet, "sheet"}, {fabrication::CutStock::Boards, "boards"}},
               "lamellas nested on sheets, or cut from boards of the lamella's width and "
               "stock_length_mm (cut/boards.csv)"),
        choice("dxf_version", EGG_AT(fabrication.options.dxfVersion),
               {{fabrication::DxfVersion::R2000, "R2000"}, {fabrication::DxfVersion::R12, "R12"}},
               "DXF flavour of the cut files (R12 for old CAM software)"),
        choice("sheet_pdf", EGG_AT(fabrication.options.sheetPdf),
               {{fabrication::SheetPdf::Fit, "fit"},
                {fabrication::SheetPdf::Tile, "tile"},
                {fabrication::SheetPdf::TrueSize, "true_size"}},
               "sheets.pdf: a sheet fitted to a page at 1:n, tiled at 1:1, or at its own size "
               "with hairlines (laser print drivers)"),
        choice("paper_size", EGG_AT(fabrication.options.paperSize),
               {{fabrication::PaperSize::A0, "A0"},
                {fabrication::PaperSize::A1, "A1"},
                {fabrication::PaperSize::A2, "A2"},
                {fabrication::PaperSize::A3, "A3"},
                {fabrication::PaperSize::A4, "A4"}},
               "ISO paper of sheets.pdf, assembly.pdf and the DXF sheets' print set-up"),
        optionalNumber("tool_diameter_mm", EGG_AT(fabrication.options.toolDiameterMm), 0.1, 100.0,
                       "router bit: parts this far apart, TOOLPATH layer (default: a laser, "
                       "kerf_mm only)")},
       checkFabrication});

  sections.push_back(
      {"acceptance",
       "The limits a run is judged by (docs/acceptance.md): a run that misses one fails (exit 1) "
       "and names it. Lengths are fractions of the span, the longer side of the surface's plan.",
       {number("max_error_over_span", EGG_AT(acceptance.maxErrorOverSpan), 1e-6, 1.0,
               "largest distance of the deployed grid from the design surface (span / 50)"),
        number("rmse_over_span", EGG_AT(acceptance.rmseOverSpan), 1e-6, 1.0,
               "its root mean square (span / 200)"),
        number("max_sag_over_span", EGG_AT(acceptance.maxSagOverSpan), 1e-6, 1.0,
               "largest sag under self-weight from the weightless equilibrium (span / 250)"),
        number("max_stress_ratio", EGG_AT(acceptance.maxStressRatio), 1e-3, 100.0,
               "largest bending and torsion stress of a lamella over its strength")},
       {}});
  sections.push_back(
      {"loads",
       "Load cases of the FE check (output \"fem\", docs/verification.md); self-weight is always "
       "one.",
       {number("uniform_kn_m2", EGG_AT(loads.uniformKnM2), 0.0, 100.0,
               "snow or live load on the plan area, shared by tributary plan length (0: no case)"),
        number("point_load_kn", EGG_AT(loads.pointLoadKn), 0.0, 1e4,
               "downwards at each of point_load_connections (0: no case)"),
        {"point_load_connections",
         "array of names",
         "FE connection names (model.inp sets: P<patch>_C<i>, J<i> between patches)",
         readPointLoadConnections,
         [](const Scene& s) { return some(s.loads.pointLoadConnections); },
         {{"type", "array"}, {"items", stringSchema()}}},
        integer("buckling_modes", EGG_AT(loads.bucklingModes), 0, 20,
                "linear buckling factors of the governing case (0: no buckling step)"),
        number("ccx_time_limit_s", EGG_AT(loads.ccxTimeLimitS), 1.0, 1e5,
               "each ccx run is stopped after this"),
        integer("max_fe_elements", EGG_AT(loads.maxFeElements), 1, 10000000,
                "beam elements above which the FE decks are written to fem/ but ccx is not run"),
        integer("max_nonlinear_fe_elements", EGG_AT(loads.maxNonlinearFeElements), 0, 10000000,
                "beam elements above which the load cases are solved first order (linear "
                "static), their nonlinear decks written beside (0: always nonlinear)")},
       checkLoads});
  sections.push_back(
      {"deployment",
       "The path from the flat grid to the deployed one (output \"deployment\", "
       "docs/deployment.md).",
       {integer("steps", EGG_AT(deployment.steps), 1, 1000,
                "equal, synchronised support moves from the flat grid to the deployed supports "
                "(a step that fails or jumps is split in halves up to 4 times)"),
        number("jam_force_n", EGG_AT(deployment.jamForceN), 0.0, 1e9,
               "a sliding bolt at a notch end pressing on it harder than this is jammed (0: the "
               "bolt's embedment capacity in the lamella, EN 1995-1-1 8.5)"),
        number("snap_energy_drop", EGG_AT(deployment.snapEnergyDrop), 1e-6, 0.99,
               "a drop of the lamellas' elastic energy over one finest step by more than this "
               "fraction is a snap-through"),
        number("time_limit_s", EGG_AT(deployment.timeLimitS), 1.0, 1e6,
               "wall-clock limit of one patch's path: a path not at its end by then is reported "
               "up to where it got, as a failure of the run"),
        boolean(
            "join_patches", EGG_AT(deployment.joinPatches),
            "when the joined simulation ran: join the standing patches as a crew would "
            "(self-weight, joints pulled closed and bolted, shoring let go) and compare the end "
            "with the joined simulation")},
       {}});
}

}  // namespace egg::pipeline
