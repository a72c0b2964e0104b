#include "floorgrid/pipeline/map_registration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/maps/distance_field.hpp"
#include "floorgrid/maps/wall_surface_field.hpp"

namespace floorgrid {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The angle in [0, pi/2) at which the points' projections on the two turned axes are sharpest
// (the sum of the squared counts of `bin`-wide bins is largest), searched every quarter degree:
// walls along the turned axes put their points into few bins, walls a degree off spread them.
double projection_angle(const std::vector<Eigen::Vector2d>& points, double bin) {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points)
    centre += p;
  centre /= double(points.size());
  double reach = 0.0;
  for (const Eigen::Vector2d& p : points)
    reach = std::max(reach, (p - centre).norm());
  const auto bins = static_cast<std::size_t>(2.0 * reach / bin) + 2;
  std::vector<double> along(bins), across(bins);
  constexpr int kSteps = 360;
  double best_angle = 0.0, best_sharpness = -1.0;
  for (int k = 0; k < kSteps; ++k) {
    const double angle = k * (kPi / 2) / kSteps;
    const double c = std::cos(angle), s = std::sin(angle);
    std::fill(along.begin(), along.end(), 0.0);
    std::fill(across.begin(), across.end(), 0.0);
    for (const Eigen::Vector2d& p : points) {
      const Eigen::Vector2d q = p - centre;
      along[static_cast<std::size_t>((c * q.x() + s * q.y() + reach) / bin)] += 1.0;
      across[static_cast<std::size_t>((-s * q.x() + c * q.y() + reach) / bin)] += 1.0;
    }
    double sharpness = 0.0;
    for (std::size_t i = 0; i < bins; ++i)
      sharpness += along[i] * along[i] + across[i] * across[i];
    if (sharpness > best_sharpness) {
      best_sharpness = sharpness;
      best_angle = angle;
    }
  }
  return best_angle;
}

// The walls' dominant direction modulo 90 degrees (radians in [0, pi/2)) and how strongly it
// dominates. The strength is the peak's share over a uniform spread of the gradient directions
// of the occupied cells. The angle is where the walls' cells project sharpest: a line drawn one
// cell wide a few degrees off the grid's axes is a staircase whose edges all run along the axes,
// so its gradients point along the axes whatever the line's angle (a DXF plan drawn 8 degrees
// off was taken as axis-aligned, and its long corridor's registration failed). `walls` are the
// grid's wall points.
struct Direction {
  double angle = 0.0;
  double strength = 0.0;
};

Direction dominant_direction(const OccupancyGrid& grid, const std::vector<Eigen::Vector2d>& walls) {
  cv::Mat mask(grid.height(), grid.width(), CV_32FC1, cv::Scalar(0));
  for (int iy = 0; iy < grid.height(); ++iy) {
    auto* row = mask.ptr<float>(iy);
    for (int ix = 0; ix < grid.width(); ++ix)
      row[ix] = grid.state(ix, iy) == CellState::occupied ? 1.0f : 0.0f;
  }
  cv::GaussianBlur(mask, mask, {5, 5}, 1.0);
  cv::Mat gx, gy;
  cv::Sobel(mask, gx, CV_32F, 1, 0);
  cv::Sobel(mask, gy, CV_32F, 0, 1);
  constexpr int kBins = 90;
  std::vector<double> histogram(kBins, 0.0);
  double total = 0.0;
  for (int y = 0; y < mask.rows; ++y) {
    const float* rx = gx.ptr<float>(y);
    const float* ry = gy.ptr<float>(y);
    for (int x = 0; x < mask.cols; ++x) {
      const double magnitude = std::hypot(rx[x], ry[x]);
      if (magnitude < 1e-3)
        continue;
      double a = std::atan2(ry[x], rx[x]) + grid.geometry().origin.theta;
      a = std::fmod(std::fmod(a, kPi / 2) + kPi / 2, kPi / 2);
      histogram[static_cast<std::size_t>(a / (kPi / 2) * kBins) % kBins] += magnitude;
      total += magnitude;
    }
  }
  Direction best;
  if (total <= 0.0)
    return best;
  for (int b = 0; b < kBins; ++b) {
    double window = 0.0;  // +-2 degrees, circular
    for (int d = -2; d <= 2; ++d)
      window += histogram[static_cast<std::size_t>((b + d + kBins) % kBins)];
    best.strength = std::max(best.strength, window / total * kBins / 5.0);
  }
  best.angle = projection_angle(walls, grid.geometry().resolution);
  return best;
}

