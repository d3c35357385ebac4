// The Kalman filter (Thrun table 3.1) on its own, and the particle filter on the generic
// StateStore checked against it on 1D and 2D linear-Gaussian models.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdio>
#include <vector>

#include "mote/core/error.hpp"
#include "mote/engine/philox.hpp"
#include "mote/engine/state_store.hpp"
#include "mote/filters/kalman.hpp"

namespace mote {
namespace {

TEST(Kalman, OneStepMatchesTheHandComputedAnswer) {
  // Prior N(0, 1); predict x + u, u = 1, Q = 0.5 -> N(1, 1.5); z = 2 with R = 1.5: K = 0.5,
  // mean 1 + 0.5 (2 - 1) = 1.5, variance (1 - 0.5) 1.5 = 0.75.
  KalmanFilter<1> kf(Eigen::Matrix<double, 1, 1>(0.0), Eigen::Matrix<double, 1, 1>(1.0));
  kf.predict(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(1.0),
             Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.5));
  EXPECT_DOUBLE_EQ(kf.mean()(0), 1.0);
  EXPECT_DOUBLE_EQ(kf.covariance()(0, 0), 1.5);
  const KalmanInnovation in =
      kf.correct(Eigen::Matrix<double, 1, 1>(2.0), Eigen::Matrix<double, 1, 1>(1.0),
                 Eigen::Matrix<double, 1, 1>(1.5));
  EXPECT_NEAR(kf.mean()(0), 1.5, 1e-12);
  EXPECT_NEAR(kf.covariance()(0, 0), 0.75, 1e-12);
  // log N(1; 0, 3)
  EXPECT_NEAR(in.log_likelihood, -0.5 * (1.0 / 3.0 + std::log(2.0 * M_PI * 3.0)), 1e-12);
}

TEST(Kalman, FixedAndDynamicSizesAgreeAndStaySymmetric) {
  Eigen::Matrix3d a;
  a << 1.0, 0.1, 0.0, 0.0, 1.0, 0.1, 0.05, 0.0, 0.98;
  const Eigen::Matrix3d q = Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal();
  Eigen::Matrix<double, 2, 3> c;
  c << 1.0, 0.0, 0.3, 0.0, 1.0, -0.2;
  const Eigen::Matrix2d r = Eigen::Vector2d(1e-6, 0.5).asDiagonal();  // one very precise sensor
  KalmanFilter<3> fixed(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * 100.0);
  KalmanFilter<> dynamic(Eigen::VectorXd::Zero(3), Eigen::MatrixXd::Identity(3, 3) * 100.0);
  for (int t = 0; t < 50; ++t) {
    const Eigen::Vector2d z(std::sin(t), std::cos(0.5 * t));
    fixed.predict(a, q);
    dynamic.predict(Eigen::MatrixXd(a), Eigen::MatrixXd(q));
    fixed.correct(z, c, r);
    dynamic.correct(Eigen::VectorXd(z), Eigen::MatrixXd(c), Eigen::MatrixXd(r));
    ASSERT_EQ(fixed.covariance(), fixed.covariance().transpose());
    // Positive definite: the Cholesky factor exists.
    ASSERT_EQ(Eigen::LLT<Eigen::Matrix3d>(fixed.covariance()).info(), Eigen::Success);
  }
  EXPECT_TRUE(fixed.mean().isApprox(dynamic.mean(), 1e-9));
  EXPECT_TRUE(fixed.covariance().isApprox(dynamic.covariance(), 1e-9));
}

TEST(Kalman, RejectsShapeMismatchesAndAnIndefiniteInnovation) {
  KalmanFilter<> kf(Eigen::VectorXd::Zero(2), Eigen::MatrixXd::Identity(2, 2));
  EXPECT_THROW(kf.predict(Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd::Identity(2, 2)),
               ConfigError);
  EXPECT_THROW(kf.predict(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Ones(2, 1),
                          Eigen::VectorXd::Ones(2), Eigen::MatrixXd::Identity(2, 2)),
               ConfigError);
  EXPECT_THROW(kf.correct(Eigen::VectorXd::Ones(1), Eigen::MatrixXd::Ones(1, 3),
                          Eigen::MatrixXd::Ones(1, 1)),
               ConfigError);
  try {
    kf.correct(Eigen::VectorXd::Ones(1), Eigen::MatrixXd::Ones(1, 2),
               Eigen::MatrixXd::Constant(1, 1, -5.0));  // S = 2 - 5 < 0
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos);
  }
  EXPECT_THROW(KalmanFilter<>(Eigen::VectorXd::Zero(2), Eigen::MatrixXd::Identity(3, 3)),
               ConfigError);
}

// A linear-Gaussian model x' = A x + B u + w, w ~ N(0, Q); z = C x + v, v ~ N(0, R).
struct LinearModel {
  Eigen::MatrixXd a, b, q, c, r;
  Eigen::VectorXd u, mean0;
  Eigen::MatrixXd cov0;
};

