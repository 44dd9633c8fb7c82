// The energy of the discretised grid (RodModel, Section 2.5): the stencils of every term, their
// double evaluation for line searches and their exact derivatives for Newton (HyperDual, or
// closed forms for the stretching, bend/twist and bolt stencils).
#include "core/rods/rod_model.hpp"

#include "core/rods/connection_derivatives.hpp"
#include "core/rods/stretching_derivatives.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>
#include <tuple>
#include <type_traits>
#include <utility>

namespace egg::rods {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Local variables of a stencil as 3-vectors.
template <class A>
auto v3(const A& v, int i) {
  using S = std::decay_t<decltype(v[0])>;
  return V3<S>{v[i], v[i + 1], v[i + 2]};
}

// Sums energies of stencils (double evaluation).
struct EnergySum {
  double total = 0.0;
  template <size_t N, class F>
  void operator()(const std::array<int, N>& /*dofs*/, const std::array<double, N>& values,
                  const F& f, bool /*projectable*/ = false) {
    total += f(values);
  }
  // A stencil with closed-form derivatives `d` (not needed for the energy alone).
  template <size_t N, class F, class D>
  void closedForm(const std::array<int, N>& dofs, const std::array<double, N>& values, const F& f,
                  const D& /*d*/, bool /*projectable*/, bool /*projectedByD*/ = false) {
    (*this)(dofs, values, f);
  }
};

// The local Hessian H of one stencil replaced by its nearest positive semidefinite matrix
// (negative eigenvalues set to zero): projected Newton (Teran et al. 2005). A sum of such
// stencils is positive semidefinite, so the solver's fallback needs no diagonal shift for them.
template <int N, class H>
Eigen::Matrix<double, N, N> projectedHessian(const H& hessian) {
  Eigen::Matrix<double, N, N> m;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j <= i; ++j) m(i, j) = m(j, i) = hessian(i, j);
  // Most stencils are semidefinite already: a Cholesky factorisation (a tenth of an
  // eigendecomposition's cost) tells them apart. Their Hessians are singular (rigid motions), so
  // it is tried with the diagonal raised by round-off; it only decides, m is returned unchanged.
  // (A pivoted LDL^T is no such test: it reported indefinite stencils as semidefinite.)
  Eigen::Matrix<double, N, N> raised = m;
  raised.diagonal().array() += 1e-12 * m.diagonal().cwiseAbs().maxCoeff();
  if (Eigen::LLT<Eigen::Matrix<double, N, N>>(raised).info() == Eigen::Success) return m;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(m);
  if (eigen.eigenvalues().minCoeff() >= 0.0) return m;
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
         eigen.eigenvectors().transpose();
}

// Accumulates energy, gradient and Hessian triplets of stencils (exact, by HyperDual).
struct DerivativeSum {
  double total = 0.0;
  HessianTerms terms = HessianTerms::Exact;
  Eigen::VectorXd gradient;
  std::vector<Eigen::Triplet<double>> triplets;
  template <size_t N, class F>
  // `projectable`: whether HessianTerms::ProjectedConstraints projects the stencil: the penalty
  // constraints (bolts, fastened joints, anchors), whose negative curvature away from their
  // constraint is an artefact of the penalty. Not stretching (a compressed edge's negative
  // curvature is the geometric stiffness that lets a rod buckle: projected, Newton converged onto
  // the unstable straight state), nor the notches' friction bumps, nor end moments.
  void operator()(const std::array<int, N>& dofs, const std::array<double, N>& values, const F& f,
                  bool projectable = false) {
    using D = HyperDual<static_cast<int>(N)>;
    // Set in place: a temporary per variable (D::variable) is zeroed and copied again, which for
    // the fastened joints' twelve 157-entry duals cost more than their energy's arithmetic.
    std::array<D, N> variables;
    for (size_t i = 0; i < N; ++i) {
      variables[i].v = values[i];
      if (dofs[i] >= 0) variables[i].g[static_cast<int>(i)] = 1.0;
    }
    const D result = f(variables);
    add(
        dofs, result.v, result.g, [&](int i, int j) { return result.hessian(i, j); }, projectable);
  }
  // The same with the derivatives computed in closed form by d() (energy, gradient, full Hessian).
  // `projectable`: false for the bending and twisting stencils, which HessianTerms::
  // ProjectedConstraints keeps exact.
  // `projectedByD`: d(true) returns a positive semidefinite Hessian (stretching's projection in
  // closed form, bending and twisting's Gauss-Newton Hessian): with every stencil projected, it is
  // scattered as it is, with no Cholesky test or eigendecomposition.
  template <size_t N, class F, class D>
  void closedForm(const std::array<int, N>& dofs, const std::array<double, N>& /*values*/,
                  const F& /*f*/, const D& d, bool projectable, bool projectedByD = false) {
    const bool all = terms == HessianTerms::ProjectedAll;
    const auto result = d(all);
    auto hessian = [&](int i, int j) { return result.hessian(i, j); };
    if (all && projectedByD) {
      scatter(dofs, result.energy, result.gradient, hessian);
    } else {
      add(dofs, result.energy, result.gradient, hessian, projectable);
    }
  }
  template <size_t N, class G, class H>
  void add(const std::array<int, N>& dofs, double energy, const G& g, const H& hessian,
           bool projectable) {
    if (terms == HessianTerms::ProjectedAll ||
        (projectable && terms == HessianTerms::ProjectedConstraints)) {
      const auto projected = projectedHessian<static_cast<int>(N)>(hessian);
      scatter(dofs, energy, g, [&](int i, int j) { return projected(i, j); });
    } else {
      scatter(dofs, energy, g, hessian);
    }
  }
  template <size_t N, class G, class H>
  void scatter(const std::array<int, N>& dofs, double energy, const G& g, const H& hessian) {
    total += energy;
    for (size_t i = 0; i < N; ++i) {
      if (dofs[i] < 0) continue;
      gradient[dofs[i]] += g[i];
      for (size_t j = 0; j < N; ++j) {
        if (dofs[j] < 0 || dofs[j] > dofs[i]) continue;
        // Zeros are kept: the sparsity pattern then depends only on which edges hold the bolts,
        // and the solver can reuse its symbolic factorisation.
        triplets.emplace_back(dofs[i], dofs[j], hessian(static_cast<int>(i), static_cast<int>(j)));
      }
    }
  }
};

}  // namespace

