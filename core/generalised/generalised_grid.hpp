#pragma once
// A generalised geodesic grid on one patch with a free-form, possibly non-convex boundary (thesis
// Sections 4.4-4.6). A member is a pair of boundary samples (a point of the discrete dual space,
// Section 4.4.2); its lamella is the shortest geodesic between them. Two families g, h; members of
// one family never cross, every crossing joins one member of each.
//
// Layouts. A layout is drawn as two families of parallel straight lines in the least-squares plane
// of the patch (the rotation, skew and offsets of LayoutParameters), each line cut by the
// projected boundary into its inside segments, whose ends give the members' samples: a line
// crossing a bay of a non-convex boundary gives two members (subfamilies, Fig. 4.11). Where the
// shortest connection between a member's samples would still run along or touch a non-convex
// segment (an invalid point of the dual space, Eq. 4.4-4.6), it is split at its first and last
// contact with the boundary into the two geodesics before and after it, each ending at an anchor
// on the bay: the member count changes exactly where a member would touch the boundary. The
// thesis shifts such members to the next valid pair of the same family instead; splitting keeps
// the anchors where the layout put them and never leaves a gap in the grid next to the bay.
//
// Crossings. Two shortest geodesics in a disk cross iff their ends interleave along the boundary,
// and then once: the combinatorics follow from the sample order alone. Where they cross is found
// from the four endpoint distance fields without tracing (Section 4.5.2, geodesic_intersection).
#include "core/generalised/grid_domain.hpp"

#include <array>
#include <string>
#include <vector>

namespace egg::generalised {

struct LayoutParameters {
  double angleRad = 0.0;                       // direction of family 0's lines in the layout plane
  double skewRad = 0.0;                        // family 1 runs at angle + pi/2 + skew
  std::array<int, 2> lines = {6, 6};           // lines per family
  std::array<double, 2> offsets = {0.5, 0.5};  // lines at (k + offset) x spacing, offset in [0,1)
  void validate() const;                       // throws InvalidInput naming the field
};

struct GridMemberSpec {
  int family = 0;  // 0 (g) or 1 (h)
  int start = -1;  // boundary samples; the member runs from start to end
  int end = -1;
  int line = -1;       // the layout line it came from (neighbours are members of adjacent lines)
  bool split = false;  // a piece of a member split where it would touch the boundary
};

struct GeneralisedLayout {
  std::vector<GridMemberSpec> members;
  int splitMembers = 0;    // pieces of members split where they would touch a non-convex segment
  int droppedMembers = 0;  // inside segments without any crossing (corner slivers), left out
};

struct LayoutOptions {
  // Distinct anchors closer than this along the boundary make a layout unbuildable (metres);
  // <= 0: half the mean edge length (distinct boundary samples).
  double minAnchorSpacingM = 0.0;
  void validate() const;  // throws InvalidInput naming the field
};

// The members of one straight line of the layout plane, {p : <n, p> = offsetM} with n the
// direction turned a quarter left, in order along `direction`: one per inside segment of the
// projected boundary, each split at its contacts with a non-convex segment when `split`.
std::vector<GridMemberSpec> lineMembers(const GridDomain& domain, const Eigen::Vector2d& direction,
                                        double offsetM, int family, int line, bool split = true);

GeneralisedLayout layoutFromLines(const GridDomain& domain, const LayoutParameters& parameters,
                                  const LayoutOptions& options = {});

// Why a layout cannot be built ("" if it can): a member on an invalid pair, two members of one
// family crossing, two anchors of different members closer than the minimum spacing (split pieces
// share their contact anchor), a member crossing no other.
std::string layoutProblem(const GridDomain& domain, const GeneralisedLayout& layout,
                          const LayoutOptions& options = {});

// True if the members' ends interleave along the boundary loop (their geodesics cross).
bool membersCross(int sampleCount, const GridMemberSpec& first, const GridMemberSpec& second);

struct GridCrossing {
  int g = -1;  // member indices into the layout (family 0, family 1)
  int h = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // from the distance fields
  SurfacePoint point;
  double sGM = 0.0;  // arc length from g's start, d(p_A, q) read off the field
  double sHM = 0.0;
  bool found = false;  // false: the fields' excess stayed above the acceptance bound
};

std::vector<GridCrossing> gridCrossings(const GridDomain& domain, const GeneralisedLayout& layout);

// Consecutive members of one family (adjacent lines, overlapping along their direction), the
// second to the left of the first: the pairs whose lamellas must not overlap when cut (4.7.2).
std::vector<std::pair<int, int>> neighbourMembers(const GridDomain& domain,
                                                  const GeneralisedLayout& layout);

}  // namespace egg::generalised