LinearModel model_1d() {
  return {Eigen::MatrixXd::Constant(1, 1, 0.9),
          Eigen::MatrixXd::Constant(1, 1, 1.0),
          Eigen::MatrixXd::Constant(1, 1, 0.04),
          Eigen::MatrixXd::Constant(1, 1, 1.0),
          Eigen::MatrixXd::Constant(1, 1, 0.25),
          Eigen::VectorXd::Constant(1, 0.2),
          Eigen::VectorXd::Zero(1),
          Eigen::MatrixXd::Identity(1, 1)};
}

LinearModel model_2d() {  // constant velocity, position measured, acceleration as control
  const double dt = 0.5;
  LinearModel m;
  m.a = (Eigen::MatrixXd(2, 2) << 1.0, dt, 0.0, 1.0).finished();
  m.b = (Eigen::MatrixXd(2, 1) << 0.5 * dt * dt, dt).finished();
  m.q = (Eigen::MatrixXd(2, 2) << 0.01, 0.005, 0.005, 0.02).finished();
  m.c = (Eigen::MatrixXd(1, 2) << 1.0, 0.0).finished();
  m.r = Eigen::MatrixXd::Constant(1, 1, 0.1);
  m.u = Eigen::VectorXd::Constant(1, 0.3);
  m.mean0 = Eigen::VectorXd::Zero(2);
  m.cov0 = Eigen::MatrixXd::Identity(2, 2);
  return m;
}

constexpr int kSteps = 8;

// At most 2 dimensions: fixed-capacity Eigen types keep the per-particle loops allocation-free.
using Small = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2, 1>;
using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 2, 2>;

// The measurements of one simulated run (fixed seed; the same for every filter).
std::vector<Eigen::VectorXd> simulate(const LinearModel& m) {
  const RngStream rng{99, 0, RngPurpose::kUser};
  Eigen::VectorXd x = m.mean0;
  std::vector<Eigen::VectorXd> zs;
  for (int t = 0; t < kSteps; ++t) {
    const std::array<float, 4> n = rng.normal4(static_cast<std::uint32_t>(t));
    Eigen::VectorXd w(x.size());
    for (Eigen::Index k = 0; k < x.size(); ++k) w(k) = n[static_cast<std::size_t>(k)];
    x = m.a * x + m.b * m.u + Eigen::MatrixXd(m.q.llt().matrixL()) * w;
    zs.push_back(m.c * x + Eigen::VectorXd::Constant(1, std::sqrt(m.r(0, 0)) * n[3]));
  }
  return zs;
}

// Moves particles by the model with Philox noise: x' = A x + B u + L n, L L^T = Q.
void sample_motion(const LinearModel& m, const StateView& s, std::uint64_t seed, int step) {
  const RngStream rng{seed, static_cast<std::uint64_t>(step), RngPurpose::kMotion};
  const SmallMatrix a = m.a;
  const SmallMatrix l = m.q.llt().matrixL();
  const Small bu = m.b * m.u;
  const auto d = static_cast<Eigen::Index>(s.dims);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::array<float, 4> n = rng.normal4(static_cast<std::uint32_t>(i));
    Small x(d), w(d);
    for (Eigen::Index k = 0; k < d; ++k) {
      x(k) = s.column(static_cast<std::size_t>(k))[i];
      w(k) = n[static_cast<std::size_t>(k)];
    }
    const Small next = a * x + bu + l * w;
    for (Eigen::Index k = 0; k < d; ++k)
      s.column(static_cast<std::size_t>(k))[i] = static_cast<float>(next(k));
  }
}

void weigh(const LinearModel& m, const Eigen::VectorXd& z, const StateView& s) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    double cx = 0.0;
    for (std::size_t k = 0; k < s.dims; ++k)
      cx += m.c(0, static_cast<Eigen::Index>(k)) * s.column(k)[i];
    const double e = z(0) - cx;
    s.logw[i] += static_cast<float>(-0.5 * e * e / m.r(0, 0));
  }
}

struct Moments {
  Eigen::VectorXd mean;
  Eigen::MatrixXd cov;
  double ess = 0.0;
};

Moments weighted_moments(const ConstStateView& s, double ess) {
  const auto d = static_cast<Eigen::Index>(s.dims);
  Moments m{Eigen::VectorXd::Zero(d), Eigen::MatrixXd::Zero(d, d), ess};
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double w = std::exp(double{s.logw[i]});
    for (Eigen::Index k = 0; k < d; ++k) m.mean(k) += w * s.column(static_cast<std::size_t>(k))[i];
  }
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double w = std::exp(double{s.logw[i]});
    Small e(d);
    for (Eigen::Index k = 0; k < d; ++k)
      e(k) = s.column(static_cast<std::size_t>(k))[i] - m.mean(k);
    m.cov += w * e * e.transpose();
  }
  return m;
}

