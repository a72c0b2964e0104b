#include "floorgrid/evaluation/model_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace floorgrid {

std::vector<double> model_errors(const PointMapping& model, const Eigen::Matrix2Xd& points,
                                 const GroundTruth& truth) {
  const Eigen::Matrix2Xd mapped = model.forward_batch(points);
  std::vector<double> errors(static_cast<std::size_t>(points.cols()));
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    errors[static_cast<std::size_t>(i)] = (mapped.col(i) - truth(points.col(i))).norm();
  }
  return errors;
}

BackAndForth back_and_forth(const PointMapping& model, const Eigen::Matrix2Xd& points, int rounds,
                            std::size_t max_points) {
  BackAndForth result;
  const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(points.cols()), max_points);
  if (n == 0)
    return result;
  double sum = 0.0;
  result.min_m = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Index i =
        static_cast<Eigen::Index>(k * static_cast<std::size_t>(points.cols()) / n);
    const Eigen::Vector2d start = points.col(i);
    Eigen::Vector2d p = start;
    bool lost = false;
    for (int r = 0; r < rounds && !lost; ++r) {
      const InverseMapping back = model.inverse(model.forward(p));
      if (!back.invertible) {
        lost = true;
      } else {
        p = back.point;
      }
    }
    ++result.points;
    if (lost) {
      ++result.not_invertible;
      continue;
    }
    const double drift = (p - start).norm();
    result.min_m = std::min(result.min_m, drift);
    result.max_m = std::max(result.max_m, drift);
    sum += drift;
  }
  const std::size_t kept = result.points - result.not_invertible;
  result.mean_m = kept > 0 ? sum / static_cast<double>(kept) : 0.0;
  if (kept == 0)
    result.min_m = 0.0;
  return result;
}

std::vector<std::size_t> error_histogram(const std::vector<double>& errors, double bin, int bins) {
  std::vector<std::size_t> counts(static_cast<std::size_t>(bins) + 1, 0);
  for (const double e : errors) {
    const auto k = std::isfinite(e) ? static_cast<std::size_t>(std::max(0.0, std::floor(e / bin)))
                                    : static_cast<std::size_t>(bins);
    ++counts[std::min(k, static_cast<std::size_t>(bins))];
  }
  return counts;
}

}  // namespace floorgrid
