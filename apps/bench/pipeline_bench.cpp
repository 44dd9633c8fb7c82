// `egg bench pipeline` (see pipeline_bench.hpp).
#include "apps/bench/pipeline_bench.hpp"
#include "core/timing.hpp"

#include "apps/egg/commands.hpp"
#include "apps/egg/progress.hpp"
#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/xml_text.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/scene.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>

namespace egg::app {
using namespace egg::pipeline;

std::vector<size_t> paretoFront(const std::vector<std::pair<double, double>>& points) {
  std::vector<size_t> order(points.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return points[a].first < points[b].first ||
           (points[a].first == points[b].first && points[a].second < points[b].second);
  });
  std::vector<size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i : order) {
    if (!std::isfinite(points[i].second) || points[i].second >= best)
      continue;  // beaten: as close and no faster
    front.push_back(i);
    best = points[i].second;
  }
  return front;
}

namespace {

// Table 3.3 of the thesis: RMSE and max error [m] at its sections and patch counts.
struct PaperFigures {
  double rmseM, maxErrorM, widthM, thicknessM;
  int patches;
};
const std::map<std::string, PaperFigures> kPaper{{"great_court", {0.143, 0.491, 0.25, 0.04, 4}},
                                                 {"lilium", {0.242, 1.761, 0.50, 0.05, 16}},
                                                 {"yas", {0.318, 1.141, 0.40, 0.05, 16}}};

struct Row {
  std::string scene, varied;
  double edgeFactor = 1.0, edgeLengthM = 0.0, mapTolerance = NAN, newtonTolerance = NAN,
         spacingFactor = NAN, widthM = NAN, thicknessM = NAN;
  int proxy = 0;
  double wallS = 0.0;
  int vertices = 0, patches = 0, failures = 0;
  double rmse = NAN, maxError = NAN, joinedRmse = NAN, joinedMax = NAN;
  bool converged = false, pareto = false;
  // The structure's error: joined when the joined run gave one, else patch by patch.
  bool joined() const { return std::isfinite(joinedRmse); }
  double error() const { return joined() ? joinedRmse : rmse; }
  double maxOf() const { return joined() ? joinedMax : maxError; }
};

double number(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN;
}

std::string csvNumber(double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : ""; }

void writeCsv(const std::filesystem::path& file, const std::vector<Row>& rows) {
  // Atomically, never through a link or into a FIFO (writeFileAtomically's checks; issue 40).
  std::ostringstream out;
  out << "scene,edge_factor,edge_length_m,map_proxy_vertices,wall_s,vertices,patches,rmse_m,max_"
         "error_m,joined_rmse_m,"
         "joined_max_error_m,converged,failures,pareto,paper_rmse_m,paper_max_error_m,varied,map_"
         "tolerance_relative,"
         "newton_tolerance,member_spacing_factor,lamella_width_m,lamella_thickness_m,paper_"
         "patches\n";
  for (const auto& r : rows) {
    const auto paper = kPaper.find(r.scene);
    const bool known = paper != kPaper.end();
    out << r.scene << ',' << csvNumber(r.edgeFactor) << ',' << csvNumber(r.edgeLengthM) << ','
        << r.proxy << ',' << csvNumber(r.wallS) << ',' << r.vertices << ',' << r.patches << ','
        << csvNumber(r.rmse) << ',' << csvNumber(r.maxError) << ',' << csvNumber(r.joinedRmse)
        << ',' << csvNumber(r.joinedMax) << ',' << (r.converged ? 1 : 0) << ',' << r.failures << ','
        << (r.pareto ? 1 : 0) << ',' << (known ? csvNumber(paper->second.rmseM) : "") << ','
        << (known ? csvNumber(paper->second.maxErrorM) : "") << ',' << r.varied << ','
        << csvNumber(r.mapTolerance) << ',' << csvNumber(r.newtonTolerance) << ','
        << csvNumber(r.spacingFactor) << ',' << csvNumber(r.widthM) << ','
        << csvNumber(r.thicknessM) << ',' << (known ? std::to_string(paper->second.patches) : "")
        << '\n';
  }
  writeFileAtomically(file, out.str());
}

const std::array<const char*, 6> kColours{"#1f77b4", "#d62728", "#2ca02c",
                                          "#9467bd", "#ff7f0e", "#8c564b"};

// One panel of the plot: `error(row)` against wall time (log scale), a colour per scene, its Pareto
// front joined, the paper's figure as a dashed line in the scene's colour. `top` offsets it.
std::string panelSvg(const std::vector<Row>& rows, const std::vector<std::string>& scenes,
                     double top, const std::string& what,
                     const std::function<double(const Row&)>& error,
                     const std::function<double(const PaperFigures&)>& paperError) {
  const double w = 760, h = 420, left = 70, right = 200, margin = 20, bottom = 50;
  double tMin = std::numeric_limits<double>::infinity(), tMax = 0, eMax = 0;
  for (const auto& r : rows)
    if (std::isfinite(error(r)) && r.wallS > 0)
      tMin = std::min(tMin, r.wallS), tMax = std::max(tMax, r.wallS),
      eMax = std::max(eMax, error(r));
  for (const auto& [name, paper] : kPaper)
    if (std::find(scenes.begin(), scenes.end(), name) != scenes.end())
      eMax = std::max(eMax, paperError(paper));
  if (!(tMax > 0)) tMin = 1, tMax = 10;
  const double l0 = std::floor(std::log10(tMin)),
               l1 = std::max(l0 + 1, std::ceil(std::log10(tMax)));
  eMax = eMax > 0 ? 1.1 * eMax : 1.0;
  const double y0 = top + margin, y1 = top + h - bottom;
  const auto x = [&](double t) {
    return left + (std::log10(t) - l0) / (l1 - l0) * (w - left - right);
  };
  const auto y = [&](double e) { return y1 - e / eMax * (y1 - y0); };
  std::string svg = fmt::format(
      "<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"black\"/><line x1=\"{0}\" "
      "y1=\"{1}\" x2=\"{0}\" y2=\"{3}\" stroke=\"black\"/>\n",
      left, y1, w - right, y0);
  for (double l = l0; l <= l1 + 1e-9; ++l)
    for (double m : {1.0, 2.0, 5.0}) {
      const double t = m * std::pow(10.0, l);
      if (t < std::pow(10.0, l0) || t > std::pow(10.0, l1) * 1.0001) continue;
      svg += fmt::format(
          "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/><text "
          "x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4:g}</text>\n",
          x(t), y1, y0, y1 + 16, t);
    }
  for (int k = 0; k <= 5; ++k) {
    const double e = eMax * k / 5.0;
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#eee\"/><text "
        "x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:.3g}</text>\n",
        left, y(e), w - right, left - 6, y(e) + 4, e);
  }
  svg += fmt::format(
      "<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">wall time of the run [s] (log "
      "scale)</text>\n",
      0.5 * (left + w - right), y1 + 34);
  svg += fmt::format(
      "<text x=\"16\" y=\"{0:.1f}\" transform=\"rotate(-90 16 {0:.1f})\" "
      "text-anchor=\"middle\">{1} [m]</text>\n",
      0.5 * (y0 + y1), escapeXml(what));
  for (size_t s = 0; s < scenes.size(); ++s) {
    const std::string colour = kColours[s % kColours.size()];
    std::vector<std::pair<double, double>> points;
    std::vector<const Row*> mine;
    for (const auto& r : rows)
      if (r.scene == scenes[s]) mine.push_back(&r), points.emplace_back(r.wallS, error(r));
    std::string front;
    std::vector<char> onFront(points.size(), 0);
    for (size_t i : paretoFront(points))
      front += fmt::format("{:.1f},{:.1f} ", x(points[i].first), y(points[i].second)),
          onFront[i] = 1;
    if (!front.empty())
      svg +=
          fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"2\"/>\n",
                      front, colour);
    for (size_t i = 0; i < mine.size(); ++i) {
      const Row& r = *mine[i];
      if (!std::isfinite(error(r)) || !(r.wallS > 0)) continue;
      svg += fmt::format(
          "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" fill=\"{}\" stroke=\"{}\" "
          "stroke-width=\"1.5\"><title>{} ({}): {:.2f} s, {:.3f} m{}</title></circle>\n",
          x(r.wallS), y(error(r)), onFront[i] ? 5 : 3.5, onFront[i] ? colour : "white",
          onFront[i] ? "black" : colour, escapeXml(r.scene), escapeXml(r.varied), r.wallS, error(r),
          r.joined() ? "" : " (patch by patch)");
    }
    if (const auto paper = kPaper.find(scenes[s]); paper != kPaper.end())
      svg += fmt::format(
          "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"{3}\" "
          "stroke-dasharray=\"6 4\"/>\n",
          left, y(paperError(paper->second)), w - right, colour);
    const double ly = y0 + 20 + 34.0 * s;
    svg += fmt::format(
        "<circle cx=\"{}\" cy=\"{:.1f}\" r=\"5\" fill=\"{}\" stroke=\"black\"/><text x=\"{}\" "
        "y=\"{:.1f}\">{}</text>\n",
        w - right + 20, ly, colour, w - right + 32, ly + 4, escapeXml(scenes[s]));
    if (kPaper.count(scenes[s]))
      svg += fmt::format("<text x=\"{}\" y=\"{:.1f}\" font-size=\"10\">dashed: Table 3.3</text>\n",
                         w - right + 32, ly + 17);
  }
  return svg;
}

