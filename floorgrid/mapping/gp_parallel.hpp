#pragma once

#include <Eigen/Core>
#include <functional>

namespace floorgrid {

/// Runs work(task) for every task in [0, tasks) on up to `threads` threads (the caller's and
/// threads - 1 more; tasks t, t + threads, ... go to thread t). The split of the work into
/// tasks is the caller's and must not depend on `threads`, so that results do not either.
/// An exception thrown by a task is rethrown here after every thread has finished.
void gp_run_tasks(Eigen::Index tasks, int threads, const std::function<void(Eigen::Index)>& work);

/// Runs work(begin, end) over [0, count) in blocks of `block` items (the last may be
/// shorter), on up to `threads` threads, as gp_run_tasks.
void gp_run_blocks(Eigen::Index count, Eigen::Index block, int threads,
                   const std::function<void(Eigen::Index begin, Eigen::Index end)>& work);

}  // namespace floorgrid
