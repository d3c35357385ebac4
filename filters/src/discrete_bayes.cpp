// Thrun et al., Probabilistic Robotics, table 4.1: the discrete Bayes filter.
#include <cmath>
#include <string>

#include "mote/core/error.hpp"
#include "mote/filters/histogram_filter.hpp"

namespace mote {
namespace {

void require_distribution(const Eigen::VectorXd& v, const std::string& what) {
  if (!v.allFinite() || (v.array() < 0.0).any()) {
    throw ConfigError(what + ": probabilities must be finite and non-negative");
  }
}

// A plain loop: GCC 12 reports a false maybe-uninitialized inside Eigen's vectorized sum() with
// AVX-512 enabled.
template <class V>
double total_of(const V& v) {
  double s = 0.0;
  for (Eigen::Index i = 0; i < v.size(); ++i) s += v(i);
  return s;
}

}  // namespace

DiscreteBayesFilter::DiscreteBayesFilter(Eigen::VectorXd belief) : belief_(std::move(belief)) {
  require_distribution(belief_, "DiscreteBayesFilter: initial belief");
  const double total = total_of(belief_);
  if (!(total > 0.0)) throw ConfigError("DiscreteBayesFilter: the initial belief sums to 0");
  belief_ /= total;
}

DiscreteBayesFilter DiscreteBayesFilter::uniform(std::size_t k) {
  if (k == 0) throw ConfigError("DiscreteBayesFilter::uniform: need at least one state");
  return DiscreteBayesFilter(Eigen::VectorXd::Ones(static_cast<Eigen::Index>(k)));
}

void DiscreteBayesFilter::predict(const Eigen::MatrixXd& transition) {
  const Eigen::Index k = belief_.size();
  if (transition.rows() != k || transition.cols() != k) {
    throw ConfigError("DiscreteBayesFilter::predict: transition is " +
                      std::to_string(transition.rows()) + "x" + std::to_string(transition.cols()) +
                      ", expected " + std::to_string(k) + "x" + std::to_string(k));
  }
  for (Eigen::Index i = 0; i < k; ++i) {
    require_distribution(transition.col(i),
                         "DiscreteBayesFilter::predict: column " + std::to_string(i));
    if (std::abs(total_of(transition.col(i)) - 1.0) > 1e-9) {
      throw ConfigError("DiscreteBayesFilter::predict: column " + std::to_string(i) +
                        " (p(x_t | u, x_{t-1} = " + std::to_string(i) + ")) does not sum to 1");
    }
  }
  belief_ = transition * belief_;
}

double DiscreteBayesFilter::correct(const Eigen::VectorXd& likelihood) {
  if (likelihood.size() != belief_.size()) {
    throw ConfigError("DiscreteBayesFilter::correct: likelihood has " +
                      std::to_string(likelihood.size()) + " entries, expected " +
                      std::to_string(belief_.size()));
  }
  require_distribution(likelihood, "DiscreteBayesFilter::correct: likelihood");
  const Eigen::VectorXd posterior = likelihood.cwiseProduct(belief_);
  const double evidence = total_of(posterior);
  if (!(evidence > 0.0)) {
    throw ConfigError("DiscreteBayesFilter::correct: p(z) = 0, no state with belief explains z");
  }
  belief_ = posterior / evidence;
  return std::log(evidence);
}

}  // namespace mote
