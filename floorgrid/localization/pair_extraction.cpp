#include "floorgrid/localization/pair_extraction.hpp"

#include <cmath>
#include <vector>

namespace floorgrid {

PairRejections& PairRejections::operator+=(const PairRejections& o) {
  not_converged += o.not_converged;
  no_return += o.no_return;
  off_plan_wall += o.off_plan_wall;
  off_grid_wall += o.off_grid_wall;
  subsampled += o.subsampled;
  per_scan_cap += o.per_scan_cap;
  too_far += o.too_far;
  degenerate += o.degenerate;
  unmatched += o.unmatched;
  inconsistent += o.inconsistent;
  outlier_scan += o.outlier_scan;
  return *this;
}

std::map<std::string, std::size_t> PairRejections::by_reason() const {
  return {{"not_converged", not_converged},
          {"no_return", no_return},
          {"off_plan_wall", off_plan_wall},
          {"off_grid_wall", off_grid_wall},
          {"subsampled", subsampled},
          {"per_scan_cap", per_scan_cap},
          {"too_far", too_far},
          {"degenerate", degenerate},
          {"unmatched", unmatched},
          {"inconsistent", inconsistent},
          {"outlier_scan", outlier_scan}};
}

std::size_t PairRejections::total() const {
  return not_converged + no_return + off_plan_wall + off_grid_wall + subsampled + per_scan_cap +
         too_far + degenerate + unmatched + inconsistent + outlier_scan;
}

void reject_scan(const LaserScan& scan, PairRejections& rejections) {
  rejections.not_converged += scan.ranges.size();
}

void extract_scan_pairs(const LaserScan& scan, const Pose2& pose_in_plan, double plan_scale,
                        const Pose2& pose_in_grid, const WallField& plan_walls,
                        const WallField& grid_walls, const PairExtractionOptions& options,
                        PairCollector& pairs, PairRejections& rejections) {
  const Pose2 laser_in_robot = scan.robot_pose.between(scan.laser_pose);
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> valid;
  const int step = std::max(1, options.beam_step);
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (i % static_cast<std::size_t>(step) != 0) {
      ++rejections.subsampled;
      continue;
    }
    if (!scan.is_return(i)) {
      ++rejections.no_return;
      continue;
    }
    const double r = scan.ranges[i];
    if (r > options.max_range) {
      ++rejections.too_far;
      continue;
    }
    const double a = laser_in_robot.theta + scan.angle(i);
    const Eigen::Vector2d end_in_robot =
        laser_in_robot.translation() + r * Eigen::Vector2d(std::cos(a), std::sin(a));
    const Eigen::Vector2d in_plan = pose_in_plan.transform(end_in_robot / plan_scale);
    const Eigen::Vector2d in_grid = pose_in_grid.transform(end_in_robot);
    // Furniture and clutter are in the gridmap but not in the plan: keep only wall hits.
    if (plan_walls.distance(in_plan) * plan_scale > options.max_wall_distance) {
      ++rejections.off_plan_wall;
      continue;
    }
    if (grid_walls.distance(in_grid) > options.max_wall_distance) {
      ++rejections.off_grid_wall;
      continue;
    }
    valid.emplace_back(in_plan, in_grid);
  }
  const std::size_t cap = static_cast<std::size_t>(std::max(0, options.max_pairs_per_scan));
  const std::size_t keep = std::min(valid.size(), cap);
  rejections.per_scan_cap += valid.size() - keep;
  for (std::size_t k = 0; k < keep; ++k) {
    const auto& [p, g] = valid[k * valid.size() / keep];  // evenly spread over the scan
    pairs.plan.push_back(p);
    pairs.grid.push_back(g);
  }
}

ReferencePairs PairCollector::pairs() const {
  ReferencePairs out;
  const auto n = static_cast<Eigen::Index>(plan.size());
  out.points_in_plan.resize(2, n);
  out.points_in_grid.resize(2, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.points_in_plan.col(i) = plan[static_cast<std::size_t>(i)];
    out.points_in_grid.col(i) = grid[static_cast<std::size_t>(i)];
  }
  return out;
}

}  // namespace floorgrid