// ---------------------------------------------------------------- energy

SliderParameters RodModel::sliderParameters(const BoltSide& side) const {
  const RodData& r = rods_[side.point.rod];
  SliderParameters p;
  p.edgeStart = side.point.edge * r.h;
  p.edgeLength = r.h;
  p.notchMin = side.notchMin;
  p.notchMax = side.notchMax;
  p.mu = options_.frictionMu;
  p.epsilon = options_.frictionEpsilon;
  // The thesis gives E_p and E_n without units. Their barrier at every vertex, ~8.5 mu^2 high,
  // must be climbed over half an edge, so a bolt passes a vertex when the sliding force exceeds
  // ~17 mu^2 unit / h. With unit = EI_weak h / L^2 that threshold is 17 mu^2 EI/L^2 (mu = 0.1:
  // a sixth of the rod's Euler load), independent of the model's size and of the discretisation.
  p.unit = r.stiffness.bendingWeak * r.h / (r.length * r.length);
  return p;
}

namespace {

// The stencils are split into a fixed number of parts (round robin, so each part gets a mix of
// every kind) that TBB's threads take one at a time (`egg run --threads` bounds them). Fixed parts
// reduced in part order give results that do not depend on the thread count or on scheduling, bit
// for bit; taking parts as they come keeps every core busy when another process preempts one
// thread (with one static half per thread, measured under load: two threads slower than one).
constexpr int kParts = 16;

template <class Work>
void runParts(int threads, const Work& work) {
  if (threads <= 1) {
    for (int part = 0; part < kParts; ++part) work(part);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, kParts, 1), [&](const tbb::blocked_range<int>& r) {
    for (int part = r.begin(); part < r.end(); ++part) work(part);
  });
}

}  // namespace

void RodModel::frameDerivatives(const Eigen::VectorXd& z, int threads,
                                std::vector<EdgeFrameDerivatives>& frames) const {
  frames.resize(references_.size());
  runParts(threads, [&](int part) {
    for (int r = 0; r < rodCount(); ++r) {
      for (int j = 0; j < rods_[r].edges; ++j) {
        const int index = edgeReferenceBase_[r] + j;
        if (index % kParts != part) continue;
        const Eigen::Vector3d e = z.segment<3>(vertexDof(r, j + 1)) - z.segment<3>(vertexDof(r, j));
        edgeFrameDerivatives(e, z[thetaDof(r, j)], references_[index], frames[index]);
      }
    }
  });
}

