#pragma once
/// \file
/// The thread pool mote's kernels run on: an engine-owned task arena (design.md section 3,
/// "Threads"). No process-wide TBB setting is touched, so several Localizers with different
/// thread counts can live in one process.

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>

namespace mote {

/// A fixed-size pool of worker threads. Every mote kernel called from inside run() splits its
/// work over at most threads() threads; the same kernels called outside any Executor use the
/// process's default pool. Results never depend on the thread count (determinism contract).
class Executor {
 public:
  /// threads <= 0 means every core of the machine.
  explicit Executor(int threads = 0);
  ~Executor();
  Executor(Executor&&) noexcept;
  Executor& operator=(Executor&&) noexcept;
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  /// Number of threads the arena runs, including the calling thread.
  [[nodiscard]] int threads() const noexcept;

  /// Runs job on this executor's threads and waits for it; exceptions propagate.
  void run(const std::function<void()>& job) const;

  /// Runs f on this executor's threads and returns its result (by value).
  template <class F>
  std::invoke_result_t<F&> operator()(F&& f) const {
    using R = std::invoke_result_t<F&>;
    if constexpr (std::is_void_v<R>) {
      run([&] { f(); });
    } else {
      std::optional<R> result;
      run([&] { result.emplace(f()); });
      return std::move(*result);
    }
  }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mote
