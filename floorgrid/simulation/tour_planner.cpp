#include "floorgrid/simulation/tour_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <queue>

#include "floorgrid/core/error.hpp"

namespace floorgrid {

namespace {

constexpr double kMinReachableArea = 4.0;  // square metres
constexpr double kVisitRadius = 1.5;       // metres: a place passed this close is visited

// The planning grid: where the robot's centre may be, and how far from obstacles it is.
struct Planning {
  GridGeometry geometry;  // yaw 0, rows from the bottom
  cv::Mat clearance;      // CV_32F, metres to the nearest obstacle
  cv::Mat free;           // CV_8U, clearance > the robot's
  cv::Mat region;         // CV_32S, region per cell, or -1
  int width() const { return geometry.width; }
  int height() const { return geometry.height; }
};

Planning planning_grid(const PlanWorld& w, const TourPlanOptions& o) {
  const GridGeometry& g = w.raster;
  const cv::Mat walkable(g.height, g.width, CV_8UC1, const_cast<std::uint8_t*>(w.walkable.data()));
  const cv::Mat regions(g.height, g.width, CV_32S, const_cast<std::int32_t*>(w.region_of.data()));
  // The clearance on the world's raster: from a pixel's centre to the nearest blocked pixel's
  // edge.
  const cv::Mat walkable_mask = walkable * 255;
  cv::Mat fine;
  cv::distanceTransform(walkable_mask, fine, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  fine = (fine - 0.5) * g.resolution;
  Planning p;
  const int k = std::max(1, static_cast<int>(std::lround(o.resolution / g.resolution)));
  p.geometry = g;
  p.geometry.width = std::max(1, g.width / k);
  p.geometry.height = std::max(1, g.height / k);
  p.geometry.resolution = g.resolution * k;
  // A planning cell has the least clearance of its pixels, and the region of its middle one.
  p.clearance = cv::Mat(p.height(), p.width(), CV_32F);
  p.region = cv::Mat(p.height(), p.width(), CV_32S);
  for (int y = 0; y < p.height(); ++y) {
    for (int x = 0; x < p.width(); ++x) {
      float least = std::numeric_limits<float>::infinity();
      for (int dy = 0; dy < k; ++dy) {
        const float* row = fine.ptr<float>(y * k + dy);
        for (int dx = 0; dx < k; ++dx)
          least = std::min(least, row[x * k + dx]);
      }
      p.clearance.at<float>(y, x) = least;
      p.region.at<int>(y, x) = regions.at<int>(y * k + k / 2, x * k + k / 2);
    }
  }
  cv::compare(p.clearance, o.clearance, p.free, cv::CMP_GT);
  return p;
}

// The cheapest paths from one cell (Dijkstra over 8 neighbours on free cells), stopping at
// the first cell `is_goal` accepts; the path there, or empty.
class PathSearch {
 public:
  explicit PathSearch(const Planning& p, const TourPlanOptions& o)
      : p_(p), o_(o), cost_(p.geometry.size(), kInf), parent_(p.geometry.size(), -1) {}

  template <class Goal>
  std::vector<int> to_nearest(int start, const Goal& is_goal) {
    std::fill(cost_.begin(), cost_.end(), kInf);
    using Entry = std::pair<float, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    cost_[static_cast<std::size_t>(start)] = 0.0f;
    parent_[static_cast<std::size_t>(start)] = -1;
    queue.emplace(0.0f, start);
    const int w = p_.width();
    const float h = static_cast<float>(p_.geometry.resolution);
    const std::uint8_t* free = p_.free.ptr<std::uint8_t>(0);
    const float* clearance = p_.clearance.ptr<float>(0);
    while (!queue.empty()) {
      const auto [c, i] = queue.top();
      queue.pop();
      if (c > cost_[static_cast<std::size_t>(i)])
        continue;
      if (i != start && is_goal(i))
        return path_to(i);
      const int x = i % w, y = i / w;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= p_.height())
            continue;
          const int j = ny * w + nx;
          if (!free[j])
            continue;
          const float near = std::max(0.0f, static_cast<float>(o_.wall_distance) - clearance[j]);
          const float step = h * ((dx != 0 && dy != 0) ? 1.41421356f : 1.0f) *
                             (1.0f + static_cast<float>(o_.wall_penalty) * near /
                                         static_cast<float>(o_.wall_distance));
          const float next = c + step;
          if (next < cost_[static_cast<std::size_t>(j)]) {
            cost_[static_cast<std::size_t>(j)] = next;
            parent_[static_cast<std::size_t>(j)] = i;
            queue.emplace(next, j);
          }
        }
      }
    }
    return {};
  }

