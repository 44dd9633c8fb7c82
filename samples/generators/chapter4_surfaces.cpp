// Desktop-size free-form patches of the kinds in Table 4.1 (Chapter 4, generalised geodesic grids):
// topological disks over smooth free-form footprints, about 0.6 m wide. The thesis's own shapes
// are not published, so these are analogues with the table's extents: a dome over a non-convex
// (kidney) footprint like Moon (Fig. 4.21), a saddle, a gently domed surface with inner bumps like
// Hills, and an elongated dome like Starship. Each is a height field meshed in its footprint.
#include "samples/generators/catalog.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

namespace egg::samples::detail {
namespace {

constexpr double kCh4Pi = std::numbers::pi;
// Dense sampling of a footprint for its extents: the boundary mesh vertices are sampled at the
// edge length, so the mesh's box is within a sagitta (~1e-5 m at 0.012 m edges) of this one.
constexpr int kCh4Samples = 4096;

// Footprint: a smooth closed unit-scale curve c(t), t in [0, 2 pi), counter-clockwise, mapped
// affinely onto the box [-length/2, length/2] x [-width/2, width/2]. An axis-aligned scaling keeps
// convex stretches convex and reflex ones reflex, so a shape designed at unit scale keeps its bay.
struct Ch4Footprint {
  std::function<Vec2(double)> curve;
  Vec2 scale = Vec2::Ones();
  Vec2 offset = Vec2::Zero();  // domain = scale .* unit + offset
  // Dense polygon of the domain curve for the inside test, its edges binned by y: with
  // kCh4Samples vertices it is within ~1e-8 m of the curve (chord sagitta), far below any
  // triangle, so it decides "inside the true footprint" for the remesher's moves.
  std::shared_ptr<const std::vector<Vec2>> polygon;
  std::shared_ptr<const std::vector<std::vector<int>>> bands;
  double yMin = 0.0, bandHeight = 1.0;

  Vec2 at(double t) const { return scale.cwiseProduct(curve(t)) + offset; }

