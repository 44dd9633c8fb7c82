#pragma once
// Error against run time of the simulation itself (issue 18): the deviation of the contact points
// from the design surface (RMSE and max, Sections 2.6.2, 3.5.2) as the Newton iterations of a run
// go by (SimulationRun::history, recorded through the solver's observer). report.json carries each
// run's history (simulation.patches[].history, simulation.joined.history); report.html draws it.
#include "core/rods/simulation.hpp"
#include "pipeline/plot_frame.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace egg::pipeline {

// Newton iterations between two samples of a simulation's error against run time in `egg run`
// (SimulationOptions::historyEvery; the start and the end of every load step are always sampled).
inline constexpr int kErrorHistoryEvery = 8;

// report.json history: [{seconds, iteration, load_step, rmse_m, max_error_m}], oldest first.
nlohmann::json historyJson(const std::vector<rods::DeviationSample>& history);
// Reads it back; throws InvalidInput naming `where` and the key when it is malformed.
std::vector<rods::DeviationSample> historyFromJson(const nlohmann::json& history,
                                                   const std::string& where);

struct ErrorTimeSeries {
  std::string label;  // "patch 3", "joined"
  std::vector<rods::DeviationSample> samples;
};

// The two panels of a chart: 0 RMSE, 1 max error, against seconds; the ranges cover every series
// (0 to the largest time and error, errors with 8 % headroom).
PlotFrame errorTimeFrame(int panel, const std::vector<ErrorTimeSeries>& series);

// <svg id="`id`"> (without the namespace, as the page's other charts) with both panels, a polyline
// per series and a legend; `title` above. Series without samples are left out.
std::string errorTimeSvg(const std::string& id, const std::string& title,
                         const std::vector<ErrorTimeSeries>& series);

}  // namespace egg::pipeline
