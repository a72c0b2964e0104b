#pragma once

#include <optional>
#include <vector>

#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/plan_layers.hpp"

namespace floorgrid {

/// A waypoint through the model: its pose in the target frame and how far to trust it.
struct MappedWaypoint {
  Waypoint waypoint;            ///< name, index, position and heading in the target frame
  std::optional<double> std_m;  ///< the model's std_m at it, metres (none without error model)
  double nearest_pair_m = 0.0;  ///< metres from the source point to the nearest pair
  MapFlag flag = MapFlag::ok;   ///< the model's flag
  /// Flagged extrapolated, outside_hull or not_invertible: kept, never dropped, but not to be
  /// trusted as a goal without a look.
  bool extrapolated = false;
  /// Inside the target gridmap's bounds (true when no gridmap geometry was given).
  bool on_gridmap = true;
};

/// The waypoints (source frame, metres) through `model` forward: position forward, heading
/// through the Jacobian (absent stays absent). Validates each (validate_waypoint; InputError
/// naming `where`). `gridmap`, when given, sets on_gridmap.
std::vector<MappedWaypoint> map_waypoints(const PointMapping& model,
                                          const std::vector<Waypoint>& waypoints,
                                          const std::optional<GridGeometry>& gridmap = {},
                                          const std::string& where = "waypoints");

}  // namespace floorgrid
