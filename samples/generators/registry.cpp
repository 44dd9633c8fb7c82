// Public entry points of the samples: the catalogue, parameter checking, and the size guard.
#include "core/errors.hpp"
#include "samples/generators/catalog.hpp"
#include "samples/generators/samples.hpp"
#include "samples/generators/surface_mesher.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

namespace egg::samples {
namespace detail {

BoundaryLoop rectangleLoop(double x0, double x1, double y0, double y1) {
  const Vec2 corners[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  BoundaryLoop loop;
  for (int i = 0; i < 4; ++i) {
    const Vec2 from = corners[i], to = corners[(i + 1) % 4];
    loop.push_back({[from, to](double s) { return Vec2(from + s * (to - from)); }});
  }
  return loop;
}

BoundaryLoop ellipseLoop(const Vec2& centre, double rx, double ry) {
  return {{[centre, rx, ry](double s) {
    const double angle = 2 * std::numbers::pi * s;
    return Vec2(centre.x() + rx * std::cos(angle), centre.y() + ry * std::sin(angle));
  }}};
}

void require(bool ok, const std::string& sample, const std::string& key, double value,
             const std::string& requirement) {
  if (ok) return;
  std::ostringstream message;
  message << "sample '" << sample << "': parameter '" << key << "' " << requirement << " (got "
          << value << ")";
  throw InvalidInput(message.str());
}

namespace {

const std::vector<SampleEntry>& catalogue() {
  static const std::vector<SampleEntry> entries = [] {
    std::vector<SampleEntry> all = architecturalSamples();
    for (auto& entry : testSurfaceSamples()) all.push_back(std::move(entry));
    for (auto& entry : chapter4Samples()) all.push_back(std::move(entry));
    return all;
  }();
  return entries;
}

const SampleEntry& findSample(const std::string& name) {
  for (const SampleEntry& entry : catalogue()) {
    if (entry.info.name == name) return entry;
  }
  std::string known;
  for (const SampleEntry& entry : catalogue())
    known += (known.empty() ? "" : ", ") + entry.info.name;
  throw InvalidInput("unknown sample '" + name + "' (known samples: " + known + ")");
}

// Defaults overlaid with the caller's values; unknown keys and non-finite values are refused.
Params completeParams(const SampleInfo& info, const Params& given) {
  Params complete = info.defaults;
  for (const auto& [key, value] : given) {
    if (!info.defaults.count(key)) {
      std::string accepted;
      for (const auto& [name, unused] : info.defaults)
        accepted += (accepted.empty() ? "" : ", ") + name;
      throw InvalidInput("sample '" + info.name + "': unknown parameter '" + key + "' (accepted: " +
                         (accepted.empty() ? std::string("none") : accepted) + ")");
    }
    require(std::isfinite(value), info.name, key, value, "must be finite");
    complete[key] = value;
  }
  return complete;
}

// Triangles of an equilateral mesh: area / (sqrt(3)/4 h^2). Beyond this the caller surely
// mistyped the edge length (millimetres for metres) and would wait minutes for gigabytes.
constexpr double kMaxTriangles = 5.0e6;

}  // namespace
}  // namespace detail

std::vector<SampleInfo> listSamples() {
  std::vector<SampleInfo> infos;
  for (const auto& entry : detail::catalogue()) infos.push_back(entry.info);
  return infos;
}

bool isSample(const std::string& name) {
  for (const auto& entry : detail::catalogue()) {
    if (entry.info.name == name) return true;
  }
  return false;
}

TriMesh generateSample(const std::string& name, const Params& params, double edgeLengthM) {
  const detail::SampleEntry& entry = detail::findSample(name);
  if (!(edgeLengthM > 0) || !std::isfinite(edgeLengthM)) {
    std::ostringstream message;
    message << "sample '" << name << "': edge_length_m must be positive and finite (got "
            << edgeLengthM << ")";
    throw InvalidInput(message.str());
  }
  const detail::SurfaceSpec spec = entry.build(detail::completeParams(entry.info, params));
  // A long thin surface can have few triangles but millions of boundary samples: check first.
  const double boundaryEdges = detail::boundaryLength(spec) / edgeLengthM;
  if (boundaryEdges > detail::kMaxTriangles) {
    std::ostringstream message;
    message << "sample '" << name << "': edge_length_m " << edgeLengthM << " would put about "
            << std::llround(boundaryEdges)
            << " edges on the boundary (limit 5 million); use a longer edge";
    throw InvalidInput(message.str());
  }
  const double area = detail::estimateArea(spec);
  // area / perimeter is half the width of a strip, R/2 of a disc: a surface a small fraction of an
  // edge wide cannot hold near-equilateral triangles of that edge (refinement would never end).
  if (area < 0.05 * edgeLengthM * detail::boundaryLength(spec)) {
    std::ostringstream message;
    message << "sample '" << name << "': the surface is far thinner than edge_length_m "
            << edgeLengthM << " (area " << area << " m^2 for a boundary of "
            << detail::boundaryLength(spec) << " m)";
    throw InvalidInput(message.str());
  }
  const double triangles = area / (std::sqrt(3.0) / 4.0 * edgeLengthM * edgeLengthM);
  if (triangles > detail::kMaxTriangles) {
    std::ostringstream message;
    message << "sample '" << name << "': edge_length_m " << edgeLengthM << " would give about "
            << std::llround(triangles) << " triangles on " << std::llround(area)
            << " m^2 (limit 5 million); use a longer edge";
    throw InvalidInput(message.str());
  }
  try {
    return meshFromSoup(detail::meshSurface(spec, edgeLengthM, triangles));
  } catch (const InvalidInput& error) {
    std::ostringstream message;
    message << "sample '" << name << "' at edge_length_m " << edgeLengthM << ": " << error.what();
    throw InvalidInput(message.str());
  }
}

}  // namespace egg::samples
