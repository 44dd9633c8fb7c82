// `egg sweep --collect DIR` (see sweep.hpp): one row per variant of DIR/variants.csv, a missing or
// failed run listed as such, and a Pareto plot of the structure's error against its mass.
#include "apps/bench/pipeline_bench.hpp"
#include "apps/bench/sweep.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/xml_text.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

namespace egg::app {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
        out.back() += '"', ++i;
      else if (c == '"')
        quoted = false;
      else
        out.back() += c;
    } else if (c == '"')
      quoted = true;
    else if (c == ',')
      out.emplace_back();
    else
      out.back() += c;
  }
  return out;
}

std::string field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

double jsonNumber(const json& j, const json::json_pointer& p) {
  return j.contains(p) && j[p].is_number() ? j[p].get<double>() : NAN;
}
std::string csvCell(double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : ""; }

struct SweepRow {
  std::string variant, status;
  std::vector<std::string> values;
  double patches = NAN, joinedRmse = NAN, joinedMax = NAN, rmse = NAN, maxError = NAN, mass = NAN,
         stress = NAN, lamellas = NAN, wall = NAN;
  bool pareto = false;
  // The structure's error: joined when the joined run gave one, else patch by patch (as egg bench
  // pipeline).
  double error() const { return std::isfinite(joinedRmse) ? joinedRmse : rmse; }
};

// Error against mass, linear axes, the front joined and filled (pipeline_bench's paretoFront).
std::string svgOf(const std::vector<SweepRow>& rows) {
  const double w = 760, h = 480, left = 70, right = 40, top = 30, bottom = 60;
  double mMin = std::numeric_limits<double>::infinity(), mMax = 0, eMax = 0;
  for (const auto& r : rows)
    if (std::isfinite(r.error()) && std::isfinite(r.mass))
      mMin = std::min(mMin, r.mass), mMax = std::max(mMax, r.mass),
      eMax = std::max(eMax, r.error());
  if (!(mMax > 0)) mMin = 0, mMax = 1;
  if (mMax - mMin < 1e-9 * std::max(1.0, mMax))
    mMin -= 0.5 * std::max(1.0, mMin * 0.1), mMax += 0.5 * std::max(1.0, mMax * 0.1);
  const double pad = 0.05 * (mMax - mMin);
  mMin -= pad, mMax += pad;
  eMax = eMax > 0 ? 1.1 * eMax : 1.0;
  const auto x = [&](double m) { return left + (m - mMin) / (mMax - mMin) * (w - left - right); };
  const auto y = [&](double e) { return h - bottom - e / eMax * (h - top - bottom); };
  std::string svg = fmt::format(
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="12">)"
      "\n<rect width=\"{0}\" height=\"{1}\" fill=\"white\"/>\n",
      w, h);
  svg += fmt::format(
      "<text x=\"{}\" y=\"18\" font-size=\"14\">egg sweep: RMSE of the deployed grid against the "
      "design surface, against lamella mass</text>\n",
      left);
  svg += fmt::format(
      "<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"black\"/><line x1=\"{0}\" "
      "y1=\"{1}\" x2=\"{0}\" y2=\"{3}\" stroke=\"black\"/>\n",
      left, h - bottom, w - right, top);
  for (int k = 0; k <= 5; ++k) {
    const double e = eMax * k / 5.0, m = mMin + (mMax - mMin) * k / 5.0;
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#eee\"/><text "
        "x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:.3g}</text>\n",
        left, y(e), w - right, left - 6, y(e) + 4, e);
    svg += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{:.4g}</text>\n", x(m),
                       h - bottom + 16, m);
  }
  svg += fmt::format(
      "<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">mass of the lamellas [kg] "
      "(fabrication.mass_kg)</text>\n",
      0.5 * (left + w - right), h - 24);
  svg += fmt::format(
      "<text x=\"16\" y=\"{0:.1f}\" transform=\"rotate(-90 16 {0:.1f})\" "
      "text-anchor=\"middle\">RMSE [m] (joined structure, else patch by patch)</text>\n",
      0.5 * (top + h - bottom));
  std::vector<std::pair<double, double>> points;
  for (const auto& r : rows)
    points.emplace_back(std::isfinite(r.mass) ? r.mass : std::numeric_limits<double>::infinity(),
                        r.error());
  std::string front;
  for (size_t i : paretoFront(points))
    if (std::isfinite(points[i].first))
      front += fmt::format("{:.1f},{:.1f} ", x(points[i].first), y(points[i].second));
  if (!front.empty())
    svg += fmt::format(
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"2\"/>\n", front);
  for (const auto& r : rows)
    if (std::isfinite(r.error()) && std::isfinite(r.mass))
      svg += fmt::format(
          "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{}\" fill=\"{}\" stroke=\"#1f77b4\" "
          "stroke-width=\"1.5\"><title>{}: {:.4g} kg, RMSE {:.4f} m</title></circle>"
          "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"10\">{}</text>\n",
          x(r.mass), y(r.error()), r.pareto ? 5 : 3.5, r.pareto ? "#1f77b4" : "white",
          escapeXml(r.variant), r.mass, r.error(), x(r.mass) + 7, y(r.error()) - 5,
          escapeXml(r.variant));
  svg += fmt::format(
      "<text x=\"{}\" y=\"{}\" font-size=\"10\">filled, joined: Pareto front (no variant both "
      "lighter and closer); not plotted: runs without a report, mass or error (see "
      "sweep.csv)</text>\n",
      left, h - 4);
  return svg + "</svg>\n";
}

}  // namespace

