#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/simulation/laser_simulator.hpp"

namespace floorgrid {

/// A warp from the world frame into the grid frame (metres to metres), e.g.
/// SimulatedWarp::world_to_grid.
using WorldToGrid = std::function<Eigen::Vector2d(const Eigen::Vector2d&)>;

/// One scan as the SLAM-like map builder takes it: the TRUE laser pose and the noisy readings.
struct SlamMapInput {
  Pose2 laser_pose_in_world;     ///< the true laser pose, world metres and radians
  double start_angle = 0.0;      ///< radians, beam 0 relative to the laser pose
  double angle_increment = 0.0;  ///< radians between neighbouring beams
  double max_range = 0.0;        ///< metres; readings at or above it are "no return"
  std::vector<double> ranges;    ///< metres, one reading per beam
};

/// The map builder's input for a simulated scan: its true laser pose and its noisy readings.
SlamMapInput to_slam_map_input(const SimulatedScan& scan);

/// How build_slam_map counts and classifies cells.
struct SlamMapOptions {
  double resolution = 0.05;      ///< metres per cell, finite and > 0
  double margin = 1.0;           ///< metres of unknown border around every observed cell, >= 0
  int min_hits = 2;              ///< an occupied cell has at least this many hits, >= 1
  double occupied_ratio = 0.25;  ///< and hits / (hits + misses) at least this, in [0, 1]
  /// metres: a world ray is cut into pieces at most this long, whose ends go through the warp
  /// and are joined by straight lines in the grid; finite and > 0
  double max_piece_length = 1.0;
  /// metres a no-return beam marks free (no hit); nullopt: the scan's max_range; finite, > 0
  std::optional<double> free_range_for_no_return;
  std::size_t max_cells = 400'000'000;  ///< refuse grids larger than this (memory guard)
};

/// Checks `options`; throws InputError naming the field (`slam_map.resolution`, ...).
void validate_slam_map_options(const SlamMapOptions& options);

/// Per-cell hit and miss counts of a SLAM-like map, before classification.
struct SlamMapCounts {
  GridGeometry geometry;              ///< axis-aligned (yaw 0) in the grid frame
  std::vector<std::uint32_t> hits;    ///< beam endpoints per cell, row-major from the bottom row
  std::vector<std::uint32_t> misses;  ///< beams passing through per cell, same order
  std::size_t beams_used = 0;         ///< beams traced (returns and no-returns)
  std::size_t beams_skipped = 0;      ///< readings that are not finite or not > 0
};

/// Traces every beam of `scans` into hit and miss counts in the grid frame.
///
/// A reading in (0, max_range) is a return: its endpoint, the world point at the reading's range
/// along the beam, maps exactly through `world_to_grid` and scores a hit in its cell. A reading
/// at or above max_range is a no-return: it scores no hit and reaches free_range_for_no_return.
/// Readings that are not finite or not > 0 are skipped. Free space: the world ray from the laser
/// to its end is cut into ceil(length / max_piece_length) equal pieces, the piece ends map
/// through the warp, and each piece is walked cell by cell in the grid (a 4-connected DDA that
/// ends exactly in the cell of the piece's end). Every distinct cell on the way scores one miss,
/// except the last cell of a return (its hit cell). The grid is axis-aligned, its origin a
/// multiple of the resolution, and it covers every point traced plus the margin (so every
/// traced cell lies inside it). Throws InputError on bad options or when the grid would exceed
/// max_cells. With nothing to trace, the geometry is 0 x 0.
SlamMapCounts count_slam_map(const std::vector<SlamMapInput>& scans,
                             const WorldToGrid& world_to_grid, const SlamMapOptions& options = {});

/// Classifies counts like a SLAM occupancy map: occupied when hits >= min_hits and
/// hits / (hits + misses) >= occupied_ratio; free when the cell has misses and is not occupied;
/// unknown otherwise (never crossed, or too few hits and no miss). Values are the canonical ones.
OccupancyGrid classify_slam_map(const SlamMapCounts& counts, const SlamMapOptions& options = {});

/// The SLAM-like occupancy gridmap of `scans` in the grid frame: count_slam_map, then
/// classify_slam_map. Deterministic: the same inputs give the same grid.
OccupancyGrid build_slam_map(const std::vector<SlamMapInput>& scans,
                             const WorldToGrid& world_to_grid, const SlamMapOptions& options = {});

}  // namespace floorgrid
