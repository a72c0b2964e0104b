#include "floorgrid/evaluation/domain.hpp"

#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/geometry/convex_hull.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"
#include "floorgrid/maps/distance_field.hpp"

namespace floorgrid {

namespace {
Eigen::Matrix2Xd keep(const Eigen::Matrix2Xd& points, const std::vector<Eigen::Index>& indices) {
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(indices.size()));
  for (std::size_t k = 0; k < indices.size(); ++k)
    out.col(static_cast<Eigen::Index>(k)) = points.col(indices[k]);
  return out;
}
}  // namespace

EvaluationDomain warp_domain(
    const VectorFloorplan& walls, const OccupancyGrid& gridmap,
    const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid, double spacing,
    double radius) {
  return warp_domain(walls.sample_points(spacing), gridmap, plan_to_grid, spacing, radius);
}

EvaluationDomain warp_domain(
    const Eigen::Matrix2Xd& samples, const OccupancyGrid& gridmap,
    const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid, double spacing,
    double radius) {
  const DistanceField observed = observed_distance_field(gridmap, 2.0 * radius + 1.0);
  std::vector<Eigen::Index> inside;
  for (Eigen::Index i = 0; i < samples.cols(); ++i) {
    if (observed.at(plan_to_grid(samples.col(i))) <= radius)
      inside.push_back(i);
  }
  return {"warp", keep(samples, inside), spacing, std::nullopt};
}

EvaluationDomain hull_domain(const VectorFloorplan& walls, const Eigen::Matrix2Xd& pair_points,
                             double spacing) {
  return hull_domain(walls.sample_points(spacing), pair_points, spacing);
}

EvaluationDomain hull_domain(const Eigen::Matrix2Xd& samples, const Eigen::Matrix2Xd& pair_points,
                             double spacing) {
  const auto hull = convex_hull(pair_points);
  std::vector<Eigen::Index> inside;
  for (Eigen::Index i = 0; i < samples.cols(); ++i) {
    if (inside_convex_polygon(hull, samples.col(i)))
      inside.push_back(i);
  }
  return {"manual_pairs_hull", keep(samples, inside), spacing, std::nullopt};
}

std::optional<double> truth_plan_scale(
    const EvaluationDomain& domain,
    const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid) {
  if (domain.points_in_plan.cols() < 2)
    return std::nullopt;
  Eigen::Matrix2Xd in_grid(2, domain.points_in_plan.cols());
  for (Eigen::Index i = 0; i < in_grid.cols(); ++i)
    in_grid.col(i) = plan_to_grid(domain.points_in_plan.col(i));
  try {
    return estimate_transform(domain.points_in_plan, in_grid).scale;
  } catch (const InputError&) {
    return std::nullopt;  // all at one place: no similarity
  }
}

ErrorStatistics error_statistics(std::vector<double> errors) {
  ErrorStatistics s;
  s.count = errors.size();
  if (errors.empty())
    return s;
  std::sort(errors.begin(), errors.end());  // the sum in ascending order: the smallest first
  double sum = 0.0;
  for (const double e : errors)
    sum += e;
  s.mean = sum / static_cast<double>(errors.size());
  s.median = quantile(errors, 0.5);
  s.p95 = quantile(errors, 0.95);
  s.max = errors.back();
  return s;
}

}  // namespace floorgrid
