// Left-looking supernodal sparse Cholesky (see supernodal_cholesky.hpp).
#include "core/rods/supernodal_cholesky.hpp"

#include "core/errors.hpp"

#include <cholmod.h>
#include <Eigen/OrderingMethods>

#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <numeric>

namespace egg::rods {
namespace {

// Position in the factor of each unknown. CHOLMOD's analysis tries AMD and, on a large grid,
// METIS (nested dissection), and keeps the one with the fewer nonzeros in L, postordered. Nested
// dissection pays off only on large grids: over the three samples' patch grids and the joined
// Great Court and Lilium (up to 23k unknowns) AMD filled less or at most 1.3 % more, and METIS took
// three quarters of the analysis' time (80 of 107 ms on the joined Great Court); on the joined
// Yas (143k unknowns) METIS fills 12 % less (docs/measurements.md). Only the ordering is
// CHOLMOD's; the factorisation stays ours.
constexpr int kNestedDissectionFrom = 40000;  // unknowns

std::vector<int> fillReducingOrder(const Eigen::SparseMatrix<double>& lower) {
  const int n = static_cast<int>(lower.rows());
  cholmod_common common;
  cholmod_start(&common);
  common.nmethods = n >= kNestedDissectionFrom ? 2 : 1;
  common.method[0].ordering = CHOLMOD_AMD;
  common.method[1].ordering = CHOLMOD_METIS;
  common.postorder = 1;
  common.supernodal = CHOLMOD_SIMPLICIAL;  // no supernodal symbolic work: the ordering is all
  common.print = 0;
  common.error_handler = nullptr;
  cholmod_sparse a{};
  a.nrow = a.ncol = static_cast<size_t>(n);
  a.nzmax = static_cast<size_t>(lower.nonZeros());
  // CHOLMOD reads the pattern only (CHOLMOD_PATTERN): the casts drop a const it never writes.
  a.p = const_cast<int*>(lower.outerIndexPtr());
  a.i = const_cast<int*>(lower.innerIndexPtr());
  a.stype = -1;  // the lower triangle of a symmetric matrix
  a.itype = CHOLMOD_INT;
  a.xtype = CHOLMOD_PATTERN;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  cholmod_factor* factor = cholmod_analyze(&a, &common);
  std::vector<int> position(n);
  if (factor == nullptr || common.status < CHOLMOD_OK) {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
    // AMD alone, as in Eigen's SimplicialCholesky (CHOLMOD out of memory, say).
    const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(full, inverse);
    const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation =
        inverse.inverse();
    position.assign(permutation.indices().data(), permutation.indices().data() + n);
    return position;
  }
  const int* perm = static_cast<const int*>(factor->Perm);  // perm[k]: the unknown placed k-th
  for (int k = 0; k < n; ++k) position[perm[k]] = k;
  cholmod_free_factor(&factor, &common);
  cholmod_finish(&common);
  return position;
}

// The raw arrays of a factorisation (SupernodalCholesky's members): the numeric loop is a free
// function so that it can be compiled twice, for AVX2 and for plain x86-64, and picked when the
// program starts (GCC target_clones). Without FMA the vector code does the same operations in the
// same order as the scalar one: both give the same factor to the bit (docs/measurements.md, issue
// 36).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define EGG_FACTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define EGG_FACTOR_CLONES
#endif

// A subtree with less work than this (multiply-adds, about a millisecond) is factorised by one
// thread: a task costs more than it would save.
constexpr double kSerialSubtreeWork = 2e6;

struct FactorArrays {
  const int *first, *rowStart, *rows;
  const long* valueStart;
  const int* supernodeOf;
  double* values;
  int *head, *next, *pointer;
};

// Pushes supernode K onto the list of supernodes that update `target`. Lists of an ancestor
// receive from subtrees factorised on other threads at the same time; a list is read only once
// every descendant of its supernode is done.
inline void pushUpdate(const FactorArrays& x, int target, int K) {
  std::atomic_ref<int> head(x.head[target]);
  int old = head.load(std::memory_order_relaxed);
  do {
    x.next[K] = old;
  } while (
      !head.compare_exchange_weak(old, K, std::memory_order_release, std::memory_order_relaxed));
}

// sum_k[ii] = sum over t of L_K(p + ii, t) L_K(p + jj + k, t) for rows ii in [from, to) and the
// C target columns jj + k (sum_k at sums + k * stride), in a fixed order per entry: four source
// columns per pass, then one at a time (one load and store of a sum for four products).
template <int C>
[[gnu::always_inline]] inline void sumColumns(const double* lK, int mK, int wK, int p, int jj,
                                              int from, int to, double* sums, int stride) {
  double* const sumA = sums;
  double* const sumB = sums + (C == 2 ? stride : 0);
  int t = 0;
  if (wK >= 4) {
    const double* s0 = lK + p;
    const double *s1 = s0 + mK, *s2 = s1 + mK, *s3 = s2 + mK;
    const double a0 = s0[jj], a1 = s1[jj], a2 = s2[jj], a3 = s3[jj];
    const double b0 = s0[jj + C - 1], b1 = s1[jj + C - 1], b2 = s2[jj + C - 1], b3 = s3[jj + C - 1];
    for (int ii = from; ii < to; ++ii) {
      sumA[ii] = a0 * s0[ii] + a1 * s1[ii] + a2 * s2[ii] + a3 * s3[ii];
      if constexpr (C == 2) sumB[ii] = b0 * s0[ii] + b1 * s1[ii] + b2 * s2[ii] + b3 * s3[ii];
    }
    t = 4;
  } else {
    for (int ii = from; ii < to; ++ii) {
      sumA[ii] = 0.0;
      if constexpr (C == 2) sumB[ii] = 0.0;
    }
  }
  for (; t + 4 <= wK; t += 4) {
    const double* s0 = lK + static_cast<long>(t) * mK + p;
    const double *s1 = s0 + mK, *s2 = s1 + mK, *s3 = s2 + mK;
    const double a0 = s0[jj], a1 = s1[jj], a2 = s2[jj], a3 = s3[jj];
    const double b0 = s0[jj + C - 1], b1 = s1[jj + C - 1], b2 = s2[jj + C - 1], b3 = s3[jj + C - 1];
    for (int ii = from; ii < to; ++ii) {
      sumA[ii] += a0 * s0[ii] + a1 * s1[ii] + a2 * s2[ii] + a3 * s3[ii];
      if constexpr (C == 2) sumB[ii] += b0 * s0[ii] + b1 * s1[ii] + b2 * s2[ii] + b3 * s3[ii];
    }
  }
  for (; t < wK; ++t) {
    const double* source = lK + static_cast<long>(t) * mK + p;
    const double a = source[jj], b = source[jj + C - 1];
    for (int ii = from; ii < to; ++ii) {
      sumA[ii] += a * source[ii];
      if constexpr (C == 2) sumB[ii] += b * source[ii];
    }
  }
}

// Supernode J, left-looking: every update from its descendants, then its own columns; false at
// the first pivot that is not positive. The updates come in increasing order of their source, so
// that the factor does not depend on which thread finished first.
EGG_FACTOR_CLONES bool factorSupernode(const FactorArrays& x, CholeskyWorkspace& work, int J) {
  {
    const int f = x.first[J], last = x.first[J + 1] - 1, w = x.first[J + 1] - x.first[J];
    const int* rowsJ = x.rows + x.rowStart[J];
    const int m = x.rowStart[J + 1] - x.rowStart[J];
    double* const blockData = x.values + x.valueStart[J];
    int* const relative = work.relative.data();
    int* const localRow = work.localRow.data();
    double* const accumulator = work.accumulator.data();
    for (int i = 0; i < m; ++i) relative[rowsJ[i]] = i;
    // Updates from every earlier supernode with rows in this one's columns.
    std::vector<int>& sources = work.sources;
    sources.clear();
    for (int K = x.head[J]; K != -1; K = x.next[K]) sources.push_back(K);
    std::sort(sources.begin(), sources.end(), std::greater<>());
    for (const int K : sources) {
      const int* rowsK = x.rows + x.rowStart[K];
      const int mK = x.rowStart[K + 1] - x.rowStart[K], wK = x.first[K + 1] - x.first[K];
      const double* const lK = x.values + x.valueStart[K];
      const int p = x.pointer[K];
      int q = p;
      while (q < mK && rowsK[q] <= last) ++q;
      // Subtract L_K(rows p.., :) L_K(rows p..q-1, :)^T from this supernode's columns, column
      // by column with contiguous inner loops (blocks are too small for a blocked product).
      const int r = mK - p, c = q - p;
      for (int ii = 0; ii < r; ++ii) localRow[ii] = relative[rowsK[p + ii]];
      // Two target columns per pass share the loads of the source columns (the loop is bound by
      // loads, not products); the first column's diagonal row goes alone.
      int jj = 0;
      for (; jj + 1 < c; jj += 2) {
        double* const sumA = accumulator;
        double* const sumB = accumulator + r;
        sumColumns<1>(lK, mK, wK, p, jj, jj, jj + 1, sumA, r);
        sumColumns<2>(lK, mK, wK, p, jj, jj + 1, r, sumA, r);
        double* columnA = blockData + static_cast<long>(rowsK[p + jj] - f) * m;
        double* columnB = blockData + static_cast<long>(rowsK[p + jj + 1] - f) * m;
        columnA[localRow[jj]] -= sumA[jj];
        for (int ii = jj + 1; ii < r; ++ii) {
          columnA[localRow[ii]] -= sumA[ii];
          columnB[localRow[ii]] -= sumB[ii];
        }
      }
      if (jj < c) {
        double* const sum = accumulator;
        sumColumns<1>(lK, mK, wK, p, jj, jj, r, sum, r);
        double* column = blockData + static_cast<long>(rowsK[p + jj] - f) * m;
        for (int ii = jj; ii < r; ++ii) column[localRow[ii]] -= sum[ii];
      }
      x.pointer[K] = q;
      if (q < mK) pushUpdate(x, x.supernodeOf[rowsK[q]], K);
    }
    // Column by column: L(:, j) = (A(:, j) - L(:, 0..j-1) L(j, 0..j-1)^T) / L(j, j).
    double* a = blockData;
    for (int j = 0; j < w; ++j) {
      double* column = a + static_cast<long>(j) * m;
      int t = 0;
      for (; t + 4 <= j; t += 4) {
        const double* p0 = a + static_cast<long>(t) * m;
        const double *p1 = p0 + m, *p2 = p1 + m, *p3 = p2 + m;
        const double f0 = p0[j], f1 = p1[j], f2 = p2[j], f3 = p3[j];
        for (int i = j; i < m; ++i) column[i] -= f0 * p0[i] + f1 * p1[i] + f2 * p2[i] + f3 * p3[i];
      }
      for (; t < j; ++t) {
        const double* previous = a + static_cast<long>(t) * m;
        const double factor = previous[j];
        for (int i = j; i < m; ++i) column[i] -= factor * previous[i];
      }
      const double pivot = column[j];
      if (!(pivot > 0.0)) return false;
      const double root = std::sqrt(pivot);
      column[j] = root;
      const double inverse = 1.0 / root;
      for (int i = j + 1; i < m; ++i) column[i] *= inverse;
    }
    if (m > w) {
      x.pointer[J] = w;
      pushUpdate(x, x.supernodeOf[rowsJ[w]], J);
    }
  }
  return true;
}

}  // namespace

void SupernodalCholesky::analyzePattern(const Eigen::SparseMatrix<double>& lower) {
  if (lower.rows() != lower.cols() || !lower.isCompressed()) {
    throw InvalidInput("SupernodalCholesky: square compressed matrix expected");
  }
  n_ = static_cast<int>(lower.rows());
  newIndex_ = fillReducingOrder(lower);

  // The permuted lower triangle, column by column.
  std::vector<std::vector<int>> columnRows(n_);
  const int* outer = lower.outerIndexPtr();
  const int* inner = lower.innerIndexPtr();
  for (int j = 0; j < n_; ++j) {
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int a = newIndex_[inner[k]], b = newIndex_[j];
      columnRows[std::min(a, b)].push_back(std::max(a, b));
    }
  }
  // Structure of every column of L: its own entries and its children's below itself
  // (elimination tree: the parent is the first row below the diagonal).
  std::vector<std::vector<int>> pattern(n_);
  std::vector<std::vector<int>> children(n_);
  std::vector<int> parent(n_, -1), mark(n_, -1);
  for (int j = 0; j < n_; ++j) {
    std::vector<int>& p = pattern[j];
    mark[j] = j;
    p.push_back(j);
    for (int r : columnRows[j]) {
      if (mark[r] != j) mark[r] = j, p.push_back(r);
    }
    for (int c : children[j]) {
      for (int r : pattern[c]) {
        if (r > c && mark[r] != j) mark[r] = j, p.push_back(r);
      }
    }
    std::sort(p.begin(), p.end());
    if (p.size() > 1) {
      parent[j] = p[1];
      children[p[1]].push_back(j);
    }
  }
  // Supernodes: j continues the supernode of j - 1 when j is its parent and the structures nest.
  first_.clear();
  supernodeOf_.assign(n_, -1);
  for (int j = 0; j < n_; ++j) {
    const bool extends =
        j > 0 && parent[j - 1] == j && pattern[j].size() + 1 == pattern[j - 1].size();
    if (!extends) first_.push_back(j);
    supernodeOf_[j] = static_cast<int>(first_.size()) - 1;
  }
  first_.push_back(n_);
  const int count = supernodeCount();
  rowStart_.assign(count + 1, 0);
  valueStart_.assign(count + 1, 0);
  rows_.clear();
  for (int s = 0; s < count; ++s) {
    const std::vector<int>& p = pattern[first_[s]];
    rows_.insert(rows_.end(), p.begin(), p.end());
    rowStart_[s + 1] = static_cast<int>(rows_.size());
    const long width = first_[s + 1] - first_[s];
    valueStart_[s + 1] = valueStart_[s] + width * static_cast<long>(p.size());
  }
  values_.assign(valueStart_[count], 0.0);
  // Where each input entry goes.
  slot_.assign(lower.nonZeros(), -1);
  for (int j = 0; j < n_; ++j) {
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      const int a = std::max(newIndex_[inner[k]], newIndex_[j]),
                b = std::min(newIndex_[inner[k]], newIndex_[j]);
      const int s = supernodeOf_[b];
      const int* begin = rows_.data() + rowStart_[s];
      const int* end = rows_.data() + rowStart_[s + 1];
      const long localRow = std::lower_bound(begin, end, a) - begin;
      slot_[k] = valueStart_[s] + (b - first_[s]) * static_cast<long>(end - begin) + localRow;
    }
  }
  patternOuter_.assign(outer, outer + n_ + 1);
  patternInner_.assign(inner, inner + lower.nonZeros());
  factored_ = false;
  head_.assign(count, -1);
  next_.assign(count, -1);
  pointer_.assign(count, 0);
  analyzeTree();
  workspaces_ = std::make_shared<Workspaces>(CholeskyWorkspace(n_));
}

