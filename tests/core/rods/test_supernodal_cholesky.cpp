// The supernodal Cholesky against Eigen's SimplicialLLT (same ordering, same answers) on sparse
// symmetric matrices with the structure of rod networks, and its positive-definiteness test.
#include "core/rods/supernodal_cholesky.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <Eigen/SparseCholesky>

#include <random>
#include <vector>

namespace egg::rods {
namespace {

// A grid of crossing "rods": nx x ny nodes with `block` unknowns each, coupled to their
// neighbours along both directions (dense blocks), diagonally dominant plus `diagonalShift`.
Eigen::SparseMatrix<double> gridMatrix(int nx, int ny, int block, double diagonalShift,
                                       unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = nx * ny * block;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> rowSum(n, 0.0);
  auto couple = [&](int a, int b) {
    for (int i = 0; i < block; ++i) {
      for (int j = 0; j < block; ++j) {
        const int r = a * block + i, c = b * block + j;
        if (r <= c) continue;
        const double v = u(rng);
        triplets.emplace_back(r, c, v);
        rowSum[r] += std::abs(v);
        rowSum[c] += std::abs(v);
      }
    }
  };
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      const int node = y * nx + x;
      couple(node, node);
      if (x > 0) couple(node, node - 1);
      if (y > 0) couple(node, node - nx);
      if (x > 1 && y > 0) couple(node, node - nx - 2);  // longer links (bolts between rods)
    }
  }
  for (int i = 0; i < n; ++i) triplets.emplace_back(i, i, rowSum[i] + diagonalShift);
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(triplets.begin(), triplets.end());
  lower.makeCompressed();
  return lower;
}

TEST(SupernodalCholesky, SolvesLikeSimplicialLLT) {
  for (int block : {1, 3, 4, 12}) {  // 12: wide supernodes
    const Eigen::SparseMatrix<double> lower = gridMatrix(9, 7, block, 0.5, 5 + block);
    SupernodalCholesky cholesky;
    cholesky.analyzePattern(lower);
    ASSERT_TRUE(cholesky.factorize(lower));
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower> reference(lower);
    ASSERT_EQ(reference.info(), Eigen::Success);
    // CHOLMOD's ordering (the better of AMD and METIS) fills no more than SimplicialLLT's AMD.
    EXPECT_LE(cholesky.factorNonZeros(), reference.matrixL().nestedExpression().nonZeros());
    EXPECT_LT(cholesky.supernodeCount(), lower.rows());
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd b(lower.rows());
    for (int i = 0; i < b.size(); ++i) b[i] = u(rng);
    const Eigen::VectorXd x = cholesky.solve(b);
    const Eigen::VectorXd expected = reference.solve(b);
    EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
    const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
    EXPECT_LT((full * x - b).norm(), 1e-12 * b.norm());
  }
}

TEST(SupernodalCholesky, RefactorisesNewValuesOnTheSamePattern) {
  Eigen::SparseMatrix<double> lower = gridMatrix(6, 5, 3, 0.1, 3);
  SupernodalCholesky cholesky;
  cholesky.analyzePattern(lower);
  ASSERT_TRUE(cholesky.factorize(lower));
  for (int k = 0; k < lower.nonZeros(); ++k) lower.valuePtr()[k] *= 2.0;
  ASSERT_TRUE(cholesky.factorize(lower));
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(lower.rows(), -1.0, 2.0);
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  EXPECT_LT((full * cholesky.solve(b) - b).norm(), 1e-12 * b.norm());
}

TEST(SupernodalCholesky, SubtreesOnSeveralThreadsGiveTheOneThreadFactorToTheBit) {
  // Large enough that subtrees are factorised as separate tasks (over 2e6 multiply-adds).
  const Eigen::SparseMatrix<double> lower = gridMatrix(40, 36, 6, 0.5, 21);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(lower.rows(), -1.0, 2.0);
  auto solveWith = [&](int threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    SupernodalCholesky cholesky;
    cholesky.analyzePattern(lower);
    EXPECT_TRUE(cholesky.factorize(lower));
    return Eigen::VectorXd(cholesky.solve(b));
  };
  const Eigen::VectorXd one = solveWith(1);
  for (int repeat = 0; repeat < 3; ++repeat) {
    const Eigen::VectorXd four = solveWith(4);
    for (int i = 0; i < one.size(); ++i) ASSERT_EQ(one[i], four[i]) << "unknown " << i;
  }
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  EXPECT_LT((full * one - b).norm(), 1e-12 * b.norm());
  // A pivot that fails in one subtree fails the whole factorisation, on any thread count.
  Eigen::SparseMatrix<double> broken = lower;
  broken.coeffRef(123, 123) = -1.0;
  for (int threads : {1, 4}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    SupernodalCholesky cholesky;
    cholesky.analyzePattern(broken);
    EXPECT_FALSE(cholesky.factorize(broken)) << threads << " threads";
  }
}