Eigen::Vector2d rotate(const Eigen::Vector2d& p, double angle) {
  return rotation_2d(angle) * p;
}

// A 1-D profile of point coordinates, `bin` wide, starting at `start`, `bins` long; each point
// adds one to its bin, then the counts are square-rooted (long walls should not drown the rest)
// and smoothed over a bin either side.
cv::Mat profile(const std::vector<double>& coordinates, double start, double bin, int bins) {
  cv::Mat counts(1, bins, CV_32FC1, cv::Scalar(0));
  auto* c = counts.ptr<float>(0);
  for (const double x : coordinates) {
    const auto i = static_cast<long>(std::floor((x - start) / bin));
    if (i >= 0 && i < bins)
      c[i] += 1.0f;
  }
  for (int i = 0; i < bins; ++i)
    c[i] = std::sqrt(c[i]);
  cv::Mat smooth;
  cv::GaussianBlur(counts, smooth, {5, 1}, 1.0, 0.0, cv::BORDER_CONSTANT);
  return smooth;
}

struct AxisMatch {
  double value = -1.0;  // normalized correlation
  double shift = 0.0;   // world metres: plan coordinate / scale = grid coordinate + shift
};

// The shift of one axis's grid coordinates that best matches the plan's coordinates divided by
// `scale`, by normalized cross-correlation of their profiles.
AxisMatch match_axis(double grid_min, int grid_bins, const cv::Mat& grid_profile,
                     const std::vector<double>& plan_scaled, double plan_min, double plan_max,
                     double bin) {
  const double start = plan_min - grid_bins * bin;
  const int bins = static_cast<int>(std::ceil((plan_max - start) / bin)) + grid_bins + 1;
  const cv::Mat plan_profile = profile(plan_scaled, start, bin, bins);
  cv::Mat result;
  cv::matchTemplate(plan_profile, grid_profile, result, cv::TM_CCOEFF_NORMED);
  double best = 0.0;
  cv::Point at;
  cv::minMaxLoc(result, nullptr, &best, nullptr, &at);
  return {best, start + at.x * bin - grid_min};
}

struct Candidate {
  MapSimilarity transform;
  double profile_score = 0.0;
};

// Pattern search over log scale, angle and translation, steps halving from coarse to fine.
ScoredSimilarity refine(const MapFitScorer& scorer, const MapSimilarity& start, double sigma,
                        const MapRegistrationOptions& options) {
  const Eigen::Vector2d& centre = scorer.centre();
  ScoredSimilarity best = scorer.score(start, sigma);
  double step_log = 0.03, step_angle = 2.0 * kDegree, step_t = 4.0 * sigma * start.scale;
  for (int round = 0; round < 12; ++round) {
    bool improved = true;
    for (int moves = 0; improved && moves < 40; ++moves) {
      improved = false;
      for (int axis = 0; axis < 4; ++axis) {
        for (const double sign : {-1.0, 1.0}) {
          MapSimilarity t = best.transform;
          if (axis == 0) {
            t.scale *= std::exp(sign * step_log);
            if (t.scale < options.min_scale || t.scale > options.max_scale)
              continue;
          }
          if (axis == 1)
            t.theta += sign * step_angle;
          if (axis == 2)
            t.translation.x() += sign * step_t * t.scale / start.scale;
          if (axis == 3)
            t.translation.y() += sign * step_t * t.scale / start.scale;
          // A turn or a scale about the gridmap walls' centre, not the frame's origin.
          if (axis <= 1)
            t.translation += best.transform.apply(centre) - t.apply(centre);
          const ScoredSimilarity s = scorer.score(t, sigma);
          if (s.score > best.score + 1e-9) {
            best = s;
            improved = true;
          }
        }
      }
    }
    step_log *= 0.5;
    step_angle *= 0.5;
    step_t *= 0.5;
  }
  return best;
}

