// Planarisation of a generalised geodesic grid (Section 4.7): see planarisation.hpp.
#include "core/generalised/planarisation.hpp"

#include "core/errors.hpp"

#include <nlopt.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace egg::generalised {

namespace {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
// A point of the fabrication term as a linear map of its pair's 8 endpoint coordinates
// (s_first, e_first, s_second, e_second).
using PointMap = Eigen::Matrix<double, 2, 8>;

constexpr double kOverlapTolerance = 1e-9;  // m: an overlap above this is reported

Vec2 at(const std::vector<double>& x, int member, int end) {
  return {x[4 * member + 2 * end], x[4 * member + 2 * end + 1]};
}

std::string where(const char* field, size_t index) {
  return std::string("PlanarisationProblem.") + field + "[" + std::to_string(index) + "]";
}

// The facing edges of a neighbour pair (Fig. 4.18): the left edge of `first` (P1 at its start,
// P2 at its end) and the right edge of `second` (P3, P4), each offset by w/2 along the member's
// left normal R (e - s) / l (R: a quarter turn counter-clockwise), linear in the endpoints since
// l is the member's fixed length.
std::array<PointMap, 4> facingEdges(const PlanarisationProblem& problem,
                                    const NeighbourPair& pair) {
  Mat2 quarter;
  quarter << 0.0, -1.0, 1.0, 0.0;
  const double half = 0.5 * problem.widthM;
  const Mat2 ra = (half / problem.members[pair.first].lengthM) * quarter;
  const Mat2 rb = (half / problem.members[pair.second].lengthM) * quarter;
  const Mat2 identity = Mat2::Identity();
  std::array<PointMap, 4> p;
  for (auto& m : p) m.setZero();
  p[0].block<2, 2>(0, 0) = identity - ra;  // P1 = s_a + h n_a
  p[0].block<2, 2>(0, 2) = ra;
  p[1].block<2, 2>(0, 0) = -ra;  // P2 = e_a + h n_a
  p[1].block<2, 2>(0, 2) = identity + ra;
  p[2].block<2, 2>(0, 4) = identity + rb;  // P3 = s_b - h n_b
  p[2].block<2, 2>(0, 6) = -rb;
  p[3].block<2, 2>(0, 4) = rb;  // P4 = e_b - h n_b
  p[3].block<2, 2>(0, 6) = identity - rb;
  return p;
}

Eigen::Matrix<double, 8, 1> pairVariables(const std::vector<double>& x, const NeighbourPair& pair) {
  Eigen::Matrix<double, 8, 1> y;
  for (int k = 0; k < 4; ++k) {
    y[k] = x[4 * pair.first + k];
    y[4 + k] = x[4 * pair.second + k];
  }
  return y;
}

// e = sign det(P_j - P_i, P_k - P_i) and its gradient over the pair's 8 coordinates.
double signedDeterminant(const std::array<PointMap, 4>& p, const Eigen::Matrix<double, 8, 1>& y,
                         int i, int j, int k, double sign, Eigen::Matrix<double, 8, 1>* gradient) {
  const PointMap du = p[j] - p[i], dv = p[k] - p[i];
  const Vec2 u = du * y, v = dv * y;
  if (gradient != nullptr) {
    *gradient =
        sign * (du.transpose() * Vec2(v.y(), -v.x()) + dv.transpose() * Vec2(-u.y(), u.x()));
  }
  return sign * (u.x() * v.y() - u.y() * v.x());
}

// The four determinants of Fig. 4.18 for a pair (P3, P4 left of P1->P2; P1, P2 right of P3->P4),
// each <= 0 when the lamellas keep apart.
std::array<double, 4> determinants(const std::array<PointMap, 4>& p,
                                   const Eigen::Matrix<double, 8, 1>& y,
                                   std::array<Eigen::Matrix<double, 8, 1>, 4>* gradients) {
  auto g = [&](int n) { return gradients != nullptr ? &(*gradients)[n] : nullptr; };
  return {signedDeterminant(p, y, 0, 1, 2, -1.0, g(0)),
          signedDeterminant(p, y, 0, 1, 3, -1.0, g(1)), signedDeterminant(p, y, 2, 3, 0, 1.0, g(2)),
          signedDeterminant(p, y, 2, 3, 1, 1.0, g(3))};
}

double notchTerms(const PlanarisationProblem& problem, const std::vector<double>& x,
                  std::vector<double>* gradient, std::vector<double>* lengths) {
  double energy = 0.0;
  for (const MemberCrossing& c : problem.crossings) {
    const Vec2 qg = (1.0 - c.lambdaG) * at(x, c.g, 0) + c.lambdaG * at(x, c.g, 1);
    const Vec2 qh = (1.0 - c.lambdaH) * at(x, c.h, 0) + c.lambdaH * at(x, c.h, 1);
    const Vec2 d = qg - qh;
    energy += d.squaredNorm();
    if (lengths != nullptr) lengths->push_back(d.norm());
    if (gradient == nullptr) continue;
    for (int a = 0; a < 2; ++a) {
      (*gradient)[4 * c.g + a] += 2.0 * (1.0 - c.lambdaG) * d[a];
      (*gradient)[4 * c.g + 2 + a] += 2.0 * c.lambdaG * d[a];
      (*gradient)[4 * c.h + a] -= 2.0 * (1.0 - c.lambdaH) * d[a];
      (*gradient)[4 * c.h + 2 + a] -= 2.0 * c.lambdaH * d[a];
    }
  }
  return energy;
}

// NLopt works on the free coordinates: all but the first member's start (the rigid translation).
struct SolveData {
  const PlanarisationProblem* problem;
  std::vector<double> full;  // every coordinate, the held ones at their initial values
  std::vector<double> gradient;
  int evaluations = 0;
};

constexpr int kHeld = 2;

void expand(SolveData& data, const double* free) {
  std::copy(free, free + data.full.size() - kHeld, data.full.begin() + kHeld);
}

double objectiveCallback(unsigned /*n*/, const double* free, double* grad, void* raw) {
  SolveData& data = *static_cast<SolveData*>(raw);
  ++data.evaluations;
  expand(data, free);
  if (grad != nullptr) data.gradient.assign(data.full.size(), 0.0);
  const double value =
      notchTerms(*data.problem, data.full, grad != nullptr ? &data.gradient : nullptr, nullptr);
  if (grad != nullptr) std::copy(data.gradient.begin() + kHeld, data.gradient.end(), grad);
  return value;
}

// G_len divided by l^2: every member's constraint is dimensionless and of the same size.
void lengthCallback(unsigned m, double* result, unsigned n, const double* free, double* grad,
                    void* raw) {
  SolveData& data = *static_cast<SolveData*>(raw);
  expand(data, free);
  std::vector<double> values, jacobian;
  lengthConstraints(*data.problem, data.full, values, grad != nullptr ? &jacobian : nullptr);
  const size_t columns = data.full.size();
  for (unsigned i = 0; i < m; ++i) {
    const double l = data.problem->members[i].lengthM;
    result[i] = values[i] / (l * l);
    if (grad == nullptr) continue;
    for (unsigned k = 0; k < n; ++k) grad[i * n + k] = jacobian[i * columns + kHeld + k] / (l * l);
  }
}

// The overlap distances of every neighbour pair, four each, <= 0.
void overlapCallback(unsigned m, double* result, unsigned n, const double* free, double* grad,
                     void* raw) {
  SolveData& data = *static_cast<SolveData*>(raw);
  expand(data, free);
  if (grad != nullptr) std::fill(grad, grad + static_cast<size_t>(m) * n, 0.0);
  for (size_t k = 0; k < data.problem->neighbours.size(); ++k) {
    const NeighbourPair& pair = data.problem->neighbours[k];
    std::array<Eigen::Matrix<double, 8, 1>, 4> gradients;
    const auto e =
        overlapDistances(*data.problem, pair, data.full, grad != nullptr ? &gradients : nullptr);
    for (int i = 0; i < 4; ++i) {
      const size_t row = 4 * k + i;
      result[row] = e[i];
      if (grad == nullptr) continue;
      for (int c = 0; c < 8; ++c) {
        const int coordinate = 4 * (c < 4 ? pair.first : pair.second) + c % 4 - kHeld;
        if (coordinate >= 0) grad[row * n + coordinate] += gradients[i][c];
      }
    }
  }
}

// Each member rescaled about its midpoint to its length.
void keepLengths(const PlanarisationProblem& problem, std::vector<double>& x) {
  for (size_t i = 0; i < problem.members.size(); ++i) {
    const int m = static_cast<int>(i);
    const Vec2 s = at(x, m, 0), e = at(x, m, 1);
    const Vec2 mid = 0.5 * (s + e), direction = (e - s).normalized();
    const double half = 0.5 * problem.members[i].lengthM;
    const Vec2 s2 = mid - half * direction, e2 = mid + half * direction;
    x[4 * i] = s2.x(), x[4 * i + 1] = s2.y(), x[4 * i + 2] = e2.x(), x[4 * i + 3] = e2.y();
  }
}

double lengthResidual(const PlanarisationProblem& problem, const std::vector<double>& x) {
  double worst = 0.0;
  for (size_t i = 0; i < problem.members.size(); ++i) {
    const int m = static_cast<int>(i);
    worst =
        std::max(worst, std::abs((at(x, m, 1) - at(x, m, 0)).norm() - problem.members[i].lengthM));
  }
  return worst;
}

}  // namespace

