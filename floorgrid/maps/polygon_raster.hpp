#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// Cells of a grid marked in or out (a zone drawn on a gridmap), row-major from the bottom row
/// as OccupancyGrid::index().
struct CellMask {
  GridGeometry geometry;            ///< the grid the cells belong to
  std::vector<std::uint8_t> cells;  ///< 1 inside, 0 outside; geometry.size() entries

  /// An empty mask of `geometry`.
  explicit CellMask(const GridGeometry& geometry = {});
  /// Whether cell (ix, iy) is marked; the cell must exist.
  bool at(int ix, int iy) const {
    return cells[static_cast<std::size_t>(iy) * geometry.width + ix] != 0;
  }
  /// Marked cells.
  std::size_t count() const;
};

/// The cells whose centre lies inside the polygon made of `rings` (each a closed ring of points
/// in the grid's frame, metres, the closing point not repeated), by the even-odd rule: a centre
/// is inside when a ray from it crosses the rings an odd number of times, so holes need no
/// orientation. Scanline over cell-centre rows in cell coordinates (the grid's yaw applies).
/// Rings reaching outside the grid are clipped to it.
CellMask rasterize_rings(const std::vector<Eigen::Matrix2Xd>& rings, const GridGeometry& geometry);

/// Marks, for each column of `points` (grid frame, metres), every cell whose centre lies within
/// `radii(i)` metres of it (a disk per point; radii <= 0 mark nothing). Returns the cells newly
/// marked.
std::size_t stamp_disks(CellMask& mask, const Eigen::Matrix2Xd& points,
                        const Eigen::VectorXd& radii);

/// Intersection over union of two masks of one geometry (1 when both are empty).
double intersection_over_union(const CellMask& a, const CellMask& b);

}  // namespace floorgrid