 private:
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  std::vector<int> path_to(int goal) const {
    std::vector<int> path;
    for (int i = goal; i >= 0; i = parent_[static_cast<std::size_t>(i)])
      path.push_back(i);
    std::reverse(path.begin(), path.end());
    return path;
  }
  const Planning& p_;
  const TourPlanOptions& o_;
  std::vector<float> cost_;
  std::vector<int> parent_;
};

// Places to visit in each region: its point farthest from obstacles, then farthest-point
// samples at least `spacing` apart.
std::vector<std::vector<int>> choose_goals(const Planning& p, const cv::Mat& reached,
                                           std::size_t regions, double spacing) {
  std::vector<std::vector<int>> cells(regions);
  for (int y = 0; y < p.height(); ++y) {
    for (int x = 0; x < p.width(); ++x) {
      const int r = p.region.at<int>(y, x);
      if (r >= 0 && reached.at<std::uint8_t>(y, x))
        cells[static_cast<std::size_t>(r)].push_back(y * p.width() + x);
    }
  }
  std::vector<std::vector<int>> goals(regions);
  const int w = p.width();
  const double h = p.geometry.resolution;
  for (std::size_t r = 0; r < regions; ++r) {
    if (cells[r].empty())
      continue;
    int best = cells[r].front();
    for (const int i : cells[r]) {
      if (p.clearance.at<float>(i / w, i % w) > p.clearance.at<float>(best / w, best % w))
        best = i;
    }
    goals[r].push_back(best);
    std::vector<double> nearest(cells[r].size(), std::numeric_limits<double>::infinity());
    for (;;) {
      const int last = goals[r].back();
      std::size_t far = 0;
      for (std::size_t k = 0; k < cells[r].size(); ++k) {
        const int i = cells[r][k];
        const double d = std::hypot(i % w - last % w, i / w - last / w) * h;
        nearest[k] = std::min(nearest[k], d);
        if (nearest[k] > nearest[far])
          far = k;
      }
      if (nearest[far] < spacing)
        break;
      goals[r].push_back(cells[r][far]);
    }
  }
  return goals;
}

// Straight legs along the path that stay as far from obstacles as the path did (or 0.5 m).
std::vector<Eigen::Vector2d> straighten(const Planning& p, const std::vector<int>& path) {
  const int w = p.width();
  const auto point = [&](int i) { return p.geometry.cell_center(i % w, i / w); };
  const auto clear_at = [&](const Eigen::Vector2d& q) {
    int x = 0, y = 0;
    return p.geometry.cell_of(q, x, y) ? p.clearance.at<float>(y, x) : 0.0f;
  };
  const auto line_clear = [&](int from, int to, float needed) {
    const Eigen::Vector2d a = point(path[static_cast<std::size_t>(from)]);
    const Eigen::Vector2d b = point(path[static_cast<std::size_t>(to)]);
    const int steps = static_cast<int>((b - a).norm() / (p.geometry.resolution / 2)) + 1;
    for (int k = 0; k <= steps; ++k) {
      if (clear_at(a + (b - a) * (double(k) / steps)) < needed)
        return false;
    }
    return true;
  };
  std::vector<Eigen::Vector2d> legs{point(path.front())};
  std::size_t i = 0;
  while (i + 1 < path.size()) {
    float needed = std::min(0.5f, p.clearance.at<float>(path[i] / w, path[i] % w));
    std::size_t j = i + 1;
    for (std::size_t k = i + 1; k < path.size(); ++k) {
      needed = std::min(needed, p.clearance.at<float>(path[k] / w, path[k] % w));
      if (k % 4 != 0 && k + 1 != path.size())
        continue;
      if (!line_clear(static_cast<int>(i), static_cast<int>(k), needed - 0.02f))
        break;
      j = k;
    }
    legs.push_back(point(path[j]));
    i = j;
  }
  return legs;
}

}  // namespace