int collectSweep(const fs::path& dir) {
  const std::string text = readRegularFile(dir / "variants.csv", 1 << 24, "variants file");
  std::istringstream lines(text);
  std::string line;
  if (!std::getline(lines, line)) throw InvalidInput((dir / "variants.csv").string() + ": empty");
  const std::vector<std::string> header = splitCsv(line);
  if (header.empty() || header[0] != "variant")
    throw InvalidInput((dir / "variants.csv").string() + ": the first column must be 'variant'");
  std::vector<SweepRow> rows;
  int missing = 0;
  for (int lineNo = 2; std::getline(lines, line); ++lineNo) {
    if (line.empty()) continue;
    const auto fields = splitCsv(line);
    if (fields.size() != header.size())
      throw InvalidInput(fmt::format("{}: line {}: {} fields, the header has {}",
                                     (dir / "variants.csv").string(), lineNo, fields.size(),
                                     header.size()));
    if (!portableNameProblem(fields[0], 200).empty())
      throw InvalidInput(
          fmt::format("{}: line {}: bad variant name", (dir / "variants.csv").string(), lineNo));
    SweepRow row;
    row.variant = fields[0];
    row.values.assign(fields.begin() + 1, fields.end());
    const fs::path reportFile = dir / "runs" / row.variant / "report.json";
    json report;
    if (!fs::exists(reportFile)) {
      row.status = "missing";
    } else {
      try {
        report = json::parse(readRegularFile(reportFile, 1 << 28, "report file"));
        row.status = report.contains("failures") && !report["failures"].empty() ? "failed" : "ok";
      } catch (const std::exception&) {
        row.status = "unreadable";
      }
    }
    if (row.status != "ok") ++missing;
    if (report.is_object()) {
      using P = json::json_pointer;
      row.patches = jsonNumber(report, P("/patching/patches"));
      row.rmse = jsonNumber(report, P("/simulation/rmse_m")),
      row.maxError = jsonNumber(report, P("/simulation/max_error_m"));
      row.joinedRmse = jsonNumber(report, P("/simulation/joined/rmse_m")),
      row.joinedMax = jsonNumber(report, P("/simulation/joined/max_error_m"));
      row.mass = jsonNumber(report, P("/fabrication/mass_kg")),
      row.stress = jsonNumber(report, P("/fabrication/max_stress_ratio"));
      row.lamellas = jsonNumber(report, P("/fabrication/lamellae")),
      row.wall = jsonNumber(report, P("/timings/total_s"));
    }
    rows.push_back(std::move(row));
  }
  std::vector<std::pair<double, double>> points;
  for (const auto& r : rows)
    points.emplace_back(std::isfinite(r.mass) && r.status == "ok"
                            ? r.mass
                            : std::numeric_limits<double>::infinity(),
                        r.status == "ok" ? r.error() : NAN);
  for (size_t i : paretoFront(points))
    if (std::isfinite(points[i].first)) rows[i].pareto = true;
  std::string csv = "variant";
  for (size_t k = 1; k < header.size(); ++k) csv.append(1, ',').append(field(header[k]));
  csv +=
      ",status,patches,joined_rmse_m,joined_max_error_m,rmse_m,max_error_m,mass_kg,max_stress_"
      "ratio,lamellas,wall_s,pareto\n";
  for (const auto& r : rows) {
    csv += r.variant;
    for (const auto& v : r.values) csv.append(1, ',').append(field(v));
    csv += fmt::format(",{},{},{},{},{},{},{},{},{},{},{}\n", r.status, csvCell(r.patches),
                       csvCell(r.joinedRmse), csvCell(r.joinedMax), csvCell(r.rmse),
                       csvCell(r.maxError), csvCell(r.mass), csvCell(r.stress), csvCell(r.lamellas),
                       csvCell(r.wall), r.pareto ? 1 : 0);
    if (r.status != "ok")
      std::cerr << fmt::format("egg sweep: {}: {} ({})\n", r.variant, r.status,
                               (dir / "runs" / r.variant / "report.json").string());
  }
  writeFileAtomically(dir / "sweep.csv", csv);
  writeFileAtomically(dir / "sweep.svg", svgOf(rows));
  return missing;
}

}  // namespace egg::app
