#include "fabrication/fabricate.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "fabrication/cut_sheets.hpp"
#include "fabrication/dxf_writer.hpp"
#include "fabrication/pdf_writer.hpp"
#include "fabrication/sheet_layout.hpp"

#include <fmt/printf.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace egg::fabrication {
namespace {

void checkRules(const std::vector<FabricationPatch>& patches, FabricationResult& r) {
  const auto& o = r.options;
  // Section 3.5.2: t < w/5, or the lamella no longer behaves like a geodesic ribbon.
  if (o.lamellaThicknessMm >= o.lamellaWidthMm / 5.0) {
    r.warnings.push_back("lamella thickness " + fmt::sprintf("%.3g", o.lamellaThicknessMm) +
                         " mm is not below w/5 = " + fmt::sprintf("%.3g", o.lamellaWidthMm / 5.0) +
                         " mm (Section 3.5.2)");
  }
  // Section 3.5.2: for desktop and medium models a width of about 2 % of the size works well.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : patches) {
    for (const auto* family : {&p.grid->u, &p.grid->v}) {
      for (const auto& m : *family) {
        for (const auto& q : m.spatial) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      }
    }
  }
  if ((hi - lo).allFinite()) {
    const double sizeMm = (hi - lo).maxCoeff() * 1000.0;
    const double ratio = o.lamellaWidthMm / sizeMm;
    if (sizeMm <= 10000.0 && (ratio < 0.01 || ratio > 0.04)) {
      r.warnings.push_back(
          "lamella width " + fmt::sprintf("%.3g", o.lamellaWidthMm) + " mm is " +
          fmt::sprintf("%.2f", 100.0 * ratio) + " % of the model size " +
          fmt::sprintf("%.0f", sizeMm) +
          " mm; about 2 % works well for desktop and medium models (Section 3.5.2)");
    }
  }
  if (r.maxStressRatio > 1.0) {
    r.warnings.push_back("lamella " + r.maxStressLamella + " is stressed to " +
                         fmt::sprintf("%.2f", r.maxStressRatio) + " of the strength of " +
                         r.material.name + " (Section 3.5.2: check sigma = E kappa t / 2)");
  }
  // Splices that had to go closer to a hole or slot than splice_clearance_mm (placeSplices): the
  // splice plate there can be at most twice that free length.
  int tight = 0;
  const LamellaPlan* tightest = nullptr;
  size_t tightestIndex = 0;
  for (const auto& plan : r.lamellae) {
    for (size_t k = 0; k < plan.spliceClearancesMm.size(); ++k) {
      if (k < plan.spliceIsScarf.size() && plan.spliceIsScarf[k])
        continue;  // glued, checked in checkScarfs
      if (plan.spliceClearancesMm[k] >= o.effectiveSpliceClearanceMm() - 1e-9) continue;
      ++tight;
      if (!tightest || plan.spliceClearancesMm[k] < tightest->spliceClearancesMm[tightestIndex])
        tightest = &plan, tightestIndex = k;
    }
  }
  if (tightest) {
    r.warnings.push_back(
        std::to_string(tight) + " splices lie closer than fabrication.splice_clearance_mm = " +
        fmt::sprintf("%.0f", o.effectiveSpliceClearanceMm()) +
        " mm to a hole or slot (no clearer position within a stock length); the tightest, " +
        tightest->id + " S" + std::to_string(tightestIndex + 1) + " at " +
        fmt::sprintf("%.0f", tightest->splicesMm[tightestIndex]) + " mm, has " +
        fmt::sprintf("%.0f", tightest->spliceClearancesMm[tightestIndex]) +
        " mm free each side: a splice plate there is at most " +
        fmt::sprintf("%.0f", 2.0 * tightest->spliceClearancesMm[tightestIndex]) +
        " mm long (bom.csv splice_joint rows)");
  }
  if (r.maxScarfRatio > 1.0) {
    r.warnings.push_back("scarf joint " + r.maxScarfJoint + " is stressed to " +
                         fmt::sprintf("%.2f", r.maxScarfRatio) +
                         " of its strength (fabrication.scarf_efficiency " +
                         fmt::sprintf("%.2f", o.scarfEfficiency) + " of " + r.material.name +
                         ", net of the holes and slots it crosses): move it or use plates");
  }
  if (r.counts.droppedBoundary > 0) {
    r.warnings.push_back(std::to_string(r.counts.droppedBoundary) +
                         " notches on boundary members are cut as plain holes (no notches on "
                         "boundaries, Section 3.5.3)");
  }
}

