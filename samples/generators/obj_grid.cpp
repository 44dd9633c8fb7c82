#include "samples/generators/obj_grid.hpp"

#include <fmt/format.h>

#include <cmath>

namespace egg::samples {

void addHeightFieldGrid(ObjText& obj, int nx, int ny, double lx, double ly,
                        const std::function<double(double, double)>& height,
                        const std::function<bool(double, double)>& skip, double offsetX) {
  const int base = obj.vertices;
  std::string& s = obj.text;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = -lx / 2 + lx * i / nx, y = -ly / 2 + ly * j / ny;
      s += fmt::format("v {:.9g} {:.9g} {:.9g}\n", x + offsetX, y, height(x, y));
    }
  obj.vertices += (nx + 1) * (ny + 1);
  const auto id = [&](int i, int j) { return base + j * (nx + 1) + i + 1; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double cx = -lx / 2 + lx * (i + 0.5) / nx, cy = -ly / 2 + ly * (j + 0.5) / ny;
      if (skip && skip(cx, cy)) continue;
      s += fmt::format("f {} {} {}\nf {} {} {}\n", id(i, j), id(i + 1, j), id(i + 1, j + 1),
                       id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
}

std::function<double(double, double)> gaussianBump(double h, double sigma) {
  return [h, sigma](double x, double y) {
    return h * std::exp(-(x * x + y * y) / (2 * sigma * sigma));
  };
}

}  // namespace egg::samples
