// 04: the three Bayes filters side by side on one problem. A robot moves along a 1D corridor
// (x' = x + u + w) and measures its position (z = x + v). The Kalman filter is exact; the
// histogram filter is exact on its grid; the particle filter (the engine's normalize and
// systematic resampling on a one-column StateStore) approaches both as particles grow.
#include <cmath>
#include <cstdio>
#include <vector>

#include "mote/engine/philox.hpp"
#include "mote/engine/state_store.hpp"
#include "mote/filters/histogram_filter.hpp"
#include "mote/filters/kalman.hpp"

namespace {

constexpr double kQ = 0.04;                          // process noise variance, m^2
constexpr double kR = 0.25;                          // measurement noise variance, m^2
constexpr double kU = 0.5;                           // commanded motion per step, m
constexpr double kCell = 0.02;                       // histogram cell, m
constexpr double kLo = -4.0;                         // histogram range, m
constexpr int kCells = 800;                          // [-4, 12)
const double kZ[] = {0.3, 1.2, 1.4, 2.1, 2.4, 3.1};  // measurements, m

double gauss(double x, double var) { return std::exp(-0.5 * x * x / var); }

// Histogram filter: cell centres c_k; the transition integrates N(x' - x - u, Q) over cells.
Eigen::MatrixXd transition() {
  Eigen::MatrixXd t(kCells, kCells);
  for (int from = 0; from < kCells; ++from) {
    double total = 0.0;  // a plain loop: GCC 12 warns falsely inside Eigen's AVX-512 sum()
    for (int to = 0; to < kCells; ++to) total += t(to, from) = gauss((to - from) * kCell - kU, kQ);
    t.col(from) /= total;
  }
  return t;
}

struct Summary {
  double mean = 0.0, var = 0.0;
};

Summary histogram_filter() {
  Eigen::VectorXd prior(kCells);
  for (int k = 0; k < kCells; ++k) prior(k) = gauss(kLo + (k + 0.5) * kCell, 1.0);  // N(0, 1)
  mote::DiscreteBayesFilter f(prior);
  const Eigen::MatrixXd t = transition();
  for (const double z : kZ) {
    f.predict(t);
    Eigen::VectorXd l(kCells);
    for (int k = 0; k < kCells; ++k) l(k) = gauss(z - (kLo + (k + 0.5) * kCell), kR);
    f.correct(l);
  }
  Summary s;
  for (int k = 0; k < kCells; ++k) s.mean += f.belief()(k) * (kLo + (k + 0.5) * kCell);
  for (int k = 0; k < kCells; ++k)
    s.var += f.belief()(k) * std::pow(kLo + (k + 0.5) * kCell - s.mean, 2);
  return s;
}

Summary kalman_filter() {
  mote::KalmanFilter<1> kf(Eigen::Matrix<double, 1, 1>(0.0), Eigen::Matrix<double, 1, 1>(1.0));
  const Eigen::Matrix<double, 1, 1> one(1.0);
  for (const double z : kZ) {
    kf.predict(one, one, Eigen::Matrix<double, 1, 1>(kU), Eigen::Matrix<double, 1, 1>(kQ));
    kf.correct(Eigen::Matrix<double, 1, 1>(z), one, Eigen::Matrix<double, 1, 1>(kR));
  }
  return {kf.mean()(0), kf.covariance()(0, 0)};
}

Summary particle_filter(std::size_t n, std::uint64_t seed) {
  mote::StateStore store(1, n);
  const mote::RngStream init{seed, 0, mote::RngPurpose::kInitial};
  for (std::size_t i = 0; i < n; ++i)
    store.view().column(0)[i] = init.normal4(static_cast<std::uint32_t>(i))[0];
  double ess = static_cast<double>(n);
  std::uint64_t step = 0;
  for (const double z : kZ) {
    ++step;
    if (mote::should_resample(ess, n)) mote::resample_systematic(store, n, seed, step);
    const mote::RngStream rng{seed, step, mote::RngPurpose::kMotion};
    const mote::StateView s = store.view();
    for (std::size_t i = 0; i < n; ++i) {
      float& x = s.column(0)[i];
      x += static_cast<float>(kU + std::sqrt(kQ) * rng.normal4(static_cast<std::uint32_t>(i))[0]);
      s.logw[i] += static_cast<float>(-0.5 * (z - x) * (z - x) / kR);
    }
    ess = mote::normalize(store.view()).effective_sample_size;
  }
  Summary r;
  const mote::ConstStateView s = std::as_const(store).view();
  for (std::size_t i = 0; i < n; ++i) r.mean += std::exp(double{s.logw[i]}) * s.column(0)[i];
  for (std::size_t i = 0; i < n; ++i)
    r.var += std::exp(double{s.logw[i]}) * std::pow(s.column(0)[i] - r.mean, 2);
  return r;
}

}  // namespace

int main() {
  const Summary kf = kalman_filter();
  const Summary hf = histogram_filter();
  std::printf("%-26s %10s %10s %12s\n", "filter", "mean (m)", "var (m^2)", "|mean - KF|");
  std::printf("%-26s %10.5f %10.6f %12s\n", "Kalman (exact)", kf.mean, kf.var, "-");
  std::printf("%-26s %10.5f %10.6f %12.2e\n", "histogram (2 cm cells)", hf.mean, hf.var,
              std::abs(hf.mean - kf.mean));
  for (const std::size_t n : {100UL, 1000UL, 10000UL, 100000UL, 1000000UL}) {
    const Summary pf = particle_filter(n, 7);
    char name[40];
    std::snprintf(name, sizeof name, "particle (N = %zu)", n);
    std::printf("%-26s %10.5f %10.6f %12.2e\n", name, pf.mean, pf.var, std::abs(pf.mean - kf.mean));
  }
  return 0;
}
