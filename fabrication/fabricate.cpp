#include "fabrication/fabricate.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "fabrication/dxf_writer.hpp"
#include "fabrication/pdf_writer.hpp"
#include "fabrication/sheet_layout.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace egg::fabrication {
namespace {

std::string formatted(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string numbered(const std::string& stem, int number, int digits,
                     const std::string& extension) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%0*d", digits, number);
  return stem + buffer + extension;
}

std::vector<Drawing> emptySheets(int count, std::array<double, 2> sizeMm,
                                 const std::string& title) {
  std::vector<Drawing> sheets(count);
  for (int i = 0; i < count; ++i) {
    sheets[i].title = title + " " + std::to_string(i + 1) + "/" + std::to_string(count);
    sheets[i].widthMm = sizeMm[0];
    sheets[i].heightMm = sizeMm[1];
  }
  return sheets;
}

void checkRules(const std::vector<FabricationPatch>& patches, FabricationResult& r) {
  const auto& o = r.options;
  // Section 3.5.2: t < w/5, or the lamella no longer behaves like a geodesic ribbon.
  if (o.lamellaThicknessMm >= o.lamellaWidthMm / 5.0) {
    r.warnings.push_back("lamella thickness " + formatted("%.3g", o.lamellaThicknessMm) +
                         " mm is not below w/5 = " + formatted("%.3g", o.lamellaWidthMm / 5.0) +
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
          "lamella width " + formatted("%.3g", o.lamellaWidthMm) + " mm is " +
          formatted("%.2f", 100.0 * ratio) + " % of the model size " + formatted("%.0f", sizeMm) +
          " mm; about 2 % works well for desktop and medium models (Section 3.5.2)");
    }
  }
  if (r.maxStressRatio > 1.0) {
    r.warnings.push_back("lamella " + r.maxStressLamella + " is stressed to " +
                         formatted("%.2f", r.maxStressRatio) + " of the strength of " +
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
        formatted("%.0f", o.effectiveSpliceClearanceMm()) +
        " mm to a hole or slot (no clearer position within a stock length); the tightest, " +
        tightest->id + " S" + std::to_string(tightestIndex + 1) + " at " +
        formatted("%.0f", tightest->splicesMm[tightestIndex]) + " mm, has " +
        formatted("%.0f", tightest->spliceClearancesMm[tightestIndex]) +
        " mm free each side: a splice plate there is at most " +
        formatted("%.0f", 2.0 * tightest->spliceClearancesMm[tightestIndex]) +
        " mm long (bom.csv splice_joint rows)");
  }
  if (r.maxScarfRatio > 1.0) {
    r.warnings.push_back("scarf joint " + r.maxScarfJoint + " is stressed to " +
                         formatted("%.2f", r.maxScarfRatio) +
                         " of its strength (fabrication.scarf_efficiency " +
                         formatted("%.2f", o.scarfEfficiency) + " of " + r.material.name +
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
    const double a = (from - plan.overhangMm) / 1000.0, b = (to - plan.overhangMm) / 1000.0;
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
  for (const auto& patch : patches)
    r.connections += static_cast<int>(patch.grid->connections.size());
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

  // Lamella sheets: every segment is a part.
  std::vector<NestPart> parts;
  std::vector<std::pair<int, int>> partOf;  // (lamella, segment)
  for (size_t i = 0; i < r.lamellae.size(); ++i) {
    const auto& plan = r.lamellae[i];
    for (size_t k = 0; k < plan.segments.size(); ++k) {
      parts.push_back(
          {segmentLabel(plan, static_cast<int>(k)), plan.segments[k].lengthMm(), plan.widthMm});
      partOf.emplace_back(static_cast<int>(i), static_cast<int>(k));
    }
  }
  r.lamellaNesting =
      nestParts(parts, options.sheetMm, options.kerfMm, options.marginMm, "fabrication.sheet_mm");
  r.sheets = emptySheets(r.lamellaNesting.sheets, options.sheetMm, "lamella sheet");
  for (size_t p = 0; p < parts.size(); ++p) {
    const auto& at = r.lamellaNesting.placements[p];
    drawLamellaSegment(r.lamellae[partOf[p].first], partOf[p].second, {at.xMm, at.yMm}, options,
                       r.sheets[at.sheet]);
  }

  // PTFE stickers.
  for (const auto& patch : patches) {
    auto stickers = planStickers(patch, r.lamellae, options);
    r.stickers.insert(r.stickers.end(), stickers.begin(), stickers.end());
  }
  std::vector<NestPart> stickerParts;
  for (const auto& s : r.stickers) {
    stickerParts.push_back({"sticker " + s.id, s.lengthMm, s.widthMm});
    r.stickerAreaM2 += s.areaM2();
  }
  r.stickerNesting = nestParts(stickerParts, options.effectiveStickerSheetMm(), options.kerfMm,
                               options.marginMm, "fabrication.sticker_sheet_mm");
  r.stickerSheets =
      emptySheets(r.stickerNesting.sheets, options.effectiveStickerSheetMm(), "PTFE sticker sheet");
  for (size_t p = 0; p < r.stickers.size(); ++p) {
    const auto& at = r.stickerNesting.placements[p];
    drawSticker(r.stickers[p], {at.xMm, at.yMm}, options, r.stickerSheets[at.sheet]);
  }

  // Supports.
  r.supports = planSupports(patches, options, &r.groundHeightM, &r.anchorsOnSharedSides);
  std::vector<std::string> brackets, sunk;
  int narrowed = 0;
  for (auto& s : r.supports) {
    if (!s.block) {
      r.supportSolids.emplace_back();  // no block: listed in supports.csv as a bracket
      brackets.push_back(s.id + " (" + formatted("%.1f", s.inclinationDeg) + " deg)");
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
      named.push_back(deepest[i]->id + " (" + formatted("%.0f", deepest[i]->belowGroundMm) +
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

std::string bomCsv(const FabricationResult& r) {
  std::ostringstream s;
  const auto& o = r.options;
  s << "item,id,count,length_mm,width_mm,thickness_mm,area_m2,volume_m3,mass_kg,note\n";
  char line[512];
  const double rho = r.material.densityKgM3;
  for (size_t i = 0; i < r.lamellae.size(); ++i) {
    const auto& p = r.lamellae[i];
    int holes = 0, slots = 0;
    for (const auto& f : p.features) (f.kind == FeatureKind::Slot ? slots : holes)++;
    const double volume = p.lengthMm * p.widthMm * o.lamellaThicknessMm * 1e-9;
    const char* notCut = p.unspliceable.empty()
                             ? ""
                             : "; NOT CUT: no splice position (report.json unspliceable_lamellae)";
    std::snprintf(line, sizeof line,
                  "lamella,%s,1,%.2f,%.2f,%.2f,,%.6g,%.6g,%s; %d holes; %d slots; %zu segments; "
                  "stress ratio %.3f%s\n",
                  p.id.c_str(), p.lengthMm, p.widthMm, o.lamellaThicknessMm, volume, volume * rho,
                  r.material.name.c_str(), holes, slots, p.segments.size(), r.stress[i].stressRatio,
                  notCut);
    s << line;
  }
  s << "splice,," << r.splices - r.scarfJoints
    << ",,,,,,,butt joints with bolted plates clear of holes by "
    << formatted("%.1f", o.effectiveSpliceClearanceMm())
    << " mm where a stock length allows, else at least "
    << formatted("%.1f", o.effectiveMinSpliceClearanceMm()) << " mm\n";
  if (r.scarfJoints > 0) {
    s << "scarf,," << r.scarfJoints << "," << formatted("%.1f", o.scarfLengthMm())
      << ",,,,,,glued scarf joints 1:" << formatted("%g", o.scarfSlope)
      << " to 1:" << formatted("%g", 2.0 * o.scarfSlope)
      << " (length_mm: the shortest), glued before assembly; the pieces overlap on the slope\n";
  }
  // Every splice: where along its lamella (length_mm = the cut's distance from the strip's start).
  for (size_t i = 0; i < r.lamellae.size(); ++i) {
    const auto& p = r.lamellae[i];
    for (size_t k = 0; k < p.splicesMm.size(); ++k) {
      if (k < p.spliceIsScarf.size() && p.spliceIsScarf[k]) {
        std::snprintf(line, sizeof line,
                      "splice_joint,%s S%zu,1,%.2f,%.2f,%.2f,,,,scarf between pieces %zu and %zu; "
                      "feather ends %.1f mm from "
                      "the nearest hole or slot; %.0f mm long; stress ratio %.3f\n",
                      p.id.c_str(), k + 1, p.splicesMm[k], p.widthMm, o.lamellaThicknessMm, k + 1,
                      k + 2, p.spliceClearancesMm[k],
                      p.segments[k].endMm - p.segments[k + 1].startMm, r.stress[i].scarfRatios[k]);
      } else {
        std::snprintf(line, sizeof line,
                      "splice_joint,%s S%zu,1,%.2f,%.2f,%.2f,,,,between pieces %zu and %zu; %.1f "
                      "mm free each side\n",
                      p.id.c_str(), k + 1, p.splicesMm[k], p.widthMm, o.lamellaThicknessMm, k + 1,
                      k + 2, p.spliceClearancesMm[k]);
      }
      s << line;
    }
  }
  s << "bolt,," << r.connections << ",,,,,,,diameter " << formatted("%.1f", o.boltDiameterMm)
    << " mm; one per connection (merged on shared lamellas)\n";
  s << "washer,," << 2 * r.connections << ",,,,,,,two per bolt\n";
  s << "brass_sleeve,," << r.counts.slots << ",,,,,,,one per slot (Section 3.5.1)\n";
  s << "ptfe_sticker,," << r.stickers.size() << ",,,," << formatted("%.6g", r.stickerAreaM2)
    << ",,,two per notched connection (Section 3.5.1)\n";
  s << "support,," << r.supports.size() << ",,,,,,,see supports/supports.csv\n";
  s << "lamella_sheet,," << r.lamellaNesting.sheets << "," << o.sheetMm[0] << "," << o.sheetMm[1]
    << "," << o.lamellaThicknessMm << ",,,,yield " << formatted("%.3f", r.lamellaNesting.yield)
    << "\n";
  s << "sticker_sheet,," << r.stickerNesting.sheets << "," << o.effectiveStickerSheetMm()[0] << ","
    << o.effectiveStickerSheetMm()[1] << ",,,,,PTFE foil\n";
  s << "total_lamellae,," << r.lamellae.size() << "," << formatted("%.2f", r.totalLengthM * 1000.0)
    << ",,,," << formatted("%.6g", r.volumeM3) << "," << formatted("%.6g", r.massKg)
    << ",self-weight " << formatted("%.1f", r.massKg * 9.81) << " N\n";
  return s.str();
}

std::vector<std::string> writeFabricationFiles(const FabricationResult& r,
                                               const std::filesystem::path& dir,
                                               const FabricationOutputs& outputs) {
  std::vector<std::string> files;
  auto write = [&](const std::string& relative, const std::string& text) {
    const auto path = dir / relative;
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
    if (error)
      throw WriteError("cannot create the folder " + path.parent_path().string() + ": " +
                       error.message());
    writeFileAtomically(path, text);
    files.push_back(relative);
  };
  auto writeSheets = [&](const std::vector<Drawing>& sheets, const std::string& stem,
                         const std::string& pdf) {
    for (size_t i = 0; i < sheets.size(); ++i) {
      write(numbered("cut/" + stem, static_cast<int>(i + 1), 2, ".svg"), toSvg(sheets[i]));
      write(numbered("cut/" + stem, static_cast<int>(i + 1), 2, ".dxf"), toDxf(sheets[i]));
    }
    if (!sheets.empty()) write("cut/" + pdf, toPdf(sheets));
  };
  if (outputs.cutFiles) writeSheets(r.sheets, "sheet_", "sheets.pdf");
  if (outputs.stickers) writeSheets(r.stickerSheets, "stickers_", "stickers.pdf");
  if (outputs.supports) {
    write("supports/supports.csv", supportsCsv(r.supports));
    for (size_t i = 0; i < r.supports.size(); ++i) {
      if (!r.supports[i].block) continue;
      write(numbered("supports/support_", static_cast<int>(i + 1), 3, ".stl"),
            toBinaryStl(r.supportSolids[i], "eggshell support " + r.supports[i].id + " (mm)"));
    }
  }
  write("bom.csv", bomCsv(r));
  return files;
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
