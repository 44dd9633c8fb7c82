#pragma once
// Small test meshes built inside the geodesic tests (independent of the sample generators, so the
// oracle comparisons do not move when a generator changes): height-field grids (plane, bump,
// hypar, jittered variants), a closed UV sphere, and an open N-gon prism that unrolls exactly.
#include "core/mesh/mesh.hpp"

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

namespace egg::geodesic::testing {

// Grid of nx x ny cells over [0, sizeX] x [0, sizeY], z = height(x, y). Interior vertices are moved
// in the plane by up to `jitter` times the cell size (seeded, so reproducible). Diagonals alternate
// so the mesh has no preferred direction.
inline TriMesh gridMesh(int nx, int ny, double sizeX, double sizeY,
                        const std::function<double(double, double)>& height, double jitter = 0.0,
                        unsigned seed = 7) {
  TriangleSoup soup;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double hx = sizeX / nx, hy = sizeY / ny;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      double x = i * hx, y = j * hy;
      const double jx = uniform(rng), jy = uniform(rng);
      if (i > 0 && i < nx && j > 0 && j < ny) {
        x += jitter * hx * jx;
        y += jitter * hy * jy;
      }
      soup.vertices.emplace_back(x, y, height(x, y));
    }
  }
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        soup.triangles.push_back({a, b, c});
        soup.triangles.push_back({a, c, d});
      } else {
        soup.triangles.push_back({a, b, d});
        soup.triangles.push_back({b, c, d});
      }
    }
  }
  return meshFromSoup(soup);
}

// The square [0,2]x[0,2], n cells per unit, z = height(x, y); with `notch` the L-shaped domain
// [0,2]^2 minus (1,2]x(1,2], whose reflex boundary corner (1,1) shortest paths between the two arms
// bend around. Each cell is split along the diagonal (i,j)-(i+1,j+1), or the other one.
inline TriMesh squareDomainMesh(int n, const std::function<double(double, double)>& height,
                                bool notch, bool otherDiagonal = false) {
  TriangleSoup soup;
  std::vector<int> index((2 * n + 1) * (2 * n + 1), -1);
  for (int j = 0; j <= 2 * n; ++j) {
    for (int i = 0; i <= 2 * n; ++i) {
      if (notch && i > n && j > n) continue;
      const double x = double(i) / n, y = double(j) / n;
      index[j * (2 * n + 1) + i] = static_cast<int>(soup.vertices.size());
      soup.vertices.emplace_back(x, y, height(x, y));
    }
  }
  for (int j = 0; j < 2 * n; ++j) {
    for (int i = 0; i < 2 * n; ++i) {
      const int a = index[j * (2 * n + 1) + i], b = index[j * (2 * n + 1) + i + 1];
      const int c = index[(j + 1) * (2 * n + 1) + i + 1], d = index[(j + 1) * (2 * n + 1) + i];
      if (a < 0 || b < 0 || c < 0 || d < 0) continue;
      if (otherDiagonal) {
        soup.triangles.push_back({a, b, d});
        soup.triangles.push_back({b, c, d});
      } else {
        soup.triangles.push_back({a, b, c});
        soup.triangles.push_back({a, c, d});
      }
    }
  }
  return meshFromSoup(soup);
}

inline TriMesh lShapeMesh(int n, const std::function<double(double, double)>& height) {
  return squareDomainMesh(n, height, true);
}

inline double flat(double, double) { return 0.0; }

// Gaussian bump of height `amplitude` and width `width` centred at (cx, cy).
inline std::function<double(double, double)> bump(double cx, double cy, double amplitude,
                                                  double width) {
  return [=](double x, double y) {
    const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
    return amplitude * std::exp(-r2 / (width * width));
  };
}

// Hyperbolic paraboloid z = c (x - cx)(y - cy): negative curvature, every interior vertex a saddle.
inline std::function<double(double, double)> hypar(double cx, double cy, double c) {
  return [=](double x, double y) { return c * (x - cx) * (y - cy); };
}

// Closed UV sphere of radius R with `rings` latitude bands and `segments` longitudes.
inline TriMesh sphereMesh(double radius, int rings, int segments) {
  TriangleSoup soup;
  soup.vertices.emplace_back(0, 0, radius);
  for (int r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * std::numbers::pi * (s + 0.5 * (r % 2)) / segments;
      soup.vertices.emplace_back(radius * std::sin(theta) * std::cos(phi),
                                 radius * std::sin(theta) * std::sin(phi),
                                 radius * std::cos(theta));
    }
  }
  soup.vertices.emplace_back(0, 0, -radius);
  const int south = static_cast<int>(soup.vertices.size()) - 1;
  auto ring = [&](int r, int s) {
    return 1 + (r - 1) * segments + ((s % segments) + segments) % segments;
  };
  for (int s = 0; s < segments; ++s) soup.triangles.push_back({0, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      // Ring r+1 is shifted by half a segment relative to ring r when r is even.
      const int a = ring(r, s), b = ring(r, s + 1);
      if (r % 2 == 1) {
        const int c = ring(r + 1, s), d = ring(r + 1, s + 1);
        soup.triangles.push_back({a, c, d});
        soup.triangles.push_back({a, d, b});
      } else {
        const int c = ring(r + 1, s), d = ring(r + 1, s - 1);
        soup.triangles.push_back({a, d, c});
        soup.triangles.push_back({a, c, b});
      }
    }
  }
  for (int s = 0; s < segments; ++s)
    soup.triangles.push_back({south, ring(rings - 1, s + 1), ring(rings - 1, s)});
  return meshFromSoup(soup);
}

// Open prism over a regular N-gon of circumradius R (no caps), `layers` rows of height H/layers.
// Its surface is flat: it unrolls into a strip of width N * side, so distances are planar.
inline TriMesh prismMesh(int sides, double radius, double height, int layers) {
  TriangleSoup soup;
  for (int l = 0; l <= layers; ++l) {
    for (int s = 0; s < sides; ++s) {
      const double phi = 2.0 * std::numbers::pi * s / sides;
      soup.vertices.emplace_back(radius * std::cos(phi), radius * std::sin(phi),
                                 height * l / layers);
    }
  }
  auto id = [&](int l, int s) { return l * sides + (s % sides); };
  for (int l = 0; l < layers; ++l) {
    for (int s = 0; s < sides; ++s) {
      const int a = id(l, s), b = id(l, s + 1), c = id(l + 1, s + 1), d = id(l + 1, s);
      if ((l + s) % 2 == 0) {
        soup.triangles.push_back({a, b, c});
        soup.triangles.push_back({a, c, d});
      } else {
        soup.triangles.push_back({a, b, d});
        soup.triangles.push_back({b, c, d});
      }
    }
  }
  return meshFromSoup(soup);
}

// The surface point of face `face` with barycentric weights (a, b, c).
inline SurfacePoint facePoint(int face, double a, double b, double c) {
  SurfacePoint p;
  p.face = face;
  p.barycentric = Eigen::Vector3d(a, b, c);
  return p;
}

}  // namespace egg::geodesic::testing