bool SupernodalCholesky::factorize(const Eigen::SparseMatrix<double>& lower) {
  factored_ = false;
  if (static_cast<long>(slot_.size()) != lower.nonZeros() || lower.rows() != n_ ||
      !lower.isCompressed() ||
      !std::equal(patternOuter_.begin(), patternOuter_.end(), lower.outerIndexPtr()) ||
      !std::equal(patternInner_.begin(), patternInner_.end(), lower.innerIndexPtr())) {
    throw InvalidInput("SupernodalCholesky: factorize needs the pattern given to analyzePattern");
  }
  std::fill(values_.begin(), values_.end(), 0.0);
  const double* input = lower.valuePtr();
  for (size_t k = 0; k < slot_.size(); ++k) values_[slot_[k]] += input[k];
  std::fill(head_.begin(), head_.end(), -1);
  const FactorArrays arrays{first_.data(),      rowStart_.data(),    rows_.data(),
                            valueStart_.data(), supernodeOf_.data(), values_.data(),
                            head_.data(),       next_.data(),        pointer_.data()};
  std::atomic<bool> failed{false};
  // A subtree of the elimination tree needs only its own supernodes: disjoint subtrees are
  // factorised on TBB's threads at the same time, down to subtrees of little work, which one
  // thread takes in order (postorder: a subtree is a range of supernodes).
  const std::function<void(int)> subtree = [&](int J) {
    if (failed.load(std::memory_order_relaxed)) return;
    if (!postordered_ || work_[J] < kSerialSubtreeWork) {
      CholeskyWorkspace& work = workspaces_->local();
      for (int s = subtreeFirst_[J]; s <= J && !failed.load(std::memory_order_relaxed); ++s)
        if (!factorSupernode(arrays, work, s)) failed = true;
      return;
    }
    tbb::task_group group;
    for (int k = childStart_[J]; k < childStart_[J + 1]; ++k)
      group.run([&, child = children_[k]] { subtree(child); });
    group.wait();
    if (!failed.load() && !factorSupernode(arrays, workspaces_->local(), J)) failed = true;
  };
  if (postordered_) {
    tbb::task_group group;
    for (const int root : roots_) group.run([&, root] { subtree(root); });
    group.wait();
  } else {
    CholeskyWorkspace& work = workspaces_->local();
    for (int J = 0; J < supernodeCount() && !failed; ++J)
      if (!factorSupernode(arrays, work, J)) failed = true;
  }
  if (failed) return false;
  factored_ = true;
  return true;
}

