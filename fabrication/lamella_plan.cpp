#include "fabrication/lamella_plan.hpp"

#include "core/errors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace egg::fabrication {

double LamellaFeature::minXMm(double boltDiameterMm) const {
  return std::min(xMm, xMm + slideMm) - boltDiameterMm / 2.0;
}

double LamellaFeature::maxXMm(double boltDiameterMm) const {
  return std::max(xMm, xMm + slideMm) + boltDiameterMm / 2.0;
}

std::string LamellaFeature::label() const {
  std::string text = connectionId;
  for (const auto& id : alsoConnectionIds) text += "=" + id;
  return text;
}

bool LamellaFeature::holds(int patch, int index) const {
  if (patch == patchId && index == connection) return true;
  for (const auto& [p, c] : alsoConnections) {
    if (p == patch && c == index) return true;
  }
  return false;
}

namespace {

std::string lamellaId(int patchId, Family family, int index) {
  return "P" + std::to_string(patchId) + "-" + (family == Family::U ? "U" : "V") +
         std::to_string(index);
}

std::string connectionId(int patchId, int i, int j) {
  return "P" + std::to_string(patchId) + "-C" + std::to_string(i) + "-" + std::to_string(j);
}

LamellaPlan planMember(const FabricationPatch& patch, const GridMember& member,
                       const FabricationOptions& options) {
  const EggGrid& grid = *patch.grid;
  LamellaPlan plan;
  plan.patchId = patch.patchId;
  plan.family = member.family;
  plan.index = member.index;
  plan.boundary = member.boundary;
  plan.id = lamellaId(patch.patchId, member.family, member.index);
  plan.widthMm = options.lamellaWidthMm;
  plan.overhangMm = options.effectiveEndOverhangMm();
  plan.lengthMm = member.planarLength * 1000.0 + 2.0 * plan.overhangMm;
  const bool isU = member.family == Family::U;
  // The connections on this member: for a quad patch row `index` of the grid (u) or its column
  // (v); a generalised patch lists only the pairs that cross (assembly/generalised_patch.hpp).
  for (int k = 0; k < static_cast<int>(grid.connections.size()); ++k) {
    const GridConnection& c = grid.connections[k];
    if ((isU ? c.memberU : c.memberV) != member.index) continue;
    const int i = c.memberU, j = c.memberV;
    LamellaFeature f;
    f.patchId = patch.patchId;
    f.connection = k;
    f.connectionId = connectionId(patch.patchId, i, j);
    f.xMm = plan.overhangMm + (isU ? c.sBarU : c.sBarV) * 1000.0;
    const double notchMm = (isU ? c.notchU : c.notchV) * 1000.0;
    if (member.boundary) {
      f.droppedBoundaryNotch = std::abs(notchMm) >= options.minNotchMm && notchMm != 0.0;
    } else if (std::abs(notchMm) >= options.minNotchMm && notchMm != 0.0) {
      f.kind = FeatureKind::Slot;
      f.slideMm = notchMm;
    } else {
      f.demotedNotch = notchMm != 0.0;
    }
    plan.features.push_back(f);
  }
  for (const auto& hole : patch.extraHoles) {
    if (hole.family != member.family || hole.member != member.index) continue;
    const double x = plan.overhangMm + hole.sM * 1000.0;
    // A generalised member end continuing one of this lamella's connections (C0 across the
    // side) shares its hole: one bolt through three lamellas.
    const auto same = std::find_if(plan.features.begin(), plan.features.end(), [&](const auto& f) {
      return f.connection >= 0 && std::abs(f.xMm - x) <= 0.5;
    });
    if (same != plan.features.end()) {
      same->alsoConnections.emplace_back(patch.patchId, -1);
      same->alsoConnectionIds.push_back(hole.id);
      continue;
    }
    LamellaFeature f;
    f.patchId = patch.patchId;
    f.connection = -1;
    f.connectionId = hole.id;
    f.xMm = x;
    plan.features.push_back(f);
  }
  for (const auto& trim : patch.endTrims) {
    if (trim.family != member.family || trim.member != member.index) continue;
    (trim.atStart ? plan.trimStartMm : plan.trimEndMm) += trim.trimMm;
  }
  plan.lengthMm -= plan.trimStartMm + plan.trimEndMm;
  for (auto& f : plan.features) f.xMm -= plan.trimStartMm;
  if (!(plan.lengthMm > 0.0))
    throw InvalidInput("lamella " + plan.id + ": its end trims leave no strip");
  std::sort(plan.features.begin(), plan.features.end(),
            [](const LamellaFeature& a, const LamellaFeature& b) { return a.xMm < b.xMm; });
  const double d = options.boltDiameterMm;
  for (const auto& f : plan.features) {
    if (f.minXMm(d) < -1e-9 || f.maxXMm(d) > plan.lengthMm + 1e-9) {
      std::ostringstream msg;
      msg << "lamella " << plan.id << ": the " << (f.kind == FeatureKind::Slot ? "slot" : "hole")
          << " of connection " << f.connectionId
          << " reaches beyond the strip end (raise fabrication.end_overhang_mm)";
      throw InvalidInput(msg.str());
    }
  }
  return plan;
}

}  // namespace

