#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// How well a model's std_m describes its true errors over a domain.
struct Calibration {
  std::size_t points = 0;      ///< points with a finite error and a std_m
  double within_1sigma = 0.0;  ///< share of them with |error| <= std_m
  double within_2sigma = 0.0;  ///< share with |error| <= 2 std_m
  double median_std_m = 0.0;   ///< median std_m over them, metres
};

/// The model's std_m (PointMapping::error_std) at each of `points_in_plan` against the true
/// errors there (`errors`, as model_errors gives them); nullopt when the model states no
/// std_m or no point has a finite error.
std::optional<Calibration> calibration(const PointMapping& model,
                                       const Eigen::Matrix2Xd& points_in_plan,
                                       const std::vector<double>& errors);

}  // namespace floorgrid
