#include "floorgrid/geometry/pose2.hpp"

#include <numbers>

namespace floorgrid {

double normalize_angle(double angle) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  angle = std::fmod(angle, kTwoPi);
  if (angle <= -std::numbers::pi)
    angle += kTwoPi;
  if (angle > std::numbers::pi)
    angle -= kTwoPi;
  return angle;
}

Eigen::Matrix2d rotation_2d(double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

Eigen::Matrix2d Pose2::rotation() const {
  return rotation_2d(theta);
}

Eigen::Matrix3d Pose2::matrix() const {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  m.topLeftCorner<2, 2>() = rotation();
  m(0, 2) = x;
  m(1, 2) = y;
  return m;
}

Eigen::Vector2d Pose2::transform(const Eigen::Vector2d& point_in_local) const {
  return rotation() * point_in_local + translation();
}

Pose2 Pose2::compose(const Pose2& other) const {
  const Eigen::Vector2d p = transform(other.translation());
  return {p.x(), p.y(), normalize_angle(theta + other.theta)};
}

Pose2 Pose2::inverse() const {
  const Eigen::Vector2d p = -(rotation().transpose() * translation());
  return {p.x(), p.y(), normalize_angle(-theta)};
}

Pose2 Pose2::between(const Pose2& other) const {
  return inverse().compose(other);
}

}  // namespace floorgrid