// The supernodal elimination tree: the parent of a supernode is the one holding its first row
// below its columns. Its children, the work of each subtree (multiply-adds of its columns' outer
// products) and whether every subtree is a range of supernodes (CHOLMOD's postorder; the AMD
// fallback is not postordered and then runs in one thread).
void SupernodalCholesky::analyzeTree() {
  const int count = supernodeCount();
  std::vector<int> parent(count, -1), size(count, 1);
  childStart_.assign(count + 2, 0);
  work_.assign(count, 0.0);
  subtreeFirst_.resize(count);
  std::iota(subtreeFirst_.begin(), subtreeFirst_.end(), 0);
  roots_.clear();
  postordered_ = true;
  for (int s = 0; s < count; ++s) {
    const int w = first_[s + 1] - first_[s], m = rowStart_[s + 1] - rowStart_[s];
    for (int c = 0; c < w; ++c) work_[s] += static_cast<double>(m - c) * (m - c);
    if (m > w) parent[s] = supernodeOf_[rows_[rowStart_[s] + w]];
  }
  for (int s = 0; s < count; ++s) {  // children have smaller numbers: their sums are complete
    if (parent[s] < 0) {
      roots_.push_back(s);
      continue;
    }
    work_[parent[s]] += work_[s];
    size[parent[s]] += size[s];
    subtreeFirst_[parent[s]] = std::min(subtreeFirst_[parent[s]], subtreeFirst_[s]);
    ++childStart_[parent[s] + 2];
  }
  for (int s = 0; s < count; ++s)
    postordered_ = postordered_ && s - subtreeFirst_[s] + 1 == size[s];
  for (int s = 0; s < count; ++s) childStart_[s + 2] += childStart_[s + 1];
  children_.assign(childStart_[count + 1], 0);
  for (int s = 0; s < count; ++s)
    if (parent[s] >= 0) children_[childStart_[parent[s] + 1]++] = s;
  childStart_.pop_back();
}