// The bootstrap particle filter (Thrun table 4.3) on a StateStore, selective systematic
// resampling; returns the weighted moments after the last correction.
Moments run_particle_filter(const LinearModel& m, const std::vector<Eigen::VectorXd>& zs,
                            std::size_t n, std::uint64_t seed) {
  const auto d = static_cast<std::size_t>(m.mean0.size());
  StateStore store(d, n);
  {
    const RngStream rng{seed, 0, RngPurpose::kInitial};
    const Eigen::MatrixXd l = m.cov0.llt().matrixL();
    const StateView s = store.view();
    for (std::size_t i = 0; i < n; ++i) {
      const std::array<float, 4> g = rng.normal4(static_cast<std::uint32_t>(i));
      const Eigen::VectorXd x =
          m.mean0 + l * Eigen::Vector2d(g[0], g[1]).head(static_cast<Eigen::Index>(d));
      for (std::size_t k = 0; k < d; ++k)
        s.column(k)[i] = static_cast<float>(x(static_cast<Eigen::Index>(k)));
    }
  }
  double ess = static_cast<double>(n);
  for (int t = 0; t < kSteps; ++t) {
    if (t > 0 && should_resample(ess, n))
      resample_systematic(store, n, seed, static_cast<std::uint64_t>(t));
    sample_motion(m, store.view(), seed, t + 1);
    weigh(m, zs[static_cast<std::size_t>(t)], store.view());
    ess = normalize(store.view()).effective_sample_size;
  }
  return weighted_moments(std::as_const(store).view(), ess);
}

KalmanFilter<> run_kalman(const LinearModel& m, const std::vector<Eigen::VectorXd>& zs) {
  KalmanFilter<> kf(m.mean0, m.cov0);
  for (const Eigen::VectorXd& z : zs) {
    kf.predict(m.a, m.b, m.u, m.q);
    kf.correct(z, m.c, m.r);
  }
  return kf;
}

// Errors of the particle filter against the Kalman filter in units of the Monte Carlo standard
// error of an importance-weighted estimate with ESS effective samples: the mean's standard
// error is sigma / sqrt(ESS) and the variance's sigma^2 sqrt(2 / ESS) (Gaussian posterior).
// Returned as the RMS over seeds and dimensions, together with the RMS raw mean error.
struct Errors {
  double mean_z = 0.0;    // RMS standardized mean error
  double var_z = 0.0;     // RMS standardized variance error
  double mean_abs = 0.0;  // RMS mean error in state units (for the 1k vs 100k ratio)
};

Errors compare(const LinearModel& m, std::size_t n) {
  const std::vector<Eigen::VectorXd> zs = simulate(m);
  const KalmanFilter<> kf = run_kalman(m, zs);
  Errors e;
  constexpr int kSeeds = 8;
  double count = 0.0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const Moments pf = run_particle_filter(m, zs, n, static_cast<std::uint64_t>(seed));
    for (Eigen::Index k = 0; k < kf.size(); ++k) {
      const double var = kf.covariance()(k, k);
      const double dm = pf.mean(k) - kf.mean()(k);
      e.mean_z += dm * dm / (var / pf.ess);
      const double dv = pf.cov(k, k) - var;
      e.var_z += dv * dv / (var * var * 2.0 / pf.ess);
      e.mean_abs += dm * dm / var;
      count += 1.0;
    }
  }
  return {std::sqrt(e.mean_z / count), std::sqrt(e.var_z / count), std::sqrt(e.mean_abs / count)};
}

// Resampling makes the particle filter's error larger than that of ESS independent draws by a
// factor sqrt(V) (V the asymptotic-variance inflation, 1 for i.i.d. samples; Chopin 2004,
// Theorem 1); with selective resampling over 8 steps and mixing process noise V stays a small
// constant (measured here: RMS z-scores 0.5-1.3). The bound of 4 allows V up to ~5 and a
// fluctuation of the 8-seed RMS; a filter that skips the correction, misweighs, or resamples
// the wrong particles is off by tens to hundreds of standard errors at 100k.
constexpr double kZBound = 4.0;

void expect_converges(const LinearModel& m) {
  const Errors small = compare(m, 1000);
  const Errors large = compare(m, 100000);
  std::printf("1k: mean %.4g (z %.2f, var z %.2f); 100k: mean %.4g (z %.2f, var z %.2f)\n",
              small.mean_abs, small.mean_z, small.var_z, large.mean_abs, large.mean_z, large.var_z);
  // sqrt(100) = 10 expected; 4 leaves room for the 8-seed RMS fluctuating.
  EXPECT_LT(large.mean_abs * 4.0, small.mean_abs);
  EXPECT_LT(large.mean_z, kZBound);
  EXPECT_LT(large.var_z, kZBound);
  EXPECT_LT(small.mean_z, kZBound);
  EXPECT_LT(small.var_z, kZBound);
}

TEST(ParticleFilterVsKalman, OneDimensionalModel) { expect_converges(model_1d()); }
TEST(ParticleFilterVsKalman, TwoDimensionalConstantVelocityModel) { expect_converges(model_2d()); }

}  // namespace
}  // namespace mote
