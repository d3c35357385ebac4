// Standard errors of a maximum-likelihood fit from its observed information: the Hessian of
// the negative log-likelihood at the minimum, by central differences, inverted (the
// asymptotic covariance of the estimate; Cramer-Rao). A parameter at a bound of its box is
// held fixed there: its row is left out, and its standard error is reported as 0.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "calibrate_minimize.hpp"

namespace mote::calibrate::detail {
namespace {

// Within 2% of the box (in log space for a scale parameter) counts as at the bound: a
// minimizer stops near a bound the likelihood runs into, not on it, and there the curvature
// says nothing about an interior optimum.
bool at_bound(const Bounded& b, double v) {
  constexpr double kNear = 0.02;
  if (b.log_scale) {
    const double span = std::log(b.hi / b.lo);
    return std::log(v / b.lo) <= kNear * span || std::log(b.hi / v) <= kNear * span;
  }
  return v - b.lo <= kNear * (b.hi - b.lo) || b.hi - v <= kNear * (b.hi - b.lo);
}

// A step small against the parameter (relative for scale parameters) that stays in the box.
double step(const Bounded& b, double v) {
  const double h = b.log_scale ? 1e-3 * v : 1e-4 * (b.hi - b.lo);
  return std::min({h, 0.5 * (v - b.lo), 0.5 * (b.hi - v)});
}

using Objective = std::function<double(const std::vector<double>&)>;

// The Hessian of f at `at` over the parameters `free`, by central differences of steps h.
Eigen::MatrixXd hessian(const Objective& f, const std::vector<double>& at,
                        const std::vector<std::size_t>& free, const std::vector<double>& h) {
  auto value = [&](std::size_t i, double si, std::size_t j, double sj) {
    std::vector<double> p = at;
    p[i] += si * h[i];
    p[j] += sj * h[j];
    return f(p);
  };
  const double f0 = f(at);
  const auto n = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd H(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    const std::size_t i = free[static_cast<std::size_t>(a)];
    H(a, a) = (value(i, 1, i, 0) - 2 * f0 + value(i, -1, i, 0)) / (h[i] * h[i]);
    for (Eigen::Index b = 0; b < a; ++b) {
      const std::size_t j = free[static_cast<std::size_t>(b)];
      H(a, b) = H(b, a) =
          (value(i, 1, j, 1) - value(i, 1, j, -1) - value(i, -1, j, 1) + value(i, -1, j, -1)) /
          (4 * h[i] * h[j]);
    }
  }
  return H;
}

}  // namespace

std::vector<double> standard_errors(const Objective& f, const std::vector<double>& at,
                                    const std::vector<Bounded>& params) {
  std::vector<std::size_t> free;
  for (std::size_t i = 0; i < at.size(); ++i) {
    if (!at_bound(params[i], at[i])) free.push_back(i);
  }
  std::vector<double> se(at.size(), 0.0);
  const auto n = static_cast<Eigen::Index>(free.size());
  if (n == 0) return se;
  std::vector<double> h(at.size());
  for (std::size_t i : free) h[i] = step(params[i], at[i]);
  const Eigen::MatrixXd H = hessian(f, at, free, h);
  // A parameter whose curvature is not positive sits at an edge the likelihood runs into (a
  // noise floor at its lower bound), not at an interior minimum: it is held too.
  std::vector<Eigen::Index> kept;
  for (Eigen::Index a = 0; a < n; ++a) {
    if (H(a, a) > 0) kept.push_back(a);
  }
  const auto m = static_cast<Eigen::Index>(kept.size());
  Eigen::MatrixXd information(m, m);
  for (Eigen::Index a = 0; a < m; ++a) {
    for (Eigen::Index b = 0; b < m; ++b) {
      information(a, b) = H(kept[static_cast<std::size_t>(a)], kept[static_cast<std::size_t>(b)]);
    }
  }
  // Not positive definite: the data do not pin the free parameters down; no error is claimed.
  const Eigen::LLT<Eigen::MatrixXd> llt(information);
  if (m == 0 || llt.info() != Eigen::Success) return se;
  const Eigen::MatrixXd covariance = llt.solve(Eigen::MatrixXd::Identity(m, m));
  for (Eigen::Index a = 0; a < m; ++a) {
    const auto index = free[static_cast<std::size_t>(kept[static_cast<std::size_t>(a)])];
    se[index] = std::sqrt(std::max(covariance(a, a), 0.0));
  }
  return se;
}

}  // namespace mote::calibrate::detail