// RMSE (top) and max error (bottom) against wall time, each with its own Pareto fronts.
void writeSvg(const std::filesystem::path& file, const std::vector<Row>& rows) {
  std::vector<std::string> scenes;
  for (const auto& r : rows)
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  const double w = 760, h = 2 * 420 + 50;
  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="12">)"
      "\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      w, h);
  svg +=
      "<text x=\"70\" y=\"18\" font-size=\"14\">egg bench pipeline: deployed grid against the "
      "design surface "
      "(joined structure, else patch by patch)</text>\n";
  svg += panelSvg(
      rows, scenes, 20, "RMSE", [](const Row& r) { return r.error(); },
      [](const PaperFigures& p) { return p.rmseM; });
  svg += panelSvg(
      rows, scenes, 440, "max error", [](const Row& r) { return r.maxOf(); },
      [](const PaperFigures& p) { return p.maxErrorM; });
  svg += fmt::format(
      "<text x=\"70\" y=\"{}\" font-size=\"10\">filled, joined: Pareto front (no run both faster "
      "and closer); "
      "hover a point for the knob it varies</text>\n",
      h - 8);
  svg += "</svg>\n";
  writeFileAtomically(file, svg);
}

std::string variantName(const std::string& scene, const PipelineVariant& v, size_t index) {
  return fmt::format("{}-{:02d}-{}", scene, index, v.varied);
}

}  // namespace