  bool contains(const Vec2& u) const {
    const int band = int(std::floor((u.y() - yMin) / bandHeight));
    if (band < 0 || band >= int(bands->size())) return false;
    bool inside = false;
    const auto& p = *polygon;
    for (int a : (*bands)[band]) {
      const Vec2& q = p[a];
      const Vec2& r = p[(a + 1) % p.size()];
      if ((q.y() > u.y()) != (r.y() > u.y()) &&
          u.x() < q.x() + (u.y() - q.y()) * (r.x() - q.x()) / (r.y() - q.y()))
        inside = !inside;
    }
    return inside;
  }
};

Eigen::AlignedBox2d ch4UnitBox(const std::function<Vec2(double)>& curve) {
  Eigen::AlignedBox2d box;
  for (int i = 0; i < kCh4Samples; ++i) box.extend(curve(2 * kCh4Pi * i / kCh4Samples));
  return box;
}

Ch4Footprint ch4Fit(std::function<Vec2(double)> curve, double length, double width) {
  Ch4Footprint footprint;
  const Eigen::AlignedBox2d box = ch4UnitBox(curve);
  footprint.curve = std::move(curve);
  footprint.scale = Vec2(length, width).cwiseQuotient(box.sizes());
  footprint.offset = -footprint.scale.cwiseProduct(box.center());
  auto polygon = std::make_shared<std::vector<Vec2>>();
  for (int i = 0; i < kCh4Samples; ++i)
    polygon->push_back(footprint.at(2 * kCh4Pi * i / kCh4Samples));
  constexpr int kBands = 64;
  footprint.yMin = -width / 2 * (1 + 1e-9);
  footprint.bandHeight = width * (1 + 2e-9) / kBands;
  auto bands = std::make_shared<std::vector<std::vector<int>>>(kBands);
  for (int a = 0; a < kCh4Samples; ++a) {
    const double y0 = (*polygon)[a].y(), y1 = (*polygon)[(a + 1) % kCh4Samples].y();
    const int first =
        std::max(0, int(std::floor((std::min(y0, y1) - footprint.yMin) / footprint.bandHeight)));
    const int last = std::min(
        kBands - 1, int(std::floor((std::max(y0, y1) - footprint.yMin) / footprint.bandHeight)));
    for (int b = first; b <= last; ++b) (*bands)[b].push_back(a);
  }
  footprint.polygon = std::move(polygon);
  footprint.bands = std::move(bands);
  return footprint;
}

// Largest value of `f` on the footprint's boundary (a convex f takes its maximum there).
double ch4BoundaryMax(const Ch4Footprint& footprint, const std::function<double(const Vec2&)>& f) {
  double best = -std::numeric_limits<double>::infinity();
  for (const Vec2& u : *footprint.polygon) best = std::max(best, f(u));
  return best;
}

// Unit curve of a star-shaped outline r(t) about the origin.
std::function<Vec2(double)> ch4Polar(std::function<double(double)> radius) {
  return [radius = std::move(radius)](double t) {
    return Vec2(radius(t) * std::cos(t), radius(t) * std::sin(t));
  };
}

// Height field z(x, y) over the footprint, one smooth closed boundary curve counter-clockwise.
SurfaceSpec ch4HeightField(const std::string& name, const Ch4Footprint& footprint,
                           std::function<double(const Vec2&)> height) {
  SurfaceSpec spec;
  spec.name = name;
  spec.position = [height = std::move(height)](const Vec2& u) {
    return Vec3(u.x(), u.y(), height(u));
  };
  spec.boundary = {{{[footprint](double s) { return footprint.at(2 * kCh4Pi * s); }}}};
  spec.inDomain = [footprint](const Vec2& u) { return footprint.contains(u); };
  return spec;
}

// Elliptic paraboloid with its apex at `apex`, scaled so z runs from 0 (the lowest boundary
// point) to `height` (the apex): positive Gaussian curvature everywhere.
std::function<double(const Vec2&)> ch4Dome(const Ch4Footprint& footprint, const Vec2& apex,
                                           const Vec2& semiAxes, double height) {
  auto q = [apex, semiAxes](const Vec2& u) {
    return (u - apex).cwiseQuotient(semiAxes).squaredNorm();
  };
  const double qMax = ch4BoundaryMax(footprint, q);
  return [q, qMax, height](const Vec2& u) { return height * (1.0 - q(u) / qMax); };
}

void ch4RequireBox(const std::string& sample, const Params& p) {
  for (const char* key : {"length", "width", "height"})
    require(p.at(key) > 0, sample, key, p.at(key), "must be positive");
}

// Moon: a kidney footprint, the unit circle with its +x side pushed in by a Gaussian in y,
// x(t) = cos t - D exp(-sin^2 t / (2 w^2)) ((1 + cos t) / 2)^2, y(t) = sin t. Near the bay's
// bottom x ~ (1 - D) + (D / w^2 - 1) y^2 / 2: reflex once D > w^2, with a curvature radius of
// w^2 / (D - w^2) (unit scale), so the bay stays round. The push D is solved so the bay is `bay`
// metres deep in x, from the horns' tips (the box's +x side) to the bay's bottom.
SurfaceSpec ch4Moon(const Params& p) {
  ch4RequireBox("ch4_moon", p);
  const double length = p.at("length"), width = p.at("width"), bay = p.at("bay");
  require(bay >= 0 && bay <= 0.2 * length, "ch4_moon", "bay", bay, "must be in [0, 0.2 length]");
  constexpr double kBayWidth = 0.4;  // w: bay half-width at unit scale (the footprint's is 1)
  auto shape = [](double push) {
    return [push](double t) {
      const double s = std::sin(t), c = std::cos(t);
      const double side = 0.25 * (1 + c) * (1 + c);  // 1 at +x, 0 at -x: the -x side stays round
      return Vec2(c - push * std::exp(-s * s / (2 * kBayWidth * kBayWidth)) * side, s);
    };
  };
  // Bay depth over length grows with the push (0 until the bottom turns reflex, then steadily;
  // 0.2 is reached near D = 0.75); bisection on [0, 0.95].
  auto depthRatio = [&shape](double push) {
    const Eigen::AlignedBox2d box = ch4UnitBox(shape(push));
    return (box.max().x() - (1.0 - push)) / box.sizes().x();
  };
  double low = 0.0, high = 0.95;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (low + high);
    (depthRatio(mid) < bay / length ? low : high) = mid;
  }
  const Ch4Footprint footprint = ch4Fit(shape(0.5 * (low + high)), length, width);
  // Apex over the centre of the footprint's round -x half: inside for every accepted bay.
  const Vec2 apex(-length / 2 + 0.45 * length, 0.0);
  return ch4HeightField("ch4_moon", footprint,
                        ch4Dome(footprint, apex, Vec2(length, width) / 2, p.at("height")));
}

// Saddle z = (height / 2) (x^2 / a^2 - y^2 / b^2) over the ellipse of semi-axes (a, b): negative
// Gaussian curvature everywhere, z from -height / 2 (at (0, +-b)) to height / 2 (at (+-a, 0)).
SurfaceSpec ch4Saddle(const Params& p) {
  ch4RequireBox("ch4_saddle", p);
  const double a = p.at("length") / 2, b = p.at("width") / 2, height = p.at("height");
  const Ch4Footprint footprint = ch4Fit([](double t) { return Vec2(std::cos(t), std::sin(t)); },
                                        p.at("length"), p.at("width"));
  return ch4HeightField("ch4_saddle", footprint, [a, b, height](const Vec2& u) {
    return height / 2 * (u.x() * u.x() / (a * a) - u.y() * u.y() / (b * b));
  });
}

// Hills: a gentle dome with three Gaussian bumps (positive K on their tops, negative K on their
// flanks, where they meet the dome) over a smooth convex free-form footprint (a circle with small
// third and second harmonics). The height field is scaled to span exactly `height`.
SurfaceSpec ch4Hills(const Params& p) {
  ch4RequireBox("ch4_hills", p);
  const double length = p.at("length"), width = p.at("width"), height = p.at("height");
  // Harmonics small enough that r^2 + 2 r'^2 - r r'' > 0: the outline stays convex.
  const Ch4Footprint footprint =
      ch4Fit(ch4Polar([](double t) {
               return 1.0 + 0.05 * std::cos(3 * t + 0.4) + 0.03 * std::sin(2 * t);
             }),
             length, width);
  const Vec2 half(length / 2, width / 2);
  auto dome = ch4Dome(footprint, Vec2::Zero(), half, 1.0);
  // Bumps at fixed fractions of the half-extents, about a fifth of the length across.
  const std::array<Vec2, 3> centres{half.cwiseProduct(Vec2(-0.45, -0.3)),
                                    half.cwiseProduct(Vec2(0.4, -0.35)),
                                    half.cwiseProduct(Vec2(0.05, 0.45))};
  const std::array<double, 3> amplitudes{1.0, 0.8, 0.9};
  const double sigma = 0.09 * length;
  auto raw = [dome, centres, amplitudes, sigma](const Vec2& u) {
    double z = 0.5 * dome(u);
    for (int i = 0; i < 3; ++i)
      z += amplitudes[i] * std::exp(-(u - centres[i]).squaredNorm() / (2 * sigma * sigma));
    return z;
  };
  // Range over the footprint: the minimum is on the boundary, the bump tops are interior maxima
  // flat enough that a 200 x 200 grid finds them to ~1e-4 of the range.
  const double zMin = -ch4BoundaryMax(footprint, [&raw](const Vec2& u) { return -raw(u); });
  double zMax = -std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 200; ++i) {
    for (int j = 0; j <= 200; ++j) {
      const Vec2 u(-half.x() + length * i / 200.0, -half.y() + width * j / 200.0);
      if (footprint.contains(u)) zMax = std::max(zMax, raw(u));
    }
  }
  return ch4HeightField("ch4_hills", footprint, [raw, zMin, zMax, height](const Vec2& u) {
    return height * (raw(u) - zMin) / (zMax - zMin);
  });
}

