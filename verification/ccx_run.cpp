#include "verification/ccx_run.hpp"

#include "core/errors.hpp"
#include "core/io/child_process.hpp"

#include <fmt/core.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

namespace egg::verification {

namespace fs = std::filesystem;

fs::path findCcx() {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const fs::path candidate = fs::path(dir) / "ccx";
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

namespace {

ChildOutcome execCcx(const fs::path& ccx, const fs::path& folder,
                     const std::vector<std::string>& args, const CcxOptions& options,
                     const fs::path& log) {
  // Everything the child needs is built here, in the parent: after the fork only system calls
  // run. Once RLIMIT_AS is set, an allocation in the child fails (under AddressSanitizer, whose
  // shadow already exceeds any limit, every mmap does: CI saw "ERROR: Failed to mmap", signal 6).
  std::vector<char*> argv{const_cast<char*>(ccx.c_str())};
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string threads = std::to_string(options.threads);
  const rlim_t bytes = static_cast<rlim_t>(options.memoryLimitMb * 1024.0 * 1024.0);
  return runChild(
      [&]() -> int {
        if (chdir(folder.c_str()) != 0) return 126;
        setenv("OMP_NUM_THREADS", threads.c_str(), 1);
        setenv("CCX_NPROC_EQUATION_SOLVER", threads.c_str(), 1);
        const struct rlimit limit { bytes, bytes };
        setrlimit(RLIMIT_AS, &limit);
        execv(ccx.c_str(), argv.data());
        return 127;  // exec failed
      },
      options.timeLimitS, log);
}

}  // namespace

std::string ccxVersion(const fs::path& folder) {
  const fs::path ccx = findCcx();
  if (ccx.empty()) return {};
  // In the caller's own folder: a log at a predictable name in $TMPDIR could be a planted link.
  const fs::path log = folder / "ccx_version.log";
  CcxOptions options;
  options.timeLimitS = 20.0;
  const ChildOutcome out = execCcx(ccx, fs::absolute(folder), {"-v"}, options, log);
  std::error_code ignored;
  fs::remove(log, ignored);
  std::smatch m;
  if (std::regex_search(out.output, m, std::regex(R"(Version\s+([0-9][0-9.]*))"))) return m[1];
  return "unknown";
}

CcxOutcome runCcx(const fs::path& folder, const std::string& job, const CcxOptions& options) {
  const fs::path ccx = findCcx();
  if (ccx.empty()) throw SolverFailure("ccx (CalculiX) is not installed (scripts/install-deps.sh)");
  if (!fs::exists(folder / (job + ".inp")))
    throw InvalidInput("ccx: no input file " + (folder / (job + ".inp")).string());
  const fs::path log = folder / (job + ".log");
  const ChildOutcome out = execCcx(ccx, fs::absolute(folder), {"-i", job}, options, log);
  CcxOutcome result{out.seconds, out.output};
  std::string errors;
  std::istringstream lines(out.output);
  for (std::string line; std::getline(lines, line);)
    if (line.find("*ERROR") != std::string::npos) errors += (errors.empty() ? "" : "; ") + line;
  std::string failure;
  if (out.timedOut)
    failure = fmt::format("ccx {} ran past its time limit of {} s and was stopped", job,
                          options.timeLimitS);
  else if (out.signal != 0)
    failure = fmt::format("ccx {} was ended by signal {}", job, out.signal);
  else if (out.exitCode != 0)
    failure = fmt::format("ccx {} exited with code {}", job, out.exitCode);
  else if (!errors.empty())
    failure = "ccx " + job + " reported an error";
  if (!failure.empty()) {
    if (errors.empty()) {  // the last lines say what happened
      const std::string& o = out.output;
      errors = o.substr(o.size() > 400 ? o.size() - 400 : 0);
    }
    throw SolverFailure(failure + ": " + errors + " (log: " + log.string() + ")");
  }
  return result;
}

namespace {

// Fortran-style fixed-width numbers run together ("1.0E+00-2.0E+00"): split at each sign that
// follows a digit.
std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  const char* p = text.c_str();
  char* end = nullptr;
  for (;;) {
    while (*p == ' ') ++p;
    if (!*p) break;
    const double v = std::strtod(p, &end);
    if (end == p) break;
    out.push_back(v);
    p = end;
  }
  return out;
}

}  // namespace

DatResults readDat(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw IoError("cannot read " + file.string());
  DatResults out;
  static const std::regex header(R"(^\s*(displacements|forces) \(.*\) for set (\S+) and time)");
  std::string line;
  std::map<int, Eigen::Vector3d>* block = nullptr;
  bool buckling = false;
  std::vector<std::pair<std::string, size_t>> pending;  // displacement blocks: set, index
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, header)) {
      if (m[1] == "displacements") {
        out.displacementBlocks.emplace_back();
        block = &out.displacementBlocks.back();
        pending.emplace_back(m[2], out.displacementBlocks.size() - 1);
      } else {
        block = &out.forces[m[2]];
        block->clear();
      }
      buckling = false;
      continue;
    }
    if (line.find("B U C K L I N G") != std::string::npos) {
      buckling = true;
      block = nullptr;
      continue;
    }
    if (line.find(" for set ") != std::string::npos ||
        line.find("E I G E N") != std::string::npos) {
      block = nullptr;  // another kind of block (totals, mode shapes)
      continue;
    }
    const std::vector<double> v = numbers(line);
    if (block && v.size() == 4)
      (*block)[static_cast<int>(v[0])] = Eigen::Vector3d(v[1], v[2], v[3]);
    if (buckling && v.size() == 2 && v[0] == static_cast<int>(v[0]) &&
        static_cast<int>(v[0]) == static_cast<int>(out.bucklingFactors.size()) + 1)
      out.bucklingFactors.push_back(v[1]);
  }
  for (const auto& [set, index] : pending) out.displacements[set] = out.displacementBlocks[index];
  return out;
}