Eigen::VectorXd SupernodalCholesky::solve(const Eigen::VectorXd& b) const {
  if (!factored_)
    throw SolverFailure("SupernodalCholesky: solve needs a successful factorize first");
  if (b.size() != n_) throw InvalidInput("SupernodalCholesky: right-hand side of the wrong size");
  Eigen::VectorXd x(n_);
  for (int i = 0; i < n_; ++i) x[newIndex_[i]] = b[i];
  const int count = supernodeCount();
  using Block = Eigen::Map<const Eigen::MatrixXd>;
  Eigen::VectorXd work;
  for (int J = 0; J < count; ++J) {
    const int f = first_[J], w = first_[J + 1] - first_[J];
    const int* rowsJ = rows_.data() + rowStart_[J];
    const int m = rowStart_[J + 1] - rowStart_[J];
    const Block block(values_.data() + valueStart_[J], m, w);
    auto xJ = x.segment(f, w);
    block.topLeftCorner(w, w).triangularView<Eigen::Lower>().solveInPlace(xJ);
    if (m > w) {
      work.noalias() = block.bottomRows(m - w) * xJ;
      for (int i = w; i < m; ++i) x[rowsJ[i]] -= work[i - w];
    }
  }
  for (int J = count - 1; J >= 0; --J) {
    const int f = first_[J], w = first_[J + 1] - first_[J];
    const int* rowsJ = rows_.data() + rowStart_[J];
    const int m = rowStart_[J + 1] - rowStart_[J];
    const Block block(values_.data() + valueStart_[J], m, w);
    auto xJ = x.segment(f, w);
    if (m > w) {
      work.resize(m - w);
      for (int i = w; i < m; ++i) work[i - w] = x[rowsJ[i]];
      xJ.noalias() -= block.bottomRows(m - w).transpose() * work;
    }
    block.topLeftCorner(w, w).triangularView<Eigen::Lower>().transpose().solveInPlace(xJ);
  }
  Eigen::VectorXd out(n_);
  for (int i = 0; i < n_; ++i) out[i] = x[newIndex_[i]];
  return out;
}

long SupernodalCholesky::factorNonZeros() const {
  long total = 0;
  for (int s = 0; s < supernodeCount(); ++s) {
    const long w = first_[s + 1] - first_[s], m = rowStart_[s + 1] - rowStart_[s];
    total += w * m - w * (w - 1) / 2;
  }
  return total;
}

}  // namespace egg::rods