template <class Visitor>
void RodModel::forEachStencil(const Eigen::VectorXd& z, Visitor&& visit, int part, int parts,
                              const std::vector<EdgeFrameDerivatives>* frames) const {
  long counter = 0;
  auto mine = [&]() { return (counter++ % parts) == part; };
  // Material frame of edge `edge` of rod `rod` over the stencil's variables v, whose local
  // indices start, end, theta hold the edge's two vertices and its angle.
  auto frameOf = [&](const auto& v, int rod, int edge, int start, int end, int theta) {
    using S = std::decay_t<decltype(v[0])>;
    const int index = edgeReferenceBase_[rod] + edge;
    if constexpr (std::is_same_v<S, double>) {
      return materialFrame(v3(v, end) - v3(v, start), v[theta], references_[index]);
    } else {
      constexpr int N = static_cast<int>(std::tuple_size_v<std::decay_t<decltype(v)>>);
      const Frame<HyperDual<4>>& f = (*frames)[index].frame;
      auto lift = [&](const V3<HyperDual<4>>& a) {
        return V3<S>{liftEdgeQuantity<N>(a.x, start, end, theta),
                     liftEdgeQuantity<N>(a.y, start, end, theta),
                     liftEdgeQuantity<N>(a.z, start, end, theta)};
      };
      return Frame<S>{lift(f.tangent), lift(f.normal), lift(f.side)};
    }
  };
  for (int r = 0; r < rodCount(); ++r) {
    const RodData& data = rods_[r];
    for (int j = 0; j < data.edges; ++j) {
      if (!mine()) continue;
      std::array<int, 6> dofs;
      std::array<double, 6> values;
      for (int k = 0; k < 6; ++k) dofs[k] = vertexDof(r, j) + k;
      for (int k = 0; k < 6; ++k) values[k] = z[dofs[k]];
      const double stiffness = stiffFactor_ * data.stiffness.stretching, h = data.h;
      visit.closedForm(
          dofs, values,
          [&](const auto& v) { return stretchingEnergy(v3(v, 0), v3(v, 3), stiffness, h); },
          [&](bool projected) {
            return stretchingDerivatives(Eigen::Vector3d(values[0], values[1], values[2]),
                                         Eigen::Vector3d(values[3], values[4], values[5]),
                                         stiffness, h, projected);
          },
          false, true);
    }
    for (int i = 1; i < data.edges; ++i) {
      if (!mine()) continue;
      // Unknowns x_{i-1}, x_i, x_{i+1} (consecutive dofs), theta_{i-1}, theta_i; the energy depends
      // on the vertices through e0 = x_i - x_{i-1}, e1 = x_{i+1} - x_i. Derivatives in closed form
      // (bend_twist_derivatives.hpp) from the precomputed edge frames.
      std::array<int, 11> dofs;
      std::array<double, 11> values;
      for (int k = 0; k < 9; ++k) dofs[k] = vertexDof(r, i - 1) + k;
      dofs[9] = thetaDof(r, i - 1);
      dofs[10] = thetaDof(r, i);
      for (int k = 0; k < 11; ++k) values[k] = z[dofs[k]];
      const int index = edgeReferenceBase_[r] + i;
      visit.closedForm(
          dofs, values,
          [&](const auto& v) {
            const auto e0 = v3(v, 3) - v3(v, 0), e1 = v3(v, 6) - v3(v, 3);
            return bendTwistEnergyOfEdges(e0, e1, materialFrame(e0, v[9], references_[index - 1]),
                                          materialFrame(e1, v[10], references_[index]),
                                          data.stiffness, data.h);
          },
          [&](bool gaussNewton) {
            return onVertices(bendTwistDerivatives((*frames)[index - 1], (*frames)[index],
                                                   data.stiffness, data.h, gaussNewton));
          },
          false, true);
    }
  }
  for (const Bolt& b : bolts_) {
    if (!mine()) continue;
    std::array<int, 16> dofs;
    std::array<double, 16> values;
    int k = 0;
    for (const BoltSide* s : {&b.lower, &b.upper}) {
      for (int c = 0; c < 6; ++c) dofs[k + c] = vertexDof(s->point.rod, s->point.edge) + c;
      dofs[k + 6] = thetaDof(s->point.rod, s->point.edge);
      dofs[k + 7] = s->betaDof;
      for (int c = 0; c < 7; ++c) values[k + c] = z[dofs[k + c]];
      values[k + 7] = beta(z, *s);
      k += 8;
    }
    // Derivatives in closed form (connection_derivatives.hpp) from the precomputed edge frames.
    visit.closedForm(
        dofs, values,
        [&](const auto& v) {
          const auto mg = frameOf(v, b.lower.point.rod, b.lower.point.edge, 0, 3, 6).normal;
          const auto mh = frameOf(v, b.upper.point.rod, b.upper.point.edge, 8, 11, 14).normal;
          return connectionEnergy(v3(v, 0), v3(v, 3), mg, v[7], v3(v, 8), v3(v, 11), mh, v[15],
                                  b.offset, stiffFactor_ * b.positionWeight, b.angleWeight);
        },
        [&](bool /*gaussNewton*/) {
          auto at = [&](int i) { return Eigen::Vector3d(values[i], values[i + 1], values[i + 2]); };
          const EdgeFrameDerivatives& fg =
              (*frames)[edgeReferenceBase_[b.lower.point.rod] + b.lower.point.edge];
          const EdgeFrameDerivatives& fh =
              (*frames)[edgeReferenceBase_[b.upper.point.rod] + b.upper.point.edge];
          return connectionDerivatives(at(0), at(3), fg, values[7], at(8), at(11), fh, values[15],
                                       b.offset, stiffFactor_ * b.positionWeight, b.angleWeight);
        },
        true);
  }
  for (const Bolt& b : bolts_) {
    if (b.fastenedWeight <= 0.0 || !mine()) continue;
    // The vertices of the two edges only: a subset of the bolt stencil's, so the sparsity pattern
    // is the same fastened or not.
    std::array<int, 12> dofs;
    std::array<double, 12> values;
    for (int c = 0; c < 6; ++c) dofs[c] = vertexDof(b.lower.point.rod, b.lower.point.edge) + c;
    for (int c = 0; c < 6; ++c) dofs[6 + c] = vertexDof(b.upper.point.rod, b.upper.point.edge) + c;
    for (int c = 0; c < 12; ++c) values[c] = z[dofs[c]];
    visit(
        dofs, values,
        [&](const auto& v) {
          return fastenedJointEnergy(v3(v, 0), v3(v, 3), v3(v, 6), v3(v, 9), b.fastenedCos,
                                     b.fastenedSin, b.fastenedAxis, b.fastenedWeight);
        },
        true);
  }
  for (const Bolt& b : bolts_) {
    for (const BoltSide* s : {&b.lower, &b.upper}) {
      if (s->betaDof < 0 || !mine()) continue;
      const SliderParameters p = sliderParameters(*s);
      visit(std::array<int, 1>{s->betaDof}, std::array<double, 1>{z[s->betaDof]},
            [&](const auto& v) { return sliderEnergy(v[0], p); });
    }
  }
  for (const AnchorData& a : anchors_) {
    if (!mine()) continue;
    std::array<int, 7> dofs;
    std::array<double, 7> values;
    for (int c = 0; c < 6; ++c) dofs[c] = vertexDof(a.point.rod, a.point.edge) + c;
    dofs[6] = thetaDof(a.point.rod, a.point.edge);
    for (int c = 0; c < 7; ++c) values[c] = z[dofs[c]];
    visit(
        dofs, values,
        [&](const auto& v) {
          const auto m = frameOf(v, a.point.rod, a.point.edge, 0, 3, 6).normal;
          return anchorEnergy(v3(v, 0), v3(v, 3), m, a.point.beta, a.target, a.targetNormal,
                              stiffFactor_ * a.positionWeight, a.angleWeight);
        },
        true);
  }
  for (const EndMoment& m : endMoments_) {
    if (!mine()) continue;
    const int n = rods_[m.rod].edges;
    std::array<int, 6> dofs;
    std::array<double, 6> values;
    for (int c = 0; c < 6; ++c) dofs[c] = vertexDof(m.rod, n - 1) + c;
    for (int c = 0; c < 6; ++c) values[c] = z[dofs[c]];
    visit(dofs, values, [&](const auto& v) {
      return endMomentPotential(v3(v, 0), v3(v, 3), m.axis, loadFactor_ * m.moment, m.direction,
                                m.angle);
    });
  }
}

