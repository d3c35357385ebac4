// The Kalman filter's two steps (Thrun table 3.1), once for every KalmanFilter<N>.
#include "mote/filters/kalman.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <numbers>

#include "mote/core/error.hpp"

namespace mote::detail {
namespace {

// Rounding leaves the products a hair off symmetric; the filter's covariance must stay so.
void symmetrize(Eigen::Ref<Eigen::MatrixXd> cov) {
  const Eigen::MatrixXd half_sum = 0.5 * (cov + cov.transpose());
  cov = half_sum;
}

// log N(v; 0, S) from S's Cholesky factor L: -(|L^-1 v|^2 + log det S + k log 2 pi) / 2.
double gaussian_log_density(const Eigen::LLT<Eigen::MatrixXd>& llt, const Eigen::VectorXd& v) {
  const Eigen::VectorXd w = llt.matrixL().solve(v);
  const double log_det = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  const auto k = static_cast<double>(v.size());
  return -0.5 * (w.squaredNorm() + log_det + k * std::log(2.0 * std::numbers::pi));
}

}  // namespace

void kalman_predict(Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::MatrixXd> cov,
                    Eigen::Ref<const Eigen::MatrixXd> a, Eigen::Ref<const Eigen::VectorXd> bu,
                    Eigen::Ref<const Eigen::MatrixXd> q) {
  const Eigen::VectorXd predicted_mean = a * mean + bu;
  const Eigen::MatrixXd predicted_cov = a * cov * a.transpose() + q;
  mean = predicted_mean;
  cov = predicted_cov;
  symmetrize(cov);
}

KalmanInnovation kalman_correct(Eigen::Ref<Eigen::VectorXd> mean, Eigen::Ref<Eigen::MatrixXd> cov,
                                Eigen::Ref<const Eigen::VectorXd> z,
                                Eigen::Ref<const Eigen::MatrixXd> c,
                                Eigen::Ref<const Eigen::MatrixXd> r) {
  KalmanInnovation out;
  out.innovation = z - c * mean;
  out.covariance = c * cov * c.transpose() + r;
  const Eigen::LLT<Eigen::MatrixXd> llt(out.covariance);
  if (llt.info() != Eigen::Success) {
    throw ConfigError(
        "KalmanFilter::correct: the innovation covariance C Sigma C^T + R is not positive "
        "definite (check R)");
  }
  // K = Sigma C^T S^-1, through the Cholesky factor instead of an explicit inverse.
  const Eigen::MatrixXd gain = llt.solve(c * cov).transpose();
  mean += gain * out.innovation;
  const Eigen::MatrixXd ikc = Eigen::MatrixXd::Identity(cov.rows(), cov.cols()) - gain * c;
  const Eigen::MatrixXd corrected = ikc * cov * ikc.transpose() + gain * r * gain.transpose();
  cov = corrected;
  symmetrize(cov);
  out.log_likelihood = gaussian_log_density(llt, out.innovation);
  return out;
}

}  // namespace mote::detail
