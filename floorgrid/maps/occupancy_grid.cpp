#include "floorgrid/maps/occupancy_grid.hpp"

#include <cmath>

namespace floorgrid {

Eigen::Vector2d GridGeometry::cell_center(int ix, int iy) const {
  return from_cell_coordinates({ix + 0.5, iy + 0.5});
}

Eigen::Vector2d GridGeometry::from_cell_coordinates(const Eigen::Vector2d& cell_coordinates) const {
  return origin.transform(resolution * cell_coordinates);
}

Eigen::Vector2d GridGeometry::to_cell_coordinates(const Eigen::Vector2d& point) const {
  return origin.rotation().transpose() * (point - origin.translation()) / resolution;
}

bool GridGeometry::cell_of(const Eigen::Vector2d& point, int& ix, int& iy) const {
  const Eigen::Vector2d c = to_cell_coordinates(point);
  if (!(c.x() >= 0.0 && c.y() >= 0.0 && c.x() < width && c.y() < height))
    return false;
  ix = static_cast<int>(c.x());
  iy = static_cast<int>(c.y());
  return true;
}

Eigen::AlignedBox2d GridGeometry::bounds() const {
  Eigen::AlignedBox2d box;
  for (const auto& corner : {Eigen::Vector2d(0, 0), Eigen::Vector2d(width, 0),
                             Eigen::Vector2d(0, height), Eigen::Vector2d(width, height)}) {
    box.extend(from_cell_coordinates(corner));
  }
  return box;
}

std::int8_t canonical_value(CellState state) {
  switch (state) {
    case CellState::free:
      return kOccupancyFree;
    case CellState::occupied:
      return kOccupancyOccupied;
    case CellState::unknown:
      break;
  }
  return kOccupancyUnknown;
}

OccupancyGrid::OccupancyGrid(const GridGeometry& geometry, CellState fill)
    : geometry_(geometry),
      states_(geometry.size(), fill),
      values_(geometry.size(), canonical_value(fill)) {}

void OccupancyGrid::set_state(int ix, int iy, CellState state) {
  set_cell(ix, iy, state, canonical_value(state));
}

void OccupancyGrid::set_cell(int ix, int iy, CellState state, std::int8_t value) {
  const std::size_t i = index(ix, iy);
  states_[i] = state;
  values_[i] = value;
}

CellCounts OccupancyGrid::counts() const {
  CellCounts counts;
  for (CellState s : states_) {
    switch (s) {
      case CellState::free:
        ++counts.free;
        break;
      case CellState::occupied:
        ++counts.occupied;
        break;
      case CellState::unknown:
        ++counts.unknown;
        break;
    }
  }
  return counts;
}

}  // namespace floorgrid
