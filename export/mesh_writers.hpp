#pragma once
// The structure model as plain meshes: a Wavefront OBJ of the whole structure with one object and
// group per lamella named by its id (P3-U7), per patch's bolts and per support, and one binary STL
// of every support block at its site position. Metres, site coordinates (z up).
#include "export/model.hpp"

#include <string>

namespace egg::exporter {

std::string modelObj(const StructureModel& model);

// All support blocks in one binary STL (site coordinates, metres). Throws InvalidInput when the
// model has no support block.
std::string supportsStl(const StructureModel& model);

}  // namespace egg::exporter
