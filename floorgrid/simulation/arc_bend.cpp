#include "floorgrid/simulation/arc_bend.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid {
namespace {

// (1 - cos t)/t peaks at t* with tan(t*/2) = t*; beyond t* a larger bend deviates less.
constexpr double kPeakAngle = 2.3311223704144224;
constexpr double kPeakRatio = 0.7246113537767085;

// sin(x)/x without the 0/0 at x = 0 (sin x / x itself loses no precision elsewhere).
double sinc(double x) {
  if (std::abs(x) < 1e-8)
    return 1.0 - x * x / 6.0;
  return std::sin(x) / x;
}

// (1 - cos t)/t = sin(t/2) sinc(t/2): the cancellation-free form, exact 0 at t = 0.
double versine_ratio(double t) {
  return std::sin(0.5 * t) * sinc(0.5 * t);
}

// d/dt (1 - cos t)/t = (sin t - (1 - cos t)/t)/t, by its series where that form cancels.
double versine_ratio_slope(double t) {
  if (std::abs(t) < 1e-3) {
    const double t2 = t * t;
    return 0.5 - t2 / 8.0 + t2 * t2 / 144.0;
  }
  return (std::sin(t) - versine_ratio(t)) / t;
}

struct AxisFrame {
  Eigen::Vector2d along;   // unit axis direction
  Eigen::Vector2d normal;  // unit normal, to the axis's left
};

AxisFrame axis_frame(const ArcBend& bend) {
  const Eigen::Vector2d along(std::cos(bend.axis_angle), std::sin(bend.axis_angle));
  return {along, Eigen::Vector2d(-along.y(), along.x())};
}

}  // namespace

Eigen::Vector2d bend_point(const ArcBend& bend, const Eigen::Vector2d& point_in_world) {
  const AxisFrame axis = axis_frame(bend);
  const Eigen::Vector2d d = point_in_world - bend.axis_origin;
  const double u = axis.along.dot(d);
  const double v = axis.normal.dot(d);
  const double k = bend.curvature;
  const double t = k * u;
  // (1/k - v) sin(k u) and 1/k - (1/k - v) cos(k u), rewritten without 1/k so that small and
  // zero curvatures are exact.
  const double u_bent = (1.0 - k * v) * u * sinc(t);
  const double v_bent = u * versine_ratio(t) + v * std::cos(t);
  return bend.axis_origin + u_bent * axis.along + v_bent * axis.normal;
}

Eigen::Matrix2d bend_jacobian(const ArcBend& bend, const Eigen::Vector2d& point_in_world) {
  const AxisFrame axis = axis_frame(bend);
  const Eigen::Vector2d d = point_in_world - bend.axis_origin;
  const double u = axis.along.dot(d);
  const double v = axis.normal.dot(d);
  const double k = bend.curvature;
  Eigen::Matrix2d basis;
  basis.col(0) = axis.along;
  basis.col(1) = axis.normal;
  const Eigen::Matrix2d stretch = Eigen::Vector2d(1.0 - k * v, 1.0).asDiagonal();
  return basis * rotation_2d(k * u) * stretch * basis.transpose();
}

Eigen::Vector2d unbend_point(const ArcBend& bend, const Eigen::Vector2d& bent_point) {
  const AxisFrame axis = axis_frame(bend);
  const Eigen::Vector2d d = bent_point - bend.axis_origin;
  const double u_bent = axis.along.dot(d);
  const double v_bent = axis.normal.dot(d);
  const double k = bend.curvature;
  // k (u', v') = (m sin(k u), 1 - m cos(k u)) with m = 1 - k v > 0: polar coordinates about the
  // arc's centre give m and k u.
  const double m = std::hypot(k * u_bent, 1.0 - k * v_bent);
  const double u = k == 0.0 ? u_bent : std::atan2(k * u_bent, 1.0 - k * v_bent) / k;
  // v = (1 - m)/k, with 1 - m = (1 - m²)/(1 + m) to avoid cancelling when k v is small.
  const double v = (2.0 * v_bent - k * (u_bent * u_bent + v_bent * v_bent)) / (1.0 + m);
  return bend.axis_origin + u * axis.along + v * axis.normal;
}

double bend_deviation(double curvature, double length) {
  return length * versine_ratio(curvature * length);
}

double curvature_for_deviation(double deviation, double length) {
  if (!(std::isfinite(length) && length > 0.0)) {
    throw InputError("must be a finite number > 0 " + got(length), {}, 0, "bend.length");
  }
  const double ratio = std::abs(deviation) / length;
  if (!(std::isfinite(deviation) && ratio <= kPeakRatio)) {
    throw InputError("must be finite and at most 0.7246 times the length " + got(deviation), {}, 0,
                     "bend.deviation");
  }
  // Solve (1 - cos t)/t = ratio for t = |k| L on [0, t*], where the left side increases:
  // Newton steps, falling back to bisection whenever a step leaves the bracket.
  double lo = 0.0;
  double hi = kPeakAngle;
  double t = std::min(2.0 * ratio, hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double residual = versine_ratio(t) - ratio;
    if (residual == 0.0)
      break;
    (residual < 0.0 ? lo : hi) = t;
    const double slope = versine_ratio_slope(t);
    double next = slope > 0.0 ? t - residual / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi))
      next = 0.5 * (lo + hi);
    const double step = std::abs(next - t);
    t = next;
    if (step <= 4.0 * std::numeric_limits<double>::epsilon() * t || hi - lo <= 0.0)
      break;
  }
  return std::copysign(t, deviation) / length;
}

double max_strain(double curvature, double half_width) {
  return std::abs(curvature) * std::abs(half_width);
}

}  // namespace floorgrid
