#include "floorgrid/maps/distance_field.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace floorgrid {

DistanceField::DistanceField(const OccupancyGrid& grid,
                             const std::function<bool(CellState)>& is_target, double max_distance)
    : geometry_(grid.geometry()), max_distance_(static_cast<float>(max_distance)) {
  const int w = geometry_.width, h = geometry_.height;
  distances_.assign(geometry_.size(), max_distance_);
  if (w == 0 || h == 0)
    return;
  // OpenCV measures the distance to the nearest zero pixel: targets are 0, the rest 255.
  cv::Mat source(h, w, CV_8UC1);
  bool any = false;
  for (int iy = 0; iy < h; ++iy) {
    auto* row = source.ptr<std::uint8_t>(iy);
    for (int ix = 0; ix < w; ++ix) {
      const bool target = is_target(grid.state(ix, iy));
      row[ix] = target ? 0 : 255;
      any = any || target;
    }
  }
  if (!any)
    return;
  cv::Mat distance;
  cv::distanceTransform(source, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  const auto resolution = static_cast<float>(geometry_.resolution);
  for (int iy = 0; iy < h; ++iy) {
    const float* row = distance.ptr<float>(iy);
    for (int ix = 0; ix < w; ++ix) {
      distances_[static_cast<std::size_t>(iy) * w + ix] =
          std::min(row[ix] * resolution, max_distance_);
    }
  }
}

float DistanceField::at(const Eigen::Vector2d& point) const {
  int ix = 0, iy = 0;
  if (!geometry_.cell_of(point, ix, iy))
    return max_distance_;
  return at(ix, iy);
}

DistanceField occupied_distance_field(const OccupancyGrid& grid, double max_distance) {
  return DistanceField(
      grid, [](CellState s) { return s == CellState::occupied; }, max_distance);
}

DistanceField observed_distance_field(const OccupancyGrid& grid, double max_distance) {
  return DistanceField(
      grid, [](CellState s) { return s != CellState::unknown; }, max_distance);
}

}  // namespace floorgrid
