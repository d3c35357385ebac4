#include "mote/engine/state_store.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <numeric>

#include "log_weights.hpp"
#include "mote/core/error.hpp"
#include "mote/core/parallel.hpp"
#include "resample_impl.hpp"

namespace mote {

void StateStore::AlignedFree::operator()(float* p) const noexcept {
  ::operator delete[](p, std::align_val_t{kParticleAlignment});
}

StateStore::StateStore(std::size_t dims, std::size_t n) : dims_(dims) {
  if (dims == 0) throw ConfigError("StateStore: dims must be at least 1");
  resize(n);
}

void StateStore::reserve(std::size_t n) {
  const std::size_t cap = pad_particles(std::max<std::size_t>(n, 1));
  if (cap <= capacity_) return;
  const std::size_t columns = dims_ + 1;
  for (auto& buffer : buffers_) {
    // cap is a multiple of 16 floats, so every column starts on a 64-byte boundary.
    std::unique_ptr<float[], AlignedFree> fresh(static_cast<float*>(
        ::operator new[](columns* cap * sizeof(float), std::align_val_t{kParticleAlignment})));
    for (std::size_t c = 0; c < columns && buffer; ++c) {
      std::copy_n(buffer.get() + c * capacity_, capacity_, fresh.get() + c * cap);
    }
    buffer = std::move(fresh);
  }
  for (auto& s : scratch_) s = std::make_unique<std::uint64_t[]>(cap + 1);
  capacity_ = cap;
}

void StateStore::resize(std::size_t n) {
  reserve(n);
  const std::size_t old = size_;
  size_ = n;
  fill_tail(std::min(old, n));
}

void StateStore::swap_buffers(std::size_t n) noexcept {
  current_ = 1 - current_;
  size_ = n;
  fill_tail(n);  // padding lanes of the new buffer get defined values
}

void StateStore::set_uniform_weights() noexcept {
  const float logw = size_ == 0 ? 0.0F : -std::log(static_cast<float>(size_));
  std::fill_n(view().logw, pad_particles(size_), logw);
}

void StateStore::fill_tail(std::size_t from) noexcept {
  const StateView v = view();
  const std::size_t end = pad_particles(size_);
  for (std::size_t c = 0; c < dims_; ++c) std::fill(v.column(c) + from, v.column(c) + end, 0.0F);
  const float logw = size_ == 0 ? 0.0F : -std::log(static_cast<float>(size_));
  std::fill(v.logw + from, v.logw + end, logw);
}

StateView StateStore::view_of(int buffer, std::size_t n) const noexcept {
  float* base = buffers_[buffer].get();
  return {base, base + dims_ * capacity_, capacity_, dims_, n};
}

NormalizeResult normalize(const StateView& states, std::size_t grain) {
  return detail::normalize_log_weights(states.logw, states.size(), grain);
}

double effective_sample_size(const ConstStateView& states) {
  return detail::log_weights_ess(states.logw, states.size());
}

namespace {

// The generic store as resample_impl.hpp sees it: every column gathered by one ancestor index.
struct StateResampling {
  StateStore& store;

  void reserve(std::size_t n) { store.reserve(n); }
  [[nodiscard]] std::size_t size() const { return store.size(); }
  [[nodiscard]] const float* log_weights() const { return store.view().logw; }
  [[nodiscard]] std::uint64_t* scratch(int which) const { return store.scratch(which); }

  [[nodiscard]] auto gather(std::size_t n_out) const {
    return [in = ConstStateView(store.view()), out = store.spare(n_out)](std::size_t i,
                                                                         std::size_t j) {
      for (std::size_t c = 0; c < in.dims; ++c) out.column(c)[j] = in.column(c)[i];
    };
  }
  void commit(std::size_t n_out) const {
    store.swap_buffers(n_out);
    store.set_uniform_weights();
  }
};

}  // namespace

void resample_systematic(StateStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain) {
  StateResampling s{store};
  detail::systematic(s, n_out, seed, step, grain);
}

void resample_systematic_serial(StateStore& store, std::size_t n_out, std::uint64_t seed,
                                std::uint64_t step) {
  StateResampling s{store};
  detail::systematic_serial(s, n_out, seed, step);
}

void resample_multinomial(StateStore& store, std::size_t n_out, std::uint64_t seed,
                          std::uint64_t step, std::size_t grain) {
  StateResampling s{store};
  detail::multinomial(s, n_out, seed, step, grain);
}

void resample_stratified(StateStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain) {
  StateResampling s{store};
  detail::stratified(s, n_out, seed, step, grain);
}

void resample_residual(StateStore& store, std::size_t n_out, std::uint64_t seed,
                       std::uint64_t step) {
  StateResampling s{store};
  detail::residual(s, n_out, seed, step);
}

StateKldBins::StateKldBins(std::vector<double> bin_sizes) {
  if (bin_sizes.empty()) throw ConfigError("StateKldBins: need one bin size per state column");
  for (const double b : bin_sizes) {
    if (!(b > 0.0)) throw ConfigError("StateKldBins: bin sizes must be positive");
    inv_sizes_.push_back(static_cast<float>(1.0 / b));
  }
}

std::size_t StateKldBins::count(const ConstStateView& states, std::size_t grain) {
  const std::size_t dims = inv_sizes_.size();
  if (states.dims != dims) {
    throw ConfigError("StateKldBins::count: the store has " + std::to_string(states.dims) +
                      " columns, the bins " + std::to_string(dims));
  }
  const std::size_t n = states.size();
  if (n == 0) return 0;
  rows_.resize(n * dims);
  order_.resize(n);
  // Bin indices in parallel (each particle writes its own row); float -> int64 clamps the
  // range so a NaN or huge value still gives a defined (border) bin.
  constexpr float kLimit = 9.0e15F;
  par::for_each_chunk(n, grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = 0; c < dims; ++c) {
      const float* col = states.column(c);
      for (std::size_t i = begin; i < end; ++i) {
        const float v = std::floor(col[i] * inv_sizes_[c]);
        rows_[i * dims + c] =
            static_cast<std::int64_t>(std::clamp(v == v ? v : 0.0F, -kLimit, kLimit));
      }
    }
  });
  std::iota(order_.begin(), order_.end(), 0U);
  const auto row = [&](std::uint32_t i) {
    return rows_.begin() + static_cast<std::ptrdiff_t>(i * dims);
  };
  const auto row_end = [&](std::uint32_t i) { return row(i) + static_cast<std::ptrdiff_t>(dims); };
  std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) {
    return std::lexicographical_compare(row(a), row_end(a), row(b), row_end(b));
  });
  std::size_t k = 1;
  for (std::size_t r = 1; r < n; ++r) {
    if (!std::equal(row(order_[r - 1]), row_end(order_[r - 1]), row(order_[r]))) ++k;
  }
  return k;
}

std::size_t kld_sample_count(const ConstStateView& states, StateKldBins& bins,
                             const KldConfig& config, std::size_t grain) {
  if (config.min_particles == config.max_particles) return config.max_particles;  // as kld.cpp
  return kld_sample_count(bins.count(states, grain), config);
}

std::size_t resample_kld_systematic(StateStore& store, StateKldBins& bins, const KldConfig& config,
                                    std::uint64_t seed, std::uint64_t step, std::size_t grain) {
  const std::size_t n = kld_sample_count(std::as_const(store).view(), bins, config, grain);
  resample_systematic(store, n, seed, step, grain);
  return n;
}

}  // namespace mote