// Every scarf of `plan` (Section 3.5.2's check over the joint): the largest bending and torsion
// stress over the scarf's length against scarf_efficiency x the strength, on the net width
// w - d where a hole or slot runs through the joint. A lamella is as strong as its weakest scarf.
void checkScarfs(const LamellaPlan& plan, FabricationResult& r, LamellaStress& s) {
  const auto& o = r.options;
  s.scarfRatios.assign(plan.splicesMm.size(), 0.0);
  const double d = o.boltDiameterMm;
  for (size_t k = 0; k < plan.splicesMm.size(); ++k) {
    if (k >= plan.spliceIsScarf.size() || !plan.spliceIsScarf[k]) continue;
    const double from = plan.segments[k + 1].startMm, to = plan.segments[k].endMm;
    bool crossed = false;
    for (const auto& f : plan.features)
      crossed = crossed || (f.maxXMm(d) > from && f.minXMm(d) < to);
    const double net = crossed ? (plan.widthMm - d) / plan.widthMm : 1.0;
    // Strip coordinates (mm from the strip's start) to arc length along the member (m).
    const double a = (from + plan.trimStartMm - plan.overhangMm) / 1000.0,
                 b = (to + plan.trimStartMm - plan.overhangMm) / 1000.0;
    const double sigma = maxStressOver(s.bendingArcM, s.bendingPa, a, b);
    const double tau = maxStressOver(s.torsionArcM, s.torsionPa, a, b);
    const double ratio =
        std::max(sigma / r.material.bendingStrengthPa, tau / r.material.shearStrengthPa) /
        (o.scarfEfficiency * net);
    s.scarfRatios[k] = ratio;
    s.stressRatio = std::max(s.stressRatio, ratio);
    ++r.scarfJoints;
    if (ratio > r.maxScarfRatio)
      r.maxScarfRatio = ratio, r.maxScarfJoint = plan.id + " S" + std::to_string(k + 1);
  }
}

}  // namespace

