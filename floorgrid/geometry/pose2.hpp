#pragma once

#include <Eigen/Core>
#include <cmath>

namespace floorgrid {

/// Wraps an angle to (-pi, pi].
double normalize_angle(double angle);

/// A planar pose: position in metres and heading in radians, in some named frame.
struct Pose2 {
  double x = 0.0;      ///< metres
  double y = 0.0;      ///< metres
  double theta = 0.0;  ///< radians, counter-clockwise from the frame's x axis

  /// The position as a vector.
  Eigen::Vector2d translation() const { return {x, y}; }
  /// The 2x2 rotation of the heading.
  Eigen::Matrix2d rotation() const;
  /// The homogeneous 3x3 matrix T_frame_local.
  Eigen::Matrix3d matrix() const;

  /// Maps a point given in this pose's local frame into the pose's frame.
  Eigen::Vector2d transform(const Eigen::Vector2d& point_in_local) const;
  /// This pose composed with `other` (other is expressed relative to this pose).
  Pose2 compose(const Pose2& other) const;
  /// The inverse pose: maps the frame into this pose's local frame.
  Pose2 inverse() const;
  /// The pose `other` expressed relative to this one: inverse() * other.
  Pose2 between(const Pose2& other) const;
};

/// Rotation matrix of `angle` radians.
Eigen::Matrix2d rotation_2d(double angle);

}  // namespace floorgrid