bool RodModel::edgesValid(const Eigen::VectorXd& z) const {
  if (!z.allFinite()) return false;
  for (int r = 0; r < rodCount(); ++r) {
    const RodData& data = rods_[r];
    Eigen::Vector3d previous = Eigen::Vector3d::Zero();
    for (int j = 0; j < data.edges; ++j) {
      const Eigen::Vector3d e = z.segment<3>(vertexDof(r, j + 1)) - z.segment<3>(vertexDof(r, j));
      const double length = e.norm();
      if (!(length > 1e-6 * data.h)) return false;
      const Eigen::Vector3d t = e / length;
      // The time-parallel transport is singular for a reversed edge; a step that turns an edge
      // by more than 120 degrees is rejected and the line search backs off.
      if (t.dot(references_[edgeReferenceBase_[r] + j].tangent) < -0.5) return false;
      if (j > 0 && t.dot(previous) < -0.99)
        return false;  // folded back: curvature binormal blows up
      previous = t;
    }
  }
  return true;
}

double RodModel::externalPotential(const Eigen::VectorXd& z) const {
  double moments = 0.0;
  for (const EndMoment& m : endMoments_) {
    const int n = rods_[m.rod].edges;
    const V3<double> x0 = constant<double>(z.segment<3>(vertexDof(m.rod, n - 1)));
    const V3<double> x1 = constant<double>(z.segment<3>(vertexDof(m.rod, n)));
    moments += endMomentPotential(x0, x1, m.axis, loadFactor_ * m.moment, m.direction, m.angle);
  }
  return moments + constantGradient_.dot(z);
}

