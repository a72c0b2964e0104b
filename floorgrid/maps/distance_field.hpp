#pragma once

#include <functional>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// Distance from every cell of a grid to the nearest cell of a chosen kind (Euclidean, exact;
/// OpenCV's distance transform), in metres, with lookups by point.
class DistanceField {
 public:
  /// An empty field.
  DistanceField() = default;
  /// Distances to the nearest cell where `is_target(state)` holds; cells beyond `max_distance`
  /// metres (and everything when there is no target) read max_distance.
  DistanceField(const OccupancyGrid& grid, const std::function<bool(CellState)>& is_target,
                double max_distance);

  /// The grid's geometry.
  const GridGeometry& geometry() const { return geometry_; }
  /// Distance at cell (ix, iy), metres; max_distance outside the grid.
  float at(int ix, int iy) const {
    return geometry_.contains(ix, iy)
               ? distances_[static_cast<std::size_t>(iy) * geometry_.width + ix]
               : max_distance_;
  }
  /// Distance at the cell holding `point`, metres (max_distance outside the grid).
  float at(const Eigen::Vector2d& point) const;
  /// The cap.
  float max_distance() const { return max_distance_; }
  /// All distances, row-major from the bottom row.
  const std::vector<float>& distances() const { return distances_; }

 private:
  GridGeometry geometry_;
  std::vector<float> distances_;
  float max_distance_ = 0.0f;
};

/// Distance to the nearest occupied cell.
DistanceField occupied_distance_field(const OccupancyGrid& grid, double max_distance);
/// Distance to the nearest observed (free or occupied) cell.
DistanceField observed_distance_field(const OccupancyGrid& grid, double max_distance);

}  // namespace floorgrid
