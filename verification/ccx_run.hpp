#pragma once
// Running CalculiX (`ccx`, Debian package calculix-ccx) as a child process and reading its results
// back: the .dat (printed displacements, reactions, buckling factors) and the .frd (nodal stresses
// of the 3D elements ccx expands the beams into). The formats are ccx 2.20's (the Debian
// bookworm version), fixed-width as its manual describes them.
#include <Eigen/Core>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace egg::verification {

// The `ccx` on PATH, or empty.
std::filesystem::path findCcx();
// "2.20" from `ccx -v` (its output logged in `folder`, then removed); empty when there is no ccx.
std::string ccxVersion(const std::filesystem::path& folder);

struct CcxOptions {
  double timeLimitS = 600.0;
  double memoryLimitMb = 8192.0;  // address-space limit of the ccx process
  int threads = 1;                // OMP_NUM_THREADS / CCX_NPROC_EQUATION_SOLVER
};

struct CcxOutcome {
  double seconds = 0.0;
  std::string log;  // ccx's stdout and stderr
};

// Runs `ccx -i job` in `folder` (job.inp must be there). Throws SolverFailure with ccx's own error
// lines (or the time-out, or the signal) when it does not finish cleanly.
CcxOutcome runCcx(const std::filesystem::path& folder, const std::string& job,
                  const CcxOptions& options);

// What a .dat holds: per set name the last block of each kind printed for it (the end of the step),
// and the buckling factors.
struct DatResults {
  std::map<std::string, std::map<int, Eigen::Vector3d>> displacements;  // set -> node -> u (m)
  std::map<std::string, std::map<int, Eigen::Vector3d>> forces;         // set -> node -> RF (N)
  std::vector<double> bucklingFactors;
  std::vector<std::map<int, Eigen::Vector3d>> displacementBlocks;  // every one, in order
};
DatResults readDat(const std::filesystem::path& file);

// The .frd's expanded 3D model and the last result block of a kind (e.g. "STRESS", "DISP").
struct FrdResults {
  std::map<int, Eigen::Vector3d> nodes;
  std::map<int, std::vector<int>> elements;   // beam element id -> its brick's nodes
  std::map<int, std::vector<double>> values;  // node -> components
};
FrdResults readFrd(const std::filesystem::path& file, const std::string& block);
// Every block of that kind in order (a *BUCKLE step writes one DISP block per mode).
std::vector<std::map<int, std::vector<double>>> readFrdBlocks(const std::filesystem::path& file,
                                                              const std::string& block);

}  // namespace egg::verification