constexpr int kMaxPipelineVariants = 1000;

std::vector<PipelineVariant> pipelineVariants(const PipelineBenchOptions& o,
                                              const std::string& sample) {
  const auto first = [](const auto& list, auto fallback) {
    return list.empty() ? fallback : list.front();
  };
  PipelineVariant base;
  base.edgeFactor = first(o.edgeFactors, 1.0);
  base.mapProxyVertices = first(o.mapProxyVertices, -1);
  base.mapTolerance = first(o.mapTolerances, -1.0);
  base.newtonTolerance = first(o.newtonTolerances, -1.0);
  base.spacingFactor = first(o.spacingFactors, -1.0);
  std::vector<PipelineVariant> out;
  if (o.product) {
    const auto orOne = [](const auto& list, auto fallback) {
      return list.empty() ? std::vector<decltype(fallback)>{fallback} : list;
    };
    // Each variant is a whole run per sample: the product of long lists was unbounded (issue 40).
    double count = 1.0;
    for (size_t n : {o.edgeFactors.size(), o.mapProxyVertices.size(), o.mapTolerances.size(),
                     o.newtonTolerances.size(), o.spacingFactors.size()})
      count *= static_cast<double>(std::max<size_t>(n, 1));
    if (count > kMaxPipelineVariants)
      throw InvalidInput(fmt::format(
          "--product: {:.0f} combinations of --edge-factors, --map-proxy, --map-tolerances, "
          "--newton-tolerances and --spacing-factors, more than {} runs per sample; give "
          "shorter lists, or leave out --product to vary one knob at a time",
          count, kMaxPipelineVariants));
    for (double e : orOne(o.edgeFactors, 1.0))
      for (int p : orOne(o.mapProxyVertices, -1))
        for (double mt : orOne(o.mapTolerances, -1.0))
          for (double nt : orOne(o.newtonTolerances, -1.0))
            for (double sf : orOne(o.spacingFactors, -1.0)) {
              PipelineVariant v{e, p, mt, nt, sf};
              v.varied = out.empty() ? "base" : "product";
              out.push_back(v);
            }
  } else {
    out.push_back(base);
    // Each knob alone: its values after the first, the others at the base.
    const auto vary = [&](const auto& values, const auto& set) {
      for (size_t i = 1; i < values.size(); ++i) {
        PipelineVariant v = base;
        v.varied = set(v, values[i]);
        out.push_back(v);
      }
    };
    vary(o.edgeFactors, [](PipelineVariant& v, double f) {
      return v.edgeFactor = f, fmt::format("edge_x{:g}", f);
    });
    vary(o.mapProxyVertices, [](PipelineVariant& v, int p) {
      return v.mapProxyVertices = p, fmt::format("proxy_{}", p);
    });
    // The row tolerance acts only on maps computed on the patch itself
    // (grid.map_tolerance_relative).
    vary(o.mapTolerances, [](PipelineVariant& v, double t) {
      return v.mapTolerance = t, v.mapProxyVertices = 0, fmt::format("map_tol_{:g}", t);
    });
    vary(o.newtonTolerances, [](PipelineVariant& v, double t) {
      return v.newtonTolerance = t, fmt::format("newton_tol_{:g}", t);
    });
    vary(o.spacingFactors, [](PipelineVariant& v, double f) {
      return v.spacingFactor = f, fmt::format("spacing_x{:g}", f);
    });
  }
  if (o.paperSection)
    if (const auto paper = kPaper.find(sample); paper != kPaper.end()) {
      PipelineVariant v = base;
      v.widthM = paper->second.widthM, v.thicknessM = paper->second.thicknessM;
      v.varied = fmt::format("paper_section_{:g}x{:g}cm", 100 * v.widthM, 100 * v.thicknessM);
      out.push_back(v);
    }
  return out;
}

