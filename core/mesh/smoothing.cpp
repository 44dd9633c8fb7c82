#include "core/mesh/smoothing.hpp"

#include "core/errors.hpp"
#include "core/mesh/laplacian.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace egg {

void SmoothingOptions::validate() const {
  if (!(std::isfinite(strength) && strength > 0.0)) {
    std::ostringstream s;
    s << "SmoothingOptions.strength must be a positive number, got " << strength;
    throw InvalidInput(s.str());
  }
  if (!(cgTolerance > 0.0 && cgTolerance < 1e-2)) {
    std::ostringstream s;
    s << "SmoothingOptions.cg_tolerance must be in (0, 0.01), got " << cgTolerance;
    throw InvalidInput(s.str());
  }
}

SmoothingResult smoothMeshStep(const TriMesh& mesh, const SmoothingOptions& options) {
  options.validate();
  const int n = static_cast<int>(mesh.n_vertices());
  if (n == 0 || mesh.n_faces() == 0) throw InvalidInput("smoothMeshStep: the mesh is empty");
  for (int v : options.fixedVertices)
    if (v < 0 || v >= n)
      throw InvalidInput("SmoothingOptions.fixed_vertices holds " + std::to_string(v) +
                         ", but the mesh has " + std::to_string(n) + " vertices");
  const auto start = std::chrono::steady_clock::now();

  std::vector<char> fixed(n, 0);
  if (options.fixBoundary)
    for (auto vh : mesh.vertices())
      if (mesh.is_boundary(vh)) fixed[vh.idx()] = 1;
  for (int v : options.fixedVertices) fixed[v] = 1;

  SmoothingResult result;
  result.mesh = mesh;
  const double edge = meanEdgeLength(mesh);
  result.timeStepM2 = options.strength * edge * edge;
  std::vector<int> freeIndex(n, -1);
  int freeCount = 0;
  for (int v = 0; v < n; ++v) {
    if (fixed[v])
      ++result.fixedVertices;
    else
      freeIndex[v] = freeCount++;
  }
  if (freeCount == 0) return result;

  const Eigen::SparseMatrix<double> L = options.weights == LaplacianWeights::Cotangent
                                            ? cotanLaplacian(mesh)
                                            : uniformLaplacian(mesh);
  // Mixed Voronoi areas: with them M^-1 L X is the mean curvature normal 2Hn to second order on
  // any triangulation (Meyer et al. 2003); barycentric areas are off by a few per cent at irregular
  // vertices, which shows as uneven shrinking.
  const Eigen::VectorXd mass = mixedVoronoiAreas(mesh);
  Eigen::MatrixXd X(n, 3);
  for (int v = 0; v < n; ++v) X.row(v) = toEigen(mesh.point(TriMesh::VertexHandle(v))).transpose();

  // (M + t L)_ff X'_f = M_f X_f - t L_fb X_b: fixed vertices move to the right-hand side.
  const double t = result.timeStepM2;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(L.nonZeros());
  Eigen::MatrixXd rhs(freeCount, 3);
  for (int v = 0; v < n; ++v)
    if (!fixed[v]) rhs.row(freeIndex[v]) = mass(v) * X.row(v);
  for (int k = 0; k < L.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it) {
      const int i = static_cast<int>(it.row()), j = static_cast<int>(it.col());
      if (fixed[i]) continue;
      if (fixed[j])
        rhs.row(freeIndex[i]) -= t * it.value() * X.row(j);
      else
        entries.emplace_back(freeIndex[i], freeIndex[j], t * it.value());
    }
  for (int v = 0; v < n; ++v)
    if (!fixed[v]) entries.emplace_back(freeIndex[v], freeIndex[v], mass(v));
  Eigen::SparseMatrix<double> A(freeCount, freeCount);
  A.setFromTriplets(entries.begin(), entries.end());

  constexpr int kCholeskyLimit =
      100000;  // beyond this, fill-in makes the simplicial factorisation slow
  result.usedCholesky = options.solver == FairingSolver::Cholesky ||
                        (options.solver == FairingSolver::Auto && freeCount <= kCholeskyLimit);
  Eigen::MatrixXd solved(freeCount, 3);
  if (result.usedCholesky) {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
    if (solver.info() != Eigen::Success)
      throw SolverFailure(
          "smoothMeshStep: the implicit fairing system could not be factorised (degenerate "
          "faces?)");
    solved = solver.solve(rhs);
    if (solver.info() != Eigen::Success)
      throw SolverFailure("smoothMeshStep: the implicit fairing solve failed");
  } else {
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> solver(A);
    solver.setTolerance(options.cgTolerance);
    solver.setMaxIterations(std::max(1000, freeCount / 10));
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::VectorXd guess(freeCount);
      for (int v = 0; v < n; ++v)
        if (!fixed[v]) guess(freeIndex[v]) = X(v, axis);
      solved.col(axis) = solver.solveWithGuess(rhs.col(axis), guess);
      if (solver.info() != Eigen::Success)
        throw SolverFailure("smoothMeshStep: conjugate gradients did not converge (" +
                            std::to_string(solver.iterations()) +
                            " iterations, relative residual " + std::to_string(solver.error()) +
                            ")");
      result.iterations = std::max(result.iterations, static_cast<int>(solver.iterations()));
      result.residual = std::max(result.residual, solver.error());
    }
  }
  if (!solved.allFinite())
    throw SolverFailure("smoothMeshStep: the implicit fairing solve produced non-finite positions");

  double sum = 0.0;
  for (int v = 0; v < n; ++v) {
    if (fixed[v]) continue;
    const Eigen::Vector3d moved = solved.row(freeIndex[v]).transpose();
    const double displacement = (moved - X.row(v).transpose()).norm();
    result.maxDisplacementM = std::max(result.maxDisplacementM, displacement);
    sum += displacement;
    result.mesh.set_point(TriMesh::VertexHandle(v), toOpenMesh(moved));
  }
  result.meanDisplacementM = sum / n;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

SmoothingLoopResult smoothUntil(const TriMesh& mesh,
                                const std::function<bool(const TriMesh&)>& done, int maxSteps,
                                const SmoothingOptions& options) {
  options.validate();
  if (maxSteps < 0)
    throw InvalidInput("smoothUntil: maxSteps must be >= 0, got " + std::to_string(maxSteps));
  const auto start = std::chrono::steady_clock::now();
  SmoothingLoopResult loop;
  loop.mesh = mesh;
  loop.satisfied = done(loop.mesh);
  while (!loop.satisfied && loop.steps < maxSteps) {
    SmoothingResult step = smoothMeshStep(loop.mesh, options);
    loop.mesh = std::move(step.mesh);
    loop.maxDisplacementM.push_back(step.maxDisplacementM);
    loop.meanDisplacementM.push_back(step.meanDisplacementM);
    ++loop.steps;
    loop.satisfied = done(loop.mesh);
  }
  for (auto vh : mesh.vertices())
    loop.totalMaxDisplacementM =
        std::max(loop.totalMaxDisplacementM,
                 (toEigen(loop.mesh.point(vh)) - toEigen(mesh.point(vh))).norm());
  loop.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return loop;
}

}  // namespace egg
