#include "fabrication/sheet_layout.hpp"

#include "fabrication/stroke_text.hpp"

#include <algorithm>
#include <cmath>

namespace egg::fabrication {

double textLengthMm(const std::string& text, double heightMm) {
  return strokeTextWidthMm(text, heightMm);
}

void drawSheetFrame(const std::string& id, const std::string& note, double marginMm,
                    Drawing& drawing) {
  const double w = drawing.widthMm, h = drawing.heightMm;
  drawing.polylines.push_back({Layer::Reference, {{0.0, 0.0}, {w, 0.0}, {w, h}, {0.0, h}}, true});
  const double height = std::clamp(0.6 * marginMm, 2.0, 30.0);
  const double y = marginMm >= height ? marginMm / 2.0 : height;
  drawing.texts.push_back({Layer::Reference,
                           {std::max(marginMm, height), y},
                           height,
                           id + "  " + note,
                           TextAlign::Left});
}

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
      {Layer::Engrave,
       {tip + Eigen::Vector2d(back, head / 2.0), tip, tip + Eigen::Vector2d(back, -head / 2.0)},
       false});
}

// A router bit's centre path around a part's rectangular outline (lower left `a`, upper right
// `b`): the outline offset outwards by the bit's radius, quarter circles round the corners (every
// corner of a part is convex, so no dog-bone or relief is ever needed).
void addOutlineToolpath(Drawing& drawing, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        double radius) {
  std::vector<Eigen::Vector2d> path;
  const Eigen::Vector2d corners[4] = {{b.x(), a.y()}, b, {a.x(), b.y()}, a};
  const int steps = 8;
  for (int c = 0; c < 4; ++c) {
    // Corner c's arc from the outward normal of the edge before it to that of the edge after.
    const double from = -M_PI / 2.0 + c * M_PI / 2.0;
    for (int k = 0; k <= steps; ++k) {
      const double phi = from + (M_PI / 2.0) * k / steps;
      path.push_back(corners[c] + radius * Eigen::Vector2d(std::cos(phi), std::sin(phi)));
    }
  }
  drawing.polylines.push_back({Layer::Toolpath, path, true});
}

}  // namespace

std::vector<Eigen::Vector2d> clippedStadium(double x0, double x1, double radius, double lo,
                                            double hi) {
  // The stadium's outline (convex: two half circles joined by straight sides), 32 segments per
  // half circle, then clipped to lo <= x <= hi (Sutherland-Hodgman against the two lines).
  const double a = std::min(x0, x1), b = std::max(x0, x1);
  std::vector<Eigen::Vector2d> poly;
  const int steps = 32;
  for (int k = 0; k <= steps; ++k) {
    const double phi = -M_PI / 2.0 + M_PI * k / steps;
    poly.emplace_back(b + radius * std::cos(phi), radius * std::sin(phi));
  }
  for (int k = 0; k <= steps; ++k) {
    const double phi = M_PI / 2.0 + M_PI * k / steps;
    poly.emplace_back(a + radius * std::cos(phi), radius * std::sin(phi));
  }
  auto clip = [](const std::vector<Eigen::Vector2d>& in, double bound, bool keepAbove) {
    std::vector<Eigen::Vector2d> out;
    const size_t n = in.size();
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d &p = in[i], &q = in[(i + 1) % n];
      const bool pIn = keepAbove ? p.x() >= bound : p.x() <= bound,
                 qIn = keepAbove ? q.x() >= bound : q.x() <= bound;
      if (pIn) out.push_back(p);
      if (pIn != qIn) {
        const double t = (bound - p.x()) / (q.x() - p.x());
        out.emplace_back(bound, p.y() + t * (q.y() - p.y()));
      }
    }
    return out;
  };
  poly = clip(poly, lo, true);
  if (!poly.empty()) poly = clip(poly, hi, false);
  return poly;
}