int runPipelineBench(const PipelineBenchOptions& options) {
  if (options.edgeFactors.empty() && options.mapProxyVertices.empty() &&
      options.mapTolerances.empty() && options.newtonTolerances.empty() &&
      options.spacingFactors.empty() && !options.paperSection)
    throw InvalidInput("egg bench pipeline: no variants to run");
  for (double f : options.edgeFactors)
    if (!(f > 0 && f <= 20))
      throw InvalidInput(
          fmt::format("egg bench pipeline: --edge-factors: {} is not in (0, 20]", f));
  for (int p : options.mapProxyVertices)
    if (p < 0 || p > 1000000 || (p > 0 && p < 8))
      throw InvalidInput(
          fmt::format("egg bench pipeline: --map-proxy: {} is not 0 or in [8, 1000000]", p));
  for (double t : options.mapTolerances)
    if (!(t >= 0 && t <= 0.1))
      throw InvalidInput(
          fmt::format("egg bench pipeline: --map-tolerances: {} is not in [0, 0.1]", t));
  for (double t : options.newtonTolerances)
    if (!(t >= 1e-16 && t <= 1e-2))
      throw InvalidInput(
          fmt::format("egg bench pipeline: --newton-tolerances: {} is not in [1e-16, 1e-2]", t));
  for (double f : options.spacingFactors)
    if (!(f >= 2 && f <= 1000))
      throw InvalidInput(
          fmt::format("egg bench pipeline: --spacing-factors: {} is not in [2, 1000]", f));
  // Every scene is read first: a bad one stops the bench before anything runs.
  std::vector<Scene> scenes;
  std::vector<std::vector<PipelineVariant>> variants;
  size_t total = 0;
  for (const auto& name : options.scenes) {
    scenes.push_back(loadScene(benchSceneFile(name)));
    variants.push_back(pipelineVariants(options, scenes.back().name));
    total += variants.back().size();
  }
  std::filesystem::create_directories(options.out / "runs");
  std::vector<Row> rows;
  if (!options.json)
    fmt::print(
        "egg bench pipeline: each scene once per variant (a knob varied from the first value of "
        "each list), outputs [report]\n"
        "{:<12} {:<24} {:>8} {:>7} {:>8} {:>9} {:>9} {:>9} {:>9} {:>5}   paper RMSE / max "
        "(patches)\n",
        "scene", "varied", "vertices", "patches", "wall_s", "rmse_m", "max_m", "joined_m",
        "j_max_m", "conv");
  ProgressLine bar(options.progress);
  for (size_t s = 0; s < scenes.size(); ++s) {
    const Scene& base = scenes[s];
    for (size_t k = 0; k < variants[s].size(); ++k) {
      const PipelineVariant& v = variants[s][k];
      Scene scene = base;
      scene.surface.edgeLengthM *= v.edgeFactor;
      if (v.mapProxyVertices >= 0) scene.design().maps.proxyVertices = v.mapProxyVertices;
      if (v.mapTolerance >= 0) scene.design().maps.toleranceRelative = v.mapTolerance;
      if (v.newtonTolerance > 0) scene.simulation.rods.solver.tolerance = v.newtonTolerance;
      if (v.spacingFactor > 0) scene.design().members.spacingFactor = v.spacingFactor;
      if (v.widthM > 0) scene.lamella.widthM = v.widthM, scene.lamella.thicknessM = v.thicknessM;
      scene.outputs = {"report"};
      PipelineOptions run;
      run.outDir = options.out / "runs" / variantName(scene.name, v, k);
      const std::string label =
          fmt::format("{} {} ({}/{})", scene.name, v.varied, rows.size() + 1, total);
      bar.update(static_cast<double>(rows.size()) / static_cast<double>(total), label);
      if (bar.shown())
        run.progress = [&](const std::string& stage, double fraction) {
          bar.update((static_cast<double>(rows.size()) + fraction) / static_cast<double>(total),
                     label + " " + stage);
        };
      Row row;
      row.scene = scene.name;
      row.varied = v.varied;
      row.edgeFactor = v.edgeFactor;
      row.edgeLengthM = scene.surface.edgeLengthM;
      row.proxy = scene.design().maps.proxyVertices;
      row.mapTolerance = scene.design().maps.toleranceRelative;
      row.newtonTolerance = scene.simulation.rods.solver.tolerance;
      row.spacingFactor = scene.design().members.spacingFactor;
      row.widthM = scene.lamella.widthM, row.thicknessM = scene.lamella.thicknessM;
      const Stopwatch watch;
      PipelineResult result;
      try {
        result = runPipeline(scene, run);
      } catch (const InvalidInput& e) {
        // A knob can take a scene out of its own bounds (a coarser mesh measures a given block
        // grid's cells larger): that variant is a failed row with the reason, the others still run.
        row.wallS = watch.seconds();
        row.failures = 1;
        rows.push_back(row);
        bar.finish();
        if (!options.json)
          fmt::print("{:<12} {:<24} not run: {}\n", row.scene, row.varied, e.what());
        std::fflush(stdout);
        continue;
      }
      row.wallS = watch.seconds();
      const auto& report = result.report;
      row.vertices = report.contains("surface") ? report["surface"].value("vertices", 0) : 0;
      row.patches = report.contains("patching") ? report["patching"].value("patches", 0) : 0;
      row.failures = static_cast<int>(result.failures.size());
      if (report.contains("simulation")) {
        const auto& sim = report["simulation"];
        row.rmse = number(sim, "rmse_m"), row.maxError = number(sim, "max_error_m");
        if (sim.contains("joined"))
          row.joinedRmse = number(sim["joined"], "rmse_m"),
          row.joinedMax = number(sim["joined"], "max_error_m");
        const bool joinedConverged =
            !sim.contains("joined") || !sim["joined"].is_object() ||
            !sim["joined"].contains("converged") ||
            (sim["joined"]["converged"].is_boolean() && sim["joined"]["converged"].get<bool>());
        row.converged = sim.value("converged", false) && joinedConverged;
      }
      rows.push_back(row);
      if (!options.json) {
        bar.finish();
        const auto paper = kPaper.find(row.scene);
        fmt::print(
            "{:<12} {:<24} {:>8} {:>7} {:>8.2f} {:>9.4f} {:>9.4f} {:>9.4f} {:>9.4f} {:>5}   {}\n",
            row.scene, row.varied, row.vertices, row.patches, row.wallS, row.rmse, row.maxError,
            row.joinedRmse, row.joinedMax, row.converged ? "yes" : "no",
            paper == kPaper.end() ? std::string("-")
                                  : fmt::format("{:.3f} / {:.3f} ({})", paper->second.rmseM,
                                                paper->second.maxErrorM, paper->second.patches));
        std::fflush(stdout);
      }
    }
  }
  bar.finish();
  // Each scene's Pareto front (RMSE against time) over its variants.
  for (const auto& scene : scenes) {
    std::vector<size_t> index;
    std::vector<std::pair<double, double>> points;
    for (size_t i = 0; i < rows.size(); ++i)
      if (rows[i].scene == scene.name && std::isfinite(rows[i].error()))
        index.push_back(i), points.emplace_back(rows[i].wallS, rows[i].error());
    for (size_t k : paretoFront(points)) rows[index[k]].pareto = true;
  }
  writeCsv(options.out / "pipeline.csv", rows);
  writeSvg(options.out / "pipeline.svg", rows);
  if (options.json) {
    const auto optionalNumber = [](double x) {
      return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json();
    };
    nlohmann::json out = nlohmann::json::array();
    for (const auto& r : rows)
      out.push_back({{"scene", r.scene},
                     {"varied", r.varied},
                     {"edge_factor", r.edgeFactor},
                     {"map_proxy_vertices", r.proxy},
                     {"map_tolerance_relative", r.mapTolerance},
                     {"newton_tolerance", r.newtonTolerance},
                     {"member_spacing_factor", r.spacingFactor},
                     {"lamella_width_m", r.widthM},
                     {"lamella_thickness_m", r.thicknessM},
                     {"wall_s", r.wallS},
                     {"vertices", r.vertices},
                     {"patches", r.patches},
                     {"rmse_m", optionalNumber(r.rmse)},
                     {"max_error_m", optionalNumber(r.maxError)},
                     {"joined_rmse_m", optionalNumber(r.joinedRmse)},
                     {"joined_max_error_m", optionalNumber(r.joinedMax)},
                     {"converged", r.converged},
                     {"failures", r.failures},
                     {"pareto", r.pareto}});
    std::cout << out.dump(2) << "\n";
  } else {
    fmt::print("wrote {} and {}\n", (options.out / "pipeline.csv").string(),
               (options.out / "pipeline.svg").string());
  }
  return kExitOk;
}

