// `egg bench pipeline` (see pipeline_bench.hpp).
#include "apps/commands/pipeline_bench.hpp"

#include "apps/commands/commands.hpp"
#include "apps/commands/pipeline.hpp"
#include "apps/commands/scene.hpp"
#include "core/errors.hpp"
#include "core/io/xml_text.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <numeric>

namespace egg::app {

std::vector<size_t> paretoFront(const std::vector<std::pair<double, double>>& points) {
  std::vector<size_t> order(points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return points[a].first < points[b].first || (points[a].first == points[b].first && points[a].second < points[b].second);
  });
  std::vector<size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i : order) {
    if (!std::isfinite(points[i].second) || points[i].second >= best) continue;  // beaten: as close and no faster
    front.push_back(i);
    best = points[i].second;
  }
  return front;
}

namespace {

// Table 3.3 of the thesis: RMSE and max error [m] at its sections and patch counts.
const std::map<std::string, std::pair<double, double>> kPaper{
    {"great_court", {0.143, 0.491}}, {"lilium", {0.242, 1.761}}, {"yas", {0.318, 1.141}}};

struct Row {
  std::string scene;
  double edgeFactor = 1.0, edgeLengthM = 0.0;
  int proxy = 0;
  double wallS = 0.0;
  int vertices = 0, patches = 0, failures = 0;
  double rmse = NAN, maxError = NAN, joinedRmse = NAN, joinedMax = NAN;
  bool converged = false, pareto = false;
  // The structure's error: joined when the joined run gave one, else patch by patch.
  double error() const { return std::isfinite(joinedRmse) ? joinedRmse : rmse; }
};

double number(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

std::string csvNumber(double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : ""; }

void writeCsv(const std::filesystem::path& file, const std::vector<Row>& rows) {
  std::ofstream out(file);
  out << "scene,edge_factor,edge_length_m,map_proxy_vertices,wall_s,vertices,patches,rmse_m,max_error_m,joined_rmse_m,"
         "joined_max_error_m,converged,failures,pareto,paper_rmse_m,paper_max_error_m\n";
  for (const auto& r : rows) {
    const auto paper = kPaper.find(r.scene);
    out << r.scene << ',' << csvNumber(r.edgeFactor) << ',' << csvNumber(r.edgeLengthM) << ',' << r.proxy << ',' << csvNumber(r.wallS) << ','
        << r.vertices << ',' << r.patches << ',' << csvNumber(r.rmse) << ',' << csvNumber(r.maxError) << ',' << csvNumber(r.joinedRmse) << ','
        << csvNumber(r.joinedMax) << ',' << (r.converged ? 1 : 0) << ',' << r.failures << ',' << (r.pareto ? 1 : 0) << ','
        << (paper == kPaper.end() ? "" : csvNumber(paper->second.first)) << ',' << (paper == kPaper.end() ? "" : csvNumber(paper->second.second))
        << '\n';
  }
  if (!out) throw IoError("cannot write " + file.string());
}

// RMSE against wall time (log scale), a colour per scene, its Pareto front joined, the paper's
// RMSE as a dashed line in the scene's colour.
void writeSvg(const std::filesystem::path& file, const std::vector<Row>& rows) {
  const double w = 760, h = 480, left = 70, right = 200, top = 30, bottom = 60;
  double tMin = std::numeric_limits<double>::infinity(), tMax = 0, eMax = 0;
  for (const auto& r : rows)
    if (std::isfinite(r.error()) && r.wallS > 0) tMin = std::min(tMin, r.wallS), tMax = std::max(tMax, r.wallS), eMax = std::max(eMax, r.error());
  for (const auto& [name, paper] : kPaper)
    if (std::any_of(rows.begin(), rows.end(), [&](const Row& r) { return r.scene == name; })) eMax = std::max(eMax, paper.first);
  if (!(tMax > 0)) tMin = 1, tMax = 10;
  const double l0 = std::floor(std::log10(tMin)), l1 = std::max(l0 + 1, std::ceil(std::log10(tMax)));
  eMax = eMax > 0 ? 1.1 * eMax : 1.0;
  const auto x = [&](double t) { return left + (std::log10(t) - l0) / (l1 - l0) * (w - left - right); };
  const auto y = [&](double e) { return h - bottom - e / eMax * (h - top - bottom); };
  const std::array<const char*, 6> colours{"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  std::vector<std::string> scenes;
  for (const auto& r : rows)
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  std::string svg = fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="12">)"
                                "\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
                                w, h);
  svg += fmt::format("<text x=\"{}\" y=\"18\" font-size=\"14\">egg bench pipeline: deployed grid against the design surface</text>\n", left);
  svg += fmt::format("<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"black\"/><line x1=\"{0}\" y1=\"{1}\" x2=\"{0}\" y2=\"{3}\" stroke=\"black\"/>\n",
                     left, h - bottom, w - right, top);
  for (double l = l0; l <= l1 + 1e-9; ++l)
    for (double m : {1.0, 2.0, 5.0}) {
      const double t = m * std::pow(10.0, l);
      if (t < std::pow(10.0, l0) || t > std::pow(10.0, l1) * 1.0001) continue;
      svg += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/><text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4:g}</text>\n",
                         x(t), h - bottom, top, h - bottom + 16, t);
    }
  for (int k = 0; k <= 5; ++k) {
    const double e = eMax * k / 5.0;
    svg += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#eee\"/><text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:.3g}</text>\n",
                       left, y(e), w - right, left - 6, y(e) + 4, e);
  }
  svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">wall time of the run [s] (log scale)</text>\n", 0.5 * (left + w - right), h - 18);
  svg += fmt::format("<text x=\"16\" y=\"{:.1f}\" transform=\"rotate(-90 16 {:.1f})\" text-anchor=\"middle\">RMSE [m] (joined structure, else patch by patch)</text>\n",
                     0.5 * (top + h - bottom), 0.5 * (top + h - bottom));
  for (size_t s = 0; s < scenes.size(); ++s) {
    const std::string colour = colours[s % colours.size()];
    std::vector<std::pair<double, double>> points;
    std::vector<const Row*> mine;
    for (const auto& r : rows)
      if (r.scene == scenes[s]) mine.push_back(&r), points.emplace_back(r.wallS, r.error());
    std::string front;
    for (size_t i : paretoFront(points)) front += fmt::format("{:.1f},{:.1f} ", x(points[i].first), y(points[i].second));
    if (!front.empty()) svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"/>\n", front, colour);
    for (const Row* r : mine)
      if (std::isfinite(r->error()) && r->wallS > 0)
        svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" fill=\"{}\" stroke=\"{}\" stroke-width=\"1.5\"><title>{} edge x{} proxy {}: {:.2f} s, RMSE {:.3f} m</title></circle>\n",
                           x(r->wallS), y(r->error()), r->pareto ? 5 : 3.5, r->pareto ? colour : "white", r->pareto ? "black" : colour, escapeXml(r->scene), r->edgeFactor,
                           r->proxy, r->wallS, r->error());
    if (const auto paper = kPaper.find(scenes[s]); paper != kPaper.end())
      svg += fmt::format("<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"{3}\" stroke-dasharray=\"6 4\"/>\n", left, y(paper->second.first),
                         w - right, colour);
    const double ly = top + 20 + 34.0 * s;
    svg += fmt::format("<circle cx=\"{}\" cy=\"{:.1f}\" r=\"5\" fill=\"{}\" stroke=\"black\"/><text x=\"{}\" y=\"{:.1f}\">{}</text>\n", w - right + 20,
                       ly, colour, w - right + 32, ly + 4, escapeXml(scenes[s]));
    if (kPaper.count(scenes[s]))
      svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\" font-size=\"10\">dashed: Table 3.3</text>\n", w - right + 32, ly + 17);
  }
  svg += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"10\">filled, joined: Pareto front (no run both faster and closer)</text>\n", left, h - 4);
  svg += "</svg>\n";
  std::ofstream out(file);
  out << svg;
  if (!out) throw IoError("cannot write " + file.string());
}

}  // namespace

