#pragma once
// From a generalised layout to what is built (thesis Sections 4.5.2, 4.7, 4.8): the final members
// traced on the surface, the crossings read off the traced geodesics (and how far the distance
// field reconstruction of Section 4.5.2 lies from them: eps_geo of Table 4.1), the planar cut
// layout of Section 4.7 with its notches, and the rod network the simulation deploys: every member
// a straight lamella held at both ends by an anchor on the boundary ring (position and tangent
// plane, Section 4.3.1), bolted to every member of the other family it crosses.
#include "core/generalised/generalised_grid.hpp"
#include "core/generalised/planarisation.hpp"
#include "core/rods/rod_network.hpp"

#include <vector>

namespace egg::generalised {

struct GeneralisedDesignOptions {
  rods::CrossSection section;  // lamella section (also the width of the planarisation's 4.7.2)
  rods::Material material;
  PlanarisationOptions planarisation;
  bool notches = true;    // false: plain holes at the planar crossings
  void validate() const;  // throws InvalidInput naming the field
};

struct GeneralisedDesign {
  GeneralisedLayout layout;
  std::vector<GridCrossing> fieldCrossings;      // Section 4.5.2, from the distance fields
  std::vector<Eigen::Vector3d> tracedCrossings;  // the same crossings of the traced geodesics
  std::vector<double> tracedSGM, tracedSHM;      // arc lengths of the traced crossings
  // The acute angle between the two traced geodesics at each crossing (radians, in [0, pi/2]) and
  // the smallest: a bolt through two lamellas crossing at a few degrees holds nothing.
  std::vector<double> crossingAnglesRad;
  double minCrossingAngleRad = 0.0;
  // eps_geo of Table 4.1: mean distance between the field crossings and the traced ones, in
  // per cent of the mean edge length; and the largest such distance (metres).
  double epsGeoPercent = 0.0;
  double maxCrossingDeviationM = 0.0;
  PlanarisationProblem planarProblem;
  PlanarisationResult planar;
  std::vector<std::pair<int, int>> neighbours;  // layout member indices (planarProblem.neighbours)
  // Every pair of lamellas of one family whose planar outlines (centre line +- w/2) overlap by more
  // than 1e-9 m, checked independently of the planarisation's neighbour constraints; the pieces
  // of one split member, which share their anchor on the bay, are left out (they meet there on
  // the surface too).
  std::vector<std::pair<int, int>> planarOverlaps;
  rods::RodNetwork network;  // rods in layout member order
  double seconds = 0.0;
};

// Pairs (i < j) of planar lamellas, centre lines `segments` of width `widthM`, whose rectangles
// overlap by more than `tolerance` metres (separating axes), among those with equal `families`.
std::vector<std::pair<int, int>> overlappingLamellas(const std::vector<Segment2>& segments,
                                                     const std::vector<int>& families,
                                                     double widthM, double tolerance = 1e-9);

// Throws InvalidInput when the layout cannot be built (layoutProblem) or a crossing of two traced
// members cannot be found.
GeneralisedDesign designGeneralisedGrid(const GridDomain& domain, const GeneralisedLayout& layout,
                                        const GeneralisedDesignOptions& options = {});

}  // namespace egg::generalised
