#include "mote/engine/particles.hpp"

#include <algorithm>
#include <cmath>
#include <new>

namespace mote {

void ParticleStore::AlignedFree::operator()(float* p) const noexcept {
  ::operator delete[](p, std::align_val_t{kParticleAlignment});
}

namespace {
// One buffer holds the four columns back to back; cap is a multiple of 16 floats (64 bytes), so
// every column starts on a 64-byte boundary.
float* allocate_columns(std::size_t cap) {
  return static_cast<float*>(
      ::operator new[](4 * cap * sizeof(float), std::align_val_t{kParticleAlignment}));
}
}  // namespace

ParticleStore::ParticleStore(std::size_t n) { resize(n); }

void ParticleStore::reserve(std::size_t n) {
  const std::size_t cap = pad_particles(std::max<std::size_t>(n, 1));
  if (cap <= capacity_) return;
  for (int b = 0; b < 2; ++b) {
    Column fresh(allocate_columns(cap));
    if (buffers_[b]) {
      for (std::size_t c = 0; c < 4; ++c) {
        std::copy_n(buffers_[b].get() + c * capacity_, capacity_, fresh.get() + c * cap);
      }
    }
    buffers_[b] = std::move(fresh);
    scratch_[b] = std::make_unique<std::uint64_t[]>(cap + 1);
  }
  capacity_ = cap;
}

void ParticleStore::resize(std::size_t n) {
  reserve(n);
  const std::size_t old = size_;
  size_ = n;
  fill_tail(std::min(old, n));
}

void ParticleStore::swap_buffers(std::size_t n) noexcept {
  current_ = 1 - current_;
  size_ = n;
  // Padding lanes of the new buffer hold whatever was there; give them defined values.
  fill_tail(n);
}

void ParticleStore::set_uniform_weights() noexcept {
  const float logw = size_ == 0 ? 0.0F : -std::log(static_cast<float>(size_));
  std::fill_n(view().logw, pad_particles(size_), logw);
}

void ParticleStore::fill_tail(std::size_t from) noexcept {
  const ParticleView v = view();
  const std::size_t end = pad_particles(size_);
  const float logw = size_ == 0 ? 0.0F : -std::log(static_cast<float>(size_));
  std::fill(v.x + from, v.x + end, 0.0F);
  std::fill(v.y + from, v.y + end, 0.0F);
  std::fill(v.theta + from, v.theta + end, 0.0F);
  std::fill(v.logw + from, v.logw + end, logw);
}

ParticleView ParticleStore::view_of(int buffer, std::size_t n) const noexcept {
  float* base = buffers_[buffer].get();
  return {base, base + capacity_, base + 2 * capacity_, base + 3 * capacity_, n};
}

ConstParticleView ParticleStore::const_view_of(int buffer, std::size_t n) const noexcept {
  const ParticleView v = view_of(buffer, n);
  return {v.x, v.y, v.theta, v.logw, n};
}

}  // namespace mote
