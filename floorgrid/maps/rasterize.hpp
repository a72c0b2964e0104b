#pragma once

#include <optional>

#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid {

/// How a vector floorplan becomes an occupancy grid.
struct RasterizeOptions {
  double resolution = 0.05;      ///< metres per cell, > 0
  double wall_thickness = 0.10;  ///< metres; walls thinner than a cell still draw a connected line
  double margin = 1.0;           ///< metres of free border around the plan's bounds
  std::size_t max_cells = 400'000'000;  ///< refuse grids larger than this (memory guard)
};

/// Rasterizes the plan: a cell is occupied when its centre lies within
/// max(wall_thickness, resolution) / 2 of a segment or arc, free otherwise (a plan is known
/// everywhere). With `geometry` the grid is laid there; otherwise it is axis-aligned and covers
/// the plan's bounds plus the margin. Throws InputError on bad options or an empty plan.
OccupancyGrid rasterize(const VectorFloorplan& plan, const RasterizeOptions& options = {},
                        const std::optional<GridGeometry>& geometry = std::nullopt);

/// Distance from `point` to a segment, metres.
double distance_to_segment(const Eigen::Vector2d& point, const Segment& segment);
/// Distance from `point` to an arc, metres.
double distance_to_arc(const Eigen::Vector2d& point, const Arc& arc);

}  // namespace floorgrid