void drawLamellaSegment(const LamellaPlan& plan, int segment, const Eigen::Vector2d& origin,
                        const FabricationOptions& options, Drawing& drawing) {
  const LamellaSegment& seg = plan.segments[segment];
  const double w = plan.widthMm, L = seg.lengthMm();
  const double d = options.boltDiameterMm, r = d / 2.0;
  const double h = options.effectiveLabelHeightMm(), hc = 0.7 * h;
  auto at = [&](double x, double y) {
    return Eigen::Vector2d(origin + Eigen::Vector2d(x - seg.startMm, y));
  };
  drawing.polylines.push_back(
      {Layer::Cut,
       {at(seg.startMm, 0), at(seg.endMm, 0), at(seg.endMm, w), at(seg.startMm, w)},
       true});
  // A router's bit (FabricationOptions::toolDiameterMm, smaller than the holes): its centre path
  // outside the outline, inside every hole and slot.
  const double rt = options.toolDiameterMm.value_or(0.0) / 2.0;
  if (rt > 0.0) addOutlineToolpath(drawing, at(seg.startMm, 0), at(seg.endMm, w), rt);
  // Occupied stretches along the strip (features and their labels), for the lamella label.
  std::vector<std::pair<double, double>> occupied;
  for (const auto& f : plan.features) {
    // A plate keeps clear of every feature, and a scarf's feather ends lie between them where they
    // can; inside a scarf's overlap a feature is cut in both pieces. A scarf through a slit cuts
    // the slots it crosses: each piece gets the part of the slot inside it.
    if (f.maxXMm(d) <= seg.startMm + 1e-6 || f.minXMm(d) >= seg.endMm - 1e-6) continue;
    if (f.minXMm(d) < seg.startMm - 1e-6 || f.maxXMm(d) > seg.endMm + 1e-6) {
      std::vector<Eigen::Vector2d> outline;
      for (const auto& p : clippedStadium(f.xMm, f.xMm + f.slideMm, r, seg.startMm, seg.endMm))
        outline.push_back(at(p.x(), w / 2.0 + p.y()));
      if (outline.size() >= 3) drawing.polylines.push_back({Layer::Cut, outline, true});
      if (rt > 0.0) {
        // The cut-out runs through the piece's end, where the outline's cut is: the bit's centre
        // stays r - rt off the slot's axis and may run to the end itself.
        std::vector<Eigen::Vector2d> path;
        for (const auto& p :
             clippedStadium(f.xMm, f.xMm + f.slideMm, r - rt, seg.startMm, seg.endMm))
          path.push_back(at(p.x(), w / 2.0 + p.y()));
        if (path.size() >= 3) drawing.polylines.push_back({Layer::Toolpath, path, true});
      }
      continue;
    }
    const Eigen::Vector2d centre = at(f.xMm, w / 2.0);
    if (f.kind == FeatureKind::Slot) {
      drawing.slots.push_back({Layer::Cut, centre, centre + Eigen::Vector2d(f.slideMm, 0.0), r});
      if (rt > 0.0) {
        drawing.slots.push_back(
            {Layer::Toolpath, centre, centre + Eigen::Vector2d(f.slideMm, 0.0), r - rt});
      }
      const double length =
          f.slideMm > 0 ? std::max(f.slideMm, 2.0 * h) : std::min(f.slideMm, -2.0 * h);
      drawArrow(drawing, at(f.xMm, (w / 2.0 - r) / 2.0), length,
                std::min(0.5 * h, (w / 2.0 - r) / 2.0));
    } else {
      drawing.circles.push_back({Layer::Cut, centre, r});
      if (rt > 0.0) drawing.circles.push_back({Layer::Toolpath, centre, r - rt});
    }
    // After the feature, or before it where the label would run off the segment's end.
    const std::string text = f.label();
    const double labelLength = textLengthMm(text, hc);
    double labelStart = f.maxXMm(d) + 0.25 * h;
    if (labelStart + labelLength > seg.endMm) labelStart = f.minXMm(d) - 0.25 * h - labelLength;
    drawing.texts.push_back({Layer::Label, at(labelStart, w / 2.0), hc, text, TextAlign::Left});
    occupied.emplace_back(std::min(labelStart, f.minXMm(d)),
                          std::max(labelStart + labelLength, f.maxXMm(d)));
  }
  for (size_t k = 0; k < plan.splicesMm.size(); ++k) {
    if (k < plan.spliceIsScarf.size() && plan.spliceIsScarf[k]) {
      // A scarf: the line where the slope starts, the other piece's feather end.
      const double begin = plan.segments[k + 1].startMm, end = plan.segments[k].endMm;
      const double x = segment == static_cast<int>(k)       ? begin
                       : segment == static_cast<int>(k) + 1 ? end
                                                            : -1.0;
      if (x >= 0.0) drawing.polylines.push_back({Layer::Engrave, {at(x, 0.0), at(x, w)}, false});
      continue;
    }
    // The mark half the splice's clearance in from the cut (the clearance of the splice: a tight
    // one keeps less than splice_clearance_mm, placeSplices).
    const double splice = plan.splicesMm[k];
    const double clearance =
        k < plan.spliceClearancesMm.size()
            ? std::min(plan.spliceClearancesMm[k], options.effectiveSpliceClearanceMm())
            : options.effectiveSpliceClearanceMm();
    const double x = splice == seg.startMm ? splice + clearance / 2.0
                     : splice == seg.endMm ? splice - clearance / 2.0
                                           : -1;
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
  drawing.texts.push_back({Layer::Label, at((bestLo + bestHi) / 2.0, w / 2.0), h,
                           segmentLabel(plan, segment), TextAlign::Centre});
  (void)L;
}

void drawSticker(const Sticker& s, const Eigen::Vector2d& origin, const FabricationOptions& options,
                 Drawing& drawing) {
  const double w = s.widthMm, L = s.lengthMm, r = options.boltDiameterMm / 2.0;
  auto at = [&](double x, double y) { return Eigen::Vector2d(origin + Eigen::Vector2d(x, y)); };
  drawing.polylines.push_back({Layer::Cut, {at(0, 0), at(L, 0), at(L, w), at(0, w)}, true});
  const Eigen::Vector2d bolt = at(s.boltXMm, w / 2.0);
  const double rt = options.toolDiameterMm.value_or(0.0) / 2.0;
  if (s.slideMm != 0.0) {
    drawing.slots.push_back({Layer::Cut, bolt, bolt + Eigen::Vector2d(s.slideMm, 0.0), r});
    if (rt > 0.0)
      drawing.slots.push_back(
          {Layer::Toolpath, bolt, bolt + Eigen::Vector2d(s.slideMm, 0.0), r - rt});
  } else {
    drawing.circles.push_back({Layer::Cut, bolt, r});
    if (rt > 0.0) drawing.circles.push_back({Layer::Toolpath, bolt, r - rt});
  }
  if (rt > 0.0) addOutlineToolpath(drawing, at(0, 0), at(L, w), rt);
  // Labels in the longer end beside the cut-out.
  const double lo = std::min(s.boltXMm, s.boltXMm + s.slideMm) - r,
               hi = std::max(s.boltXMm, s.boltXMm + s.slideMm) + r;
  const double x = lo > L - hi ? lo / 2.0 : (hi + L) / 2.0;
  const double h = std::min(options.effectiveLabelHeightMm(), 0.3 * w);
  drawing.texts.push_back({Layer::Label, at(x, 0.7 * w), h, s.connectionId, TextAlign::Centre});
  drawing.texts.push_back({Layer::Label, at(x, 0.3 * w), h, s.lamellaId, TextAlign::Centre});
}

}  // namespace egg::fabrication