std::vector<LamellaPlan> planLamellae(const std::vector<FabricationPatch>& patches,
                                      const FabricationOptions& options,
                                      const std::vector<SharedBoundary>& shared) {
  std::vector<LamellaPlan> plans;
  for (const auto& patch : patches) {
    if (!patch.grid)
      throw InvalidInput("fabrication: patch " + std::to_string(patch.patchId) + " has no grid");
    const EggGrid& grid = *patch.grid;
    for (size_t k = 0; k < grid.connections.size(); ++k) {
      const GridConnection& c = grid.connections[k];
      if (c.memberU < 0 || c.memberU >= static_cast<int>(grid.u.size()) || c.memberV < 0 ||
          c.memberV >= static_cast<int>(grid.v.size()))
        throw InvalidInput("fabrication: patch " + std::to_string(patch.patchId) + ": connection " +
                           std::to_string(k) + " joins members " + std::to_string(c.memberU) +
                           " and " + std::to_string(c.memberV) + " of a grid with " +
                           std::to_string(grid.u.size()) + " u and " +
                           std::to_string(grid.v.size()) + " v members");
    }
    for (const auto& hole : patch.extraHoles) {
      const size_t count = hole.family == Family::U ? grid.u.size() : grid.v.size();
      if (hole.member < 0 || hole.member >= static_cast<int>(count))
        throw InvalidInput("fabrication: patch " + std::to_string(patch.patchId) + ": hole " +
                           hole.id + " is on a member the grid does not have");
    }
    if (patch.deployedCentrelines &&
        patch.deployedCentrelines->size() != grid.u.size() + grid.v.size()) {
      throw InvalidInput("fabrication: patch " + std::to_string(patch.patchId) + ": " +
                         std::to_string(patch.deployedCentrelines->size()) +
                         " deployed centrelines for " +
                         std::to_string(grid.u.size() + grid.v.size()) + " members");
    }
    for (const auto& m : grid.u) plans.push_back(planMember(patch, m, options));
    for (const auto& m : grid.v) plans.push_back(planMember(patch, m, options));
  }
  mergeSharedBoundaries(plans, shared, 0.5);
  const double piece = longestPieceMm(options);
  const std::string field =
      options.stock == CutStock::Boards
          ? "fabrication.stock_length_mm (a board less its trimmed ends, fabrication.margin_mm)"
      : piece < options.stockLengthMm ? "fabrication.sheet_mm (the longest strip a sheet holds)"
                                      : "fabrication.stock_length_mm";
  for (auto& plan : plans) {
    try {
      placeSplices(plan, piece, options.effectiveSpliceClearanceMm(), options.boltDiameterMm, field,
                   options.effectiveMinSpliceClearanceMm(), options.spliceJoint,
                   options.scarfLengthMm());
    } catch (const InvalidInput& e) {
      // Slots that leave no room for any splice within a stock length (overlapping slots on the
      // Yas canopy's 45 m lamellas): no cut file can make it; the rest of the grid still can.
      plan.splicesMm.clear();
      plan.spliceClearancesMm.clear();
      plan.spliceIsScarf.clear();
      plan.segments.clear();
      plan.unspliceable = e.what();
    }
  }
  return plans;
}

