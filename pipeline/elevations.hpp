#pragma once
// elevations.svg of `egg run` (issue 39): the deployed shape seen from the side, as an architect
// draws it. Two elevations (south, looking north; east, looking west) with the design surface's
// silhouette behind the simulated lamella centrelines, and two sections through the middle of the
// plan (A-A at constant y, B-B at constant x: the design surface cut as a line, every lamella the
// plane cuts as a dot), all at one scale with a scale bar, the ground line and the levels of the
// design's and the deployed grid's highest points. plan.svg marks the two section lines.
#include "core/mesh/mesh.hpp"
#include "pipeline/deviation_plan.hpp"

#include <string>
#include <vector>

namespace egg::pipeline {

// A vertical cutting plane: constant y (alongX: the section runs west-east) or constant x.
struct SectionPlane {
  std::string name;  // "A" or "B"
  bool alongX = true;
  double atM = 0.0;
};

// The two sections elevationsSvg draws: through the middle of the design surface's plan box.
std::vector<SectionPlane> sectionPlanes(const TriMesh& surface);

// The figure: an <svg id="elevations"> that renders alone and inline in report.html. Throws
// InvalidInput for an empty surface.
std::string elevationsSvg(const TriMesh& surface, const std::vector<DeployedRod>& rods,
                          const std::string& caption);

}  // namespace egg::pipeline
