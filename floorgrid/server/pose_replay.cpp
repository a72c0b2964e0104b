#include "floorgrid/server/pose_replay.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace floorgrid::server {

std::vector<double> replay_waits(const std::vector<io::TimedPose>& track,
                                 const ReplayOptions& options) {
  std::vector<double> waits(track.size(), 0.0);
  for (std::size_t i = 1; i < track.size(); ++i) {
    const double gap = track[i].time - track[i - 1].time;
    waits[i] = std::isfinite(gap) && gap > 0.0 && gap <= options.max_gap_s ? gap : options.gap_s;
  }
  return waits;
}

PoseReplay::PoseReplay(ViewerSession& session, std::vector<io::TimedPose> track,
                       ReplayOptions options)
    : session_(session), track_(std::move(track)), options_(options) {
  if (track_.empty())
    throw std::invalid_argument("PoseReplay: no poses to replay");
  if (!(options_.speed > 0.0) || !std::isfinite(options_.speed))
    throw std::invalid_argument("PoseReplay: the speed must be > 0");
  waits_ = replay_waits(track_, options_);
  thread_ = std::thread([this] { run(); });
}

PoseReplay::~PoseReplay() {
  stop();
}

void PoseReplay::stop() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable())
    thread_.join();
}

std::uint64_t PoseReplay::posted() const {
  const std::lock_guard lock(mutex_);
  return posted_;
}

void PoseReplay::run() {
  using Clock = std::chrono::steady_clock;
  constexpr double kLoopPauseS = 2.0;
  std::unique_lock lock(mutex_);
  // Each pose is due at a time from the pass's start, so that waits do not add up drift.
  auto due = Clock::now();
  do {
    for (std::size_t i = 0; i < track_.size(); ++i) {
      due += std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(waits_[i] / options_.speed));
      if (wake_.wait_until(lock, due, [this] { return stopping_; }))
        return;
      session_.post_robot_pose(track_[i].pose_in_grid);
      ++posted_;
    }
    due += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kLoopPauseS));
  } while (options_.loop);
}

}  // namespace floorgrid::server
