#pragma once
// deployed.svg of `egg run` (issue 18, "the deployed grid coloured by deviation from the design
// surface"): the simulated centrelines seen from above, each stretch coloured by the distance of
// its contact points to the design surface (the error measure of Sections 2.6.2 and 3.5.2), with a
// colour bar in centimetres. report.html inlines it and renders its PNG preview.
#include <Eigen/Core>

#include <string>
#include <vector>

namespace egg::pipeline {

// One deployed rod: its contact points and each point's distance to the design surface (metres).
struct DeployedRod {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> distanceM;
  int patch = -1;  // layout patch id
  int rod = -1;    // the rod's index in its patch's network
};

// The colour of a distance on the bar from 0 (blue #2c7bb6) through scale/2 (pale yellow #ffffbf)
// to `scale_m` and beyond (red #d7191c), linear between those stops, as "#rrggbb".
std::string deviationColour(double distanceM, double scaleM);

// The bar's top value: the largest distance rounded up to 1, 2 or 5 x 10^k metres (> 0).
double deviationScale(double maxDistanceM);

// The figure: an <svg id="deployed"> that renders alone (it has the namespace) and inline in the
// page. Consecutive segments in the same of 16 colour bins are one polyline, which keeps the Great
// Court's ~40k segments to a few hundred kilobytes. `caption` says which run is drawn.
std::string deployedPlanSvg(const std::vector<DeployedRod>& rods, const std::string& caption);

}  // namespace egg::pipeline