TEST(SupernodalCholesky, RejectsIndefiniteMatrices) {
  Eigen::SparseMatrix<double> lower = gridMatrix(6, 5, 3, 0.1, 9);
  // Flip one diagonal entry: no longer positive definite.
  lower.coeffRef(40, 40) = -1.0;
  SupernodalCholesky cholesky;
  cholesky.analyzePattern(lower);
  EXPECT_FALSE(cholesky.factorize(lower));
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower> reference(lower);
  EXPECT_NE(reference.info(), Eigen::Success);
  lower.coeffRef(40, 40) = 1e3;
  EXPECT_TRUE(cholesky.factorize(lower));
}

TEST(SupernodalCholesky, RejectsIndefiniteMatricesWithAPositiveDiagonalLikeSimplicialLLT) {
  // Diagonal shifts below the dominance margin: every diagonal entry stays positive, but small
  // shifts make the matrix indefinite. The two factorisations must agree on every shift.
  Eigen::SparseMatrix<double> lower = gridMatrix(6, 5, 3, 0.0, 11);
  SupernodalCholesky cholesky;
  cholesky.analyzePattern(lower);
  int accepted = 0, rejected = 0;
  for (const double scale : {0.05, 0.2, 0.4, 0.6, 0.8, 1.0}) {
    Eigen::SparseMatrix<double> trial = lower;
    for (int j = 0; j < trial.outerSize(); ++j) trial.coeffRef(j, j) *= scale;
    const bool ours = cholesky.factorize(trial);
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower> reference(trial);
    EXPECT_EQ(ours, reference.info() == Eigen::Success) << "diagonal scaled by " << scale;
    (ours ? accepted : rejected) += 1;
  }
  EXPECT_GT(accepted, 0);
  EXPECT_GT(rejected, 0);
}

TEST(SupernodalCholesky, RefusesAnotherPatternAndASolveAfterAFailure) {
  Eigen::SparseMatrix<double> lower = gridMatrix(6, 5, 3, 0.1, 3);
  SupernodalCholesky cholesky;
  cholesky.analyzePattern(lower);
  // Same size and entry count, one entry moved (as when a bolt slides to another edge).
  std::vector<Eigen::Triplet<double>> triplets;
  for (int j = 0; j < lower.outerSize(); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(lower, j); it; ++it)
      triplets.emplace_back(it.row(), it.col(), it.value());
  }
  for (auto& t : triplets) {
    if (t.row() != t.col()) {
      const int row = t.row() + 1 < lower.rows() ? t.row() + 1 : t.row() - 1;
      bool taken = false;
      for (const auto& o : triplets) taken = taken || (o.row() == row && o.col() == t.col());
      if (taken || row <= t.col()) continue;
      t = Eigen::Triplet<double>(row, t.col(), t.value());
      break;
    }
  }
  Eigen::SparseMatrix<double> moved(lower.rows(), lower.cols());
  moved.setFromTriplets(triplets.begin(), triplets.end());
  moved.makeCompressed();
  ASSERT_EQ(moved.nonZeros(), lower.nonZeros());
  EXPECT_THROW(cholesky.factorize(moved), InvalidInput);
  // A failed factorisation leaves no factor to solve with.
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(lower.rows());
  EXPECT_THROW(cholesky.solve(b), SolverFailure);
  Eigen::SparseMatrix<double> indefinite = lower;
  indefinite.coeffRef(40, 40) = -1.0;
  EXPECT_FALSE(cholesky.factorize(indefinite));
  EXPECT_THROW(cholesky.solve(b), SolverFailure);
  ASSERT_TRUE(cholesky.factorize(lower));
  EXPECT_NO_THROW(cholesky.solve(b));
}

}  // namespace
}  // namespace egg::rods
