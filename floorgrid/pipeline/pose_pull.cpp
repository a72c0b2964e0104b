#include "floorgrid/pipeline/pose_pull.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "floorgrid/core/statistics.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"

namespace floorgrid {

namespace {

constexpr std::size_t kBlocks = 10;        // blocks of scans in time for the standard error
constexpr std::size_t kMinBlockScans = 5;  // a block with fewer scans is not counted
constexpr std::size_t kMinBlocks = 3;      // fewer counted blocks: no standard error

/// The linear part of the least-squares similarity taking the gridmap positions to the plan
/// positions (grid metres -> plan metres); differences between nearby scans go through it.
/// nullopt when the positions determine none (all at one place).
std::optional<Eigen::Matrix2d> grid_to_plan_linear(const std::vector<PullSample>& samples) {
  PairMoments moments;
  moments.origin_in_plan = samples.front().pose_in_plan.translation();
  moments.origin_in_grid = samples.front().pose_in_grid.translation();
  for (const PullSample& s : samples)
    moments.add(s.pose_in_plan.translation(), s.pose_in_grid.translation());
  const std::optional<TransformEstimate> fit = fit_transform(moments, {});
  if (!fit)
    return std::nullopt;
  return Eigen::Matrix2d(fit->T_grid_plan.topLeftCorner<2, 2>().inverse());
}

/// Each scan's comparisons with the later visits of its place: the plan poses' difference less
/// the gridmap poses' through the similarity is pull times the difference of the headings'
/// unit vectors; projected on that difference, one measure of the pull (world metres).
std::vector<std::vector<double>> compare_visits(const std::vector<PullSample>& samples,
                                                const Eigen::Matrix2d& A, double plan_scale,
                                                const PosePullOptions& options,
                                                std::size_t& comparisons) {
  const std::size_t n = samples.size();
  // |h_i - h_j|^2 = 2 - 2 cos(turn)
  const double min_heading_change = 2.0 - 2.0 * std::cos(options.min_turn);
  std::vector<std::size_t> by_x(n);
  std::iota(by_x.begin(), by_x.end(), 0);
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
    return samples[a].pose_in_grid.x < samples[b].pose_in_grid.x;
  });
  std::vector<std::vector<double>> per_scan(n);
  comparisons = 0;
  for (std::size_t a = 0; a < n; ++a) {
    const PullSample& si = samples[by_x[a]];
    const Eigen::Vector2d hi(std::cos(si.pose_in_plan.theta), std::sin(si.pose_in_plan.theta));
    for (std::size_t b = a + 1; b < n; ++b) {
      const PullSample& sj = samples[by_x[b]];
      if (sj.pose_in_grid.x - si.pose_in_grid.x >= options.radius)
        break;
      const Eigen::Vector2d grid_step =
          si.pose_in_grid.translation() - sj.pose_in_grid.translation();
      if (grid_step.squaredNorm() >= options.radius * options.radius ||
          std::abs(si.time - sj.time) < options.min_time_apart)
        continue;
      const Eigen::Vector2d dh =
          hi - Eigen::Vector2d(std::cos(sj.pose_in_plan.theta), std::sin(sj.pose_in_plan.theta));
      if (dh.squaredNorm() < min_heading_change)
        continue;
      const Eigen::Vector2d d =
          si.pose_in_plan.translation() - sj.pose_in_plan.translation() - A * grid_step;
      const double pull = d.dot(dh) / dh.squaredNorm() * plan_scale;
      per_scan[by_x[a]].push_back(pull);
      per_scan[by_x[b]].push_back(pull);
      ++comparisons;
    }
  }
  return per_scan;
}

/// The standard error of the median of `values` (in time order) from the spread of the
/// medians of kBlocks consecutive blocks: neighbouring scans share their filters' errors, so
/// the scans are not independent measures. Infinite with too few blocks.
double block_standard_error(const std::vector<double>& values) {
  std::vector<double> medians;
  const std::size_t n = values.size();
  for (std::size_t k = 0; k < kBlocks; ++k) {
    const std::size_t first = n * k / kBlocks, last = n * (k + 1) / kBlocks;
    if (last - first >= kMinBlockScans)
      medians.push_back(
          median(std::vector<double>(values.begin() + static_cast<std::ptrdiff_t>(first),
                                     values.begin() + static_cast<std::ptrdiff_t>(last))));
  }
  if (medians.size() < kMinBlocks)
    return std::numeric_limits<double>::infinity();
  const double mean =
      std::accumulate(medians.begin(), medians.end(), 0.0) / static_cast<double>(medians.size());
  double sum = 0.0;
  for (const double m : medians)
    sum += (m - mean) * (m - mean);
  const double count = static_cast<double>(medians.size());
  return std::sqrt(sum / (count - 1.0) / count);
}

}  // namespace

std::optional<PosePull> measure_pose_pull(const std::vector<PullSample>& samples, double plan_scale,
                                          const PosePullOptions& options) {
  if (samples.size() < 2)
    return std::nullopt;
  const std::optional<Eigen::Matrix2d> A = grid_to_plan_linear(samples);
  if (!A)
    return std::nullopt;
  PosePull pull;
  const std::vector<std::vector<double>> per_scan =
      compare_visits(samples, *A, plan_scale, options, pull.comparisons);
  std::vector<double> values;  // one per scan, in time order
  for (const std::vector<double>& v : per_scan) {
    if (!v.empty())
      values.push_back(median(v));
  }
  if (values.empty())
    return std::nullopt;
  pull.scans = values.size();
  pull.along_m = median(values);
  pull.std_m = block_standard_error(values);
  pull.applied = options.enabled && pull.scans >= options.min_scans &&
                 pull.std_m <= options.max_std && std::abs(pull.along_m) <= options.max_pull;
  return pull;
}

Pose2 without_pull(const Pose2& pose_in_plan, double pull_m, double plan_scale) {
  const double back = pull_m / plan_scale;
  return {pose_in_plan.x - back * std::cos(pose_in_plan.theta),
          pose_in_plan.y - back * std::sin(pose_in_plan.theta), pose_in_plan.theta};
}

}  // namespace floorgrid