void registerPipelineBench(CLI::App& bench, Action& action) {
  auto args = std::make_shared<PipelineBenchOptions>();
  auto* cmd = bench.add_subcommand(
      "pipeline",
      "Error against run time over the whole job: each scene per variant of the mesh edge length, "
      "the maps' "
      "proxy size and tolerance, the Newton tolerance, the member spacing and the paper's lamella "
      "section; CSV and SVG (RMSE and max error against time) with the Pareto front, beside Table "
      "3.3");
  cmd->add_option("scenes", args->scenes,
                  "sample scenes (samples/<name>.json, from the repository root) or scene files");
  cmd->add_option("--edge-factors", args->edgeFactors,
                  "factors on the scene's surface.edge_length_m")
      ->delimiter(',');
  cmd->add_option("--map-proxy", args->mapProxyVertices,
                  "grid.map_proxy_vertices values (0 = maps on the patch)")
      ->delimiter(',');
  cmd->add_option("--map-tolerances", args->mapTolerances,
                  "grid.map_tolerance_relative values (their runs use map proxy 0)")
      ->delimiter(',');
  cmd->add_option("--newton-tolerances", args->newtonTolerances,
                  "simulation.newton_tolerance values")
      ->delimiter(',');
  cmd->add_option("--spacing-factors", args->spacingFactors,
                  "grid.member_spacing_factor values: members' target spacing in lamella widths "
                  "(members per family)")
      ->delimiter(',');
  cmd->add_flag("!--no-paper-section", args->paperSection,
                "skip the run of each sample at Table 3.3's lamella section");
  cmd->add_flag("--product", args->product,
                "every combination of the values instead of one knob at a time");
  cmd->add_option("--out", args->out, "folder for pipeline.csv, pipeline.svg and the runs");
  cmd->add_flag("--json", args->json, "print the rows as JSON only");
  cmd->callback([args, &action] {
    args->progress = !args->json;
    action = [args] { return runPipelineBench(*args); };
  });
}

}  // namespace egg::app
