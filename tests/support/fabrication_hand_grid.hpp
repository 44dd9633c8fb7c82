#pragma once
// Shared by the fabrication tests: a hand-checkable 3 x 3 grid and runners for the external
// readers (ezdxf, rsvg-convert, pdfinfo, admesh). A missing tool fails the test: install-deps.sh
// installs them.
#include "core/egg/grid.hpp"
#include "fabrication/options.hpp"
#include "tests/support/tool_run.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace egg::fabrication::testing {

// Three u members (rows, y = 0, 0.1, 0.2 m) and three v members (columns, x = 0, 0.1, 0.2 m) of a
// flat 0.2 m square, lifted to z = 0.5 m. Connection (i, j) sits at (0.1 j, 0.1 i); s_bar along u
// member i is 0.1 j, along v member j 0.1 i. Notches: (1,1) u +5 mm, v -3 mm (two slots);
// (1,0) u 0.4 mm (below min_notch: a plain hole); (0,1) u 2 mm on the boundary member u0 (dropped).
// Anchors at the four corners. `shiftXM` moves the spatial grid along x (a neighbouring patch).
inline EggGrid handGrid(double shiftXM = 0.0) {
  EggGrid g;
  for (int k = 0; k < 3; ++k) {
    GridMember u;
    u.family = Family::U;
    u.index = k;
    u.boundary = k != 1;
    u.planarStart = {0.0, 0.1 * k};
    u.planarEnd = {0.2, 0.1 * k};
    u.planarLength = u.spatialLength = 0.2;
    for (int s = 0; s <= 4; ++s) {
      u.spatial.emplace_back(shiftXM + 0.05 * s, 0.1 * k, 0.5);
      u.normals.emplace_back(0.0, 0.0, 1.0);
    }
    GridMember v = u;
    v.family = Family::V;
    v.planarStart = {0.1 * k, 0.0};
    v.planarEnd = {0.1 * k, 0.2};
    v.spatial.clear();
    for (int s = 0; s <= 4; ++s) v.spatial.emplace_back(shiftXM + 0.1 * k, 0.05 * s, 0.5);
    g.u.push_back(u);
    g.v.push_back(v);
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      GridConnection c;
      c.memberU = i;
      c.memberV = j;
      c.planar = {0.1 * j, 0.1 * i};
      c.spatial = {shiftXM + 0.1 * j, 0.1 * i, 0.5};
      c.sU = c.sBarU = 0.1 * j;
      c.sV = c.sBarV = 0.1 * i;
      c.onBoundary = i != 1 || j != 1;
      g.connections.push_back(c);
    }
  }
  auto at = [&](int i, int j) -> GridConnection& { return g.connections[i * 3 + j]; };
  at(1, 1).notchU = 0.005;
  at(1, 1).sU = 0.105;
  at(1, 1).notchV = -0.003;
  at(1, 1).sV = 0.097;
  at(1, 0).notchU = 0.0004;
  at(0, 1).notchU = 0.002;
  for (int k : {0, 2, 6, 8}) g.anchors.push_back({k, "corner"});
  g.maxNotch = 0.005;
  return g;
}

// The options the hand-checked numbers below assume (millimetres).
inline FabricationOptions handOptions() {
  FabricationOptions o;
  o.lamellaWidthMm = 10.0;
  o.lamellaThicknessMm = 1.0;
  o.material = "limewood";
  o.sheetMm = {500.0, 300.0};
  o.kerfMm = 0.5;
  o.marginMm = 5.0;
  o.boltDiameterMm = 3.0;
  o.minNotchMm = 1.0;
  o.stockLengthMm = 1000.0;
  o.endOverhangMm = 5.0;
  o.labelHeightMm = 3.0;
  o.stickerSheetMm = std::array<double, 2>{200.0, 100.0};
  o.supportBlockMm = 30.0;
  return o;
}

using egg::test::haveTool;
using egg::test::runTool;
using egg::test::ToolRun;

