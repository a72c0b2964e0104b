#pragma once

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "floorgrid/io/formats/scans_csv.hpp"
#include "floorgrid/server/viewer_session.hpp"

namespace floorgrid::server {

/// How a run is replayed as the live pose.
struct ReplayOptions {
  double speed = 1.0;      ///< times real time (> 0)
  double max_gap_s = 2.0;  ///< run seconds: a longer or unknown gap between scans is replaced
  double gap_s = 0.1;      ///< by this (logs with garbage or repeated timestamps)
  bool loop = true;        ///< start again after the last pose (after a pause of 2 s)
};

/// The wait before each pose of `track`, run seconds: its time since the previous pose, or
/// options.gap_s where that is unknown, not positive or above options.max_gap_s (0 first).
std::vector<double> replay_waits(const std::vector<io::TimedPose>& track,
                                 const ReplayOptions& options = {});

/// Posts a run's gridmap poses to a session as the robot's pose, at their times (scaled by
/// options.speed), on its own thread until stopped or destroyed.
class PoseReplay {
 public:
  /// Starts replaying `track` (not empty) into `session` (which must outlive the replay).
  PoseReplay(ViewerSession& session, std::vector<io::TimedPose> track, ReplayOptions options = {});
  ~PoseReplay();
  PoseReplay(const PoseReplay&) = delete;
  PoseReplay& operator=(const PoseReplay&) = delete;

  /// Stops the replay (idempotent); returns once its thread has ended.
  void stop();
  /// Poses posted so far.
  std::uint64_t posted() const;

 private:
  void run();

  ViewerSession& session_;
  std::vector<io::TimedPose> track_;
  std::vector<double> waits_;
  ReplayOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::uint64_t posted_ = 0;
  std::thread thread_;
};

}  // namespace floorgrid::server