int runPipelineBench(const PipelineBenchOptions& options) {
  if (options.edgeFactors.empty() || options.mapProxyVertices.empty()) throw InvalidInput("egg bench pipeline: no variants to run");
  for (double f : options.edgeFactors)
    if (!(f > 0 && f <= 20)) throw InvalidInput(fmt::format("egg bench pipeline: --edge-factors: {} is not in (0, 20]", f));
  for (int p : options.mapProxyVertices)
    if (p < 0 || p > 1000000) throw InvalidInput(fmt::format("egg bench pipeline: --map-proxy: {} is not in [0, 1000000]", p));
  // Every scene is read first: a bad one stops the bench before anything runs.
  std::vector<Scene> scenes;
  for (const auto& name : options.scenes) {
    const std::filesystem::path file = benchSceneFile(name);
    scenes.push_back(loadScene(file));
  }
  std::filesystem::create_directories(options.out / "runs");
  std::vector<Row> rows;
  if (!options.json)
    fmt::print("egg bench pipeline: each scene once per variant (edge length factor x map proxy), outputs [report]\n"
               "{:<14} {:>6} {:>7} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9} {:>5}   paper RMSE / max\n",
               "scene", "edge", "proxy", "vertices", "patches", "wall_s", "rmse_m", "max_m", "joined_m", "conv");
  for (const Scene& base : scenes) {
    for (double f : options.edgeFactors)
      for (int proxy : options.mapProxyVertices) {
        Scene scene = base;
        scene.surface.edge_length_m *= f;
        scene.grid.map_proxy_vertices = proxy;
        scene.outputs = {"report"};
        PipelineOptions run;
        run.out_dir = options.out / "runs" / fmt::format("{}-edge{:g}-proxy{}", scene.name, f, proxy);
        Row row;
        row.scene = scene.name;
        row.edgeFactor = f;
        row.edgeLengthM = scene.surface.edge_length_m;
        row.proxy = proxy;
        const auto started = std::chrono::steady_clock::now();
        const PipelineResult result = runPipeline(scene, run);
        row.wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        const auto& report = result.report;
        row.vertices = report.contains("surface") ? report["surface"].value("vertices", 0) : 0;
        row.patches = report.contains("patching") ? report["patching"].value("patches", 0) : 0;
        row.failures = static_cast<int>(result.failures.size());
        if (report.contains("simulation")) {
          const auto& sim = report["simulation"];
          row.rmse = number(sim, "rmse_m"), row.maxError = number(sim, "max_error_m");
          if (sim.contains("joined")) row.joinedRmse = number(sim["joined"], "rmse_m"), row.joinedMax = number(sim["joined"], "max_error_m");
          const bool joinedConverged = !sim.contains("joined") || !sim["joined"].is_object() || !sim["joined"].contains("converged") ||
                                       (sim["joined"]["converged"].is_boolean() && sim["joined"]["converged"].get<bool>());
          row.converged = sim.value("converged", false) && joinedConverged;
        }
        rows.push_back(row);
        if (!options.json) {
          const auto paper = kPaper.find(row.scene);
          fmt::print("{:<14} {:>6g} {:>7} {:>8} {:>8} {:>8.2f} {:>9.4f} {:>9.4f} {:>9.4f} {:>5}   {}\n", row.scene, f, proxy, row.vertices,
                     row.patches, row.wallS, row.rmse, row.maxError, row.joinedRmse, row.converged ? "yes" : "no",
                     paper == kPaper.end() ? std::string("-") : fmt::format("{:.3f} / {:.3f}", paper->second.first, paper->second.second));
        }
      }
  }
  // Each scene's Pareto front over its variants.
  for (const auto& scene : scenes) {
    std::vector<size_t> index;
    std::vector<std::pair<double, double>> points;
    for (size_t i = 0; i < rows.size(); ++i)
      if (rows[i].scene == scene.name) index.push_back(i), points.emplace_back(rows[i].wallS, rows[i].error());
    for (size_t k : paretoFront(points)) rows[index[k]].pareto = true;
  }
  writeCsv(options.out / "pipeline.csv", rows);
  writeSvg(options.out / "pipeline.svg", rows);
  if (options.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& r : rows)
      out.push_back({{"scene", r.scene}, {"edge_factor", r.edgeFactor}, {"map_proxy_vertices", r.proxy}, {"wall_s", r.wallS},
                     {"vertices", r.vertices}, {"patches", r.patches}, {"rmse_m", std::isfinite(r.rmse) ? nlohmann::json(r.rmse) : nlohmann::json()},
                     {"joined_rmse_m", std::isfinite(r.joinedRmse) ? nlohmann::json(r.joinedRmse) : nlohmann::json()},
                     {"converged", r.converged}, {"failures", r.failures}, {"pareto", r.pareto}});
    std::cout << out.dump(2) << "\n";
  } else {
    fmt::print("wrote {} and {}\n", (options.out / "pipeline.csv").string(), (options.out / "pipeline.svg").string());
  }
  return kExitOk;
}

void registerPipelineBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<PipelineBenchOptions>();
  auto* cmd = bench.add_subcommand("pipeline", "Error against run time over the whole job: each scene per variant of the mesh edge length and "
                                               "the maps' proxy size; CSV and SVG with the Pareto front, beside the paper's Table 3.3");
  cmd->add_option("scenes", args->scenes, "sample scenes (samples/<name>.json, from the repository root) or scene files");
  cmd->add_option("--edge-factors", args->edgeFactors, "factors on the scene's surface.edge_length_m")->delimiter(',');
  cmd->add_option("--map-proxy", args->mapProxyVertices, "grid.map_proxy_vertices values (0 = maps on the patch)")->delimiter(',');
  cmd->add_option("--out", args->out, "folder for pipeline.csv, pipeline.svg and the runs");
  cmd->add_flag("--json", args->json, "print the rows as JSON only");
  cmd->callback([args, &action] { action = [args] { return runPipelineBench(*args); }; });
}

}  // namespace egg::app
