#include "floorgrid/maps/visible_walls.hpp"

#include <cstdint>
#include <deque>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace floorgrid {

namespace {

/// Breadth-first fill over 4-neighbours from the cells marked in `seeds` through the cells
/// where `passable` holds.
template <typename Passable>
std::vector<std::uint8_t> flood(int w, int h, const std::vector<std::uint8_t>& seeds,
                                const Passable& passable) {
  std::vector<std::uint8_t> reached(seeds.size(), 0);
  std::deque<std::size_t> queue;
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    if (seeds[i] && passable(i)) {
      reached[i] = 1;
      queue.push_back(i);
    }
  }
  const auto visit = [&](std::size_t j) {
    if (!reached[j] && passable(j)) {
      reached[j] = 1;
      queue.push_back(j);
    }
  };
  while (!queue.empty()) {
    const std::size_t i = queue.front();
    queue.pop_front();
    const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    if (x > 0)
      visit(i - 1);
    if (x + 1 < w)
      visit(i + 1);
    if (y > 0)
      visit(i - w);
    if (y + 1 < h)
      visit(i + w);
  }
  return reached;
}

/// Euclidean distance (cells) of every cell to the nearest cell marked in `targets`.
cv::Mat distance_to(int w, int h, const std::vector<std::uint8_t>& targets) {
  cv::Mat source(h, w, CV_8UC1);
  for (int y = 0; y < h; ++y) {
    auto* row = source.ptr<std::uint8_t>(y);
    for (int x = 0; x < w; ++x)
      row[x] = targets[static_cast<std::size_t>(y) * w + x] ? 0 : 255;
  }
  cv::Mat distance;
  cv::distanceTransform(source, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  return distance;
}

}  // namespace

VisibleWalls visible_walls(const OccupancyGrid& plan, const VisibleWallsOptions& options) {
  VisibleWalls result;
  result.grid = plan;
  const int w = plan.width(), h = plan.height();
  if (w < 3 || h < 3)
    return result;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  const double resolution = plan.resolution();
  std::vector<std::uint8_t> wall(n, 0), free_cell(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    wall[i] = plan.states()[i] == CellState::occupied;
    free_cell[i] = plan.states()[i] == CellState::free;
    result.walls += wall[i];
  }
  if (result.walls == 0)
    return result;
  const cv::Mat to_wall = distance_to(w, h, wall);
  const auto wall_distance = [&](std::size_t i) {
    return static_cast<double>(
               to_wall.at<float>(static_cast<int>(i / w), static_cast<int>(i % w))) *
           resolution;
  };

  // The outside: flooded from the border through everything but the walls grown by
  // gap_closing (so that doors in the outline stay shut), then grown back along free space.
  std::vector<std::uint8_t> border(n, 0);
  for (int x = 0; x < w; ++x)
    border[x] = border[static_cast<std::size_t>(h - 1) * w + x] = 1;
  for (int y = 0; y < h; ++y)
    border[static_cast<std::size_t>(y) * w] = border[static_cast<std::size_t>(y) * w + w - 1] = 1;
  std::vector<std::uint8_t> outside = flood(w, h, border, [&](std::size_t i) {
    return !wall[i] && wall_distance(i) > options.gap_closing;
  });
  const cv::Mat to_outside = distance_to(w, h, outside);
  for (std::size_t i = 0; i < n; ++i) {
    const double d = static_cast<double>(
                         to_outside.at<float>(static_cast<int>(i / w), static_cast<int>(i % w))) *
                     resolution;
    if (!wall[i] && d <= options.gap_closing + resolution)
      outside[i] = 1;
  }
  // Rooms: free space inside, flooded from the cells where a robot fits.
  std::vector<std::uint8_t> roomy(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    roomy[i] = free_cell[i] && !outside[i] && wall_distance(i) >= options.min_clearance;
  const std::vector<std::uint8_t> room =
      flood(w, h, roomy, [&](std::size_t i) { return free_cell[i] && !outside[i]; });
  for (std::size_t i = 0; i < n; ++i)
    result.room_cells += room[i];
  result.room = room;
  if (result.room_cells == 0)
    return result;
  const cv::Mat to_room = distance_to(w, h, room);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      if (!wall[i])
        continue;
      const double d = static_cast<double>(to_room.at<float>(y, x)) * resolution;
      if (d > options.reach && d <= options.max_thickness) {
        result.grid.set_state(x, y, CellState::unknown);
        ++result.hidden;
      }
    }
  }
  result.applied = true;
  return result;
}

}  // namespace floorgrid
