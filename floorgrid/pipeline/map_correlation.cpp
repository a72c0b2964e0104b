#include "floorgrid/pipeline/map_correlation.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/maps/distance_field.hpp"

namespace floorgrid {

namespace {

// Local maxima of one turn and scale's correlation kept before the free-space check.
constexpr int kPeaksPerImage = 4;

Eigen::AlignedBox2d bounds_of(const std::vector<Eigen::Vector2d>& points) {
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector2d& p : points)
    box.extend(p);
  return box;
}

// The gridmap turned: its wall cells as an image over their bounds, and its free cells (far
// from any wall) and observed cells as cell lists of that image.
struct TurnedGridmap {
  Eigen::AlignedBox2d bounds;
  cv::Mat walls;  // CV_32F, 1 on a wall cell
  double wall_cells = 0.0;
  std::vector<cv::Point> free, observed;
};

TurnedGridmap turn_gridmap(const CorrelationInputs& in, const DistanceField& grid_distance,
                           double turn, double cell) {
  const Eigen::Matrix2d R = rotation_2d(turn) * rotation_2d(-in.grid_angle);
  TurnedGridmap t;
  std::vector<Eigen::Vector2d> walls;
  walls.reserve(in.grid_walls.size());
  for (const Eigen::Vector2d& g : in.grid_walls)
    walls.push_back(R * g);
  t.bounds = bounds_of(walls);
  const int width = static_cast<int>(std::ceil(t.bounds.sizes().x() / cell)) + 1;
  const int height = static_cast<int>(std::ceil(t.bounds.sizes().y() / cell)) + 1;
  t.walls = cv::Mat(height, width, CV_32FC1, cv::Scalar(0));
  const auto cell_of = [&](const Eigen::Vector2d& r) {
    return cv::Point(static_cast<int>((r.x() - t.bounds.min().x()) / cell),
                     static_cast<int>((r.y() - t.bounds.min().y()) / cell));
  };
  for (const Eigen::Vector2d& r : walls) {
    const cv::Point c = cell_of(r);
    t.walls.at<float>(c.y, c.x) = 1.0f;
  }
  t.wall_cells = cv::sum(t.walls)[0];
  // Free and observed cells, sampled about twice per coarse cell, each coarse cell once.
  const OccupancyGrid& grid = in.gridmap;
  const int stride = std::max(1, static_cast<int>(cell / grid.geometry().resolution / 2.0));
  cv::Mat seen(height, width, CV_8UC1, cv::Scalar(0));
  for (int iy = 0; iy < grid.height(); iy += stride) {
    for (int ix = 0; ix < grid.width(); ix += stride) {
      const CellState state = grid.state(ix, iy);
      if (state == CellState::unknown)
        continue;
      const cv::Point c = cell_of(R * grid.geometry().cell_center(ix, iy));
      if (c.x < 0 || c.y < 0 || c.x >= width || c.y >= height)
        continue;
      const bool is_free =
          state == CellState::free && grid_distance.at(ix, iy) > in.free_violation_distance;
      std::uint8_t& s = seen.at<std::uint8_t>(c.y, c.x);
      if (!(s & 1)) {
        t.observed.push_back(c);
        s |= 1;
      }
      if (is_free && !(s & 2)) {
        t.free.push_back(c);
        s |= 2;
      }
    }
  }
  return t;
}

// The plan's walls turned by -plan_angle and divided by `scale`, as a wall image and a
// closeness image padded by half the gridmap's image on every side (the gridmap may stick out
// of the plan by half its size).
struct ScaledPlan {
  double x0 = 0, y0 = 0;  // world metres of cell (0, 0)
  cv::Mat walls;          // CV_8U, 1 on a wall cell
  cv::Mat closeness;      // CV_32F
};

ScaledPlan scale_plan(const std::vector<Eigen::Vector2d>& plan_turned,
                      const Eigen::AlignedBox2d& plan_bounds, double scale, int pad_x, int pad_y,
                      double cell, double closeness) {
  ScaledPlan p;
  p.x0 = plan_bounds.min().x() / scale - pad_x * cell;
  p.y0 = plan_bounds.min().y() / scale - pad_y * cell;
  const int width =
      static_cast<int>(std::ceil(plan_bounds.sizes().x() / scale / cell)) + 2 * pad_x + 1;
  const int height =
      static_cast<int>(std::ceil(plan_bounds.sizes().y() / scale / cell)) + 2 * pad_y + 1;
  p.walls = cv::Mat(height, width, CV_8UC1, cv::Scalar(0));
  cv::Mat not_wall(height, width, CV_8UC1, cv::Scalar(1));
  for (const Eigen::Vector2d& q : plan_turned) {
    const int x = static_cast<int>((q.x() / scale - p.x0) / cell);
    const int y = static_cast<int>((q.y() / scale - p.y0) / cell);
    if (x >= 0 && y >= 0 && x < width && y < height) {
      p.walls.at<std::uint8_t>(y, x) = 1;
      not_wall.at<std::uint8_t>(y, x) = 0;
    }
  }
  cv::Mat distance;
  cv::distanceTransform(not_wall, distance, cv::DIST_L2, 3);
  const double k = -0.5 * (cell * cell) / (closeness * closeness);
  cv::Mat squared;
  cv::multiply(distance, distance, squared, k);
  cv::exp(squared, p.closeness);
  return p;
}

// The share of the plan's wall cells over the gridmap's observed cells that fall on its free
// cells, with the gridmap's image at (u, v) of the plan's.
double free_share(const TurnedGridmap& g, const ScaledPlan& p, int u, int v) {
  const auto walls_at = [&](const std::vector<cv::Point>& cells) {
    std::size_t n = 0;
    for (const cv::Point& c : cells) {
      const int x = c.x + u, y = c.y + v;
      if (x >= 0 && y >= 0 && x < p.walls.cols && y < p.walls.rows)
        n += p.walls.at<std::uint8_t>(y, x);
    }
    return n;
  };
  const std::size_t observed = walls_at(g.observed);
  return observed ? double(walls_at(g.free)) / double(observed) : 0.0;
}

}  // namespace