// Starship: an elongated dome over a smooth convex egg-shaped outline, r = 1 - 0.2 cos t +
// 0.15 cos 2t (r^2 + 2 r'^2 - r r'' > 0 throughout), blunt at -x and narrowing to a rounded nose
// at +x; the apex sits towards the blunt end.
SurfaceSpec ch4Starship(const Params& p) {
  ch4RequireBox("ch4_starship", p);
  const double length = p.at("length"), width = p.at("width");
  const Ch4Footprint footprint =
      ch4Fit(ch4Polar([](double t) { return 1.0 - 0.2 * std::cos(t) + 0.15 * std::cos(2 * t); }),
             length, width);
  const Vec2 apex(-0.1 * length, 0.0);
  return ch4HeightField("ch4_starship", footprint,
                        ch4Dome(footprint, apex, Vec2(length, width) / 2, p.at("height")));
}

}  // namespace

std::vector<SampleEntry> chapter4Samples() {
  auto box = [](double length, double width, double height) {
    return Params{{"length", length}, {"width", width}, {"height", height}};
  };
  const std::map<std::string, std::string> boxHelp{{"length", "footprint extent along x (m)"},
                                                   {"width", "footprint extent along y (m)"},
                                                   {"height", "extent along z (m)"}};
  Params moon = box(0.542, 0.6, 0.106);
  moon["bay"] = 0.08;
  auto moonHelp = boxHelp;
  moonHelp["bay"] = "depth of the bay in x from the horns' tips (m), in [0, 0.2 length]";
  return {
      {{"ch4_moon",
        "Chapter 4 Moon analogue: elliptic-paraboloid dome over a kidney footprint with one smooth "
        "bay on its +x side (non-convex boundary), length x width x height",
        moon, moonHelp},
       ch4Moon},
      {{"ch4_saddle",
        "Chapter 4 saddle: z = (height/2)(x^2/a^2 - y^2/b^2) over the ellipse of axes length x "
        "width (negative Gaussian curvature)",
        box(0.6, 0.45, 0.07), boxHelp},
       ch4Saddle},
      {{"ch4_hills",
        "Chapter 4 Hills analogue: gentle dome with three inner bumps (mixed curvature) over a "
        "smooth convex free-form footprint, length x width x height",
        box(0.6, 0.475, 0.059), boxHelp},
       ch4Hills},
      {{"ch4_starship",
        "Chapter 4 Starship analogue: elongated dome over a smooth egg-shaped outline narrowing "
        "towards +x, length x width x height",
        box(0.6, 0.404, 0.068), boxHelp},
       ch4Starship},
  };
}

}  // namespace egg::samples::detail
