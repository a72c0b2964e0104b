#pragma once

#include <functional>
#include <optional>

#include "floorgrid/evaluation/domain.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// A ground truth: where a plan point truly lies on the grid.
using GroundTruth = std::function<Eigen::Vector2d(const Eigen::Vector2d&)>;

/// Errors |model(p) - truth(p)| over a domain's points, metres (thesis Table 6.1).
std::vector<double> model_errors(const PointMapping& model, const Eigen::Matrix2Xd& points_in_plan,
                                 const GroundTruth& truth);

/// Drift of points mapped there and back (thesis 6.5, Table 6.3), metres.
struct BackAndForth {
  std::size_t points = 0;          ///< points followed
  std::size_t not_invertible = 0;  ///< points lost on the way (inverse failed): not in the drift
  double min_m = 0.0;              ///< smallest drift after all rounds
  double mean_m = 0.0;             ///< mean drift
  double max_m = 0.0;              ///< largest drift
};

/// Maps each point plan -> grid -> plan `rounds` times and measures how far it ends from its
/// start. At most `max_points` points are followed (evenly spread through `points_in_plan`).
BackAndForth back_and_forth(const PointMapping& model, const Eigen::Matrix2Xd& points_in_plan,
                            int rounds = 100, std::size_t max_points = 500);

/// Error histogram with 0.05 m bins up to "1.0 m and more" (thesis Table 6.2): 21 counts.
std::vector<std::size_t> error_histogram(const std::vector<double>& errors, double bin = 0.05,
                                         int bins = 20);

}  // namespace floorgrid
