#pragma once
/// \file
/// The one entry point public templates (predict, reweight) use to run a body over particle
/// chunks in parallel without a TBB header in the public API: the callable is passed by
/// reference through a function pointer and invoked once per chunk.

#include <cstddef>
#include <type_traits>

namespace mote {

/// Default particles per task; chunk starts are multiples of the grain rounded up to 16.
inline constexpr std::size_t kDefaultGrain = 4096;

/// A non-owning reference to a callable body(begin, end).
class ChunkBody {
 public:
  template <class F>
  requires std::is_invocable_v<const F&, std::size_t, std::size_t> ChunkBody(const F& f)
  noexcept  // NOLINT(google-explicit-constructor)
      : object_(&f), call_([](const void* o, std::size_t b, std::size_t e) {
          (*static_cast<const F*>(o))(b, e);
        }) {}
  void operator()(std::size_t begin, std::size_t end) const { call_(object_, begin, end); }

 private:
  const void* object_;
  void (*call_)(const void*, std::size_t, std::size_t);
};

/// Calls body(begin, end) over disjoint chunks covering [0, n) in the current task arena (see
/// mote::Executor). Chunk boundaries depend on n and grain only, never on the thread count.
void for_each_particle_chunk(std::size_t n, std::size_t grain, ChunkBody body);

}  // namespace mote
