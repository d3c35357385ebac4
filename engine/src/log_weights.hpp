#pragma once
// The log-weight column kernels behind normalize() and effective_sample_size(), on a bare
// column, so the pose store (weights.cpp) and the generic StateStore (state_store.cpp) run the
// same code. Internal: not installed.

#include <cstddef>

#include "mote/engine/weights.hpp"

namespace mote::detail {

/// normalize() on logw[0, n): see weights.hpp for the contract.
NormalizeResult normalize_log_weights(float* logw, std::size_t n, std::size_t grain);

/// effective_sample_size() on already normalized logw[0, n).
[[nodiscard]] double log_weights_ess(const float* logw, std::size_t n);

}  // namespace mote::detail
