#pragma once

#include <Eigen/Core>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid {

/// A pose at a time.
struct TimedPose {
  double time = 0.0;  ///< seconds
  Pose2 pose;         ///< metres, radians
};

/// How the simulated robot drives its tour.
struct TourOptions {
  double speed = 0.6;             ///< m/s when driving straight
  double turn_rate = 0.8;         ///< rad/s, turning
  double tick = 0.1;              ///< s between poses (odometry rate)
  double start_time = 1000.0;     ///< s, the first timestamp (never 0: CARMEN skips it)
  double align_angle = 0.35;      ///< rad: heading errors above it turn on the spot
  double arrive_distance = 0.05;  ///< m: a waypoint closer than this is reached
};

/// Drives a differential-drive robot through `waypoints`: at each waypoint it turns on the spot
/// towards the next one, then drives straight, steering away small heading errors. Returns the
/// pose every tick, starting at the first waypoint facing the second.
std::vector<TimedPose> drive_tour(const std::vector<Eigen::Vector2d>& waypoints,
                                  const TourOptions& options = {});

/// Drives the tour over and over, forth and then back (turning on the spot at either end),
/// until `duration` seconds have passed: the poses of drive_tour over that longer tour, up to
/// start_time + duration (the last pose within half a tick of it). A duration not above zero
/// (or NaN), or a tour that takes no time (one waypoint), gives drive_tour's poses unchanged.
std::vector<TimedPose> drive_tour_for(const std::vector<Eigen::Vector2d>& waypoints,
                                      double duration, const TourOptions& options = {});

/// Total length driven, metres.
double path_length(const std::vector<TimedPose>& poses);

}  // namespace floorgrid
