#pragma once
/// \file
/// A bounded Nelder-Mead minimizer for the calibration's small maximum-likelihood problems
/// (Nelder and Mead, "A simplex method for function minimization", Computer Journal 7, 1965).
/// Bounds are kept by a smooth change of variable: a parameter p in [lo, hi] is searched as u
/// with p = lo + (hi - lo) / (1 + exp(-u)), or in log space for scale parameters.

#include <functional>
#include <vector>

namespace mote::replay::detail {

/// One bounded parameter.
struct Bounded {
  double start, lo, hi;
  bool log_scale = true;  ///< searched in log(p): for variances and other scale parameters
};

/// Minimizes f over the box; returns the parameters. Deterministic: a fixed initial simplex and
/// a fixed number of restarts from the best point.
[[nodiscard]] std::vector<double> minimize(
    const std::function<double(const std::vector<double>&)>& f, const std::vector<Bounded>& params,
    int max_evaluations, int& evaluations);

}  // namespace mote::replay::detail