double longestPieceMm(const FabricationOptions& options) {
  // Boards: a board's length less its trimmed ends; sheets: also the sheet's usable first side.
  if (options.stock == CutStock::Boards) return options.stockLengthMm - 2.0 * options.marginMm;
  return std::min(options.stockLengthMm, options.sheetMm[0] - 2.0 * options.marginMm);
}

namespace {

using Interval = std::pair<double, double>;

// What is cut out of the strip (holes, slots with their round ends), merged where they overlap.
std::vector<Interval> mergedCutOuts(const LamellaPlan& plan, double boltDiameterMm) {
  std::vector<Interval> cutOut;
  for (const auto& f : plan.features)
    cutOut.emplace_back(f.minXMm(boltDiameterMm), f.maxXMm(boltDiameterMm));
  std::sort(cutOut.begin(), cutOut.end());
  std::vector<Interval> merged;
  for (const auto& e : cutOut) {
    if (!merged.empty() && e.first <= merged.back().second)
      merged.back().second = std::max(merged.back().second, e.second);
    else
      merged.push_back(e);
  }
  return merged;
}

// One lamella's splices placed from its start: where a plate or a scarf may go between its
// cut-outs, and the splices placed so far (into `plan`).
struct Splicer {
  LamellaPlan& plan;
  double stockLengthMm, scarfLengthMm;
  std::vector<Interval> merged;  // the cut-outs
  double longestScarf = 0.0;
  std::vector<Interval> gaps;  // where a feather end may lie

  Splicer(LamellaPlan& plan_, double stockLengthMm_, double boltDiameterMm, double scarfLengthMm_)
      : plan(plan_),
        stockLengthMm(stockLengthMm_),
        scarfLengthMm(scarfLengthMm_),
        merged(mergedCutOuts(plan_, boltDiameterMm)) {
    // (Scarf joints: see furthestScarf.)
    const double endClear = boltDiameterMm / 2.0;
    longestScarf = 2.0 * scarfLengthMm;
    for (size_t k = 0; k <= merged.size(); ++k) {
      const double lo = (k == 0 ? 0.0 : merged[k - 1].second) + endClear;
      const double hi = (k == merged.size() ? plan.lengthMm : merged[k].first) - endClear;
      if (hi >= lo) gaps.emplace_back(lo, hi);
    }
  }

