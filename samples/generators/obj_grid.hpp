#pragma once
// Meshes written as OBJ text, for the paths that read a mesh file (the stress suite's slivers,
// holes, disconnected parts and a million faces; tests of the importers): height fields over a
// regular grid, two triangles per cell.
#include <functional>
#include <string>

namespace egg::samples {

struct ObjText {
  std::string text;  // "v x y z" and "f a b c" lines, 1-based
  int vertices = 0;
};

// Appends a grid of nx x ny cells over [-lx/2, lx/2] x [-ly/2, ly/2] (metres) on z = height(x, y)
// to `obj`; `skip(x, y)` at a cell's centre drops the cell (holes); `offsetX` shifts the grid.
void addHeightFieldGrid(ObjText& obj, int nx, int ny, double lx, double ly,
                        const std::function<double(double, double)>& height,
                        const std::function<bool(double, double)>& skip = {}, double offsetX = 0.0);

// z = h exp(-(x^2 + y^2) / (2 sigma^2)).
std::function<double(double, double)> gaussianBump(double h, double sigma);

}  // namespace egg::samples
