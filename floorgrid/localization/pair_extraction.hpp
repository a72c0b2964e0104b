#pragma once

#include <map>
#include <string>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/localization/wall_field.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid {

/// How laser endpoints become reference pairs (thesis 4.6.1).
struct PairExtractionOptions {
  int beam_step = 2;            ///< keep every k-th beam of a scan (beam subsampling)
  int max_pairs_per_scan = 40;  ///< then at most this many pairs per scan, evenly spread
  /// Metres: longer readings are not used (a filter's heading error moves an endpoint by the
  /// range times the error, so far endpoints make poor pairs); counted as `too_far`.
  double max_range = 10.0;
  /// Metres (world): an endpoint must lie this close to a wall of each map (WallField::distance,
  /// so to a raster plan's ink edge where its WallField meets walls there; drops furniture hits).
  double max_wall_distance = 0.10;
};

/// Why endpoints did not become pairs, counted (metrics.json `pairs.rejected.<reason>`).
struct PairRejections {
  std::size_t not_converged = 0;  ///< beams of scans where a filter was not converged
  std::size_t no_return = 0;      ///< readings at or above max range (or invalid)
  std::size_t off_plan_wall = 0;  ///< endpoints far from every wall of the plan
  std::size_t off_grid_wall = 0;  ///< endpoints far from every occupied gridmap cell
  std::size_t subsampled = 0;     ///< beams skipped by the beam subsampling
  std::size_t per_scan_cap = 0;   ///< valid pairs dropped by the per-scan cap
  std::size_t too_far = 0;        ///< returns beyond PairExtractionOptions::max_range
  /// Beams of scans whose pose a scan match could not pin down in one of the maps (it saw only
  /// parallel walls, a corridor or an aisle, so the pose along it is a guess).
  std::size_t degenerate = 0;
  /// Beams of scans a scan match rejected in one of the maps (too few endpoints on walls, or
  /// the filter's pose needed a correction beyond the match's limits).
  std::size_t unmatched = 0;
  /// Beams of scans where the plan pose disagreed with the gridmap pose through the plan's
  /// registration (one of the filters is wrong).
  std::size_t inconsistent = 0;
  /// Pairs of scans whose pairs disagreed with the other scans' at the same walls (counted in
  /// pairs, after they were made).
  std::size_t outlier_scan = 0;

  /// Adds another count.
  PairRejections& operator+=(const PairRejections& other);
  /// Reason -> count, with SPEC's names.
  std::map<std::string, std::size_t> by_reason() const;
  /// All rejected beams.
  std::size_t total() const;
};

/// Pairs as they are collected, scan by scan (appending to Eigen matrices would copy them).
struct PairCollector {
  std::vector<Eigen::Vector2d> plan;  ///< endpoints in the plan, plan metres
  std::vector<Eigen::Vector2d> grid;  ///< the same endpoints in the grid, metres
  /// The pairs collected.
  ReferencePairs pairs() const;
  /// Number of pairs.
  std::size_t size() const { return plan.size(); }
};

/// Appends the pairs of one scan taken while both filters were converged: each kept return's
/// endpoint from the plan filter's mean pose (the robot-frame endpoint divided by the plan's
/// scale, world metres per plan metre) and from the grid filter's mean pose; `plan_walls` and
/// `grid_walls` give the distance to the nearest wall of each map (plan metres, grid metres;
/// WallField::distance).
void extract_scan_pairs(const LaserScan& scan, const Pose2& pose_in_plan, double plan_scale,
                        const Pose2& pose_in_grid, const WallField& plan_walls,
                        const WallField& grid_walls, const PairExtractionOptions& options,
                        PairCollector& pairs, PairRejections& rejections);

/// Counts every beam of a scan as not_converged.
void reject_scan(const LaserScan& scan, PairRejections& rejections);

}  // namespace floorgrid
