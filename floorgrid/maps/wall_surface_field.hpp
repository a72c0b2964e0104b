#pragma once

#include <Eigen/Core>

#include "floorgrid/maps/distance_field.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// Distance to a raster's wall surfaces: the edges between its occupied cells and the cells
/// beside them, where a laser from the room meets a drawn wall, not the occupied cells' centres.
/// A wall stroke drawn several cells thick behind its surface then puts no bias into what is
/// matched to it: a point on the surface reads 0 and a point inside the stroke reads its depth.
///
/// Kept as a signed distance at cell centres (outside: distance to the nearest occupied centre
/// less half a cell; inside: minus the distance to the nearest cell that is not occupied, less
/// half a cell) and read by bilinear interpolation, so that it crosses zero on a straight edge
/// exactly, between the two cells' centres. With Line::centre it is the plain distance to the
/// nearest occupied cell's centre, interpolated the same way.
class WallSurfaceField {
 public:
  /// Where a wall drawn as occupied cells lies.
  enum class Line {
    surface,  ///< on the edges of its cells: a raster drawing's strokes, a gridmap
    centre,   ///< on its cells' centres: lines of a vector drawing rasterized along their axis
  };

  /// The walls of `grid`'s occupied cells; distances are capped at `max_distance` metres.
  WallSurfaceField(const OccupancyGrid& grid, double max_distance, Line line = Line::surface);

  /// Metres from `point` to the nearest wall surface (max_distance outside the grid or where no
  /// wall is near).
  double distance(const Eigen::Vector2d& point) const;
  /// Whether the grid had any occupied cell.
  bool has_walls() const { return has_walls_; }

 private:
  float signed_at(int ix, int iy) const;

  GridGeometry geometry_;
  DistanceField to_walls_;
  DistanceField to_rooms_;
  double max_distance_ = 0.0;
  Line line_ = Line::surface;
  bool has_walls_ = false;
};

}  // namespace floorgrid
