#pragma once

#include <functional>
#include <optional>
#include <string>

#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid {

/// Where a mapping is judged (SPEC "Evaluation"): plan wall sample points inside the ground
/// truth's domain.
struct EvaluationDomain {
  std::string kind;                 ///< "warp" or "manual_pairs_hull"
  Eigen::Matrix2Xd points_in_plan;  ///< 2 x N, metres
  double spacing = 0.05;            ///< metres between wall samples
  /// With a truth: the plan scale it gives over these points (truth_plan_scale), else none.
  std::optional<double> truth_plan_scale;
};

/// Wall samples every `spacing` metres whose true grid position has an observed (free or
/// occupied) gridmap cell within `radius` metres: the domain of a simulated dataset.
EvaluationDomain warp_domain(
    const VectorFloorplan& walls, const OccupancyGrid& gridmap,
    const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid,
    double spacing = 0.05, double radius = 0.5);

/// warp_domain over given wall samples (a raster plan's occupied cells) instead of a vector
/// plan's.
EvaluationDomain warp_domain(
    const Eigen::Matrix2Xd& wall_samples, const OccupancyGrid& gridmap,
    const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid,
    double spacing = 0.05, double radius = 0.5);

/// Wall samples every `spacing` metres inside the convex hull of the manual pairs' plan
/// points: the domain of a dataset with hand-picked pairs.
EvaluationDomain hull_domain(const VectorFloorplan& walls,
                             const Eigen::Matrix2Xd& pair_points_in_plan, double spacing = 0.05);
/// hull_domain over given wall samples.
EvaluationDomain hull_domain(const Eigen::Matrix2Xd& wall_samples,
                             const Eigen::Matrix2Xd& pair_points_in_plan, double spacing);

/// The plan scale the truth itself gives over `domain`: the scale of its least-squares
/// similarity plan -> grid at the domain's points. A bent map has no single scale; this is the
/// one over the walls where the mapping is judged (nothing for fewer than two points, or all at
/// one place).
std::optional<double> truth_plan_scale(
    const EvaluationDomain& domain,
    const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& plan_to_grid);

/// Mean, median and 95th percentile of errors (metres).
struct ErrorStatistics {
  std::size_t count = 0;  ///< errors summarized
  double mean = 0.0;      ///< metres
  double median = 0.0;    ///< metres
  double p95 = 0.0;       ///< metres
  double max = 0.0;       ///< metres
};

/// The statistics of `errors` (empty: all zero).
ErrorStatistics error_statistics(std::vector<double> errors);

}  // namespace floorgrid
