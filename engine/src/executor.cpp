#include "mote/engine/executor.hpp"

#include <oneapi/tbb/info.h>
#include <oneapi/tbb/task_arena.h>

#include "mote/core/parallel.hpp"

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

void Executor::run(const std::function<void()>& job) const {
  par::detail::ForkJoin sync;  // the arena may run the job on one of its own threads
  impl_->arena.execute([&] {
    sync.task_begins();
    job();
    sync.task_ends();
  });
  sync.joined();
}

}  // namespace mote