  // Free length from x to the nearest cut-out (zero inside one).
  double freeAt(double x) const {
    double free = std::numeric_limits<double>::infinity();
    for (const auto& [lo, hi] : merged)
      free = std::min(free, x < lo ? lo - x : x > hi ? x - hi : 0.0);
    return free;
  }
  // The furthest position in (start, start + stock] keeping `clear` from every cut-out: the stock
  // end itself or the lower end of the zone around a cut-out that covers it (zones chain, so
  // repeat); -1 when there is none.
  double furthest(double start, double clear) const {
    double cut = start + stockLengthMm;
    bool moved = true;
    while (moved && cut > start) {
      moved = false;
      for (const auto& [lo, hi] : merged) {
        if (cut > lo - clear && cut < hi + clear) {
          cut = lo - clear;
          moved = true;
        }
      }
    }
    return cut > start + 1e-9 && freeAt(cut) >= clear - 1e-9 ? cut : -1.0;
  }
  // A scarf joint: piece A ends at `end`, piece B starts at `begin` before it; they overlap by
  // end - begin, glued on the slope. The holes and slots are cut in the pieces before gluing, so
  // the two feather ends must lie between cut-outs, a bolt radius clear (no hole or slot cut open
  // at a piece's end); those inside the overlap go through both pieces. The overlap is at least
  // the scarf length (the steepest slope allowed) and at most twice it (a flatter scarf is as
  // strong, only longer to machine): between slots metres long the two gaps are rarely exactly one
  // scarf length apart. The furthest end within one stock length from `start`, with the shortest
  // overlap there; nullopt when there is none.
  std::optional<Interval> furthestScarf(double start) const {
    std::optional<Interval> best;
    for (const auto& [aLo, aHi] : gaps) {
      for (const auto& [bLo, bHi] : gaps) {
        const double hi = std::min({aHi, bHi + longestScarf, start + stockLengthMm});
        const double lo = std::max({aLo, bLo + scarfLengthMm, start + scarfLengthMm + 1e-6});
        if (hi < lo) continue;
        const double begin = std::max(bLo, std::min(bHi, hi - scarfLengthMm));
        if (begin <= start || hi - begin > longestScarf + 1e-9 || hi - begin < scarfLengthMm - 1e-9)
          continue;
        if (!best || hi > best->first + 1e-9 ||
            (std::abs(hi - best->first) <= 1e-9 && begin > best->second))
          best = std::make_pair(hi, begin);
      }
    }
    return best;
  }
  // A scarf with clean ends is worth a shorter piece, down to 40 % of the stock length; below
  // that the pieces (and joints) would multiply, and the scarf through the slit is preferred.
  Interval cleanOrSlit(double start, const Interval& slit) const {
    const auto clean = furthestScarf(start);
    return clean && clean->first >= start + 0.4 * stockLengthMm ? *clean : slit;
  }
  void addScarf(double& start, const Interval& scarf) {
    const auto [end, begin] = scarf;
    plan.splicesMm.push_back((end + begin) / 2.0);
    plan.spliceClearancesMm.push_back(std::min(freeAt(end), freeAt(begin)));
    plan.spliceIsScarf.push_back(true);
    plan.segments.push_back({start, end});
    start = begin;
  }
  void addPlate(double& start, double cut) {
    plan.splicesMm.push_back(cut);
    plan.spliceClearancesMm.push_back(freeAt(cut));
    plan.spliceIsScarf.push_back(false);
    plan.segments.push_back({start, cut});
    start = cut;
  }
  // The middle of the widest gap between cut-outs (or a cut-out and the previous splice) in the
  // stock length from `start` to `reach`, the most room a shorter splice can get here; `cut` is
  // moved there, and its free length returned (-1 when there is no gap).
  double middleOfWidestGap(double start, double reach, double& cut) const {
    double best = -1.0;
    for (size_t k = 0; k <= merged.size(); ++k) {
      const double lo = std::max(start, k == 0 ? 0.0 : merged[k - 1].second);
      const double hi = k == merged.size() ? plan.lengthMm : merged[k].first;
      if (hi <= lo || lo >= reach) continue;
      const double x = std::min((lo + hi) / 2.0, reach);
      const double free = std::min(x - lo, hi - x);
      if (free > best + 1e-9 || (std::abs(free - best) <= 1e-9 && x > cut)) best = free, cut = x;
    }
    return best;
  }
  // No position between `start` and `reach` keeps the minimum clearance: says why, and how long
  // the pieces would have to be.
  [[noreturn]] void throwUnspliceable(double start, double reach, double clearanceMm,
                                      const std::string& field, double minClearanceMm) const {
    double widest = 0.0;
    for (size_t k = 0; k <= merged.size(); ++k) {
      const double lo = std::max(start, k == 0 ? 0.0 : merged[k - 1].second);
      const double hi = std::min(reach, k == merged.size() ? plan.lengthMm : merged[k].first);
      if (hi > lo) widest = std::max(widest, hi - lo);
    }
    // The stock it would take: a splice has to jump every zone of cut-outs grown by the minimum
    // clearance, so the longest such zone (from the strip's end where one reaches it).
    double needed = 0.0, zoneLo = 0.0, zoneHi = 0.0;
    bool open = false;
    for (const auto& [lo, hi] : merged) {
      const double a = std::max(0.0, lo - minClearanceMm),
                   b = std::min(plan.lengthMm, hi + minClearanceMm);
      if (open && a <= zoneHi) {
        zoneHi = std::max(zoneHi, b);
      } else {
        if (open) needed = std::max(needed, zoneHi - zoneLo);
        zoneLo = a, zoneHi = b, open = true;
      }
    }
    if (open) needed = std::max(needed, zoneHi - zoneLo);
    std::ostringstream msg;
    msg << field << ": lamella " << plan.id << " (" << plan.lengthMm
        << " mm) cannot be spliced between " << start << " and " << reach
        << " mm (one stock length): its holes and slots leave gaps of at most " << widest
        << " mm there, and a splice needs a gap of 2 x " << minClearanceMm
        << " mm (fabrication.min_splice_clearance_mm each side; " << clearanceMm
        << " mm preferred, fabrication.splice_clearance_mm); it would take pieces of up to "
        << std::ceil(needed) << " mm";
    msg << "; fabrication.splice_joint \"plate_or_scarf\" glues a scarf where no plate fits";
    throw InvalidInput(msg.str());
  }
};

}  // namespace

