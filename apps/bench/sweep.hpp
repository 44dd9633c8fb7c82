#pragma once
// `egg sweep` (issue 18, "Sweeps beyond one machine"): a parameter grid over a base scene expanded
// into full scene files and a job list (one `egg run` per line) that GNU parallel or a Slurm job
// array runs, and `egg sweep --collect` merging the runs' report.json files into sweep.csv and a
// Pareto plot (error against mass). No scheduler of our own.
#include <filesystem>
#include <string>
#include <vector>

namespace egg::app {

struct SweepExpandOptions {
  std::filesystem::path sweepFile;  // SWEEP.json
  std::filesystem::path out;        // DIR
  std::filesystem::path eggBinary;  // written into jobs.txt (absolute)
  bool force = false;               // write into an existing non-empty DIR
  bool dryRun = false;  // expand and check every variant, write nothing (the fuzz target's mode)
};

struct SweepExpansion {
  std::vector<std::string> keys;                 // JSON pointers, in column order
  std::vector<std::string> variants;             // v001, v002, ...
  std::vector<std::vector<std::string>> values;  // per variant, per key: the value as JSON text
};

// Expands the sweep and writes DIR/scenes/<variant>.json, DIR/jobs.txt, DIR/variants.csv and
// DIR/slurm.sh. Throws InvalidInput naming the sweep file and key (nothing written then).
SweepExpansion expandSweep(const SweepExpandOptions& options);

// Reads DIR/variants.csv and DIR/runs/<variant>/report.json; writes DIR/sweep.csv and
// DIR/sweep.svg. Returns how many variants have no usable report (missing or failed).
int collectSweep(const std::filesystem::path& dir);

// A word for a POSIX shell: single-quoted, a quote inside as '\''.
std::string shellQuote(const std::string& word);

}  // namespace egg::app
