#include "mote/engine/executor.hpp"

#include <gtest/gtest.h>

#include <oneapi/tbb/task_arena.h>

#include <stdexcept>

namespace mote {
namespace {

TEST(Executor, RunsOnTheRequestedNumberOfThreads) {
  const Executor one(1);
  const Executor two(2);
  EXPECT_EQ(one.threads(), 1);
  EXPECT_EQ(two.threads(), 2);
  EXPECT_EQ(one([] { return tbb::this_task_arena::max_concurrency(); }), 1);
  EXPECT_EQ(two([] { return tbb::this_task_arena::max_concurrency(); }), 2);
}

TEST(Executor, DefaultsToEveryCore) { EXPECT_GE(Executor().threads(), 1); }

TEST(Executor, PropagatesExceptions) {
  const Executor ex(2);
  EXPECT_THROW(ex([] { throw std::runtime_error("boom"); }), std::runtime_error);
}

}  // namespace
}  // namespace mote
