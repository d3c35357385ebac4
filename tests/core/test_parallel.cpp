#include "mote/core/parallel.hpp"

#include <gtest/gtest.h>
#include <oneapi/tbb/task_arena.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace mote::par {
namespace {

TEST(ForEachChunk, CoversEveryIndexOnceWithAlignedBoundaries) {
  for (std::size_t n : {0UL, 1UL, 15UL, 16UL, 1000UL, 100'003UL}) {
    std::vector<std::atomic<int>> hits(n);
    std::atomic<bool> aligned{true};
    for_each_chunk(n, 100, [&](std::size_t begin, std::size_t end) {
      if (begin % kVectorWidth != 0) aligned = false;
      for (std::size_t i = begin; i < end; ++i) ++hits[i];
    });
    EXPECT_TRUE(aligned);
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i].load(), 1) << "index " << i;
  }
}

// A floating-point sum whose rounding depends on the order of addition.
double ill_conditioned_sum(std::size_t n, int threads, std::size_t block) {
  tbb::task_arena arena(threads);
  return arena.execute([&] {
    return reduce(
        n, block, 0.0,
        [](std::size_t b, std::size_t e) {
          double s = 0.0;
          for (std::size_t i = b; i < e; ++i) s += std::sin(static_cast<double>(i)) * 1e-3 + 1e8;
          return s;
        },
        [](double a, double c) { return a + c; });
  });
}

TEST(Reduce, IsBitIdenticalForAnyThreadCount) {
  const std::size_t n = 1'000'003;
  const double one = ill_conditioned_sum(n, 1, 4096);
  for (int threads : {2, 3, 4}) {
    for (int repeat = 0; repeat < 5; ++repeat) {
      EXPECT_EQ(ill_conditioned_sum(n, threads, 4096), one) << threads << " threads";
    }
  }
  EXPECT_NEAR(one, 1e8 * static_cast<double>(n), 1e3);
}

TEST(Reduce, EmptyRangeGivesIdentity) {
  EXPECT_EQ(reduce(
                0, 16, 7, [](std::size_t, std::size_t) { return 1; }, std::plus<>{}),
            7);
}

TEST(ExclusiveScan, EqualsSerialPrefixSum) {
  const std::size_t n = 300'001;
  std::vector<std::uint64_t> values(n);
  for (std::size_t i = 0; i < n; ++i) values[i] = (i * 2654435761U) % 1000U;
  std::vector<std::uint64_t> expected(n);
  std::exclusive_scan(values.begin(), values.end(), expected.begin(), std::uint64_t{0});
  const std::uint64_t total = std::accumulate(values.begin(), values.end(), std::uint64_t{0});

  tbb::task_arena arena(2);
  std::vector<std::uint64_t> out(n);
  const std::uint64_t got = arena.execute([&] {
    return exclusive_scan<std::uint64_t>(n, 1000, out.data(),
                                         [&](std::size_t i) { return values[i]; });
  });
  EXPECT_EQ(got, total);
  EXPECT_EQ(out, expected);
}

}  // namespace
}  // namespace mote::par
