#pragma once
// The cladding functions of report.html (issue 18; Sections 2.4.3-2.4.4, Fig. 2.7 right, Fig. 3.4):
// per patch, F_u and F_v with their members as dots, and below each the slope of F's segments on
// a log axis against the band (k_min, k_max) of patching.slope_bounds that Problem 2.3 keeps them
// in. F runs over the boundary parameters x1, x2 in [0, 1], which run at constant speed along the
// family's start and end sides (placeMembers): the axes are those sides in metres. The slope is
// dx2/dx1 as the thesis bounds it (parameters, not metres), a vertical segment c * dx2.
//
// The data travels through report.json (patches[].cladding, claddingEntry) so that reportHtml
// draws from the report alone.
#include "core/egg/cladding.hpp"
#include "core/egg/members.hpp"
#include "pipeline/plot_frame.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace egg::pipeline {

// One family's F as the plot reads it.
struct CladdingCurve {
  std::string family = "u";
  double startSideM = 1.0, endSideM = 1.0;     // side lengths x1 and x2 run along (metres)
  std::vector<std::array<double, 2>> points;   // (x1, x2) of F's polyline, (0,0) to (1,1)
  std::vector<std::array<double, 2>> members;  // (x1, x2) of the members, boundary members included
};

struct CladdingPlot {
  int patch = 0;
  double slopeMin = 0.1, slopeMax = 10.0;  // k_min, k_max
  double infiniteSlopeFactor = 1e4;  // c of a vertical segment's slope c * dx2 (Section 2.4.3)
  CladdingCurve u, v;
};

// report.json patches[].cladding of a traced patch: {slope_bounds[2], infinite_slope_factor,
// u{start_side_m, end_side_m, points_x1[], points_x2[], members_x1[], members_x2[], bijective},
// v{...}}; x1 and x2 are the boundary parameters in [0, 1] (metres = parameter x side length).
nlohmann::json claddingEntry(const CladdingFunction& u, const CladdingFunction& v,
                             const FamilyMembers& membersU, const FamilyMembers& membersV,
                             const std::array<double, 2>& sidesU,
                             const std::array<double, 2>& sidesV, double slopeMin, double slopeMax,
                             double infiniteSlopeFactor);

// Reads a patch entry's "cladding" back; empty when the entry has none (an infeasible patch).
// Throws InvalidInput naming the key when it is malformed.
std::optional<CladdingPlot> claddingFromReport(const nlohmann::json& patchEntry);

// Layout of one family's panel: F above, its slopes below; `column` 0 for u, 1 for v.
PlotFrame claddingFrame(const CladdingCurve& curve, int column);
PlotFrame slopeFrame(const CladdingCurve& curve, int column, double slopeMin, double slopeMax);

// Slopes dx2/dx1 of F's segments as (x1 start, x1 end, slope); zero-length segments skipped, a
// vertical one (dx1 = 0) gets c * dx2 (segmentSlopes, Section 2.4.3).
std::vector<std::array<double, 3>> claddingSlopes(const CladdingCurve& curve,
                                                  double infiniteSlopeFactor);

// The figure: <svg id="cladding-patch-N">, both families, without the SVG namespace, as the page's
// other charts (reportFigures adds it for the PNG preview).
std::string claddingSvg(const CladdingPlot& plot);

}  // namespace egg::pipeline
