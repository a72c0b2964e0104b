#include "floorgrid/maps/crop.hpp"

#include <algorithm>
#include <cmath>

namespace floorgrid {

CellBox known_cells_box(const OccupancyGrid& grid, int margin) {
  CellBox box{grid.width(), grid.height(), 0, 0};
  for (int iy = 0; iy < grid.height(); ++iy) {
    for (int ix = 0; ix < grid.width(); ++ix) {
      if (grid.state(ix, iy) == CellState::unknown)
        continue;
      box.x0 = std::min(box.x0, ix);
      box.y0 = std::min(box.y0, iy);
      box.x1 = std::max(box.x1, ix + 1);
      box.y1 = std::max(box.y1, iy + 1);
    }
  }
  if (box.empty())
    return {};
  return {std::max(0, box.x0 - margin), std::max(0, box.y0 - margin),
          std::min(grid.width(), box.x1 + margin), std::min(grid.height(), box.y1 + margin)};
}

OccupancyGrid crop(const OccupancyGrid& grid, const CellBox& wanted) {
  const CellBox box{std::max(0, wanted.x0), std::max(0, wanted.y0),
                    std::min(grid.width(), wanted.x1), std::min(grid.height(), wanted.y1)};
  GridGeometry geometry = grid.geometry();
  geometry.width = std::max(0, box.x1 - box.x0);
  geometry.height = std::max(0, box.y1 - box.y0);
  // The new lower-left corner is the old grid's point at cell coordinates (x0, y0).
  const Eigen::Vector2d corner =
      grid.geometry().from_cell_coordinates(Eigen::Vector2d(box.x0, box.y0));
  geometry.origin.x = corner.x();
  geometry.origin.y = corner.y();
  OccupancyGrid out(geometry);
  for (int iy = 0; iy < geometry.height; ++iy) {
    for (int ix = 0; ix < geometry.width; ++ix)
      out.set_cell(ix, iy, grid.state(box.x0 + ix, box.y0 + iy),
                   grid.value(box.x0 + ix, box.y0 + iy));
  }
  return out;
}

}  // namespace floorgrid
