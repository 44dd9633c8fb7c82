// DistanceSolver: the per-mesh tables plus single, batch and one-off queries of the window
// propagation (window_propagation.cpp explains the algorithm).
// Why window propagation: edge Dijkstra, fast marching and the heat method were ruled out by the
// accuracy bar (Section 2.3.3 needs 0.15 %); a geodesic graph (saddle vertex graph, Dijkstra over
// exact local windows) was measured on the 3.6k bump: 5.5e-3 max relative error with 84 edges per
// vertex, 2.4e-3 with 206 - far from the 1e-4 bar, because its paths bend at vertices on long
// saddle-free stretches.
#include "core/geodesic/distance_solver.hpp"

#include "core/errors.hpp"
#include "core/geodesic/window_propagation.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <string>

namespace egg::geodesic {

namespace {
double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

void DistanceSolverOptions::validate() const {
  if (!(saddleAngleTolerance >= 0.0) || !(saddleAngleTolerance < 0.1)) {
    throw InvalidInput("DistanceSolverOptions.saddleAngleTolerance must be in [0, 0.1) radians");
  }
  if (!(minWindowWidthRelative >= 0.0) || !(minWindowWidthRelative < 1e-3)) {
    throw InvalidInput("DistanceSolverOptions.minWindowWidthRelative must be in [0, 1e-3)");
  }
  if (!(imageMergeTolerance >= 0.0) || !(imageMergeTolerance < 1e-3)) {
    throw InvalidInput(
        "DistanceSolverOptions.imageMergeTolerance must be in [0, 1e-3) (a fraction of the edge "
        "length)");
  }
  if (threads < 0) throw InvalidInput("DistanceSolverOptions.threads must be >= 0 (0 = all cores)");
  if (engine != Engine::StoredWindows && engine != Engine::FrontOnly &&
      engine != Engine::Wavefront) {
    throw InvalidInput(
        "DistanceSolverOptions.engine must be StoredWindows, FrontOnly or Wavefront");
  }
}

DistanceSolverOptions DistanceSolverOptions::exact() {
  DistanceSolverOptions options;
  options.saddleAngleTolerance = 0.0;
  options.imageMergeTolerance = 0.0;
  return options;
}

DistanceSolver::DistanceSolver(const TriMesh& mesh, const DistanceSolverOptions& options)
    : options_(options) {
  options_.validate();
  const auto start = std::chrono::steady_clock::now();
  tables_ = std::make_unique<detail::MeshTables>(detail::buildTables(mesh, options_));
  precomputeSeconds_ = secondsSince(start);
}

DistanceSolver::~DistanceSolver() = default;
DistanceSolver::DistanceSolver(DistanceSolver&&) noexcept = default;
DistanceSolver& DistanceSolver::operator=(DistanceSolver&&) noexcept = default;

namespace {
// Scratch space reused by every query on a thread (single and batch calls alike): the window
// arrays of a 16k-vertex mesh are tens of MB, and faulting them in anew costs as much as the
// propagation itself. One per thread also bounds the memory: (threads) x (largest propagation).
detail::Propagation& threadScratch() {
  thread_local detail::Propagation state;
  return state;
}

DistanceField fieldFrom(const detail::MeshTables& tables, const detail::Propagation& state,
                        double seconds) {
  DistanceField field;
  field.vertexDistances = state.vertexDistance;
  field.targetDistances = state.targetDistance;
  field.windowsCreated = state.windowsCreated;
  field.peakWindows =
      static_cast<long>(state.wavefront ? state.slots.size() : state.windows.size());
  field.peakBytes = detail::peakBytes(tables, state);
  field.seconds = seconds;
  return field;
}

bool storesWindows(const DistanceSolverOptions& options) {
  return options.engine == DistanceSolverOptions::Engine::StoredWindows;
}
bool wavefront(const DistanceSolverOptions& options) {
  return options.engine == DistanceSolverOptions::Engine::Wavefront;
}
}  // namespace

DistanceField DistanceSolver::distances(const SurfacePoint& source,
                                        const std::vector<SurfacePoint>& targets) const {
  const auto start = std::chrono::steady_clock::now();
  detail::Propagation& state = threadScratch();
  detail::propagate(*tables_, options_, source, targets, state, false, storesWindows(options_),
                    wavefront(options_));
  return fieldFrom(*tables_, state, secondsSince(start));
}

DistanceField DistanceSolver::directedDistances(const SurfacePoint& source,
                                                const std::vector<SurfacePoint>& targets) const {
  const auto start = std::chrono::steady_clock::now();
  detail::Propagation& state = threadScratch();
  detail::propagate(*tables_, options_, source, targets, state, /*directedAtTargets=*/true,
                    storesWindows(options_), wavefront(options_));
  return fieldFrom(*tables_, state, secondsSince(start));
}

DistanceField DistanceSolver::distancesFromVertex(int vertex,
                                                  const std::vector<SurfacePoint>& targets) const {
  if (vertex < 0 || vertex >= tables_->vertexCount) {
    throw InvalidInput("geodesic: source vertex " + std::to_string(vertex) + " is out of range");
  }
  for (int k = tables_->outgoingStart[vertex]; k < tables_->outgoingStart[vertex + 1]; ++k) {
    const int h = tables_->outgoing[k];
    const int f = tables_->he[h].face;
    if (f < 0) continue;
    SurfacePoint p;
    p.face = f;
    for (int i = 0; i < 3; ++i) p.barycentric[i] = (tables_->faceVerts[f][i] == vertex) ? 1.0 : 0.0;
    return distances(p, targets);
  }
  throw InvalidInput("geodesic: source vertex " + std::to_string(vertex) + " belongs to no face");
}

std::vector<DistanceField> DistanceSolver::distances(
    const std::vector<SurfacePoint>& sources, const std::vector<SurfacePoint>& targets) const {
  std::vector<DistanceField> fields(sources.size());
  auto body = [&](const tbb::blocked_range<size_t>& range) {
    auto& state = threadScratch();
    for (size_t i = range.begin(); i < range.end(); ++i) {
      const auto start = std::chrono::steady_clock::now();
      detail::propagate(*tables_, options_, sources[i], targets, state, false,
                        storesWindows(options_), wavefront(options_));
      fields[i] = fieldFrom(*tables_, state, secondsSince(start));
    }
  };
  // One source per task: each field depends only on its source, never on the scheduling.
  const tbb::blocked_range<size_t> all(0, sources.size(), 1);
  if (options_.threads > 0) {
    tbb::task_arena arena(options_.threads);
    arena.execute([&] { tbb::parallel_for(all, body); });
  } else {
    tbb::parallel_for(all, body);
  }
  return fields;
}

double DistanceSolver::distance(const SurfacePoint& from, const SurfacePoint& to) const {
  detail::Propagation& state = threadScratch();
  detail::propagate(*tables_, options_, from, {to}, state, /*directedAtTargets=*/true,
                    storesWindows(options_), wavefront(options_));
  return state.targetDistance[0];
}

GeodesicPath DistanceSolver::path(const SurfacePoint& from, const SurfacePoint& to) const {
  // The thread's scratch, as for distances(): a fresh state would fault in megabytes per path.
  detail::Propagation& state = threadScratch();
  // Traced back through Window::parent: the windows are kept whatever the engine.
  detail::propagate(*tables_, options_, from, {to}, state, /*directedAtTargets=*/true,
                    /*storeWindows=*/true);
  return detail::tracePath(*tables_, state, 0, from, to);
}

int DistanceSolver::vertexCount() const { return tables_->vertexCount; }
int DistanceSolver::faceCount() const { return tables_->faceCount; }
double DistanceSolver::meanEdgeLength() const { return tables_->meanEdgeLength; }
bool DistanceSolver::isPseudoSource(int vertex) const {
  if (vertex < 0 || vertex >= tables_->vertexCount) {
    throw InvalidInput("geodesic: vertex " + std::to_string(vertex) + " is out of range");
  }
  return tables_->pseudoSource[vertex] != 0;
}
double DistanceSolver::precomputeSeconds() const { return precomputeSeconds_; }
const DistanceSolverOptions& DistanceSolver::options() const { return options_; }

DistanceField geodesicDistances(const TriMesh& mesh, const SurfacePoint& source,
                                const std::vector<SurfacePoint>& targets,
                                const DistanceSolverOptions& options) {
  return DistanceSolver(mesh, options).distances(source, targets);
}

}  // namespace egg::geodesic
