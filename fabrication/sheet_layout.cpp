#include "fabrication/sheet_layout.hpp"

#include <algorithm>
#include <cmath>

namespace egg::fabrication {

double textLengthMm(const std::string& text, double heightMm) { return 0.6 * heightMm * static_cast<double>(text.size()); }

std::string segmentLabel(const LamellaPlan& plan, int segment) {
  if (plan.segments.size() <= 1) return plan.id;
  return plan.id + " " + std::to_string(segment + 1) + "/" + std::to_string(plan.segments.size());
}

namespace {

void drawArrow(Drawing& drawing, const Eigen::Vector2d& from, double length, double head) {
  const Eigen::Vector2d tip = from + Eigen::Vector2d(length, 0.0);
  const double back = length > 0 ? -head : head;
  drawing.polylines.push_back({Layer::Engrave, {from, tip}, false});
  drawing.polylines.push_back(
      {Layer::Engrave, {tip + Eigen::Vector2d(back, head / 2.0), tip, tip + Eigen::Vector2d(back, -head / 2.0)}, false});
}

}  // namespace

void drawLamellaSegment(const LamellaPlan& plan, int segment, const Eigen::Vector2d& origin,
                        const FabricationOptions& options, Drawing& drawing) {
  const LamellaSegment& seg = plan.segments[segment];
  const double w = plan.widthMm, L = seg.lengthMm();
  const double d = options.bolt_diameter_mm, r = d / 2.0;
  const double h = options.labelHeightMm(), hc = 0.7 * h;
  auto at = [&](double x, double y) { return Eigen::Vector2d(origin + Eigen::Vector2d(x - seg.startMm, y)); };
  drawing.polylines.push_back({Layer::Cut, {at(seg.startMm, 0), at(seg.endMm, 0), at(seg.endMm, w), at(seg.startMm, w)}, true});
  // Occupied stretches along the strip (features and their labels), for the lamella label.
  std::vector<std::pair<double, double>> occupied;
  for (const auto& f : plan.features) {
    if (f.xMm < seg.startMm || f.xMm > seg.endMm) continue;
    const Eigen::Vector2d centre = at(f.xMm, w / 2.0);
    if (f.kind == FeatureKind::Slot) {
      drawing.slots.push_back({Layer::Cut, centre, centre + Eigen::Vector2d(f.slideMm, 0.0), r});
      const double length = f.slideMm > 0 ? std::max(f.slideMm, 2.0 * h) : std::min(f.slideMm, -2.0 * h);
      drawArrow(drawing, at(f.xMm, (w / 2.0 - r) / 2.0), length, std::min(0.5 * h, (w / 2.0 - r) / 2.0));
    } else {
      drawing.circles.push_back({Layer::Cut, centre, r});
    }
    // After the feature, or before it where the label would run off the segment's end.
    const std::string text = f.label();
    const double labelLength = textLengthMm(text, hc);
    double labelStart = f.maxXMm(d) + 0.25 * h;
    if (labelStart + labelLength > seg.endMm) labelStart = f.minXMm(d) - 0.25 * h - labelLength;
    drawing.texts.push_back({Layer::Label, at(labelStart, w / 2.0), hc, text, TextAlign::Left});
    occupied.emplace_back(std::min(labelStart, f.minXMm(d)), std::max(labelStart + labelLength, f.maxXMm(d)));
  }
  for (size_t k = 0; k < plan.splicesMm.size(); ++k) {
    // The mark half the splice's clearance in from the cut (the clearance of the splice: a tight
    // one keeps less than splice_clearance_mm, placeSplices).
    const double splice = plan.splicesMm[k];
    const double clearance = k < plan.spliceClearancesMm.size() ? std::min(plan.spliceClearancesMm[k], options.spliceClearanceMm())
                                                                : options.spliceClearanceMm();
    const double x = splice == seg.startMm ? splice + clearance / 2.0 : splice == seg.endMm ? splice - clearance / 2.0 : -1;
    if (x < 0) continue;
    drawing.polylines.push_back({Layer::Engrave, {at(x, 0.0), at(x, w)}, false});
  }
  // The lamella label in the longest free stretch.
  std::sort(occupied.begin(), occupied.end());
  double bestLo = seg.startMm, bestHi = seg.startMm, cursor = seg.startMm;
  for (const auto& [lo, hi] : occupied) {
    if (lo - cursor > bestHi - bestLo) bestLo = cursor, bestHi = lo;
    cursor = std::max(cursor, hi);
  }
  if (seg.endMm - cursor > bestHi - bestLo) bestLo = cursor, bestHi = seg.endMm;
  drawing.texts.push_back({Layer::Label, at((bestLo + bestHi) / 2.0, w / 2.0), h, segmentLabel(plan, segment), TextAlign::Centre});
  (void)L;
}

void drawSticker(const Sticker& s, const Eigen::Vector2d& origin, const FabricationOptions& options, Drawing& drawing) {
  const double w = s.widthMm, L = s.lengthMm, r = options.bolt_diameter_mm / 2.0;
  auto at = [&](double x, double y) { return Eigen::Vector2d(origin + Eigen::Vector2d(x, y)); };
  drawing.polylines.push_back({Layer::Cut, {at(0, 0), at(L, 0), at(L, w), at(0, w)}, true});
  const Eigen::Vector2d bolt = at(s.boltXMm, w / 2.0);
  if (s.slideMm != 0.0) {
    drawing.slots.push_back({Layer::Cut, bolt, bolt + Eigen::Vector2d(s.slideMm, 0.0), r});
  } else {
    drawing.circles.push_back({Layer::Cut, bolt, r});
  }
  // Labels in the longer end beside the cut-out.
  const double lo = std::min(s.boltXMm, s.boltXMm + s.slideMm) - r, hi = std::max(s.boltXMm, s.boltXMm + s.slideMm) + r;
  const double x = lo > L - hi ? lo / 2.0 : (hi + L) / 2.0;
  const double h = std::min(options.labelHeightMm(), 0.3 * w);
  drawing.texts.push_back({Layer::Label, at(x, 0.7 * w), h, s.connectionId, TextAlign::Centre});
  drawing.texts.push_back({Layer::Label, at(x, 0.3 * w), h, s.lamellaId, TextAlign::Centre});
}

}  // namespace egg::fabrication