void placeSplices(LamellaPlan& plan, double stockLengthMm, double clearanceMm,
                  double boltDiameterMm, const std::string& field, double minClearanceMm,
                  SpliceJoint joint, double scarfLengthMm) {
  plan.splicesMm.clear();
  plan.spliceClearancesMm.clear();
  plan.spliceIsScarf.clear();
  plan.segments.clear();
  const bool plates = joint != SpliceJoint::Scarf, scarfs = joint != SpliceJoint::Plate;
  if (scarfs && !(scarfLengthMm > 0.0 && scarfLengthMm < stockLengthMm))
    throw InvalidInput("fabrication.scarf_slope: a scarf of " + std::to_string(scarfLengthMm) +
                       " mm does not fit a piece of at most " + std::to_string(stockLengthMm) +
                       " mm");
  if (minClearanceMm < 0.0) minClearanceMm = clearanceMm;
  Splicer splicer(plan, stockLengthMm, boltDiameterMm, scarfLengthMm);
  double start = 0.0;
  while (plan.lengthMm - start > stockLengthMm + 1e-9) {
    const double reach = start + stockLengthMm;
    // Slots that overlap into one slit for metres (notches longer than the connection spacing,
    // as on the Yas canopy's 60 m patches) leave no gap for a feather end either: the scarf then
    // ends where the stock does, its ends cutting through the slit (drawn clipped to each piece,
    // sheet_layout.cpp), and is checked on the net width.
    auto slitScarf = [&]() { return std::make_pair(reach, reach - scarfLengthMm); };
    if (!plates) {
      splicer.addScarf(start, splicer.cleanOrSlit(start, slitScarf()));
      continue;
    }
    // The furthest position within one stock length with the full clearance.
    double cut = splicer.furthest(start, clearanceMm);
    if (cut < 0.0) {
      // None: the middle of the widest gap between cut-outs (or a cut-out and the previous
      // splice) in this stock length, the most room a shorter splice can get here.
      const double best = splicer.middleOfWidestGap(start, reach, cut);
      // (The previous splice counts as a side of its gap; a position closer to it than the
      // minimum but clear of the cut-outs still beats none.)
      if (best < minClearanceMm - 1e-9) cut = splicer.furthest(start, minClearanceMm);
    }
    // No position keeps the minimum either: impossible (whichever earlier cuts: from any clear
    // position the next clear one lies within a stock length when the strip can be cut at all, so
    // this stretch fails for every choice).
    if (cut < 0.0 && scarfs) {
      // No room for a plate here: a glued scarf, where its feather ends find gaps.
      splicer.addScarf(start, splicer.cleanOrSlit(start, slitScarf()));
      continue;
    }
    if (cut < 0.0) splicer.throwUnspliceable(start, reach, clearanceMm, field, minClearanceMm);
    splicer.addPlate(start, cut);
  }
  plan.segments.push_back({start, plan.lengthMm});
}

