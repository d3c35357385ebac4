#pragma once
/// \file
/// The Kalman filter (Thrun et al., Probabilistic Robotics, table 3.1): the exact Bayes filter
/// for linear-Gaussian systems, kept small so it can serve as the oracle the particle filter is
/// tested against. Sizes are fixed (KalmanFilter<3>) or dynamic (KalmanFilter<>); every matrix
/// is checked against the state size at run time and a mismatch throws ConfigError naming the
/// call, the matrix and both shapes.
///
/// Names follow the control-engineering convention the issue uses: Q is the process noise and
/// R the measurement noise (Thrun writes R_t for the process and Q_t for the measurement).

#include <Eigen/Core>
#include <string>

#include "mote/core/error.hpp"

namespace mote {

/// What a correction step saw: the innovation z - C mu and its covariance S = C Sigma C^T + R.
struct KalmanInnovation {
  Eigen::VectorXd innovation;
  Eigen::MatrixXd covariance;
  /// log N(z; C mu, S): the marginal likelihood of z under the predicted belief.
  double log_likelihood = 0.0;
};

namespace detail {
// The steps on evaluated matrices, in place, compiled once in the library for every
// KalmanFilter<N> (a body per size and argument type made the callers the slowest files of the
// build to compile). Shapes are checked by the caller.
void kalman_predict(Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::MatrixXd> cov,
                    Eigen::Ref<const Eigen::MatrixXd> a, Eigen::Ref<const Eigen::VectorXd> bu,
                    Eigen::Ref<const Eigen::MatrixXd> q);
[[nodiscard]] KalmanInnovation kalman_correct(Eigen::Ref<Eigen::VectorXd> mean,
                                              Eigen::Ref<Eigen::MatrixXd> cov,
                                              Eigen::Ref<const Eigen::VectorXd> z,
                                              Eigen::Ref<const Eigen::MatrixXd> c,
                                              Eigen::Ref<const Eigen::MatrixXd> r);
}  // namespace detail

/// A Gaussian belief N(mean, covariance) over an n-dimensional state, n = N or dynamic.
template <int N = Eigen::Dynamic>
class KalmanFilter {
 public:
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;

  /// The initial belief. Throws ConfigError when covariance is not n x n or not symmetric.
  KalmanFilter(const Vector& mean, const Matrix& covariance) : mean_(mean), cov_(covariance) {
    check("KalmanFilter", "covariance", cov_, size(), size());
    if (!cov_.isApprox(cov_.transpose(), 1e-9)) {
      throw ConfigError("KalmanFilter: the initial covariance is not symmetric");
    }
  }

  [[nodiscard]] Eigen::Index size() const noexcept { return mean_.size(); }
  [[nodiscard]] const Vector& mean() const noexcept { return mean_; }
  [[nodiscard]] const Matrix& covariance() const noexcept { return cov_; }

  /// Table 3.1, lines 2-3: mu = A mu + B u, Sigma = A Sigma A^T + Q.
  template <class DA, class DB, class DU, class DQ>
  void predict(const Eigen::MatrixBase<DA>& a, const Eigen::MatrixBase<DB>& b,
               const Eigen::MatrixBase<DU>& u, const Eigen::MatrixBase<DQ>& q) {
    check("KalmanFilter::predict", "A", a, size(), size());
    check("KalmanFilter::predict", "B", b, size(), u.rows());
    check("KalmanFilter::predict", "u", u, b.cols(), 1);
    check("KalmanFilter::predict", "Q", q, size(), size());
    detail::kalman_predict(mean_, cov_, a, Vector(b * u), q);
  }

  /// Prediction without a control input: mu = A mu, Sigma = A Sigma A^T + Q.
  template <class DA, class DQ>
  void predict(const Eigen::MatrixBase<DA>& a, const Eigen::MatrixBase<DQ>& q) {
    check("KalmanFilter::predict", "A", a, size(), size());
    check("KalmanFilter::predict", "Q", q, size(), size());
    detail::kalman_predict(mean_, cov_, a, Vector::Zero(size()), q);
  }

  /// Table 3.1, lines 4-6, with the Joseph form (I - K C) Sigma (I - K C)^T + K R K^T for the
  /// covariance: algebraically equal to (I - K C) Sigma, but symmetric and positive
  /// semi-definite under rounding for any gain. Throws ConfigError on a shape mismatch or when
  /// S = C Sigma C^T + R is not positive definite (no Cholesky factor).
  template <class DZ, class DC, class DR>
  KalmanInnovation correct(const Eigen::MatrixBase<DZ>& z, const Eigen::MatrixBase<DC>& c,
                           const Eigen::MatrixBase<DR>& r) {
    check("KalmanFilter::correct", "z", z, z.rows(), 1);
    check("KalmanFilter::correct", "C", c, z.rows(), size());
    check("KalmanFilter::correct", "R", r, z.rows(), z.rows());
    return detail::kalman_correct(mean_, cov_, z, c, r);
  }

 private:
  template <class D>
  static void check(const char* call, const char* name, const Eigen::MatrixBase<D>& m,
                    Eigen::Index rows, Eigen::Index cols) {
    if (m.rows() == rows && m.cols() == cols) return;
    throw ConfigError(std::string(call) + ": " + name + " is " + std::to_string(m.rows()) + "x" +
                      std::to_string(m.cols()) + ", expected " + std::to_string(rows) + "x" +
                      std::to_string(cols));
  }

  Vector mean_;
  Matrix cov_;
};

}  // namespace mote
