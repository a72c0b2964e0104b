#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace floorgrid::io {

/// DXF's arbitrary axis algorithm: the object coordinate system (OCS) of an entity with this
/// extrusion direction, as a rotation whose columns are the OCS x, y and z axes in world
/// coordinates. A zero extrusion gives the identity.
Eigen::Matrix3d ocs_axes(const Eigen::Vector3d& extrusion);

/// A circular arc, counter-clockwise from `start` to `end` (radians, end > start).
struct CircularArc2 {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< drawing units
  double radius = 0.0;                               ///< drawing units
  double start = 0.0;                                ///< radians
  double end = 0.0;                                  ///< radians, > start
};

/// The arc of a polyline segment from `p` to `q` with DXF bulge `bulge` (the tangent of a quarter
/// of the included angle; positive turns counter-clockwise). `p` and `q` must differ and the
/// bulge must be non-zero.
CircularArc2 bulge_arc(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double bulge);

/// Points along `center + u cos t + v sin t` for t from `t0` to `t1` (an affine image of a
/// circular arc: ellipses, and arcs under non-uniform scaling), ends included, no chord farther
/// than `tolerance` from the curve, and at least 8 chords per full turn.
std::vector<Eigen::Vector2d> ellipse_points(const Eigen::Vector2d& center, const Eigen::Vector2d& u,
                                            const Eigen::Vector2d& v, double t0, double t1,
                                            double tolerance);

/// A planar B-spline curve, possibly rational.
struct BSpline2 {
  int degree = 3;                        ///< >= 1
  std::vector<double> knots;             ///< non-decreasing, control.size() + degree + 1 of them
  std::vector<Eigen::Vector2d> control;  ///< control points
  std::vector<double> weights;           ///< one per control point, or empty (all 1)
};

/// Why the spline cannot be evaluated, or empty when it can.
std::string bspline_problem(const BSpline2& spline);
/// The spline's point at parameter `t` (de Boor's algorithm), `t` clamped to the domain
/// [knots[degree], knots[n]] with n control points.
Eigen::Vector2d bspline_point(const BSpline2& spline, double t);
/// Points along the spline over its domain, ends included, refined until every chord's midpoint
/// lies within `tolerance` of the curve's midpoint between them.
std::vector<Eigen::Vector2d> bspline_points(const BSpline2& spline, double tolerance);

}  // namespace floorgrid::io
