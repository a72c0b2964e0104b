#include "floorgrid/maps/wall_surface_field.hpp"

#include <algorithm>
#include <cmath>

namespace floorgrid {

WallSurfaceField::WallSurfaceField(const OccupancyGrid& grid, double max_distance, Line line)
    : geometry_(grid.geometry()),
      to_walls_(occupied_distance_field(grid, max_distance)),
      to_rooms_(line == Line::surface
                    ? DistanceField(
                          grid, [](CellState s) { return s != CellState::occupied; }, max_distance)
                    : DistanceField()),
      max_distance_(max_distance),
      line_(line) {
  has_walls_ = std::any_of(grid.states().begin(), grid.states().end(),
                           [](CellState s) { return s == CellState::occupied; });
}

float WallSurfaceField::signed_at(int ix, int iy) const {
  const int cx = std::clamp(ix, 0, geometry_.width - 1);
  const int cy = std::clamp(iy, 0, geometry_.height - 1);
  const float outside = to_walls_.at(cx, cy);
  if (line_ == Line::centre || outside >= to_walls_.max_distance())
    return outside;
  const auto half = static_cast<float>(0.5 * geometry_.resolution);
  if (outside > 0.0f)
    return outside - half;
  return -(to_rooms_.at(cx, cy) - half);
}

double WallSurfaceField::distance(const Eigen::Vector2d& point) const {
  if (!has_walls_)
    return max_distance_;
  const Eigen::Vector2d c = geometry_.to_cell_coordinates(point);
  if (!(c.x() >= 0.0 && c.y() >= 0.0 && c.x() < geometry_.width && c.y() < geometry_.height))
    return max_distance_;
  // Bilinear between the four cell centres around the point.
  const double fx = c.x() - 0.5, fy = c.y() - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  const double ax = fx - x0, ay = fy - y0;
  const double value = (1 - ax) * (1 - ay) * signed_at(x0, y0) +
                       ax * (1 - ay) * signed_at(x0 + 1, y0) +
                       (1 - ax) * ay * signed_at(x0, y0 + 1) + ax * ay * signed_at(x0 + 1, y0 + 1);
  return std::min(std::abs(value), max_distance_);
}

}  // namespace floorgrid
