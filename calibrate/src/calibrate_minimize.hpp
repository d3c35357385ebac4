#pragma once
/// \file
/// A bounded Nelder-Mead minimizer for the calibration's small maximum-likelihood problems
/// (Nelder and Mead, "A simplex method for function minimization", Computer Journal 7, 1965).
/// Bounds are kept by a smooth change of variable: a parameter p in [lo, hi] is searched as u
/// with p = lo + (hi - lo) / (1 + exp(-u)), or in log space for scale parameters.

#include <functional>
#include <vector>

namespace mote::calibrate::detail {

/// One bounded parameter.
struct Bounded {
  double start, lo, hi;
  bool log_scale = true;  ///< searched in log(p): for variances and other scale parameters
  /// A run ends once its simplex spans less than this (p's units) on every parameter that
  /// has one, or by the function values alone (0): for a parameter whose precision beyond
  /// some size means nothing to the caller.
  double tolerance = 0.0;
};

/// Minimizes f over the box; returns the parameters. Deterministic: a fixed initial simplex and
/// a fixed number of restarts from the best point.
[[nodiscard]] std::vector<double> minimize(
    const std::function<double(const std::vector<double>&)>& f, const std::vector<Bounded>& params,
    int max_evaluations, int& evaluations);

/// Standard errors of the parameters of f's minimum `at` (f a negative log-likelihood): the
/// square roots of the inverse observed information's diagonal (calibrate_information.cpp). A
/// parameter at a bound of `params` is held there and gets 0; all are 0 when the information
/// is not positive definite.
[[nodiscard]] std::vector<double> standard_errors(
    const std::function<double(const std::vector<double>&)>& f, const std::vector<double>& at,
    const std::vector<Bounded>& params);

}  // namespace mote::calibrate::detail
