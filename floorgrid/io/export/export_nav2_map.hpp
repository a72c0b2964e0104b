#pragma once

#include <filesystem>

#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid::io {

/// How the plan's walls are drawn into the gridmap's frame.
struct Nav2MapOptions {
  /// Wall samples per gridmap cell along a wall (after the model's scale): 4 keeps a drawn
  /// wall a connected line of cells wherever the model stretches it by less than 4x.
  double samples_per_cell = 4.0;
  /// What is not wall. Free by default: the plan is known everywhere (as rasterize reads it),
  /// and nav2's keepout filter reads free as "no keepout"; unknown for a map that claims only
  /// the walls.
  CellState background = CellState::free;
};

/// The plan's walls (DXF geometry) drawn through the model into a grid of `gridmap`'s geometry
/// (same resolution, origin and size): every cell a wall sample lands in is occupied, the rest
/// `options.background`. Walls are sampled densely in the plan and each sample is mapped, so a
/// non-rigid model bends them.
OccupancyGrid plan_walls_in_grid(const PointMapping& model, const VectorFloorplan& plan,
                                 const GridGeometry& gridmap, const Nav2MapOptions& options = {});

/// The same for a raster plan: each occupied plan cell, sampled within the cell as densely.
OccupancyGrid plan_walls_in_grid(const PointMapping& model, const OccupancyGrid& plan,
                                 const GridGeometry& gridmap, const Nav2MapOptions& options = {});

/// Writes a nav2 map: `yaml_path` (image, mode: trinary, resolution, origin, negate: 0,
/// occupied_thresh: 0.65, free_thresh: 0.25) and a PGM beside it (walls 0, free 254, unknown
/// 205), both atomically. Returns the image's path.
std::filesystem::path write_nav2_map(const OccupancyGrid& grid,
                                     const std::filesystem::path& yaml_path);

}  // namespace floorgrid::io