std::vector<CorrelationCandidate> correlation_candidates(const CorrelationInputs& in,
                                                         const MapCorrelationOptions& o) {
  std::vector<CorrelationCandidate> all;
  if (in.grid_walls.size() < 10 || in.plan_walls.size() < 10 || in.turns.empty())
    return all;
  const double cell = o.cell;
  const DistanceField grid_distance =
      occupied_distance_field(in.gridmap, 2.0 * in.free_violation_distance);
  std::vector<Eigen::Vector2d> plan_turned;
  plan_turned.reserve(in.plan_walls.size());
  for (const Eigen::Vector2d& p : in.plan_walls)
    plan_turned.push_back(rotation_2d(-in.plan_angle) * p);
  const Eigen::AlignedBox2d plan_bounds = bounds_of(plan_turned);

  std::vector<TurnedGridmap> turned;
  for (const double turn : in.turns)
    turned.push_back(turn_gridmap(in, grid_distance, turn, cell));
  const int scales =
      static_cast<int>(std::ceil(std::log(in.max_scale / in.min_scale) / o.scale_step)) + 1;
  const int suppress = std::max(1, static_cast<int>(std::ceil(2.0 / cell)));
  int pad_x = 0, pad_y = 0;
  for (const TurnedGridmap& g : turned) {
    pad_x = std::max(pad_x, g.walls.cols / 2 + 1);
    pad_y = std::max(pad_y, g.walls.rows / 2 + 1);
  }
  // Each scale on its own thread (2), its candidates in its own list: joined in scale order,
  // the candidates are the same in the same order whatever the threads.
  std::vector<std::vector<CorrelationCandidate>> per_scale(static_cast<std::size_t>(scales));
  parallel_tasks(per_scale.size(), kDefaultThreads, [&](std::size_t i) {
    const double scale =
        std::min(in.max_scale, in.min_scale * std::exp(static_cast<double>(i) * o.scale_step));
    const ScaledPlan plan =
        scale_plan(plan_turned, plan_bounds, scale, pad_x, pad_y, cell, o.closeness);
    for (std::size_t k = 0; k < turned.size(); ++k) {
      const TurnedGridmap& g = turned[k];
      if (g.walls.cols > plan.closeness.cols || g.walls.rows > plan.closeness.rows ||
          g.wall_cells <= 0.0)
        continue;
      cv::Mat on;
      cv::matchTemplate(plan.closeness, g.walls, on, cv::TM_CCORR);
      on /= g.wall_cells;
      for (int peak = 0; peak < kPeaksPerImage; ++peak) {
        double best = 0.0;
        cv::Point at;
        cv::minMaxLoc(on, nullptr, &best, nullptr, &at);
        if (best <= 0.0)
          break;
        cv::rectangle(on, {at.x - suppress, at.y - suppress}, {at.x + suppress, at.y + suppress},
                      cv::Scalar(-1.0), cv::FILLED);
        CorrelationCandidate c;
        c.transform.scale = scale;
        c.transform.theta = in.plan_angle + in.turns[k] - in.grid_angle;
        // The gridmap's turned point r lies at plan-turned-scaled r + delta.
        const Eigen::Vector2d delta =
            Eigen::Vector2d(plan.x0 + at.x * cell, plan.y0 + at.y * cell) - g.bounds.min();
        c.transform.translation = scale * (rotation_2d(in.plan_angle) * delta);
        c.score = best - free_share(g, plan, at.x, at.y);
        per_scale[i].push_back(c);
      }
    }
  });
  for (const std::vector<CorrelationCandidate>& candidates : per_scale)
    all.insert(all.end(), candidates.begin(), candidates.end());
  std::sort(all.begin(), all.end(),
            [](const CorrelationCandidate& a, const CorrelationCandidate& b) {
              return a.score > b.score;
            });
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& g : in.grid_walls)
    centre += g;
  centre /= double(in.grid_walls.size());
  std::vector<CorrelationCandidate> kept;
  for (const CorrelationCandidate& c : all) {
    if (std::all_of(kept.begin(), kept.end(), [&](const CorrelationCandidate& k) {
          return distinct(c.transform, k.transform, centre);
        }))
      kept.push_back(c);
    if (static_cast<int>(kept.size()) >= o.peaks)
      break;
  }
  return kept;
}

}  // namespace floorgrid
