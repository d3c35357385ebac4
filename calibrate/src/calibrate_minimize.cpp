// Nelder-Mead with the standard coefficients (reflection 1, expansion 2, contraction 0.5,
// shrink 0.5) over a box, by a logistic change of variable.
#include "calibrate_minimize.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace mote::calibrate::detail {
namespace {

double logistic(double u) { return 1.0 / (1.0 + std::exp(-u)); }

double to_param(const Bounded& b, double u) {
  if (b.log_scale)
    return std::exp(std::log(b.lo) + (std::log(b.hi) - std::log(b.lo)) * logistic(u));
  return b.lo + (b.hi - b.lo) * logistic(u);
}

double to_search(const Bounded& b) {
  const double f = b.log_scale
                       ? (std::log(b.start) - std::log(b.lo)) / (std::log(b.hi) - std::log(b.lo))
                       : (b.start - b.lo) / (b.hi - b.lo);
  const double c = std::clamp(f, 1e-6, 1.0 - 1e-6);
  return std::log(c / (1.0 - c));
}

using Point = std::vector<double>;

struct Simplex {
  std::vector<Point> points;
  std::vector<double> values;
};

Point lerp(const Point& a, const Point& b, double t) {  // a + t (b - a)
  Point p(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) p[i] = a[i] + t * (b[i] - a[i]);
  return p;
}

// Whether every vertex is within the parameters' tolerances of the best one (never, when no
// parameter has a tolerance).
using Collapsed = std::function<bool(const Simplex&, std::size_t best)>;

// One run of Nelder-Mead from `start` with edge length `step`, at most `budget` evaluations.
Point run(const std::function<double(const Point&)>& g, const Point& start, double step, int budget,
          int& used, const Collapsed& collapsed) {
  const std::size_t n = start.size();
  Simplex s;
  s.points.push_back(start);
  for (std::size_t i = 0; i < n; ++i) {
    Point p = start;
    p[i] += step;
    s.points.push_back(p);
  }
  for (const Point& p : s.points) s.values.push_back(g(p));
  used += static_cast<int>(n + 1);
  std::vector<std::size_t> order(n + 1);
  while (used < budget) {
    std::iota(order.begin(), order.end(), 0U);
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return s.values[a] < s.values[b]; });
    const std::size_t best = order.front(), worst = order.back(), second = order[n - 1];
    if (std::abs(s.values[worst] - s.values[best]) < 1e-11 * (1.0 + std::abs(s.values[best])))
      break;
    if (collapsed(s, best)) break;
    Point centroid(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      for (std::size_t i = 0; i < n; ++i)
        centroid[i] += s.points[order[k]][i] / static_cast<double>(n);
    }
    const Point reflected = lerp(centroid, s.points[worst], -1.0);
    const double fr = g(reflected);
    ++used;
    if (fr < s.values[best]) {
      const Point expanded = lerp(centroid, s.points[worst], -2.0);
      const double fe = g(expanded);
      ++used;
      s.points[worst] = fe < fr ? expanded : reflected;
      s.values[worst] = std::min(fe, fr);
    } else if (fr < s.values[second]) {
      s.points[worst] = reflected;
      s.values[worst] = fr;
    } else {
      const Point contracted = lerp(centroid, s.points[worst], 0.5);
      const double fc = g(contracted);
      ++used;
      if (fc < s.values[worst]) {
        s.points[worst] = contracted;
        s.values[worst] = fc;
      } else {
        for (std::size_t k = 1; k <= n; ++k) {
          s.points[order[k]] = lerp(s.points[best], s.points[order[k]], 0.5);
          s.values[order[k]] = g(s.points[order[k]]);
        }
        used += static_cast<int>(n);
      }
    }
  }
  const auto it = std::min_element(s.values.begin(), s.values.end());
  return s.points[static_cast<std::size_t>(it - s.values.begin())];
}

}  // namespace

std::vector<double> minimize(const std::function<double(const std::vector<double>&)>& f,
                             const std::vector<Bounded>& params, int max_evaluations,
                             int& evaluations) {
  auto params_of = [&](const Point& u) {
    Point p(u.size());
    for (std::size_t i = 0; i < u.size(); ++i) p[i] = to_param(params[i], u[i]);
    return p;
  };
  auto g = [&](const Point& u) { return f(params_of(u)); };
  const bool any_tolerance =
      std::any_of(params.begin(), params.end(), [](const Bounded& b) { return b.tolerance > 0.0; });
  auto within_tolerance = [&](const Point& a, const Point& b) {
    if (!any_tolerance) return false;
    const Point pa = params_of(a), pb = params_of(b);
    for (std::size_t i = 0; i < pa.size(); ++i) {
      if (params[i].tolerance > 0.0 && std::abs(pa[i] - pb[i]) >= params[i].tolerance) return false;
    }
    return true;
  };
  const Collapsed collapsed = [&](const Simplex& s, std::size_t best) {
    return std::all_of(s.points.begin(), s.points.end(), [&](const Point& vertex) {
      return within_tolerance(vertex, s.points[best]);
    });
  };
  Point u(params.size());
  for (std::size_t i = 0; i < params.size(); ++i) u[i] = to_search(params[i]);
  evaluations = 0;
  // Restarts from the best point with a smaller simplex: a collapsed simplex is Nelder-Mead's
  // known failure (McKinnon 1998), and a fresh one around the optimum costs little.
  double best = g(u);
  for (int restart = 0; restart < 12 && evaluations < max_evaluations; ++restart) {
    const double step = restart == 0 ? 1.0 : 0.3;
    const Point before = u;
    u = run(g, u, step, max_evaluations, evaluations, collapsed);
    const double now = g(u);
    const bool stalled = best - now < 1e-7 * (1.0 + std::abs(now)) || within_tolerance(before, u);
    best = now;
    if (stalled && restart > 0) break;
  }
  return params_of(u);
}

}  // namespace mote::calibrate::detail