// The scratch folders of this test program, removed when its tests end (kept with
// EGG_KEEP_TEST_FILES set, to look at what a test wrote).
class ScratchFolders : public ::testing::Environment {
 public:
  static ScratchFolders& instance() {
    static ScratchFolders* const folders = [] {
      auto* f = new ScratchFolders;
      ::testing::AddGlobalTestEnvironment(f);  // gtest owns it
      return f;
    }();
    return *folders;
  }
  void add(const std::filesystem::path& dir) { dirs_.push_back(dir); }
  void TearDown() override {
    if (std::getenv("EGG_KEEP_TEST_FILES")) return;
    std::error_code ignored;
    for (const auto& dir : dirs_) std::filesystem::remove_all(dir, ignored);
  }

 private:
  std::vector<std::filesystem::path> dirs_;
};

// A fresh, empty folder for one test (the process id keeps parallel runs of other checkouts
// apart), removed when the test program ends.
inline std::filesystem::path scratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("egg_fabrication_test_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ScratchFolders::instance().add(dir);
  return dir;
}

// Reads a DXF with ezdxf: {"audit_errors": n, "audit_fixes": n (what the audit had to repair),
// "insunits": u, "version": "AC1015", "layers": [...], "entities": [{"type", "layer", ...}]}
// (circles: centre, radius; lwpolylines: points [x, y, bulge], closed; text: text, insert, align,
// halign, valign, height).
inline nlohmann::json readDxf(const std::filesystem::path& path) {
  const std::string script = R"PY(
import json, sys, ezdxf
doc = ezdxf.readfile(sys.argv[1])
auditor = doc.audit()
out = {"audit_errors": len(auditor.errors), "audit_fixes": len(auditor.fixes), "insunits": doc.header.get("$INSUNITS", 0),
       "version": doc.dxfversion, "layers": [l.dxf.name for l in doc.layers], "entities": [],
       "layer_colours": {l.dxf.name: l.dxf.color for l in doc.layers}}
for e in doc.modelspace():
    d = {"type": e.dxftype(), "layer": e.dxf.layer}
    if e.dxftype() == "CIRCLE":
        d["centre"] = [e.dxf.center.x, e.dxf.center.y]; d["radius"] = e.dxf.radius
    elif e.dxftype() == "LWPOLYLINE":
        d["points"] = [[p[0], p[1], p[4]] for p in e.get_points()]; d["closed"] = bool(e.closed)
    elif e.dxftype() == "POLYLINE":
        d["points"] = [[v.dxf.location.x, v.dxf.location.y, v.dxf.bulge] for v in e.vertices]; d["closed"] = bool(e.is_closed)
    elif e.dxftype() == "TEXT":
        d["text"] = e.dxf.text; d["insert"] = [e.dxf.insert.x, e.dxf.insert.y]
        d["align"] = [e.dxf.align_point.x, e.dxf.align_point.y] if e.dxf.hasattr("align_point") else None
        d["halign"] = e.dxf.halign; d["valign"] = e.dxf.valign; d["height"] = e.dxf.height
    out["entities"].append(d)
print(json.dumps(out))
)PY";
  const auto scriptPath = path.parent_path() / "read_dxf.py";
  FILE* f = fopen(scriptPath.c_str(), "w");
  fputs(script.c_str(), f);
  fclose(f);
  const ToolRun run = runTool("/usr/bin/python3 " + scriptPath.string() + " " + path.string());
  if (run.status != 0) {
    ADD_FAILURE() << "ezdxf could not read " << path << ": " << run.output;
    return nlohmann::json::object();
  }
  return nlohmann::json::parse(run.output.substr(run.output.find('{')));
}