void PlanarisationProblem::validate() const {
  if (members.empty()) throw InvalidInput("PlanarisationProblem.members: no member");
  if (initial.size() != members.size()) {
    throw InvalidInput("PlanarisationProblem.initial: " + std::to_string(initial.size()) +
                       " layouts for " + std::to_string(members.size()) + " members");
  }
  for (size_t i = 0; i < members.size(); ++i) {
    if (!(members[i].lengthM > 0.0) || !std::isfinite(members[i].lengthM))
      throw InvalidInput(where("members", i) + ".lengthM must be a positive length");
    if (members[i].family != 0 && members[i].family != 1)
      throw InvalidInput(where("members", i) + ".family must be 0 or 1");
    if (!initial[i][0].allFinite() || !initial[i][1].allFinite() ||
        (initial[i][1] - initial[i][0]).norm() == 0.0)
      throw InvalidInput(where("initial", i) + ": endpoints must be finite and apart");
  }
  const int count = static_cast<int>(members.size());
  auto inRange = [&](int m) { return m >= 0 && m < count; };
  for (size_t k = 0; k < crossings.size(); ++k) {
    const MemberCrossing& c = crossings[k];
    if (!inRange(c.g) || !inRange(c.h) || members[c.g].family != 0 || members[c.h].family != 1)
      throw InvalidInput(where("crossings", k) + ": g must be a family-0 member, h a family-1 one");
    if (!(c.lambdaG >= 0.0 && c.lambdaG <= 1.0 && c.lambdaH >= 0.0 && c.lambdaH <= 1.0))
      throw InvalidInput(where("crossings", k) + ": lambdaG and lambdaH must lie in [0, 1]");
  }
  for (size_t k = 0; k < neighbours.size(); ++k) {
    const NeighbourPair& p = neighbours[k];
    if (!inRange(p.first) || !inRange(p.second) || p.first == p.second ||
        members[p.first].family != members[p.second].family)
      throw InvalidInput(where("neighbours", k) + ": two different members of one family");
  }
  if (!(widthM >= 0.0) || !std::isfinite(widthM))
    throw InvalidInput("PlanarisationProblem.widthM must be >= 0");
  if (!neighbours.empty() && !(widthM > 0.0))
    throw InvalidInput("PlanarisationProblem.widthM must be > 0 when neighbours are given");
}

