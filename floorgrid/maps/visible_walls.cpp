#include "floorgrid/maps/visible_walls.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace floorgrid {

namespace {

/// Metres: walls grown by this for the enclosure's rays, so that they do not slip through the
/// gaps of a wall drawn dotted or dashed.
constexpr double kSolidWallGrowth = 0.15;

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

/// Of the cells marked in `candidates`, those that walls surround: from them, a ray in at least
/// options.enclosing_directions of 8 directions meets a wall (a cell of `wall`: the walls grown
/// so that a dotted stroke is solid) within options.enclosure_range. Judged on a lattice of
/// about 0.25 m and spread to the cells around each lattice point.
std::vector<std::uint8_t> enclosed(int w, int h, const std::vector<std::uint8_t>& wall,
                                   const std::vector<std::uint8_t>& candidates, double resolution,
                                   const VisibleWallsOptions& options) {
  std::vector<std::uint8_t> result(candidates.size(), 0);
  if (options.enclosing_directions > 8)
    return result;
  const int stride = std::max(1, static_cast<int>(std::lround(0.25 / resolution)));
  const int range = static_cast<int>(std::lround(options.enclosure_range / resolution));
  const auto is_wall = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && wall[static_cast<std::size_t>(y) * w + x];
  };
  // Whether the ray from (x, y) in direction (dx, dy) meets a wall; a diagonal step also looks
  // at the two cells it passes between (a staircase wall has no diagonal gaps).
  const auto meets_wall = [&](int x, int y, int dx, int dy) {
    const int steps = dx != 0 && dy != 0 ? static_cast<int>(range / std::numbers::sqrt2) : range;
    for (int s = 1; s <= steps; ++s) {
      const int px = x + s * dx, py = y + s * dy;
      if (px < 0 || py < 0 || px >= w || py >= h)
        return false;
      if (is_wall(px, py) || (dx != 0 && dy != 0 && (is_wall(px - dx, py) || is_wall(px, py - dy))))
        return true;
    }
    return false;
  };
  for (int y0 = 0; y0 < h; y0 += stride) {
    for (int x0 = 0; x0 < w; x0 += stride) {
      const int x = std::min(w - 1, x0 + stride / 2), y = std::min(h - 1, y0 + stride / 2);
      bool any = false;
      for (int yy = y0; yy < std::min(h, y0 + stride) && !any; ++yy) {
        for (int xx = x0; xx < std::min(w, x0 + stride) && !any; ++xx)
          any = candidates[static_cast<std::size_t>(yy) * w + xx] != 0;
      }
      if (!any)
        continue;
      int directions = 0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx)
          directions += (dx != 0 || dy != 0) && meets_wall(x, y, dx, dy);
      }
      if (directions < options.enclosing_directions)
        continue;
      for (int yy = y0; yy < std::min(h, y0 + stride); ++yy) {
        for (int xx = x0; xx < std::min(w, x0 + stride); ++xx)
          result[static_cast<std::size_t>(yy) * w + xx] =
              candidates[static_cast<std::size_t>(yy) * w + xx];
      }
    }
  }
  return result;
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
  // Where the flood got in through an opening the drawing left, walls still surround it.
  std::vector<std::uint8_t> solid(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    solid[i] = wall_distance(i) <= kSolidWallGrowth;
  const std::vector<std::uint8_t> inside = enclosed(w, h, solid, outside, resolution, options);
  for (std::size_t i = 0; i < n; ++i)
    outside[i] = outside[i] && !inside[i];
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
      if (static_cast<double>(to_room.at<float>(y, x)) * resolution > options.reach) {
        result.grid.set_state(x, y, CellState::unknown);
        ++result.hidden;
      }
    }
  }
  result.applied = true;
  return result;
}

}  // namespace floorgrid