int mergeSharedBoundaries(std::vector<LamellaPlan>& plans,
                          const std::vector<SharedBoundary>& shared, double toleranceMm) {
  auto find = [&](int patch, Family family, int index) -> std::ptrdiff_t {
    for (size_t i = 0; i < plans.size(); ++i) {
      if (plans[i].patchId == patch && plans[i].family == family && plans[i].index == index)
        return static_cast<std::ptrdiff_t>(i);
    }
    return -1;
  };
  int merged = 0;
  for (const auto& side : shared) {
    const std::string what = "fabrication: shared side " +
                             lamellaId(side.patchA, side.familyA, side.indexA) + " = " +
                             lamellaId(side.patchB, side.familyB, side.indexB);
    const std::ptrdiff_t ia = find(side.patchA, side.familyA, side.indexA),
                         ib = find(side.patchB, side.familyB, side.indexB);
    if (ia < 0 || ib < 0 || ia == ib) throw InvalidInput(what + ": no such pair of lamellas");
    LamellaPlan& a = plans[ia];
    const LamellaPlan& b = plans[ib];
    if (!a.boundary || !b.boundary) throw InvalidInput(what + ": both must be boundary members");
    const double innerA = a.lengthMm - 2.0 * a.overhangMm, innerB = b.lengthMm - 2.0 * b.overhangMm;
    if (std::abs(innerA - innerB) > toleranceMm) {
      std::ostringstream msg;
      msg << what << ": planar lengths differ (" << innerA << " and " << innerB << " mm)";
      throw InvalidInput(msg.str());
    }
    for (LamellaFeature f : b.features) {
      const double along = f.xMm - b.overhangMm;
      f.xMm = a.overhangMm + (side.reversed ? innerA - along : along);
      f.slideMm = side.reversed ? -f.slideMm : f.slideMm;
      LamellaFeature* same = nullptr;
      for (auto& g : a.features) {
        if (g.kind == FeatureKind::Hole && f.kind == FeatureKind::Hole &&
            std::abs(g.xMm - f.xMm) <= toleranceMm)
          same = &g;
      }
      if (same) {
        same->alsoConnections.emplace_back(f.patchId, f.connection);
        same->alsoConnections.insert(same->alsoConnections.end(), f.alsoConnections.begin(),
                                     f.alsoConnections.end());
        same->alsoConnectionIds.push_back(f.connectionId);
        same->alsoConnectionIds.insert(same->alsoConnectionIds.end(), f.alsoConnectionIds.begin(),
                                       f.alsoConnectionIds.end());
        ++merged;
      } else {
        a.features.push_back(f);
      }
    }
    std::sort(a.features.begin(), a.features.end(),
              [](const LamellaFeature& x, const LamellaFeature& y) { return x.xMm < y.xMm; });
    plans.erase(plans.begin() + ib);
  }
  return merged;
}

FeatureCounts countFeatures(const std::vector<LamellaPlan>& plans) {
  FeatureCounts counts;
  for (const auto& plan : plans) {
    for (const auto& f : plan.features) {
      if (f.kind == FeatureKind::Slot) {
        ++counts.slots;
      } else {
        ++counts.holes;
      }
      counts.demoted += f.demotedNotch ? 1 : 0;
      counts.droppedBoundary += f.droppedBoundaryNotch ? 1 : 0;
    }
  }
  return counts;
}

}  // namespace egg::fabrication