void RodModel::energyParts(const Eigen::VectorXd& z, double& internal, double& external) const {
  if (!edgesValid(z)) {
    internal = kInfinity;
    external = 0.0;
    return;
  }
  double moments = 0.0;
  EnergySum sum;
  forEachStencil(z, sum, 0, 1, nullptr);
  for (const EndMoment& m : endMoments_) {
    const int n = rods_[m.rod].edges;
    const V3<double> x0 = constant<double>(z.segment<3>(vertexDof(m.rod, n - 1)));
    const V3<double> x1 = constant<double>(z.segment<3>(vertexDof(m.rod, n)));
    moments += endMomentPotential(x0, x1, m.axis, loadFactor_ * m.moment, m.direction, m.angle);
  }
  internal = sum.total - moments;
  external = moments + constantGradient_.dot(z);
}

double RodModel::energy(const Eigen::VectorXd& z) const {
  double internal = 0.0, external = 0.0;
  energyParts(z, internal, external);
  const double e = internal + external;
  return std::isnan(e) ? kInfinity : e;
}

double RodModel::derivatives(const Eigen::VectorXd& z, Eigen::VectorXd& gradient,
                             std::vector<Eigen::Triplet<double>>& hessian, int threads,
                             HessianTerms terms) const {
  DerivativeBuffers buffers;
  const double e = derivatives(z, gradient, buffers, threads, terms);
  hessian.clear();
  size_t total = 0;
  for (const auto& part : buffers.triplets) total += part.size();
  hessian.reserve(total);
  for (const auto& part : buffers.triplets) hessian.insert(hessian.end(), part.begin(), part.end());
  return e;
}

double RodModel::derivatives(const Eigen::VectorXd& z, Eigen::VectorXd& gradient,
                             DerivativeBuffers& buffers, int threads, HessianTerms terms) const {
  threads = std::max(1, threads);
  frameDerivatives(z, threads, buffers.frames);
  buffers.gradients.resize(kParts);
  buffers.triplets.resize(kParts);
  buffers.energies.assign(kParts, 0.0);
  runParts(threads, [&](int part) {
    DerivativeSum sum;
    sum.terms = terms;
    // The part's buffers move into the sum and back: their capacity is kept between calls.
    sum.gradient = std::move(buffers.gradients[part]);
    sum.triplets = std::move(buffers.triplets[part]);
    sum.gradient.setZero(dofCount_);
    sum.triplets.clear();
    forEachStencil(z, sum, part, kParts, &buffers.frames);
    buffers.gradients[part] = std::move(sum.gradient);
    buffers.triplets[part] = std::move(sum.triplets);
    buffers.energies[part] = sum.total;
  });
  gradient = constantGradient_;
  double e = constantGradient_.dot(z);
  for (int part = 0; part < kParts; ++part) {
    gradient += buffers.gradients[part];
    e += buffers.energies[part];
  }
  return e;
}

double RodModel::maxStep(const Eigen::VectorXd& z, const Eigen::VectorXd& direction) const {
  double alpha = 1.0;
  const double eps = options_.frictionEpsilon;
  for (const Bolt& b : bolts_) {
    for (const BoltSide* s : {&b.lower, &b.upper}) {
      if (s->betaDof < 0) continue;
      const double beta0 = z[s->betaDof], d = direction[s->betaDof];
      const double h = rods_[s->point.rod].h;
      const double start = s->point.edge * h;
      // Stay 1 % short of the barrier walls.
      const double high = std::min(1.0 + eps, (s->notchMax - start) / h);
      const double low = std::max(-eps, (s->notchMin - start) / h);
      if (d > 0.0) alpha = std::min(alpha, 0.99 * (high - beta0) / d);
      if (d < 0.0) alpha = std::min(alpha, 0.99 * (low - beta0) / d);
    }
  }
  return std::max(alpha, 0.0);
}

}  // namespace egg::rods
