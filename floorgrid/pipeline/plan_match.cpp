#include "floorgrid/pipeline/plan_match.hpp"

#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"

namespace floorgrid {

PlanMatch judge_plan_match(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                           PlanWalls plan_walls, const ReferencePairs& pairs,
                           const MapRegistrationOptions& options) {
  PlanMatch match;
  if (pairs.size() < 3)
    return match;
  TransformEstimate fit;
  try {
    fit = estimate_transform(pairs.points_in_plan, pairs.points_in_grid,
                             {.kind = TransformKind::similarity, .reflection = Reflection::forbid});
  } catch (const InputError&) {
    return match;  // degenerate pairs (all on one point or line): nothing to judge by
  }
  // T_grid_plan = [s R | t]; the registration's similarity goes the other way.
  const Eigen::Matrix2d linear = fit.T_grid_plan.topLeftCorner<2, 2>();
  const double scale = std::sqrt(std::abs(linear.determinant()));
  if (!(scale > 0.0) || !std::isfinite(scale))
    return match;
  MapSimilarity start;
  start.scale = 1.0 / scale;
  start.theta = -std::atan2(linear(1, 0), linear(0, 0));
  start.translation =
      -(start.scale * (rotation_2d(start.theta) * fit.T_grid_plan.col(2).head<2>()));
  match.score = refine_map_similarity(gridmap, plan, plan_walls, start, options);
  match.judged = true;
  return match;
}

bool plan_match_accepted(const PlanMatch& match, double min_score, double max_in_free_space) {
  return !match.judged ||
         (match.score.score >= min_score && match.score.in_free_space <= max_in_free_space);
}

}  // namespace floorgrid