void PlanarisationOptions::validate() const {
  if (maxEvaluations < 1) throw InvalidInput("PlanarisationOptions.maxEvaluations must be >= 1");
  if (!(relativeTolerance > 0.0))
    throw InvalidInput("PlanarisationOptions.relativeTolerance must be > 0");
}

double notchEnergy(const PlanarisationProblem& problem, const std::vector<double>& x,
                   std::vector<double>* gradient) {
  if (gradient != nullptr) gradient->assign(x.size(), 0.0);
  return notchTerms(problem, x, gradient, nullptr);
}

void lengthConstraints(const PlanarisationProblem& problem, const std::vector<double>& x,
                       std::vector<double>& values, std::vector<double>* jacobian) {
  const size_t m = problem.members.size(), n = x.size();
  values.assign(m, 0.0);
  if (jacobian != nullptr) jacobian->assign(m * n, 0.0);
  for (size_t i = 0; i < m; ++i) {
    const int member = static_cast<int>(i);
    const Vec2 d = at(x, member, 1) - at(x, member, 0);
    values[i] = d.squaredNorm() - problem.members[i].lengthM * problem.members[i].lengthM;
    if (jacobian == nullptr) continue;
    for (int a = 0; a < 2; ++a) {
      (*jacobian)[i * n + 4 * i + a] = -2.0 * d[a];
      (*jacobian)[i * n + 4 * i + 2 + a] = 2.0 * d[a];
    }
  }
}