// Reads back what our SVG writer writes, in sheet millimetres with y up again (y = height - y_svg):
// {"height": h, "circles": [[x, y, r]], "slots": [[x0, y0, ...corner points]], "texts": [[x, y,
// size, text]], "polylines": [[x0, y0, x1, y1, ...]]}.
inline nlohmann::json readSvg(const std::string& svg) {
  nlohmann::json out{{"circles", nlohmann::json::array()},
                     {"slots", nlohmann::json::array()},
                     {"texts", nlohmann::json::array()},
                     {"polylines", nlohmann::json::array()}};
  std::smatch m;
  const std::regex viewBox(R"re(viewBox="0 0 ([-0-9.]+) ([-0-9.]+)")re");
  if (!std::regex_search(svg, m, viewBox)) return out;
  const double h = std::stod(m[2]);
  out["height"] = h;
  const std::regex circle(R"re(<circle cx="([-0-9.]+)" cy="([-0-9.]+)" r="([-0-9.]+)")re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), circle); it != std::sregex_iterator();
       ++it) {
    out["circles"].push_back({std::stod((*it)[1]), h - std::stod((*it)[2]), std::stod((*it)[3])});
  }
  // Attribute values are found with string searches, not std::regex: libstdc++'s regex recurses
  // once per character of `[^"]*`, and a label's stroke path is thousands of characters (a stack
  // overflow under AddressSanitizer's larger frames). attribute(from, prefix) is the value after
  // the next `prefix` (which ends in the opening quote) and where it ends, or npos.
  struct Value {
    size_t begin = std::string::npos, end = std::string::npos;
  };
  const auto attribute = [&svg](size_t from, const std::string& prefix) {
    Value v;
    const size_t start = svg.find(prefix, from);
    if (start == std::string::npos) return v;
    const size_t end = svg.find('"', start + prefix.size());
    if (end != std::string::npos) v = {start + prefix.size(), end};
    return v;
  };
  const std::regex number(R"re(-?[0-9]+\.[0-9]+)re");
  const auto numbers = [&number](const std::string& d) {
    std::vector<double> v;
    for (auto n = std::sregex_iterator(d.begin(), d.end(), number); n != std::sregex_iterator();
         ++n)
      v.push_back(std::stod((*n)[0]));
    return v;
  };
  // Single-stroke texts: the text in the path's title, its anchor (y up) and height in its desc.
  const std::regex desc(R"re(^anchor ([-0-9.]+) ([-0-9.]+) height ([-0-9.]+) [a-z]+$)re");
  for (Value v = attribute(0, "<path class=\"text\" d=\""); v.end != std::string::npos;
       v = attribute(v.end, "<path class=\"text\" d=\"")) {
    const size_t close = svg.find('>', v.end), title = svg.find("><title>", v.end);
    const size_t titleEnd = svg.find("</title><desc>", v.end), descEnd = svg.find("</desc>", v.end);
    if (title != close || titleEnd == std::string::npos || descEnd == std::string::npos) continue;
    const std::string anchor = svg.substr(titleEnd + 14, descEnd - titleEnd - 14);
    std::smatch d;
    if (!std::regex_match(anchor, d, desc)) continue;
    out["texts"].push_back({std::stod(d[1]), std::stod(d[2]), std::stod(d[3]),
                            svg.substr(title + 8, titleEnd - title - 8)});
  }
  for (Value v = attribute(0, "<path d=\""); v.end != std::string::npos;
       v = attribute(v.end, "<path d=\"")) {
    // M x y L x y A r r 0 0 0 x y L x y A r r 0 0 0 x y Z: keep the four corners.
    const std::vector<double> p = numbers(svg.substr(v.begin, v.end - v.begin));
    if (p.size() < 12) continue;
    out["slots"].push_back({p[0], h - p[1], p[2], h - p[3], p[6], h - p[7], p[8], h - p[9]});
  }
  // Polygons and polylines in document order.
  for (size_t from = 0;;) {
    const Value a = attribute(from, "<polygon points=\""),
                b = attribute(from, "<polyline points=\"");
    const Value v = a.begin < b.begin ? a : b;
    if (v.end == std::string::npos) break;
    from = v.end;
    std::vector<double> p = numbers(svg.substr(v.begin, v.end - v.begin));
    for (size_t k = 1; k < p.size(); k += 2) p[k] = h - p[k];
    out["polylines"].push_back(p);
  }
  return out;
}

inline std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace egg::fabrication::testing
