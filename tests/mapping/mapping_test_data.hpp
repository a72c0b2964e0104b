#pragma once

// Known-truth pair sets for the mapping contract tests.

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <numbers>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"

namespace floorgrid::test {

/// A known plan -> grid truth.
using Truth = std::function<Eigen::Vector2d(const Eigen::Vector2d&)>;

/// The test domain: a 40 x 20 m building.
inline constexpr double kWidth = 40.0, kHeight = 20.0;
/// Its extent (diagonal).
inline double domain_extent() {
  return std::hypot(kWidth, kHeight);
}

/// `n` uniform random plan points over the domain.
inline Eigen::Matrix2Xd random_points(int n, std::uint64_t seed) {
  Random r(seed);
  Eigen::Matrix2Xd p(2, n);
  for (int i = 0; i < n; ++i)
    p.col(i) << r.uniform(0.0, kWidth), r.uniform(0.0, kHeight);
  return p;
}

/// Pairs: plan points and their truth, plus isotropic normal noise of `sigma` metres per axis.
inline ReferencePairs make_pairs(const Eigen::Matrix2Xd& plan, const Truth& truth, double sigma,
                                 std::uint64_t seed) {
  Random r(seed);
  ReferencePairs pairs;
  pairs.points_in_plan = plan;
  pairs.points_in_grid.resize(2, plan.cols());
  for (Eigen::Index i = 0; i < plan.cols(); ++i) {
    pairs.points_in_grid.col(i) =
        truth(plan.col(i)) + Eigen::Vector2d(r.normal(sigma), r.normal(sigma));
  }
  return pairs;
}

/// A similarity: rotate by `angle`, scale, translate.
inline Truth similarity(double angle, double scale, const Eigen::Vector2d& t) {
  return [=](const Eigen::Vector2d& p) {
    Eigen::Matrix2d R;
    R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    return Eigen::Vector2d(scale * R * p + t);
  };
}

/// Two regions split at x = 20 with transforms differing by 1.5 degrees and 0.4 m.
inline Truth two_regions() {
  const Truth left = similarity(0.3, 1.02, {5.0, -3.0});
  const Truth right = similarity(0.3 + 1.5 * std::numbers::pi / 180.0, 1.02, {5.4, -3.3});
  return [=](const Eigen::Vector2d& p) { return p.x() < kWidth / 2 ? left(p) : right(p); };
}

/// A smooth bend: the long axis curves so its far end is 1 m off, after a similarity.
inline Truth bent() {
  const Truth base = similarity(-0.7, 0.98, {12.0, 4.0});
  return [=](const Eigen::Vector2d& p) {
    const double u = p.x() / kWidth;
    return base({p.x(), p.y() + 1.0 * u * u});
  };
}

}  // namespace floorgrid::test
