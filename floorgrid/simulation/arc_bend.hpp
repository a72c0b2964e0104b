#pragma once

#include <Eigen/Core>

namespace floorgrid {

/// The smooth bend of the simulated gridmap (SPEC "Synthetic datasets"): the building's long axis
/// is rolled onto a circular arc, as slow SLAM heading drift bends a long corridor.
///
/// The axis is the line through `axis_origin` with direction `axis_angle` (world frame). In axis
/// coordinates, u along the axis and v to its left, a point maps to
///   (u', v') = ((1/k - v) sin(k u), 1/k - (1/k - v) cos(k u))
/// for curvature k, bending towards +v for k > 0. Lines across the axis stay straight and keep
/// their length; lines along it become concentric arcs. So the near end (u = 0) is untouched,
/// the Jacobian is R(k u) diag(1 - k v, 1) (strain |k v|: stretch along the axis at offset v)
/// and the far end at u = L moves (1 - cos kL)/k ≈ k L²/2 sideways (and L - sin(kL)/k ≈ k² L³/6
/// back along the axis) from where the rigid transform of the near end puts it.
///
/// The map is one-to-one where 1 - k v > 0 and |k u| < pi; the inverse returns that branch.
/// k = 0 is exactly the identity.
struct ArcBend {
  Eigen::Vector2d axis_origin = Eigen::Vector2d::Zero();  ///< near end of the axis, world metres
  double axis_angle = 0.0;                                ///< axis direction, radians (world)
  double curvature = 0.0;                                 ///< k, 1/metres; > 0 bends towards +v
};

/// Maps a world point through the bend (the result is in the same world frame).
Eigen::Vector2d bend_point(const ArcBend& bend, const Eigen::Vector2d& point_in_world);

/// d bend_point / d point, analytic: B R(k u) diag(1 - k v, 1) Bᵀ with B = [axis, normal].
Eigen::Matrix2d bend_jacobian(const ArcBend& bend, const Eigen::Vector2d& point_in_world);

/// The exact analytic inverse of bend_point on its one-to-one branch (1 - k v > 0, |k u| < pi).
Eigen::Vector2d unbend_point(const ArcBend& bend, const Eigen::Vector2d& bent_point);

/// The far end's sideways deviation (1 - cos kL)/k of a bend with curvature k over `length` L
/// metres, in metres (signed like k).
double bend_deviation(double curvature, double length);

/// The curvature k (1/m) whose far end at `length` metres deviates sideways by `deviation`
/// metres: the exact inverse of bend_deviation, solved by safeguarded Newton iterations to
/// machine precision on the increasing branch 0 <= |k| L <= 2.3311 (where (1 - cos t)/t peaks
/// at 0.7246). InputError (field "bend.length" or "bend.deviation") for length <= 0 or
/// |deviation| > 0.7246 length.
double curvature_for_deviation(double deviation, double length);

/// The largest principal strain |k| half_width of a bend over a building extending `half_width`
/// metres to either side of its axis (dimensionless, 0.003 = 0.3%).
double max_strain(double curvature, double half_width);

}  // namespace floorgrid