TourPlan plan_tour(const PlanWorld& world, const TourPlanOptions& o, Random& random) {
  const Planning p = planning_grid(world, o);
  const int w = p.width();
  const double h = p.geometry.resolution;
  // The robot starts in the largest region, at the cell farthest from obstacles there.
  int start_region = -1;
  for (std::size_t r = 0; r < world.regions.size(); ++r) {
    if (start_region < 0 ||
        world.regions[r].area > world.regions[static_cast<std::size_t>(start_region)].area)
      start_region = static_cast<int>(r);
  }
  int start = -1;
  for (int i = 0; i < w * p.height(); ++i) {
    if (!p.free.at<std::uint8_t>(i / w, i % w) || p.region.at<int>(i / w, i % w) != start_region)
      continue;
    if (start < 0 ||
        p.clearance.at<float>(i / w, i % w) > p.clearance.at<float>(start / w, start % w))
      start = i;
  }
  if (start < 0)
    throw InputError("the robot has no room to move: no region of the inside is wide enough", "", 0,
                     "plan");
  cv::Mat components;
  cv::connectedComponents(p.free, components, 8, CV_32S);
  const int home = components.at<int>(start / w, start % w);
  const cv::Mat reached = components == home;
  TourPlan plan;
  plan.reachable_area = cv::countNonZero(reached) * h * h;
  if (plan.reachable_area < kMinReachableArea)
    throw InputError("the robot can reach only " + std::to_string(plan.reachable_area) +
                         " square metres of the inside",
                     "", 0, "plan");
  // Places at least a few metres apart: in a building of one reachable room the robot still
  // drives around it.
  std::vector<std::vector<int>> goals;
  for (double spacing = o.goal_spacing;; spacing /= 2) {
    goals = choose_goals(p, reached, world.regions.size(), spacing);
    std::size_t count = 0;
    for (const auto& g : goals)
      count += g.size();
    if (count >= 3 || spacing < 1.0)
      break;
  }
  std::vector<int> reachable;
  for (std::size_t r = 0; r < goals.size(); ++r) {
    if (goals[r].empty())
      plan.unreachable.push_back(static_cast<int>(r));
    else
      reachable.push_back(static_cast<int>(r));
  }
  // A reachable room is left out when none is out of reach: a region never visited.
  if (plan.unreachable.empty() && reachable.size() > 1) {
    std::vector<int> rooms;
    for (const int r : reachable) {
      if (r != start_region && world.regions[static_cast<std::size_t>(r)].kind == "room")
        rooms.push_back(r);
    }
    if (!rooms.empty()) {
      const int skip = rooms[static_cast<std::size_t>(
          random.integer(0, static_cast<std::int64_t>(rooms.size()) - 1))];
      goals[static_cast<std::size_t>(skip)].clear();
      plan.skipped.push_back(skip);
    }
  }
  std::vector<int> goal_region(p.geometry.size(), -1);
  std::size_t left = 0;
  for (std::size_t r = 0; r < goals.size(); ++r) {
    for (const int g : goals[r]) {
      goal_region[static_cast<std::size_t>(g)] = static_cast<int>(r);
      ++left;
    }
  }
  std::vector<char> visited(world.regions.size(), 0);
  PathSearch search(p, o);
  const auto visit_near = [&](int cell) {
    // Every goal within kVisitRadius of the cell is visited.
    const int reach = static_cast<int>(kVisitRadius / h);
    const int x = cell % w, y = cell / w;
    for (int dy = -reach; dy <= reach; ++dy) {
      for (int dx = -reach; dx <= reach; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= w || ny >= p.height() || dx * dx + dy * dy > reach * reach)
          continue;
        int& r = goal_region[static_cast<std::size_t>(ny * w + nx)];
        if (r >= 0) {
          visited[static_cast<std::size_t>(r)] = 1;
          r = -1;
          --left;
        }
      }
    }
  };
  std::vector<int> route{start};
  visit_near(start);
  double length = 0.0;
  while (left > 0 && length < o.max_length) {
    const std::vector<int> leg = search.to_nearest(
        route.back(), [&](int i) { return goal_region[static_cast<std::size_t>(i)] >= 0; });
    if (leg.empty())
      break;
    for (std::size_t k = 1; k < leg.size(); ++k) {
      const int a = leg[k - 1], b = leg[k];
      length += std::hypot(a % w - b % w, a / w - b / w) * h;
      route.push_back(b);
      visit_near(b);
    }
  }
  for (std::size_t r = 0; r < visited.size(); ++r) {
    if (visited[r])
      plan.visited.push_back(static_cast<int>(r));
  }
  plan.waypoints = straighten(p, route);
  for (std::size_t k = 1; k < plan.waypoints.size(); ++k)
    plan.length += (plan.waypoints[k] - plan.waypoints[k - 1]).norm();
  return plan;
}

}  // namespace floorgrid
