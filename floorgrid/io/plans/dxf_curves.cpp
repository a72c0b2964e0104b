#include "floorgrid/io/plans/dxf_curves.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace floorgrid::io {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::size_t kMaxPointsPerCurve = 100'000;  // bounds memory whatever the tolerance

double distance_to_chord(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double length_sq = d.squaredNorm();
  if (length_sq == 0.0) {
    return (p - a).norm();
  }
  const double t = std::clamp((p - a).dot(d) / length_sq, 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

/// Index k of the knot span [knots[k], knots[k+1]) holding t, within [degree, n - 1].
int find_span(const BSpline2& s, double t) {
  const int n = static_cast<int>(s.control.size());
  if (t >= s.knots[n]) {
    int k = n - 1;
    while (k > s.degree && s.knots[k] == s.knots[k + 1]) {
      --k;
    }
    return k;
  }
  const auto it = std::upper_bound(s.knots.begin() + s.degree, s.knots.begin() + n + 1, t);
  return std::clamp(static_cast<int>(it - s.knots.begin()) - 1, s.degree, n - 1);
}

void refine(const BSpline2& s, double t0, const Eigen::Vector2d& p0, double t1,
            const Eigen::Vector2d& p1, double tolerance, int depth,
            std::vector<Eigen::Vector2d>& out) {
  const double tm = 0.5 * (t0 + t1);
  const Eigen::Vector2d pm = bspline_point(s, tm);
  if (depth < 20 && out.size() < kMaxPointsPerCurve && distance_to_chord(pm, p0, p1) > tolerance) {
    refine(s, t0, p0, tm, pm, tolerance, depth + 1, out);
    refine(s, tm, pm, t1, p1, tolerance, depth + 1, out);
    return;
  }
  out.push_back(p1);
}

}  // namespace

Eigen::Matrix3d ocs_axes(const Eigen::Vector3d& extrusion) {
  const double norm = extrusion.norm();
  if (!(norm > 0.0) || !std::isfinite(norm)) {
    return Eigen::Matrix3d::Identity();
  }
  const Eigen::Vector3d z = extrusion / norm;
  // The arbitrary axis algorithm of the DXF reference: near the world z axis use world y.
  constexpr double kLimit = 1.0 / 64.0;
  const Eigen::Vector3d helper = (std::abs(z.x()) < kLimit && std::abs(z.y()) < kLimit)
                                     ? Eigen::Vector3d::UnitY()
                                     : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d x = helper.cross(z).normalized();
  const Eigen::Vector3d y = z.cross(x).normalized();
  Eigen::Matrix3d axes;
  axes << x, y, z;
  return axes;
}

CircularArc2 bulge_arc(const Eigen::Vector2d& p, const Eigen::Vector2d& q, double bulge) {
  const double included = 4.0 * std::atan(bulge);  // signed: > 0 counter-clockwise
  const Eigen::Vector2d chord = q - p;
  const double d = chord.norm();
  const Eigen::Vector2d left(-chord.y() / d, chord.x() / d);
  // The centre lies on the chord's bisector; tan(included / 2) carries the side and distance.
  const Eigen::Vector2d center = 0.5 * (p + q) + left * (0.5 * d / std::tan(0.5 * included));
  CircularArc2 arc;
  arc.center = center;
  arc.radius = std::abs(0.5 * d / std::sin(0.5 * included));
  const double angle_p = std::atan2(p.y() - center.y(), p.x() - center.x());
  const double angle_q = std::atan2(q.y() - center.y(), q.x() - center.x());
  // Counter-clockwise from p to q, or, for a clockwise bulge, from q to p.
  arc.start = bulge > 0.0 ? angle_p : angle_q;
  arc.end = bulge > 0.0 ? angle_q : angle_p;
  while (arc.end <= arc.start) {
    arc.end += kTwoPi;
  }
  return arc;
}

std::vector<Eigen::Vector2d> ellipse_points(const Eigen::Vector2d& center, const Eigen::Vector2d& u,
                                            const Eigen::Vector2d& v, double t0, double t1,
                                            double tolerance) {
  Eigen::Matrix2d axes;
  axes << u, v;
  const double largest = Eigen::JacobiSVD<Eigen::Matrix2d>(axes).singularValues()(0);
  const double sweep = std::abs(t1 - t0);
  // A chord spanning dt in parameter lies within largest * (1 - cos(dt / 2)) of the curve: the
  // circle's sagitta, stretched at most by the largest singular value.
  double step = std::numbers::pi / 4.0;
  if (largest > tolerance) {
    step = std::min(step, 2.0 * std::acos(1.0 - tolerance / largest));
  }
  const auto n = static_cast<std::size_t>(
      std::clamp(std::ceil(sweep / step), 1.0, static_cast<double>(kMaxPointsPerCurve)));
  std::vector<Eigen::Vector2d> points;
  points.reserve(n + 1);
  for (std::size_t i = 0; i <= n; ++i) {
    const double t = t0 + (t1 - t0) * static_cast<double>(i) / static_cast<double>(n);
    points.push_back(center + u * std::cos(t) + v * std::sin(t));
  }
  return points;
}

std::string bspline_problem(const BSpline2& s) {
  const std::size_t n = s.control.size();
  if (s.degree < 1) {
    return "degree " + std::to_string(s.degree) + " is below 1";
  }
  if (n < static_cast<std::size_t>(s.degree) + 1) {
    return std::to_string(n) + " control points are too few for degree " + std::to_string(s.degree);
  }
  if (s.knots.size() != n + s.degree + 1) {
    return std::to_string(s.knots.size()) + " knots, expected " + std::to_string(n + s.degree + 1);
  }
  if (!std::is_sorted(s.knots.begin(), s.knots.end())) {
    return "the knots decrease";
  }
  if (!(s.knots[n] > s.knots[s.degree])) {
    return "the knot domain is empty";
  }
  if (!s.weights.empty() && s.weights.size() != n) {
    return std::to_string(s.weights.size()) + " weights for " + std::to_string(n) +
           " control points";
  }
  if (std::any_of(s.weights.begin(), s.weights.end(), [](double w) { return !(w > 0.0); })) {
    return "a weight is not positive";
  }
  return {};
}

Eigen::Vector2d bspline_point(const BSpline2& s, double t) {
  const int p = s.degree;
  const int n = static_cast<int>(s.control.size());
  t = std::clamp(t, s.knots[p], s.knots[n]);
  const int k = find_span(s, t);
  // De Boor on homogeneous points (w x, w y, w): a rational spline is a projected plain one.
  std::vector<Eigen::Vector3d> d(static_cast<std::size_t>(p) + 1);
  for (int j = 0; j <= p; ++j) {
    const int i = k - p + j;
    const double w = s.weights.empty() ? 1.0 : s.weights[i];
    d[j] = Eigen::Vector3d(w * s.control[i].x(), w * s.control[i].y(), w);
  }
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      const int i = k - p + j;
      const double denominator = s.knots[i + p - r + 1] - s.knots[i];
      const double alpha = denominator > 0.0 ? (t - s.knots[i]) / denominator : 0.0;
      d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j];
    }
  }
  return d[p].head<2>() / d[p].z();
}

std::vector<Eigen::Vector2d> bspline_points(const BSpline2& s, double tolerance) {
  const int n = static_cast<int>(s.control.size());
  std::vector<Eigen::Vector2d> out;
  out.push_back(bspline_point(s, s.knots[s.degree]));
  // Four pieces per knot span before refining, so that an S-shaped span whose midpoint happens to
  // lie on the chord is not taken for straight.
  for (int k = s.degree; k < n; ++k) {
    const double a = s.knots[k], b = s.knots[k + 1];
    if (!(b > a)) {
      continue;
    }
    for (int piece = 0; piece < 4; ++piece) {
      const double t0 = a + (b - a) * piece / 4.0;
      const double t1 = piece == 3 ? b : a + (b - a) * (piece + 1) / 4.0;
      refine(s, t0, out.back(), t1, bspline_point(s, t1), tolerance, 0, out);
    }
  }
  return out;
}

}  // namespace floorgrid::io