// The turns searched: both maps turned to their dominant directions and four quarter turns
// when both have one, else 36 turns of 10 degrees.
struct Turns {
  double grid_angle = 0.0;
  double plan_angle = 0.0;
  std::vector<double> turns;
};

Turns search_turns(const Direction& grid_dir, const Direction& plan_dir) {
  const bool manhattan = grid_dir.strength > 2.0 && plan_dir.strength > 2.0;
  Turns t;
  t.grid_angle = manhattan ? grid_dir.angle : 0.0;
  t.plan_angle = manhattan ? plan_dir.angle : 0.0;
  const int count = manhattan ? 4 : 36;
  const double step = manhattan ? kPi / 2 : 10.0 * kDegree;
  for (int k = 0; k < count; ++k)
    t.turns.push_back(k * step);
  return t;
}

// Candidates from the wall profiles: for every turn and scale, the best shift along each axis.
std::vector<Candidate> profile_candidates(const std::vector<Eigen::Vector2d>& grid_all,
                                          const std::vector<Eigen::Vector2d>& plan_all,
                                          const Direction& grid_dir, const Direction& plan_dir,
                                          const MapRegistrationOptions& o) {
  const Turns search = search_turns(grid_dir, plan_dir);
  const double grid_angle = search.grid_angle;
  const double plan_angle = search.plan_angle;
  const double bin = o.profile_bin;

  std::vector<double> plan_x, plan_y;
  for (const Eigen::Vector2d& p : plan_all) {
    const Eigen::Vector2d a = rotate(p, -plan_angle);
    plan_x.push_back(a.x());
    plan_y.push_back(a.y());
  }
  const auto [px_min, px_max] = std::minmax_element(plan_x.begin(), plan_x.end());
  const auto [py_min, py_max] = std::minmax_element(plan_y.begin(), plan_y.end());

  std::vector<Candidate> all;
  const int scales =
      static_cast<int>(std::ceil(std::log(o.max_scale / o.min_scale) / o.scale_step)) + 1;
  for (const double turn : search.turns) {
    std::vector<double> gx, gy;
    for (const Eigen::Vector2d& g : grid_all) {
      const Eigen::Vector2d r = rotate(rotate(g, -grid_angle), turn);
      gx.push_back(r.x());
      gy.push_back(r.y());
    }
    const double gx_min = *std::min_element(gx.begin(), gx.end());
    const double gy_min = *std::min_element(gy.begin(), gy.end());
    const int gx_bins =
        static_cast<int>(std::ceil((*std::max_element(gx.begin(), gx.end()) - gx_min) / bin)) + 1;
    const int gy_bins =
        static_cast<int>(std::ceil((*std::max_element(gy.begin(), gy.end()) - gy_min) / bin)) + 1;
    const cv::Mat gx_profile = profile(gx, gx_min, bin, gx_bins);
    const cv::Mat gy_profile = profile(gy, gy_min, bin, gy_bins);
    for (int i = 0; i < scales; ++i) {
      const double s = o.min_scale * std::exp(i * o.scale_step);
      if (s > o.max_scale * (1 + 1e-9))
        break;
      std::vector<double> sx(plan_x.size()), sy(plan_y.size());
      for (std::size_t j = 0; j < plan_x.size(); ++j) {
        sx[j] = plan_x[j] / s;
        sy[j] = plan_y[j] / s;
      }
      const AxisMatch mx =
          match_axis(gx_min, gx_bins, gx_profile, sx, *px_min / s, *px_max / s, bin);
      const AxisMatch my =
          match_axis(gy_min, gy_bins, gy_profile, sy, *py_min / s, *py_max / s, bin);
      Candidate c;
      c.transform.scale = s;
      c.transform.theta = plan_angle + turn - grid_angle;
      c.transform.translation = rotate(Eigen::Vector2d(mx.shift, my.shift) * s, plan_angle);
      c.profile_score = mx.value + my.value;
      all.push_back(c);
    }
  }
  std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) {
    return a.profile_score > b.profile_score;
  });
  // The best few, no two of the same turn within 5% of scale.
  std::vector<Candidate> kept;
  for (const Candidate& c : all) {
    const bool near = std::any_of(kept.begin(), kept.end(), [&](const Candidate& k) {
      return std::abs(std::remainder(k.transform.theta - c.transform.theta, 2 * kPi)) < 0.1 &&
             std::abs(std::log(k.transform.scale / c.transform.scale)) < 0.05;
    });
    if (!near)
      kept.push_back(c);
    if (static_cast<int>(kept.size()) >= o.candidates)
      break;
  }
  return kept;
}

