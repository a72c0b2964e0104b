#include "floorgrid/evaluation/calibration.hpp"

#include <cassert>
#include <cmath>

#include "floorgrid/core/statistics.hpp"

namespace floorgrid {

std::optional<Calibration> calibration(const PointMapping& model, const Eigen::Matrix2Xd& points,
                                       const std::vector<double>& errors) {
  assert(errors.size() == static_cast<std::size_t>(points.cols()));
  if (!model.error_model())
    return std::nullopt;
  Calibration c;
  std::vector<double> stds;
  std::size_t within1 = 0, within2 = 0;
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const double error = errors[static_cast<std::size_t>(i)];
    const std::optional<double> std_m = model.error_std(points.col(i));
    if (!std::isfinite(error) || !std_m)
      continue;
    stds.push_back(*std_m);
    within1 += error <= *std_m ? 1 : 0;
    within2 += error <= 2.0 * *std_m ? 1 : 0;
  }
  if (stds.empty())
    return std::nullopt;
  const auto n = static_cast<double>(stds.size());
  c.points = stds.size();
  c.within_1sigma = static_cast<double>(within1) / n;
  c.within_2sigma = static_cast<double>(within2) / n;
  c.median_std_m = upper_median(std::move(stds));
  return c;
}

}  // namespace floorgrid