std::array<double, 4> overlapDistances(const PlanarisationProblem& problem,
                                       const NeighbourPair& pair, const std::vector<double>& x,
                                       std::array<Eigen::Matrix<double, 8, 1>, 4>* gradients) {
  // e_1, e_2 are taken against the edge P1P2 (as long as `first`), e_3, e_4 against P3P4.
  const double lengths[4] = {
      problem.members[pair.first].lengthM, problem.members[pair.first].lengthM,
      problem.members[pair.second].lengthM, problem.members[pair.second].lengthM};
  auto e = determinants(facingEdges(problem, pair), pairVariables(x, pair), gradients);
  for (int i = 0; i < 4; ++i) {
    e[i] /= lengths[i];
    if (gradients != nullptr) (*gradients)[i] /= lengths[i];
  }
  return e;
}

PlanarisationResult planarise(const PlanarisationProblem& problem,
                              const PlanarisationOptions& options) {
  problem.validate();
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> x(4 * problem.members.size());
  for (size_t i = 0; i < problem.members.size(); ++i) {
    for (int end = 0; end < 2; ++end) {
      x[4 * i + 2 * end] = problem.initial[i][end].x();
      x[4 * i + 2 * end + 1] = problem.initial[i][end].y();
    }
  }
  keepLengths(problem, x);  // SLSQP starts feasible
  PlanarisationResult out;
  out.initialNotchEnergyM2 = notchTerms(problem, x, nullptr, nullptr);

  SolveData data{&problem, x, {}, 0};
  const unsigned n = static_cast<unsigned>(x.size() - kHeld);
  const unsigned m = static_cast<unsigned>(problem.members.size());
  nlopt_opt opt = nlopt_create(NLOPT_LD_SLSQP, n);
  nlopt_set_min_objective(opt, objectiveCallback, &data);
  const std::vector<double> tolerances(m, 1e-14);
  nlopt_add_equality_mconstraint(opt, m, lengthCallback, &data, tolerances.data());
  const unsigned overlaps = static_cast<unsigned>(4 * problem.neighbours.size());
  const std::vector<double> overlapTolerances(overlaps, 1e-12);  // metres
  if (overlaps > 0)
    nlopt_add_inequality_mconstraint(opt, overlaps, overlapCallback, &data,
                                     overlapTolerances.data());
  nlopt_set_ftol_rel(opt, options.relativeTolerance);
  nlopt_set_xtol_abs1(opt, 1e-15);
  nlopt_set_maxeval(opt, options.maxEvaluations);
  std::vector<double> free(x.begin() + kHeld, x.end());
  double value = 0.0;
  const nlopt_result result = nlopt_optimize(opt, free.data(), &value);
  nlopt_destroy(opt);
  out.status = nlopt_result_to_string(result);
  out.evaluations = data.evaluations;
  // Any other stop (round-off limited at a zero notch energy, say, or overlap constraints that
  // cannot all hold) leaves a layout whose lengths are then restored and whose notches and
  // overlaps are reported: failures as data, in `status` and `overlappingPairs`.
  const bool finite =
      std::all_of(free.begin(), free.end(), [](double v) { return std::isfinite(v); });
  if (result == NLOPT_INVALID_ARGS || result == NLOPT_OUT_OF_MEMORY || !finite) {
    throw SolverFailure("planarisation (SLSQP, Section 4.7): NLopt stopped with " + out.status +
                        " after " + std::to_string(data.evaluations) + " evaluations" +
                        (finite ? "" : ", at a non-finite layout"));
  }
  std::copy(free.begin(), free.end(), x.begin() + kHeld);
  out.solverLengthResidualM = lengthResidual(problem, x);
  keepLengths(problem, x);
  out.lengthResidualM = lengthResidual(problem, x);
  out.notchEnergyM2 = notchTerms(problem, x, nullptr, &out.notchLengthsM);
  for (size_t k = 0; k < problem.neighbours.size(); ++k) {
    const auto e = overlapDistances(problem, problem.neighbours[k], x, nullptr);
    if (*std::max_element(e.begin(), e.end()) > kOverlapTolerance)
      out.overlappingPairs.push_back(static_cast<int>(k));
  }
  out.endpoints.resize(problem.members.size());
  for (size_t i = 0; i < problem.members.size(); ++i)
    out.endpoints[i] = {at(x, static_cast<int>(i), 0), at(x, static_cast<int>(i), 1)};
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace egg::generalised
