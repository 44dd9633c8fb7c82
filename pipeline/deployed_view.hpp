#pragma once
// deployed.json and report.html's 3D view (issue 39): the deployed lamellas' contact lines in 3D,
// each point with its distance to the design surface (Sections 2.6.2, 3.5.2), the patch and rod
// it belongs to, and the design surface itself. Metres, z up.
#include "core/mesh/mesh.hpp"
#include "pipeline/deviation_plan.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace egg::pipeline {

// {"caption", "scale_m", "rods": [{"patch", "rod", "points": [x,y,z,...], "distance_m": [...]}],
//  "surface": {"positions", "triangles"}}; coordinates rounded to the millimetre. A surface of
// more than `maxSurfaceTriangles` is left out (the page would not carry it), and said so.
nlohmann::json deployedViewJson(const std::vector<DeployedRod>& rods, const TriMesh& surface,
                                const std::string& caption,
                                std::size_t maxSurfaceTriangles = 200000);

// The section of report.html: the view's canvas, its data and its script (three.js inlined), so
// that the page still works offline. Empty `viewJson`: a note that the simulation did not run.
std::string deployedViewSection(const std::string& viewJson);

// viewer.js bundled with three.js (export/js/viewer, generated at build time).
std::string_view reportViewerScript();

}  // namespace egg::pipeline
