#pragma once

#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// A block of cells [x0, x1) x [y0, y1) of a grid.
struct CellBox {
  int x0 = 0, y0 = 0;  ///< first column and row (rows count from the bottom)
  int x1 = 0, y1 = 0;  ///< one past the last
  /// Whether the box holds no cell.
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  /// Cells in the box.
  std::size_t cells() const {
    return empty() ? 0 : static_cast<std::size_t>(x1 - x0) * static_cast<std::size_t>(y1 - y0);
  }
};

/// The smallest box holding every known (free or occupied) cell, grown by `margin` cells on
/// each side and clipped to the grid; empty when no cell is known.
CellBox known_cells_box(const OccupancyGrid& grid, int margin);

/// The cells of `grid` inside `box` (clipped to the grid) as a grid of their own, in the same
/// frame: every cell keeps its place in the world (the origin moves along the grid's axes), its
/// class and its value.
OccupancyGrid crop(const OccupancyGrid& grid, const CellBox& box);

}  // namespace floorgrid
