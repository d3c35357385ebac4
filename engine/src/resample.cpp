#include "mote/engine/resample.hpp"

#include "resample_impl.hpp"

namespace mote {
namespace {

// The pose store as the schemes in resample_impl.hpp see it: three state columns gathered by
// the same ancestor index, then uniform weights.
struct PoseResampling {
  ParticleStore& store;

  void reserve(std::size_t n) { store.reserve(n); }
  [[nodiscard]] std::size_t size() const { return store.size(); }
  [[nodiscard]] const float* log_weights() const { return store.view().logw; }
  [[nodiscard]] std::uint64_t* scratch(int which) const { return store.scratch(which); }

  [[nodiscard]] auto gather(std::size_t n_out) const {
    return [in = ConstParticleView(store.view()), out = store.spare(n_out)](std::size_t i,
                                                                            std::size_t j) {
      out.x[j] = in.x[i];
      out.y[j] = in.y[i];
      out.theta[j] = in.theta[i];
    };
  }
  void commit(std::size_t n_out) const {
    store.swap_buffers(n_out);
    store.set_uniform_weights();
  }
};

}  // namespace

void resample_systematic(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain) {
  PoseResampling s{store};
  detail::systematic(s, n_out, seed, step, grain);
}

void resample_systematic_serial(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                                std::uint64_t step) {
  PoseResampling s{store};
  detail::systematic_serial(s, n_out, seed, step);
}

void resample_multinomial(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                          std::uint64_t step, std::size_t grain) {
  PoseResampling s{store};
  detail::multinomial(s, n_out, seed, step, grain);
}

void resample_stratified(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                         std::uint64_t step, std::size_t grain) {
  PoseResampling s{store};
  detail::stratified(s, n_out, seed, step, grain);
}

void resample_residual(ParticleStore& store, std::size_t n_out, std::uint64_t seed,
                       std::uint64_t step) {
  PoseResampling s{store};
  detail::residual(s, n_out, seed, step);
}

}  // namespace mote