// Refined at closeness sigma, then sigma / 3 (which resolves the scale to a few parts in 10^4
// on a building's walls); scored at sigma, as the options' thresholds are.
ScoredSimilarity refine_fine(const MapFitScorer& scorer, const MapSimilarity& start, double sigma,
                             const MapRegistrationOptions& options) {
  const ScoredSimilarity medium = refine(scorer, start, sigma, options);
  return scorer.score(refine(scorer, medium.transform, sigma / 3.0, options).transform, sigma);
}

// Refined coarse to fine: closeness 4 sigma first, then refine_fine.
ScoredSimilarity refine_in_steps(const MapFitScorer& scorer, const MapSimilarity& start,
                                 const MapRegistrationOptions& options) {
  const double sigma = options.sigma;
  return refine_fine(scorer, refine(scorer, start, 4.0 * sigma, options).transform, sigma, options);
}

// Each start refined in steps, on 2 threads (the scorer is only read), in the starts' order.
std::vector<ScoredSimilarity> refine_each(const MapFitScorer& scorer,
                                          const std::vector<MapSimilarity>& starts,
                                          const MapRegistrationOptions& options) {
  std::vector<ScoredSimilarity> refined(starts.size());
  parallel_tasks(starts.size(), kDefaultThreads,
                 [&](std::size_t i) { refined[i] = refine_in_steps(scorer, starts[i], options); });
  return refined;
}

}  // namespace

void validate(const MapRegistrationOptions& o, const std::string& prefix) {
  const auto positive = [&](double value, const char* field) {
    require_option(value > 0.0 && std::isfinite(value), prefix + field, value, "> 0");
  };
  positive(o.min_scale, "min_scale");
  require_option(o.max_scale >= o.min_scale && std::isfinite(o.max_scale), prefix + "max_scale",
                 o.max_scale, ">= min_scale");
  positive(o.scale_step, "scale_step");
  positive(o.profile_bin, "profile_bin");
  positive(o.sigma, "sigma");
  require_option(o.candidates >= 1, prefix + "candidates", o.candidates, ">= 1");
  require_option(o.max_points >= 10, prefix + "max_points", o.max_points, ">= 10");
  require_option(std::isfinite(o.correlation_below), prefix + "correlation_below",
                 o.correlation_below, "a number");
  positive(o.correlation.cell, "correlation.cell");
  positive(o.correlation.closeness, "correlation.closeness");
  positive(o.correlation.scale_step, "correlation.scale_step");
  require_option(o.correlation.peaks >= 1, prefix + "correlation.peaks", o.correlation.peaks,
                 ">= 1");
  require_option(o.alternatives >= 1 && o.alternatives <= 100, prefix + "alternatives",
                 o.alternatives, "in 1..100");
}

