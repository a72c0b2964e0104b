#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid {

/// A wall point a scan endpoint can be matched to: where it is and which way the wall faces.
struct WallPoint {
  Eigen::Vector2f point;  ///< map frame, metres
  /// Unit normal of the wall there, or zero where the wall has no clear direction (a corner,
  /// a post): such points are matched point to point.
  Eigen::Vector2f normal;
  /// Whether the wall faces one side only (the face of a wall drawn as two lines): `normal`
  /// then points to that side, and the wall can only be seen from there.
  bool one_sided = false;
};

/// The normal of the line the occupied cells near `centre` form (cell coordinates: cell (ix, iy)
/// spans [ix, ix + 1) x [iy, iy + 1)), in the grid's frame: the direction of least scatter of the
/// occupied cell centres within `radius` cells, when at least `min_cells` lie there and their
/// scatter across is at most `max_flatness` of that along (a line, not a corner or a blob);
/// zero otherwise.
Eigen::Vector2d occupied_line_normal(const OccupancyGrid& grid, const Eigen::Vector2d& centre,
                                     double radius, double max_flatness, int min_cells);

/// Settings of a WallField.
struct WallFieldOptions {
  /// Metres: cells farther than this from every wall have no nearest wall point (bounds the
  /// correspondences of a scan matcher; > 0).
  double max_distance = 1.0;
  /// Cells: a wall cell's normal comes from the occupied cells within this radius (>= 1).
  int normal_radius = 2;
  /// A wall cell gets a normal when the smaller eigenvalue of its neighbours' scatter is at
  /// most this share of the larger one (a line: ~0; a wall drawn as two lines one cell apart:
  /// ~0.3; a corner or blob: ~1), in (0, 1).
  double max_flatness = 0.5;
};

/// Throws InputError naming `wall_field.<field>` when an option is out of range.
void validate(const WallFieldOptions& options);

/// For every cell of an occupancy grid, the nearest occupied cell's centre (within
/// max_distance) and the local wall normal there: O(1) correspondences for scan matching.
/// Built once per map in O(cells) (OpenCV's labelled distance transform); immutable after
/// construction and safe to share between threads.
class WallField {
 public:
  /// An empty field (every lookup finds nothing).
  WallField() = default;
  /// The field of `grid`'s occupied cells. Throws InputError on bad options.
  /// With `rooms` (per cell of the grid, 1 in a room: VisibleWalls::room), a wall with free room
  /// space on one side only is one-sided, facing it.
  explicit WallField(const OccupancyGrid& grid, const WallFieldOptions& options = {},
                     const std::vector<std::uint8_t>* rooms = nullptr);
  /// The field of a vector plan's exact walls over the cells of `geometry`: each cell a wall
  /// passes through holds the wall's point nearest the cell centre and the wall's own normal
  /// (arcs as chords of at most a tenth of a cell's deviation), so a match is not limited by
  /// the cells' size. Throws InputError on bad options.
  /// With `visible` (a grid of the same geometry), only the walls passing through or next to
  /// one of its occupied cells count (see visible_walls).
  WallField(const VectorFloorplan& plan, const GridGeometry& geometry,
            const WallFieldOptions& options = {}, const OccupancyGrid* visible = nullptr,
            const std::vector<std::uint8_t>* rooms = nullptr);

  /// The nearest wall point to `point_in_map` (the one nearest the centre of the cell holding
  /// it), or null when the point is off the grid or farther than max_distance from every wall.
  const WallPoint* nearest(const Eigen::Vector2d& point_in_map) const {
    const Eigen::Vector2d c = geometry_.to_cell_coordinates(point_in_map);
    const int ix = static_cast<int>(std::floor(c.x()));
    const int iy = static_cast<int>(std::floor(c.y()));
    if (!geometry_.contains(ix, iy))
      return nullptr;
    const std::int32_t k = nearest_[static_cast<std::size_t>(iy) * geometry_.width + ix];
    return k < 0 ? nullptr : &walls_[static_cast<std::size_t>(k)];
  }
  /// Map metres from `point_in_map` to the nearest wall's surface: along the wall's normal where
  /// it has one (the distance to the wall's line), else to the wall point, less surface_offset()
  /// (0 inside it); +infinity when nearest() finds nothing.
  double distance(const Eigen::Vector2d& point_in_map) const;
  /// Map metres from a wall point to the surface a laser meets, on the side it looks from: 0
  /// where the wall lies on its cells' centres (a gridmap, whose hits lie anywhere in their
  /// cells; a vector plan's exact walls), half a cell where its cells' edges are its faces (a
  /// raster drawing's ink; WallSurfaceField::Line::surface).
  double surface_offset() const { return surface_offset_; }
  /// Sets surface_offset(), in [0, one cell]; throws InputError otherwise.
  void set_surface_offset(double metres);
  /// The residual of `point` against `wall` along its normal (point to line), measured from
  /// the surface on the side of `viewpoint` (the laser): positive in front of that surface.
  double surface_residual(const WallPoint& wall, const Eigen::Vector2d& point,
                          const Eigen::Vector2d& viewpoint) const {
    const Eigen::Vector2d w = wall.point.cast<double>();
    const Eigen::Vector2d n = wall.normal.cast<double>();
    const double r = n.dot(point - w);
    if (surface_offset_ == 0.0)
      return r;  // a gridmap's or a vector plan's walls: no side to tell
    return (viewpoint - w).dot(n) >= 0.0 ? r - surface_offset_ : r + surface_offset_;
  }
  /// Every wall point (one per occupied cell).
  const std::vector<WallPoint>& walls() const { return walls_; }
  /// The grid's geometry.
  const GridGeometry& geometry() const { return geometry_; }

 private:
  // Fills nearest_ from the cells holding a wall (wall_of_cell: index into walls_, or -1).
  void build_lookup(const std::vector<std::int32_t>& wall_of_cell, double max_distance);
  // Makes the walls with room space on one side only one-sided (see the constructors).
  void orient(const std::vector<std::uint8_t>& rooms);

  GridGeometry geometry_;
  std::vector<WallPoint> walls_;
  std::vector<std::int32_t> nearest_;  // per cell: index into walls_, or -1
  double surface_offset_ = 0.0;        // metres, see surface_offset()
};

}  // namespace floorgrid
