#pragma once
// Sparse Cholesky factorisation L L^T = P A P^T for the Newton systems of the rod solver
// (rod_solver.cpp), left-looking and supernodal: columns of L with the same structure below the
// diagonal are stored as one dense block, and every update between blocks is a small dense
// product with contiguous inner loops (on the rod grids, supernodes are 1 to ~40 columns wide:
// Eigen's blocked kernels cost more than they save there).
// Why not Eigen's SimplicialLLT: it updates one scalar entry at a time through index lists; on the
// benchmark grid (3330 unknowns, 90k nonzeros in L) that took half of the solver's critical path.
// The ordering is CHOLMOD's choice of AMD or METIS, whichever fills less. Like SimplicialLLT,
// factorisation stops at the first pivot that is not positive (the shift search relies on that).
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <tbb/enumerable_thread_specific.h>

#include <memory>
#include <vector>

namespace egg::rods {

// One thread's scratch space in a factorisation (sized for n unknowns).
struct CholeskyWorkspace {
  explicit CholeskyWorkspace(int n = 0)
      : relative(n), localRow(n), accumulator(2 * static_cast<size_t>(n)) {}
  std::vector<int> relative, localRow, sources;
  std::vector<double> accumulator;
};

class SupernodalCholesky {
 public:
  // Symbolic analysis of a symmetric matrix given by its lower triangle (compressed column
  // storage). Later factorisations must use a matrix with exactly this pattern.
  void analyzePattern(const Eigen::SparseMatrix<double>& lower);
  // Numeric factorisation; false when the matrix is not positive definite. Throws InvalidInput when
  // the pattern differs from the analysed one (same size and count are not enough: a bolt that
  // slid to another edge keeps the count but moves entries).
  bool factorize(const Eigen::SparseMatrix<double>& lower);
  // Solves A x = b with the factor of the last factorize call, which must have succeeded (a failed
  // one leaves the factor half overwritten): throws SolverFailure otherwise.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  long factorNonZeros()
      const;  // stored entries of L (dense blocks, lower part of the diagonal blocks counted fully)
  int supernodeCount() const { return static_cast<int>(first_.size()) - 1; }

 private:
  int n_ = 0;
  std::vector<int> newIndex_;     // position in the factor of each unknown
  std::vector<int> first_;        // first column of each supernode (and n at the end)
  std::vector<int> rowStart_;     // rows_ of supernode s: [rowStart_[s], rowStart_[s + 1])
  std::vector<int> rows_;         // sorted row indices of each supernode (its own columns first)
  std::vector<long> valueStart_;  // its dense column-major block in values_
  std::vector<double> values_;
  std::vector<int> supernodeOf_;                  // column -> supernode
  std::vector<long> slot_;                        // input nonzero k -> position in values_
  std::vector<int> patternOuter_, patternInner_;  // the analysed pattern (compressed columns)
  bool factored_ = false;                         // the last factorize succeeded
  // The supernodal elimination tree (analyzeTree).
  std::vector<int> childStart_, children_, subtreeFirst_, roots_;
  std::vector<double> work_;
  bool postordered_ = false;
  // Work space of factorize: update lists, and one workspace per thread.
  std::vector<int> head_, next_, pointer_;
  using Workspaces = tbb::enumerable_thread_specific<CholeskyWorkspace>;
  std::shared_ptr<Workspaces> workspaces_;  // shared by copies: each thread uses its own
  void analyzeTree();
};

}  // namespace egg::rods
