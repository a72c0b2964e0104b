#pragma once

#include <cstddef>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid {

/// The beams of one laser scan as the observation models use them: every beam kept (after
/// subsampling) with its direction and range, and its endpoint, all in the ROBOT frame in
/// world metres. For a particle at pose p with scale s (world metres per map metre), the laser
/// origin lies at p ∘ (laser_origin / s) and beam k's endpoint at p ∘ (endpoint_k / s): the
/// whole robot-frame geometry shrinks by s, since the map's metre is s world metres.
struct ScanObservation {
  Eigen::Vector2d laser_origin = Eigen::Vector2d::Zero();  ///< laser position, robot frame, m
  double max_range = 0.0;      ///< metres: readings at or above it are "no return"
  std::vector<float> angle;    ///< beam direction in the robot frame, radians
  std::vector<float> range;    ///< metres, a return (finite, below max_range, >= min_range)
  std::vector<float> end_x;    ///< endpoint x in the robot frame, metres
  std::vector<float> end_y;    ///< endpoint y in the robot frame, metres
  std::vector<int> beam;       ///< index of the beam in the scan
  std::size_t no_returns = 0;  ///< beams of the scan that read "no return" (not in the arrays)

  /// Number of beams kept.
  std::size_t size() const { return range.size(); }
  /// Appends beam j of `other` (its angle, range, endpoint and index).
  void push_back_beam(const ScanObservation& other, std::size_t j) {
    angle.push_back(other.angle[j]);
    range.push_back(other.range[j]);
    end_x.push_back(other.end_x[j]);
    end_y.push_back(other.end_y[j]);
    beam.push_back(other.beam[j]);
  }
};

/// How a scan becomes an observation.
struct ObservationOptions {
  int max_beams = 60;  ///< keep at most this many returns, evenly spread over the scan
};

/// The returns of `scan` (at most options.max_beams, evenly spread) in the robot frame, using
/// the scan's laser pose relative to its robot pose (both odometry poses in the log).
ScanObservation make_observation(const LaserScan& scan, const ObservationOptions& options = {});

}  // namespace floorgrid
