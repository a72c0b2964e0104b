#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid {

/// An 8-bit RGB picture, rows from the top, 3 bytes per pixel.
struct RgbImage {
  int width = 0;                  ///< pixels
  int height = 0;                 ///< pixels
  std::vector<std::uint8_t> rgb;  ///< width * height * 3 bytes

  /// Sets pixel (col, row) when it lies in the picture.
  void set(int col, int row, const std::array<std::uint8_t, 3>& colour);
};

/// An RGB colour.
using Colour = std::array<std::uint8_t, 3>;

/// The grid as a picture with one pixel per cell: occupied black, free white, unknown grey.
RgbImage grid_picture(const OccupancyGrid& grid);

/// Draws points given in the grid's frame as dots of `radius` pixels.
void draw_points(RgbImage& picture, const GridGeometry& geometry,
                 const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid, const Colour& colour,
                 int radius = 0);

/// Draws the plan's segments and arcs, each mapped into the grid's frame by `plan_to_grid`
/// (sampled every `spacing` metres of plan, default half a cell), as a connected line.
void draw_plan(RgbImage& picture, const GridGeometry& geometry, const VectorFloorplan& plan,
               const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid,
               const Colour& colour, double spacing = 0.0);

}  // namespace floorgrid
