#include "floorgrid/mapping/gp_parallel.hpp"

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace floorgrid {

void gp_run_tasks(Eigen::Index tasks, int threads, const std::function<void(Eigen::Index)>& work) {
  const Eigen::Index used = std::clamp<Eigen::Index>(threads, 1, std::max<Eigen::Index>(tasks, 1));
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(used));
  const auto run = [&](Eigen::Index thread) {
    try {
      for (Eigen::Index task = thread; task < tasks; task += used)
        work(task);
    } catch (...) {
      errors[static_cast<std::size_t>(thread)] = std::current_exception();
    }
  };
  std::vector<std::thread> helpers;
  for (Eigen::Index thread = 1; thread < used; ++thread)
    helpers.emplace_back(run, thread);
  run(0);
  for (std::thread& helper : helpers)
    helper.join();
  for (const std::exception_ptr& error : errors) {
    if (error)
      std::rethrow_exception(error);
  }
}

void gp_run_blocks(Eigen::Index count, Eigen::Index block, int threads,
                   const std::function<void(Eigen::Index begin, Eigen::Index end)>& work) {
  if (count <= 0)
    return;
  const Eigen::Index blocks = (count + block - 1) / block;
  gp_run_tasks(blocks, threads, [&](Eigen::Index b) {
    const Eigen::Index begin = b * block;
    work(begin, std::min(begin + block, count));
  });
}

}  // namespace floorgrid
