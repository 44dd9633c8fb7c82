#include "fabrication/stickers.hpp"

#include <algorithm>
#include <cmath>

namespace egg::fabrication {

double contactHalfLengthMm(double widthMm, double angleRad) {
  const double s =
      std::max(std::sin(angleRad), 1e-3);  // nearly parallel lamellas: capped, stays finite
  return widthMm * (1.0 + std::abs(std::cos(angleRad))) / (2.0 * s);
}

double crossingAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

namespace {

// Unit tangent of a polyline at arc length s.
Eigen::Vector3d tangentAt(const std::vector<Eigen::Vector3d>& polyline, double s) {
  double walked = 0.0;
  for (size_t i = 0; i + 1 < polyline.size(); ++i) {
    const Eigen::Vector3d seg = polyline[i + 1] - polyline[i];
    const double len = seg.norm();
    if (len > 0.0 && (walked + len >= s || i + 2 == polyline.size())) return seg / len;
    walked += len;
  }
  return Eigen::Vector3d::UnitX();
}

// The holes and slots of one connection, on whichever lamellas carry them (a shared boundary
// lamella holds the other patch's connections too): two for a connection of two lamellas.
std::vector<std::pair<const LamellaPlan*, const LamellaFeature*>> featuresOf(
    const std::vector<LamellaPlan>& plans, int patchId, int connection) {
  std::vector<std::pair<const LamellaPlan*, const LamellaFeature*>> found;
  for (const auto& p : plans) {
    for (const auto& f : p.features) {
      if (f.holds(patchId, connection)) found.emplace_back(&p, &f);
    }
  }
  return found;
}

}  // namespace

std::vector<Sticker> planStickers(const FabricationPatch& patch,
                                  const std::vector<LamellaPlan>& plans,
                                  const FabricationOptions& options) {
  std::vector<Sticker> stickers;
  const EggGrid& grid = *patch.grid;
  for (int k = 0; k < static_cast<int>(grid.connections.size()); ++k) {
    const GridConnection& c = grid.connections[k];
    const GridMember& mu = grid.u[c.memberU];
    const GridMember& mv = grid.v[c.memberV];
    const auto features = featuresOf(plans, patch.patchId, k);
    if (features.size() != 2) continue;
    if (features[0].second->kind != FeatureKind::Slot &&
        features[1].second->kind != FeatureKind::Slot)
      continue;
    const Eigen::Vector2d du = mu.planarEnd - mu.planarStart, dv = mv.planarEnd - mv.planarStart;
    const double planar = crossingAngle({du.x(), du.y(), 0.0}, {dv.x(), dv.y(), 0.0});
    const double deployed = crossingAngle(tangentAt(mu.spatial, c.sU), tangentAt(mv.spatial, c.sV));
    const double w = options.lamellaWidthMm;
    // The other lamella's footprint is widest at the angle furthest from a right angle.
    const double half = std::max(contactHalfLengthMm(w, planar), contactHalfLengthMm(w, deployed));
    for (const auto& [planPointer, f] : features) {
      const LamellaPlan& plan = *planPointer;
      Sticker s;
      s.connectionId = f->connectionId;
      s.lamellaId = plan.id;
      s.id = s.connectionId + "/" + s.lamellaId;
      s.widthMm = w;
      s.slideMm = f->kind == FeatureKind::Slot ? f->slideMm : 0.0;
      // The contact centre runs with the bolt from x to x + slide; the footprint reaches `half`
      // either side, the margin beyond that. At small crossing angles (a compact planar layout)
      // the footprint is long: it stops halfway to the neighbouring connections (their stickers
      // cover the rest) and at the strip's ends, but always covers the slot and a bolt radius.
      double lo = std::min(0.0, s.slideMm) - half - options.stickerMarginMm;
      double hi = std::max(0.0, s.slideMm) + half + options.stickerMarginMm;
      double limitLo = -f->xMm, limitHi = plan.lengthMm - f->xMm;
      for (const auto& other : plan.features) {
        if (&other == f) continue;
        const double gap = other.xMm - f->xMm;
        if (gap > 0) limitHi = std::min(limitHi, gap / 2.0);
        if (gap < 0) limitLo = std::max(limitLo, gap / 2.0);
      }
      const double r = options.boltDiameterMm / 2.0;
      limitLo = std::min(limitLo, std::min(0.0, s.slideMm) - 2.0 * r);
      limitHi = std::max(limitHi, std::max(0.0, s.slideMm) + 2.0 * r);
      s.clipped = lo < limitLo || hi > limitHi;
      lo = std::max(lo, limitLo);
      hi = std::min(hi, limitHi);
      s.lengthMm = hi - lo;
      s.boltXMm = -lo;
      s.planarAngleRad = planar;
      s.deployedAngleRad = deployed;
      stickers.push_back(s);
    }
  }
  return stickers;
}

}  // namespace egg::fabrication
