#pragma once

#include <Eigen/Core>
#include <Eigen/SVD>
#include <algorithm>

namespace floorgrid::test {

/// Central finite differences of a plane map `f` at `p` with step `h` metres.
template <typename Map>
Eigen::Matrix2d central_difference_jacobian(const Map& f, const Eigen::Vector2d& p,
                                            double h = 1e-5) {
  Eigen::Matrix2d J;
  for (int axis = 0; axis < 2; ++axis) {
    const Eigen::Vector2d dp = h * Eigen::Vector2d::Unit(axis);
    J.col(axis) = (f(Eigen::Vector2d(p + dp)) - f(Eigen::Vector2d(p - dp))) / (2.0 * h);
  }
  return J;
}

/// The largest principal strain of a Jacobian: how far its singular values are from 1.
inline double principal_strain(const Eigen::Matrix2d& J) {
  const Eigen::Vector2d sigma = Eigen::JacobiSVD<Eigen::Matrix2d>(J).singularValues();
  return std::max(std::abs(sigma(0) - 1.0), std::abs(1.0 - sigma(1)));
}

}  // namespace floorgrid::test
