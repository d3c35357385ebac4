// The bounded Nelder-Mead minimizer: a parameter's tolerance ends the search once the simplex is
// that small, near the minimum, in fewer evaluations than the function values alone.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "calibrate_minimize.hpp"  // calibrate/src: the minimizer's internal header

namespace mote::calibrate {
namespace {

// A pose refinement's shape: a narrow bowl (a scan's log-likelihood, curvature of 90 beams at a
// 5 cm sigma) around an offset of a few cm, x and y coupled.
double bowl(const std::vector<double>& p) {
  constexpr std::array<double, 3> kAt{0.0123, -0.0456, 0.0189};
  const double dx = p[0] - kAt[0], dy = p[1] - kAt[1], dt = p[2] - kAt[2];
  return 3.6e4 * (dx * dx + dy * dy + 0.6 * dx * dy) + 9e4 * dt * dt;
}

TEST(Minimize, AToleranceEndsTheSearchNearTheMinimumInFewerEvaluations) {
  const std::vector<detail::Bounded> exact{
      {0.0, -0.3, 0.3, false}, {0.0, -0.3, 0.3, false}, {0.0, -0.15, 0.15, false}};
  std::vector<detail::Bounded> coarse = exact;
  for (detail::Bounded& b : coarse) b.tolerance = 1e-4;
  int by_values = 0, by_tolerance = 0;
  const std::vector<double> a = detail::minimize(bowl, exact, 400, by_values);
  const std::vector<double> b = detail::minimize(bowl, coarse, 400, by_tolerance);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(b[i], a[i], 1e-3) << i;
  EXPECT_NEAR(a[0], 0.0123, 1e-5);
  EXPECT_LT(by_tolerance, by_values * 3 / 4) << by_tolerance << " against " << by_values;
}

}  // namespace
}  // namespace mote::calibrate