namespace {

int fixedInt(const std::string& line, size_t from, size_t width) {
  return from < line.size() ? std::atoi(line.substr(from, width).c_str()) : 0;
}

std::vector<double> fixedReals(const std::string& line, size_t from) {
  std::vector<double> out;
  for (size_t p = from; p + 12 <= line.size(); p += 12)
    out.push_back(std::strtod(line.substr(p, 12).c_str(), nullptr));
  return out;
}

void scanFrd(const fs::path& file, const std::string& block, FrdResults* geometry,
             std::vector<std::map<int, std::vector<double>>>& results) {
  std::ifstream in(file);
  if (!in) throw IoError("cannot read " + file.string());
  enum class Mode { None, Nodes, Elements, Result, OtherResult } mode = Mode::None;
  std::string line;
  std::vector<int>* element = nullptr;
  while (std::getline(in, line)) {
    if (line.rfind("    2C", 0) == 0)
      mode = Mode::Nodes;
    else if (line.rfind("    3C", 0) == 0)
      mode = Mode::Elements;
    else if (line.rfind(" -4", 0) == 0) {
      std::istringstream words(line.substr(3));
      std::string name;
      words >> name;
      mode = name == block ? Mode::Result : Mode::OtherResult;
      if (mode == Mode::Result) results.emplace_back();
    } else if (line.rfind(" -3", 0) == 0) {
      mode = Mode::None;
    } else if (line.rfind(" -1", 0) == 0) {
      const int id = fixedInt(line, 3, 10);
      if (mode == Mode::Nodes && geometry) {
        const auto v = fixedReals(line, 13);
        if (v.size() >= 3) geometry->nodes[id] = Eigen::Vector3d(v[0], v[1], v[2]);
      } else if (mode == Mode::Elements && geometry) {
        element = &geometry->elements[id];
      } else if (mode == Mode::Result) {
        results.back()[id] = fixedReals(line, 13);
      }
    } else if (line.rfind(" -2", 0) == 0 && mode == Mode::Elements && element) {
      for (size_t p = 3; p + 10 <= line.size(); p += 10) element->push_back(fixedInt(line, p, 10));
    }
  }
}

}  // namespace

FrdResults readFrd(const fs::path& file, const std::string& block) {
  FrdResults out;
  std::vector<std::map<int, std::vector<double>>> results;
  scanFrd(file, block, &out, results);
  if (results.empty()) throw IoError("no " + block + " results in " + file.string());
  out.values = std::move(results.back());
  return out;
}

std::vector<std::map<int, std::vector<double>>> readFrdBlocks(const fs::path& file,
                                                              const std::string& block) {
  std::vector<std::map<int, std::vector<double>>> results;
  scanFrd(file, block, nullptr, results);
  return results;
}

}  // namespace egg::verification