MapRegistration register_maps(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                              PlanWalls plan_walls, const MapRegistrationOptions& options) {
  validate(options);
  const auto clock = std::chrono::steady_clock::now();
  MapFitScorer scorer(gridmap, plan, plan_walls, options.max_points,
                      options.free_violation_distance);
  MapRegistration result = register_maps(scorer, options);
  result.seconds = seconds_since(clock);
  return result;
}

MapRegistration register_maps(MapFitScorer& scorer, const MapRegistrationOptions& options) {
  validate(options);
  const auto clock = std::chrono::steady_clock::now();
  MapRegistration result;
  if (!scorer.usable())
    return result;
  const Eigen::Vector2d& centre = scorer.centre();

  const std::vector<Eigen::Vector2d> grid_all = evenly_thinned(scorer.grid_cells(), 40000);
  const std::vector<Eigen::Vector2d> plan_all = evenly_thinned(scorer.plan_cells(), 40000);
  const Direction grid_dir = dominant_direction(scorer.gridmap(), grid_all);
  const Direction plan_dir = dominant_direction(scorer.plan(), plan_all);
  std::vector<MapSimilarity> starts;
  for (const Candidate& c : profile_candidates(grid_all, plan_all, grid_dir, plan_dir, options))
    starts.push_back(c.transform);
  std::vector<ScoredSimilarity> refined = refine_each(scorer, starts, options);
  double best_score = -1.0;
  for (const ScoredSimilarity& r : refined)
    best_score = std::max(best_score, r.score);
  if (best_score < options.correlation_below) {
    result.correlation = true;
    const Turns turns = search_turns(grid_dir, plan_dir);
    const CorrelationInputs inputs{
        scorer.gridmap(),  grid_all,          plan_all,
        turns.grid_angle,  turns.plan_angle,  turns.turns,
        options.min_scale, options.max_scale, options.free_violation_distance};
    starts.clear();
    for (const CorrelationCandidate& c : correlation_candidates(inputs, options.correlation))
      starts.push_back(c.transform);
    const std::vector<ScoredSimilarity> more = refine_each(scorer, starts, options);
    refined.insert(refined.end(), more.begin(), more.end());
  }
  result.candidates = refined.size();
  std::sort(refined.begin(), refined.end(),
            [](const ScoredSimilarity& a, const ScoredSimilarity& b) { return a.score > b.score; });
  if (refined.empty())
    return result;
  result.found = true;
  result.best = refined.front();
  for (const ScoredSimilarity& s : refined) {
    if (result.alternatives.size() >= static_cast<std::size_t>(options.alternatives))
      break;
    if (distinct(s.transform, result.best.transform, centre) &&
        std::all_of(result.alternatives.begin(), result.alternatives.end(),
                    [&](const auto& a) { return distinct(s.transform, a.transform, centre); }))
      result.alternatives.push_back(s);
  }
  if (options.final_points > options.max_points) {
    // The thinned points' scale is off by up to 0.1% (sampling): the winner once more on
    // (almost) every wall point, the others scored on the same points.
    scorer.use_points(options.final_points);
    result.best = refine_fine(scorer, result.best.transform, options.sigma, options);
    for (ScoredSimilarity& a : result.alternatives)
      a = scorer.score(a.transform, options.sigma);
  }
  result.seconds = seconds_since(clock);
  return result;
}

ScoredSimilarity refine_map_similarity(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                                       PlanWalls plan_walls, const MapSimilarity& start,
                                       const MapRegistrationOptions& options) {
  const MapFitScorer scorer(gridmap, plan, plan_walls, options.max_points,
                            options.free_violation_distance);
  if (!scorer.usable())
    return {{-1.0, 0.0, 1.0}, start};
  return refine_in_steps(scorer, start, options);
}

}  // namespace floorgrid
