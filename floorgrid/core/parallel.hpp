#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace floorgrid {

/// The default number of threads of every option named `threads` (the machine the project
/// targets has two cores; more are used only when asked).
inline constexpr int kDefaultThreads = 2;

/// The threads worth starting for `work` units of which each thread should get at least
/// `min_per_thread` (a thread start costs ~20 us): at most `threads`, at least 1.
inline int threads_for(std::size_t work, std::size_t min_per_thread, int threads) {
  const std::size_t worth =
      std::max<std::size_t>(1, work / std::max<std::size_t>(min_per_thread, 1));
  return static_cast<int>(
      std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), worth));
}

/// Runs work(task) for every task in [0, tasks) on up to `threads` threads: the caller's and
/// threads - 1 more, task t, t + used, t + 2 used, ... on thread t. How work is split into
/// tasks is the caller's and must not depend on `threads`, so that results do not either. A
/// thread that cannot be started leaves its tasks to the caller. The first exception a task
/// throws is rethrown here after every thread has finished.
template <typename Work>
void parallel_tasks(std::size_t tasks, int threads, const Work& work) {
  const std::size_t used = std::clamp<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)),
                                                   1, std::max<std::size_t>(tasks, 1));
  std::vector<std::exception_ptr> errors(used);
  const auto run = [&](std::size_t thread) {
    try {
      for (std::size_t task = thread; task < tasks; task += used)
        work(task);
    } catch (...) {
      errors[thread] = std::current_exception();
    }
  };
  std::vector<std::thread> helpers;
  std::vector<std::size_t> left_over;
  for (std::size_t thread = 1; thread < used; ++thread) {
    try {
      helpers.emplace_back(run, thread);
    } catch (const std::system_error&) {
      left_over.push_back(thread);
    }
  }
  run(0);
  for (const std::size_t thread : left_over)
    run(thread);
  for (std::thread& helper : helpers)
    helper.join();
  for (const std::exception_ptr& error : errors) {
    if (error)
      std::rethrow_exception(error);
  }
}

/// Runs work(begin, end) over [0, count) split into at most `threads` contiguous blocks of
/// nearly equal size (block b is [count b / used, count (b + 1) / used)), the first on the
/// calling thread; as parallel_tasks otherwise. For work whose result does not depend on the
/// split (each item written on its own).
template <typename Work>
void parallel_blocks(std::size_t count, int threads, const Work& work) {
  const std::size_t used = std::clamp<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)),
                                                   1, std::max<std::size_t>(count, 1));
  parallel_tasks(used, static_cast<int>(used),
                 [&](std::size_t b) { work(count * b / used, count * (b + 1) / used); });
}

/// Runs work(begin, end) over [0, count) in chunks of `chunk` items (the last may be shorter),
/// on up to `threads` threads as parallel_tasks. The chunks do not depend on `threads`: per-chunk
/// partial results summed in chunk order give the same result with any number of threads.
template <typename Work>
void parallel_chunks(std::size_t count, std::size_t chunk, int threads, const Work& work) {
  if (count == 0)
    return;
  chunk = std::max<std::size_t>(chunk, 1);
  const std::size_t chunks = (count + chunk - 1) / chunk;
  parallel_tasks(chunks, threads, [&](std::size_t c) {
    const std::size_t begin = c * chunk;
    work(begin, std::min(begin + chunk, count));
  });
}

}  // namespace floorgrid
