// Parametric test surfaces whose geodesics and curvatures are known in closed form
// (docs/architecture.md "Validation references"): other stages use them as oracles, so each map is
// exact and each developable surface is meshed in its unrolled (isometric) domain.
#include "samples/generators/catalog.hpp"

#include <cmath>
#include <map>
#include <numbers>

namespace egg::samples::detail {
namespace {

constexpr double kPi = std::numbers::pi;

// Footprint extents shared by the height fields.
void requireExtent(const std::string& sample, const Params& p) {
  require(p.at("length") > 0, sample, "length", p.at("length"), "must be positive");
  require(p.at("width") > 0, sample, "width", p.at("width"), "must be positive");
}

SurfaceSpec heightField(const std::string& name, const Params& p,
                        std::function<double(double, double)> height) {
  requireExtent(name, p);
  SurfaceSpec spec;
  spec.name = name;
  spec.position = [height = std::move(height)](const Vec2& u) {
    return Vec3(u.x(), u.y(), height(u.x(), u.y()));
  };
  const double hx = p.at("length") / 2, hy = p.at("width") / 2;
  spec.boundary = {rectangleLoop(-hx, hx, -hy, hy)};
  return spec;
}

SurfaceSpec plane(const Params& p) {
  return heightField("plane", p, [](double, double) { return 0.0; });
}

SurfaceSpec hypar(const Params& p) {
  const double c = p.at("c");
  return heightField("hypar", p, [c](double x, double y) { return c * x * y; });
}

SurfaceSpec bump(const Params& p) {
  const double height = p.at("height"), sigma = p.at("sigma");
  require(sigma > 0, "bump", "sigma", sigma, "must be positive");
  return heightField("bump", p, [height, sigma](double x, double y) {
    return height * std::exp(-(x * x + y * y) / (2 * sigma * sigma));
  });
}

SurfaceSpec waves(const Params& p) {
  const double amplitude = p.at("amplitude"), wavelength = p.at("wavelength");
  require(wavelength > 0, "waves", "wavelength", wavelength, "must be positive");
  const double k = 2 * kPi / wavelength;
  return heightField("waves", p, [amplitude, k](double x, double y) {
    return amplitude * std::sin(k * x) * std::sin(k * y);
  });
}

// Sphere cap around the north pole, centre at the origin. Domain: azimuthal equidistant disc
// (R psi cos theta, R psi sin theta), psi the polar angle, so the map is smooth at the pole and
// near-isometric; extent = radius gives the hemisphere.
SurfaceSpec sphere(const Params& p) {
  const double radius = p.at("radius"), extent = p.at("extent");
  require(radius > 0, "sphere", "radius", radius, "must be positive");
  require(extent > 0 && extent <= radius, "sphere", "extent", extent, "must be in (0, radius]");
  const double rim = radius * std::asin(extent / radius);
  SurfaceSpec spec;
  spec.name = "sphere";
  spec.position = [radius](const Vec2& u) {
    const double psi = u.norm() / radius;
    const double theta = psi > 0 ? std::atan2(u.y(), u.x()) : 0.0;
    return Vec3(radius * std::sin(psi) * std::cos(theta), radius * std::sin(psi) * std::sin(theta),
                radius * std::cos(psi));
  };
  spec.boundary = {ellipseLoop(Vec2::Zero(), rim, rim)};
  spec.inDomain = [rim](const Vec2& u) { return u.norm() <= rim; };
  return spec;
}

// Cylinder vault: axis along x through the origin, the arc `angle` centred on the top. Domain:
// the unrolled rectangle (x, arc length), an isometry.
SurfaceSpec cylinder(const Params& p) {
  const double radius = p.at("radius"), length = p.at("length"), angle = p.at("angle");
  require(radius > 0, "cylinder", "radius", radius, "must be positive");
  require(length > 0, "cylinder", "length", length, "must be positive");
  require(angle > 0 && angle < 2 * kPi, "cylinder", "angle", angle, "must be in (0, 2 pi)");
  SurfaceSpec spec;
  spec.name = "cylinder";
  spec.position = [radius](const Vec2& u) {
    return Vec3(u.x(), radius * std::sin(u.y() / radius), radius * std::cos(u.y() / radius));
  };
  const double halfArc = radius * angle / 2;
  spec.boundary = {rectangleLoop(-length / 2, length / 2, -halfArc, halfArc)};
  return spec;
}

// Cone (frustum) with axis z, base circle `radius` at z = 0, apex at (0, 0, height); the part
// between the base and the circle of `top_radius` (0 keeps the apex), over the arc `angle`
// centred on +x. Domain: the unrolled annular sector, an isometry.
SurfaceSpec cone(const Params& p) {
  const double radius = p.at("radius"), height = p.at("height"), top = p.at("top_radius"),
               angle = p.at("angle");
  require(radius > 0, "cone", "radius", radius, "must be positive");
  require(height > 0, "cone", "height", height, "must be positive");
  require(top >= 0 && top < radius, "cone", "top_radius", top, "must be in [0, radius)");
  require(angle > 0 && angle < 2 * kPi, "cone", "angle", angle, "must be in (0, 2 pi)");
  const double slant = std::hypot(radius, height);
  const double sector = angle * radius / slant;  // unrolled opening angle
  const double inner = slant * top / radius, outer = slant;
  SurfaceSpec spec;
  spec.name = "cone";
  spec.position = [radius, height, slant](const Vec2& u) {
    const double rho = u.norm();
    const double phi = rho > 0 ? std::atan2(u.y(), u.x()) * slant / radius : 0.0;
    const double r = rho * radius / slant;
    return Vec3(r * std::cos(phi), r * std::sin(phi), height * (1 - rho / slant));
  };
  auto ray = [sector](double from, double to, double side) {
    return DomainCurve{[=](double s) {
      const double rho = from + s * (to - from);
      return Vec2(rho * std::cos(side * sector / 2), rho * std::sin(side * sector / 2));
    }};
  };
  auto arc = [sector](double rho, bool counterClockwise) {
    return DomainCurve{[=](double s) {
      const double beta = (counterClockwise ? s - 0.5 : 0.5 - s) * sector;
      return Vec2(rho * std::cos(beta), rho * std::sin(beta));
    }};
  };
  if (top > 0) {
    spec.boundary = {
        {ray(inner, outer, -1), arc(outer, true), ray(outer, inner, 1), arc(inner, false)}};
  } else {
    spec.boundary = {{ray(0, outer, -1), arc(outer, true), ray(outer, 0, 1)}};
  }
  spec.inDomain = [inner, outer](const Vec2& u) { return u.norm() >= inner && u.norm() <= outer; };
  return spec;
}

// One-sheeted hyperboloid (x^2 + y^2) / a^2 - z^2 / c^2 = 1 with axis z, waist radius a at z = 0,
// for |z| <= height / 2 over the arc `angle` centred on +x. Domain: (a phi, z).
SurfaceSpec hyperboloid(const Params& p) {
  const double a = p.at("radius"), c = p.at("c"), height = p.at("height"), angle = p.at("angle");
  require(a > 0, "hyperboloid", "radius", a, "must be positive");
  require(c > 0, "hyperboloid", "c", c, "must be positive");
  require(height > 0, "hyperboloid", "height", height, "must be positive");
  require(angle > 0 && angle < 2 * kPi, "hyperboloid", "angle", angle, "must be in (0, 2 pi)");
  SurfaceSpec spec;
  spec.name = "hyperboloid";
  spec.position = [a, c](const Vec2& u) {
    const double phi = u.x() / a, z = u.y();
    const double r = a * std::sqrt(1 + z * z / (c * c));
    return Vec3(r * std::cos(phi), r * std::sin(phi), z);
  };
  spec.boundary = {rectangleLoop(-a * angle / 2, a * angle / 2, -height / 2, height / 2)};
  return spec;
}

}  // namespace

std::vector<SampleEntry> testSurfaceSamples() {
  const Params extent{{"length", 10.0}, {"width", 10.0}};
  const std::map<std::string, std::string> extentHelp{{"length", "footprint extent along x (m)"},
                                                      {"width", "footprint extent along y (m)"}};
  auto with = [](Params a, const Params& b) {
    a.insert(b.begin(), b.end());
    return a;
  };
  auto withHelp = [](std::map<std::string, std::string> a,
                     const std::map<std::string, std::string>& b) {
    a.insert(b.begin(), b.end());
    return a;
  };
  const std::string arc = "opening angle of the arc (rad, below 2 pi)";
  return {
      {{"plane", "Flat rectangle z = 0, length (x) by width (y) metres, centred at the origin",
        extent, extentHelp},
       plane},
      {{"sphere",
        "Sphere cap around the north pole of the sphere |p| = radius centred at the origin, over "
        "the "
        "footprint disc of radius extent (extent = radius: hemisphere)",
        {{"radius", 10.0}, {"extent", 8.0}},
        {{"radius", "sphere radius R (m)"},
         {"extent", "footprint radius of the cap (m), in (0, R]"}}},
       sphere},
      {{"cylinder",
        "Cylinder vault y^2 + z^2 = radius^2, axis x, x in [-length/2, length/2], arc angle (rad) "
        "centred "
        "on the top",
        {{"radius", 5.0}, {"length", 10.0}, {"angle", kPi}},
        {{"radius", "cylinder radius (m)"},
         {"length", "extent along the axis x (m)"},
         {"angle", arc}}},
       cylinder},
      {{"cone",
        "Cone x^2 + y^2 = (radius (1 - z/height))^2, apex (0, 0, height), from the base z = 0 up "
        "to the "
        "circle of top_radius (0 keeps the apex), arc angle (rad) centred on +x",
        {{"radius", 5.0}, {"height", 5.0}, {"top_radius", 1.0}, {"angle", kPi}},
        {{"radius", "base radius at z = 0 (m)"},
         {"height", "apex height (m)"},
         {"top_radius", "radius where the frustum is cut (m), in [0, radius); 0 keeps the apex"},
         {"angle", arc}}},
       cone},
      {{"hypar", "Hyperbolic paraboloid z = c x y over length (x) by width (y) metres, centred",
        with({{"c", 0.1}}, extent), withHelp({{"c", "twist c of z = c x y (1/m)"}}, extentHelp)},
       hypar},
      {{"hyperboloid",
        "One-sheeted hyperboloid (x^2 + y^2)/radius^2 - z^2/c^2 = 1, |z| <= height/2, arc angle "
        "(rad) "
        "centred on +x",
        {{"radius", 3.0}, {"c", 4.0}, {"height", 6.0}, {"angle", kPi}},
        {{"radius", "waist radius a at z = 0 (m)"},
         {"c", "axial semi-axis c (m): the asymptotic cone has slope a / c"},
         {"height", "extent along the axis z (m), centred on the waist"},
         {"angle", arc}}},
       hyperboloid},
      {{"bump",
        "Gaussian bump z = height exp(-(x^2 + y^2) / (2 sigma^2)) over length (x) by width (y), "
        "centred",
        with({{"height", 2.0}, {"sigma", 2.0}}, extent),
        withHelp(
            {{"height", "peak height (m)"}, {"sigma", "standard deviation of the Gaussian (m)"}},
            extentHelp)},
       bump},
      {{"waves",
        "Egg-crate waves z = amplitude sin(2 pi x / wavelength) sin(2 pi y / wavelength) over "
        "length (x) by "
        "width (y), centred",
        with({{"amplitude", 0.5}, {"wavelength", 5.0}}, extent),
        withHelp({{"amplitude", "wave amplitude (m)"}, {"wavelength", "wavelength in x and y (m)"}},
                 extentHelp)},
       waves},
  };
}

}  // namespace egg::samples::detail
