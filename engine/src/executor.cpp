#include "mote/engine/executor.hpp"

#include <oneapi/tbb/info.h>
#include <oneapi/tbb/task_arena.h>

namespace mote {

struct Executor::Impl {
  explicit Impl(int threads) : arena(threads) {}
  tbb::task_arena arena;
};

namespace {
int resolve_thread_count(int requested) {
  return requested > 0 ? requested : tbb::info::default_concurrency();
}
}  // namespace

Executor::Executor(int threads) : impl_(std::make_unique<Impl>(resolve_thread_count(threads))) {}
Executor::~Executor() = default;
Executor::Executor(Executor&&) noexcept = default;
Executor& Executor::operator=(Executor&&) noexcept = default;

int Executor::threads() const noexcept { return impl_->arena.max_concurrency(); }

void Executor::run(const std::function<void()>& job) const { impl_->arena.execute(job); }

}  // namespace mote