FabricationResult fabricate(const std::vector<FabricationPatch>& patches,
                            const FabricationOptions& options,
                            const std::vector<SharedBoundary>& shared) {
  const auto started = std::chrono::steady_clock::now();
  options.validate();
  FabricationResult r;
  r.options = options;
  r.material = materialByName(options.material);
  r.lamellae = planLamellae(patches, options, shared);
  r.counts = countFeatures(r.lamellae);
  for (const auto& plan : r.lamellae) {
    if (!plan.unspliceable.empty()) r.unspliceable.push_back(plan.unspliceable);
  }
  const double t = options.lamellaThicknessMm / 1000.0, w = options.lamellaWidthMm / 1000.0;

  // One bolt per connection, one for each group of connections merged on a shared lamella.
  // A generalised member end's bolt (through its anchor's support or bracket, or through a quad's
  // boundary lamella) is one more; the BOM sizes it with the two-lamella bolts, a support's blind
  // hole taking the rest of its length.
  for (const auto& patch : patches) {
    r.connections += static_cast<int>(patch.grid->connections.size());
    for (const auto& hole : patch.extraHoles) r.connections += hole.newBolt ? 1 : 0;
    r.ringBeamBrackets.insert(r.ringBeamBrackets.end(), patch.ringBeamBrackets.begin(),
                              patch.ringBeamBrackets.end());
  }
  for (const auto& plan : r.lamellae) {
    for (const auto& f : plan.features) r.connections -= static_cast<int>(f.alsoConnections.size());
  }
  // Stress and weight per lamella, from the member it was planned from.
  for (const auto& plan : r.lamellae) {
    const FabricationPatch* patch = nullptr;
    for (const auto& p : patches) {
      if (p.patchId == plan.patchId) patch = &p;
    }
    const bool isU = plan.family == Family::U;
    const GridMember& m = isU ? patch->grid->u[plan.index] : patch->grid->v[plan.index];
    LamellaStress s =
        lamellaStress(m.spatial, &m.normals, t, r.material, curvatureWindowM(m.spatial, w));
    if (patch->deployedCentrelines) {
      // Bending from the simulated shape; the twist of the surface frame from the trace.
      const auto& centreline =
          (*patch->deployedCentrelines)[isU ? plan.index : patch->grid->u.size() + plan.index];
      const LamellaStress deployed =
          lamellaStress(centreline, nullptr, t, r.material, curvatureWindowM(centreline, w));
      s.maxCurvaturePerM = deployed.maxCurvaturePerM;
      s.maxBendingStressPa = deployed.maxBendingStressPa;
      s.bendingArcM = deployed.bendingArcM;
      s.bendingPa = deployed.bendingPa;
      s.stressRatio = std::max(s.maxBendingStressPa / r.material.bendingStrengthPa,
                               s.maxTorsionStressPa / r.material.shearStrengthPa);
      s.fromSimulation = true;
    }
    checkScarfs(plan, r, s);
    r.stress.push_back(s);
    if (s.stressRatio > r.maxStressRatio)
      r.maxStressRatio = s.stressRatio, r.maxStressLamella = plan.id;
    r.maxBendingStressPa = std::max(r.maxBendingStressPa, s.maxBendingStressPa);
    r.maxTorsionStressPa = std::max(r.maxTorsionStressPa, s.maxTorsionStressPa);
    r.totalLengthM += plan.lengthMm / 1000.0;
    r.splices += static_cast<int>(plan.splicesMm.size());
  }
  r.volumeM3 = r.totalLengthM * w * t;
  r.massKg = r.volumeM3 * r.material.densityKgM3;

  // Lamella sheets (or boards) and PTFE sticker sheets, nested and drawn (cut_sheets.cpp).
  for (const auto& patch : patches) {
    auto stickers = planStickers(patch, r.lamellae, options);
    r.stickers.insert(r.stickers.end(), stickers.begin(), stickers.end());
  }
  for (const auto& s : r.stickers) r.stickerAreaM2 += s.areaM2();
  layOutCutSheets(r);
  r.shared = shared;
  r.assembly = assemblyPatches(patches, r.lamellae, shared, options.minNotchMm / 1000.0);

  // Supports.
  r.supports = planSupports(patches, options, &r.groundHeightM, &r.anchorsOnSharedSides);
  std::vector<std::string> brackets, sunk;
  int narrowed = 0;
  for (auto& s : r.supports) {
    if (!s.block) {
      r.supportSolids.emplace_back();  // no block: listed in supports.csv as a bracket
      brackets.push_back(s.id + " (" + fmt::sprintf("%.1f", s.inclinationDeg) + " deg)");
      continue;
    }
    // A steep contact plane close to the ground (the foot of a wall, as at the Lilium's base)
    // falls below the ground over a wide footprint: the plane's lowest point over a square of side
    // b is h - (b/2)(|nx| + |ny|)/nz. The default block narrows to the widest whose top stays 5 mm
    // above the ground, but not below the lamella's width (it must still carry the lamella); a
    // block that then still reaches below the ground is reported with its depth.
    double block = options.effectiveSupportBlockMm();
    const double slope = (std::abs(s.normal.x()) + std::abs(s.normal.y())) / s.normal.z();
    const double widest = slope > 0.0 ? 2.0 * (s.heightM * 1000.0 - 5.0) / slope : block;
    if (!options.supportBlockMm && widest < block) {
      block = std::min(block, std::max(std::floor(widest), options.lamellaWidthMm));
      ++narrowed;
    }
    s.blockMm = block;
    double drop = 0.0;
    r.supportSolids.push_back(
        supportSolid(s, block, options.boltDiameterMm, 3.0 * options.boltDiameterMm, &drop));
    s.belowGroundMm = drop;
    if (drop > 0.0) sunk.push_back(s.id);
  }
  r.narrowedSupportBlocks = narrowed;
  auto list = [](const std::vector<std::string>& items) {
    std::string text;
    for (size_t i = 0; i < items.size(); ++i) text += (i ? ", " : "") + items[i];
    return text;
  };
  if (!brackets.empty()) {
    r.warnings.push_back(std::to_string(brackets.size()) +
                         " supports have contact planes steeper than 80 deg, too steep for a "
                         "block: they need wall brackets "
                         "(kind bracket in supports/supports.csv, not drawn): " +
                         list(brackets));
  }
  if (!sunk.empty()) {
    // The deepest ten by name; every one in supports.csv (below_ground_mm).
    std::vector<const Support*> deepest;
    for (const auto& s : r.supports) {
      if (s.belowGroundMm > 0.0) deepest.push_back(&s);
    }
    std::sort(deepest.begin(), deepest.end(), [](const Support* a, const Support* b) {
      return a->belowGroundMm > b->belowGroundMm;
    });
    std::vector<std::string> named;
    for (size_t i = 0; i < deepest.size() && i < 10; ++i) {
      named.push_back(deepest[i]->id + " (" + fmt::sprintf("%.0f", deepest[i]->belowGroundMm) +
                      " mm)");
    }
    r.warnings.push_back(std::to_string(sunk.size()) +
                         " support blocks stand on steep contact planes too close to the ground "
                         "even at the lamella width: "
                         "their tops fall below the ground (fabrication.ground_height_m); sink "
                         "them that deep or use wall "
                         "brackets (below_ground_mm in supports/supports.csv); the deepest: " +
                         list(named));
  }
  checkRules(patches, r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

nlohmann::json fabricationReport(const FabricationResult& r,
                                 const std::vector<std::string>& files) {
  nlohmann::json j;
  j["ran"] = true;
  j["lamellae"] = r.lamellae.size();
  j["notches"] = r.counts.slots;
  j["plain_holes"] = r.counts.demoted;
  j["holes"] = r.counts.holes;
  j["boundary_notches_dropped"] = r.counts.droppedBoundary;
  j["bolts"] = r.connections;
  j["splices"] = r.splices;
  j["stickers"] = r.stickers.size();
  j["sticker_area_m2"] = r.stickerAreaM2;
  j["sticker_sheets"] = r.stickerNesting.sheets;
  j["supports"] = r.supports.size();
  j["ground_height_m"] = r.groundHeightM;
  j["anchors_on_shared_sides"] = r.anchorsOnSharedSides;
  j["narrowed_support_blocks"] = r.narrowedSupportBlocks;
  j["sheets"] = r.lamellaNesting.sheets;
  j["yield"] = r.lamellaNesting.yield;
  // Nesting (issue 38): what each sheet holds, against the first-fit shelves used before and the
  // least number of rows any packing needs; the sheet width that wastes least.
  j["stock"] = toString(r.options.stock);
  j["sheet_ids"] = r.sheetIds;
  j["sheet_utilisation"] = r.lamellaNesting.sheetUtilisation;
  j["rows"] = r.lamellaNesting.rows;
  j["rows_lower_bound"] = r.lamellaNesting.rowsLowerBound;
  j["shelf_sheets"] = r.lamellaNesting.shelfSheets;
  j["sticker_sheet_utilisation"] = r.stickerNesting.sheetUtilisation;
  j["sticker_shelf_sheets"] = r.stickerNesting.shelfSheets;
  if (r.sheetWidthSuggestion.sheets > 0) {
    const auto& s = r.sheetWidthSuggestion;
    j["suggested_sheet_mm"] = {r.options.sheetMm[0], s.widthMm};
    j["suggested_sheet_rows"] = s.rowsPerSheet;
    j["suggested_sheet_count"] = s.sheets;
    j["suggested_sheet_yield"] = s.yield;
  }
  j["material"] = r.material.name;
  j["total_length_m"] = r.totalLengthM;
  j["volume_m3"] = r.volumeM3;
  j["mass_kg"] = r.massKg;
  j["scarf_joints"] = r.scarfJoints;
  j["max_scarf_stress_ratio"] = r.maxScarfRatio;
  if (!r.maxScarfJoint.empty()) j["max_scarf_joint"] = r.maxScarfJoint;
  j["max_stress_ratio"] = r.maxStressRatio;
  j["max_stress_lamella"] = r.maxStressLamella;
  j["max_bending_stress_pa"] = r.maxBendingStressPa;
  j["max_torsion_stress_pa"] = r.maxTorsionStressPa;
  j["warnings"] = r.warnings;
  j["unspliceable_lamellae"] = r.unspliceable;
  // Per lamella (in the BOM's order): the stress check behind max_stress_ratio.
  nlohmann::json stress = nlohmann::json::array();
  for (size_t i = 0; i < r.lamellae.size() && i < r.stress.size(); ++i) {
    stress.push_back({{"id", r.lamellae[i].id},
                      {"ratio", r.stress[i].stressRatio},
                      {"bending_stress_pa", r.stress[i].maxBendingStressPa},
                      {"torsion_stress_pa", r.stress[i].maxTorsionStressPa},
                      {"from_simulation", r.stress[i].fromSimulation}});
    double scarf = 0.0;
    for (size_t k = 0; k < r.stress[i].scarfRatios.size(); ++k) {
      if (k < r.lamellae[i].spliceIsScarf.size() && r.lamellae[i].spliceIsScarf[k])
        scarf = std::max(scarf, r.stress[i].scarfRatios[k]);
    }
    if (scarf > 0.0) stress.back()["max_scarf_ratio"] = scarf;
  }
  j["lamella_stress"] = stress;
  j["files"] = files;
  j["seconds"] = r.seconds;
  return j;
}

}  // namespace egg::fabrication
