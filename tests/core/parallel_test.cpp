#include "floorgrid/core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace floorgrid {
namespace {

TEST(ParallelTasks, RunsEveryTaskExactlyOnceWithAnyThreadCount) {
  for (const int threads : {-3, 0, 1, 2, 3, 8}) {
    for (const std::size_t tasks : {0u, 1u, 2u, 7u, 100u}) {
      std::vector<std::atomic<int>> runs(tasks);
      parallel_tasks(tasks, threads, [&](std::size_t t) { ++runs[t]; });
      for (std::size_t t = 0; t < tasks; ++t)
        EXPECT_EQ(runs[t].load(), 1) << "task " << t << " of " << tasks << ", threads " << threads;
    }
  }
}

TEST(ParallelTasks, RethrowsATasksExceptionAfterAllFinished) {
  std::atomic<int> done{0};
  EXPECT_THROW(parallel_tasks(10, 2,
                              [&](std::size_t t) {
                                ++done;
                                if (t == 3)
                                  throw std::runtime_error("task 3");
                              }),
               std::runtime_error);
  // Thread 1 (odd tasks) stops at task 3; thread 0 runs all five even tasks.
  EXPECT_GE(done.load(), 7);
}

TEST(ParallelBlocks, CoversTheRangeWithContiguousBlocks) {
  for (const int threads : {1, 2, 3, 5}) {
    for (const std::size_t count : {0u, 1u, 2u, 10u, 1001u}) {
      std::vector<std::atomic<int>> hits(count);
      std::atomic<int> blocks{0};
      parallel_blocks(count, threads, [&](std::size_t begin, std::size_t end) {
        ++blocks;
        EXPECT_LE(begin, end);
        for (std::size_t i = begin; i < end; ++i)
          ++hits[i];
      });
      for (std::size_t i = 0; i < count; ++i)
        ASSERT_EQ(hits[i].load(), 1) << "item " << i;
      EXPECT_LE(blocks.load(), std::max(threads, 1));
    }
  }
}

TEST(ParallelChunks, ChunksDoNotDependOnTheThreadCount) {
  const std::size_t count = 1003, chunk = 100;
  std::vector<double> values(count);
  std::iota(values.begin(), values.end(), 0.5);
  const auto chunked_sums = [&](int threads) {
    std::vector<double> partial((count + chunk - 1) / chunk, 0.0);
    parallel_chunks(count, chunk, threads, [&](std::size_t begin, std::size_t end) {
      EXPECT_EQ(begin % chunk, 0u);
      EXPECT_TRUE(end == count || end - begin == chunk);
      for (std::size_t i = begin; i < end; ++i)
        partial[begin / chunk] += values[i];
    });
    return partial;
  };
  const std::vector<double> one = chunked_sums(1);
  EXPECT_EQ(one, chunked_sums(2));
  EXPECT_EQ(one, chunked_sums(7));
  EXPECT_DOUBLE_EQ(std::accumulate(one.begin(), one.end(), 0.0),
                   std::accumulate(values.begin(), values.end(), 0.0));
}

}  // namespace
}  // namespace floorgrid
