#include "pipeline/deployed_view.hpp"

#include <algorithm>
#include <cmath>

namespace egg::pipeline {

using nlohmann::json;

namespace {

// Millimetres are more than the page needs and keep the Great Court's view near 1 MB.
double mm(double x) { return std::round(x * 1000.0) / 1000.0; }

// Text inside <script type="application/json">: "</" would end the element early.
std::string scriptSafe(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += "\\";
  }
  return out;
}

constexpr const char* kViewStyle =
    R"(.egg-view-frame{position:relative;display:inline-block;border:1px solid #ddd;cursor:grab}
.egg-view-frame canvas{display:block}
.egg-view-tip{position:absolute;display:none;background:#fffe;border:1px solid #999;padding:2px 6px;font-size:13px;pointer-events:none;white-space:nowrap}
.egg-view-controls{margin:6px 0;font-size:14px}.egg-view-controls label{margin-right:12px;white-space:nowrap}
.egg-view-legend{display:flex;align-items:center;gap:8px;font-size:14px}.egg-view-ramp{display:inline-block;width:220px;height:12px;border:1px solid #999})";

}  // namespace

json deployedViewJson(const std::vector<DeployedRod>& rods, const TriMesh& surface,
                      const std::string& caption, std::size_t maxSurfaceTriangles) {
  double maxDistance = 0.0;
  json list = json::array();
  for (const DeployedRod& rod : rods) {
    json points = json::array(), distances = json::array();
    for (size_t i = 0; i < rod.points.size(); ++i) {
      for (int c = 0; c < 3; ++c) points.push_back(mm(rod.points[i][c]));
      const double d =
          i < rod.distanceM.size() && std::isfinite(rod.distanceM[i]) ? rod.distanceM[i] : 0.0;
      distances.push_back(std::round(d * 1e4) / 1e4);
      maxDistance = std::max(maxDistance, d);
    }
    list.push_back(
        {{"patch", rod.patch}, {"rod", rod.rod}, {"points", points}, {"distance_m", distances}});
  }
  json view = {{"caption", caption}, {"scale_m", deviationScale(maxDistance)}, {"rods", list}};
  if (static_cast<std::size_t>(surface.n_faces()) <= maxSurfaceTriangles) {
    json positions = json::array(), triangles = json::array();
    for (const auto v : surface.vertices())
      for (int c = 0; c < 3; ++c) positions.push_back(mm(surface.point(v)[c]));
    for (const auto f : surface.faces())
      for (const auto v : surface.fv_range(f)) triangles.push_back(v.idx());
    view["surface"] = {{"positions", positions}, {"triangles", triangles}};
  } else {
    view["surface_left_out"] = "the design surface has " + std::to_string(surface.n_faces()) +
                               " triangles, more than the view carries (" +
                               std::to_string(maxSurfaceTriangles) + ")";
  }
  return view;
}

std::string deployedViewSection(const std::string& viewJson) {
  std::string out =
      "<h2 id=\"view-3d\">3D view: the deployed grid against the design surface</h2>\n";
  if (viewJson.empty())
    return out +
           "<p class=\"missing\">No 3D view: the simulation did not run (deployed.json).</p>\n";
  out +=
      "<p>Drag to orbit, shift-drag or right-drag to pan, the wheel to zoom; the pointer names "
      "the patch and lamella under it and its distance to the design surface. Each lamella is "
      "drawn along its contact line, coloured as in the plan below; the design surface is grey. "
      "The data: deployed.json.</p>\n<style>";
  out += kViewStyle;
  out +=
      "</style>\n<div id=\"egg-view\"></div>\n<script type=\"application/json\" "
      "id=\"egg-view-data\">" +
      scriptSafe(viewJson) + "</script>\n<script>\n";
  out += reportViewerScript();
  return out + "\n</script>\n";
}

}  // namespace egg::pipeline
