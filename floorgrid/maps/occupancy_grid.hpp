#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid {

/// The three classes of an occupancy cell.
enum class CellState : std::uint8_t { free = 0, unknown = 1, occupied = 2 };

/// ROS occupancy values (nav_msgs/OccupancyGrid): -1 unknown, 0 free .. 100 occupied.
inline constexpr std::int8_t kOccupancyUnknown = -1;
inline constexpr std::int8_t kOccupancyFree = 0;
inline constexpr std::int8_t kOccupancyOccupied = 100;

/// Where a grid lies in its frame. Cell (ix, iy) counts iy from the bottom row; the origin is the
/// outer corner of the lower-left cell and `origin.theta` (yaw) rotates the grid about it, so the
/// centre of cell (ix, iy) is origin + R(yaw) * resolution * (ix + 0.5, iy + 0.5).
struct GridGeometry {
  int width = 0;             ///< cells along x
  int height = 0;            ///< cells along y
  double resolution = 0.05;  ///< metres per cell
  Pose2 origin;              ///< outer corner of the lower-left cell (metres) and yaw (radians)

  /// Number of cells.
  std::size_t size() const { return static_cast<std::size_t>(width) * height; }
  /// Whether (ix, iy) is a cell of the grid.
  bool contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
  /// The centre of cell (ix, iy) in the frame, metres.
  Eigen::Vector2d cell_center(int ix, int iy) const;
  /// Continuous cell coordinates of a point: cell (ix, iy) covers [ix, ix+1) x [iy, iy+1).
  Eigen::Vector2d to_cell_coordinates(const Eigen::Vector2d& point) const;
  /// The point at continuous cell coordinates.
  Eigen::Vector2d from_cell_coordinates(const Eigen::Vector2d& cell_coordinates) const;
  /// The cell holding a point; false when the point lies outside the grid.
  bool cell_of(const Eigen::Vector2d& point, int& ix, int& iy) const;
  /// Axis-aligned bounds of the grid's four outer corners, metres.
  Eigen::AlignedBox2d bounds() const;
  /// Row of the image pixel that shows cell row `iy` (images count rows from the top).
  int image_row(int iy) const { return height - 1 - iy; }
};

/// Counts of cells per class.
struct CellCounts {
  std::size_t free = 0;      ///< cells classed free
  std::size_t occupied = 0;  ///< cells classed occupied
  std::size_t unknown = 0;   ///< cells classed unknown
};

/// A 2D occupancy grid: a class per cell, plus the ROS occupancy value it came from
/// (kept so that maps written back in `raw` or `scale` mode keep their values).
class OccupancyGrid {
 public:
  OccupancyGrid() = default;
  /// A grid of the given geometry with every cell set to `fill`.
  explicit OccupancyGrid(const GridGeometry& geometry, CellState fill = CellState::unknown);

  /// Where the grid lies.
  const GridGeometry& geometry() const { return geometry_; }
  int width() const { return geometry_.width; }               ///< cells along x
  int height() const { return geometry_.height; }             ///< cells along y
  double resolution() const { return geometry_.resolution; }  ///< metres per cell

  /// Linear index of cell (ix, iy), row-major from the bottom row.
  std::size_t index(int ix, int iy) const {
    return static_cast<std::size_t>(iy) * geometry_.width + ix;
  }
  /// Class of cell (ix, iy); the cell must exist.
  CellState state(int ix, int iy) const { return states_[index(ix, iy)]; }
  /// ROS occupancy value of cell (ix, iy): -1 or 0..100.
  std::int8_t value(int ix, int iy) const { return values_[index(ix, iy)]; }
  /// Sets a cell's class; its value becomes the canonical one (0, 100 or -1).
  void set_state(int ix, int iy, CellState state);
  /// Sets a cell's class and ROS value independently (scale and raw modes keep in-between values).
  void set_cell(int ix, int iy, CellState state, std::int8_t value);
  /// Whether cell (ix, iy) exists and is occupied.
  bool is_occupied(int ix, int iy) const {
    return geometry_.contains(ix, iy) && state(ix, iy) == CellState::occupied;
  }

  /// All classes, row-major from the bottom row.
  const std::vector<CellState>& states() const { return states_; }
  /// All ROS values, row-major from the bottom row.
  const std::vector<std::int8_t>& values() const { return values_; }
  /// Cells per class.
  CellCounts counts() const;

 private:
  GridGeometry geometry_;
  std::vector<CellState> states_;
  std::vector<std::int8_t> values_;
};

/// The canonical ROS value of a class: 0, 100 or -1.
std::int8_t canonical_value(CellState state);

}  // namespace floorgrid
