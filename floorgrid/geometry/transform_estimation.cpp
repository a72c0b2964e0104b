#include "floorgrid/geometry/transform_estimation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "floorgrid/core/error.hpp"

namespace floorgrid {
namespace {

// Relative tolerances of the degeneracy tests. Coordinates carry rounding of about 1e-16 of
// their magnitude, so anything within 1e-9 of it is one point, and a point cloud whose minor
// axis is below 1e-6 of its major axis is a line.
constexpr double kDistinctRelative = 1e-9;
constexpr double kCollinearVarianceRatio = 1e-12;
constexpr double kRotationRelative = 1e-12;
constexpr double kMirrorDeterminantRelative = 1e-12;

// The moments about the weighted centroids (eq. 3.5-3.7 with weights).
struct CentredMoments {
  double weight = 0.0;
  Eigen::Vector2d centroid_in_plan;  // absolute, metres
  Eigen::Vector2d centroid_in_grid;  // absolute, metres
  Eigen::Matrix2d plan_plan;         // sum w (p - c_F)(p - c_F)^T
  Eigen::Matrix2d grid_plan;         // sum w (q - c_G)(p - c_F)^T: the cross-covariance H
  double grid_grid = 0.0;            // sum w |q - c_G|^2
  double position_magnitude = 1.0;   // metres, for the relative tolerances
};

CentredMoments centre(const PairMoments& m) {
  CentredMoments c;
  c.weight = m.weight;
  const Eigen::Vector2d mean_plan = m.plan / m.weight;
  const Eigen::Vector2d mean_grid = m.grid / m.weight;
  c.centroid_in_plan = m.origin_in_plan + mean_plan;
  c.centroid_in_grid = m.origin_in_grid + mean_grid;
  c.plan_plan = m.plan_plan - m.weight * mean_plan * mean_plan.transpose();
  c.plan_plan(0, 1) = c.plan_plan(1, 0) = 0.5 * (c.plan_plan(0, 1) + c.plan_plan(1, 0));
  c.grid_plan = m.grid_plan - m.weight * mean_grid * mean_plan.transpose();
  c.grid_grid = std::max(0.0, m.grid_grid - m.weight * mean_grid.squaredNorm());
  c.position_magnitude = std::max(
      {1.0, c.centroid_in_plan.cwiseAbs().maxCoeff(), m.origin_in_plan.cwiseAbs().maxCoeff()});
  return c;
}

// Weighted sum of squared residuals of q = L p + t with the optimal t, from the moments.
double residual_sum(const CentredMoments& c, const Eigen::Matrix2d& linear) {
  const double sum = c.grid_grid - 2.0 * (linear.transpose() * c.grid_plan).trace() +
                     (linear * c.plan_plan * linear.transpose()).trace();
  return std::max(0.0, sum);
}

TransformEstimate make_estimate(const CentredMoments& c, const Eigen::Matrix2d& linear,
                                double scale) {
  TransformEstimate e;
  e.T_grid_plan.topLeftCorner<2, 2>() = linear;
  // The translation moves the plan centroid onto the grid centroid, once (eq. 3.10; eq. 3.13
  // subtracts it a second time).
  e.T_grid_plan.topRightCorner<2, 1>() = c.centroid_in_grid - linear * c.centroid_in_plan;
  e.scale = scale;
  e.reflected = linear.determinant() < 0.0;
  e.rms = std::sqrt(residual_sum(c, linear) / c.weight);
  return e;
}

// Umeyama (1991) in 2-D. Maximizing trace(R^T H) over rotations R(theta) gives
// cos = a / m, sin = b / m with a = H00 + H11, b = H10 - H01, m = |(a, b)| (= sigma1 + sigma2
// sign(det H) of the SVD); for a mirror R(theta) diag(1, -1) the same holds with
// a = H00 - H11, b = H10 + H01. The mirror fits better exactly when det H < 0. The scale is
// m / sum w |p - c_F|^2.
std::optional<TransformEstimate> fit_orthogonal(const CentredMoments& c,
                                                const TransformEstimationOptions& options,
                                                std::string* reason) {
  const double plan_spread = c.plan_plan.trace();
  const double tiny = kDistinctRelative * c.position_magnitude;
  if (!(plan_spread > c.weight * tiny * tiny)) {
    *reason = "fewer than 2 distinct plan points (with positive weight): a " +
              std::string(transform_kind_name(options.kind)) + " needs 2";
    return std::nullopt;
  }
  const Eigen::Matrix2d& H = c.grid_plan;
  bool mirrored = false;
  switch (options.reflection) {
    case Reflection::forbid:
      mirrored = false;
      break;
    case Reflection::require:
      mirrored = true;
      break;
    case Reflection::allow:
      mirrored = H.determinant() < -kMirrorDeterminantRelative * H.squaredNorm();
      break;
  }
  const double a = mirrored ? H(0, 0) - H(1, 1) : H(0, 0) + H(1, 1);
  const double b = mirrored ? H(1, 0) + H(0, 1) : H(1, 0) - H(0, 1);
  const double m = std::hypot(a, b);
  if (!(m > kRotationRelative * std::sqrt(plan_spread * c.grid_grid)) || !(m > 0.0)) {
    *reason = c.grid_grid > 0.0 ? std::string("no ") + (mirrored ? "mirrored" : "proper") +
                                      " rotation fits the pairs (the other handedness would)"
                                : "the grid points coincide: no rotation or scale is determined";
    return std::nullopt;
  }
  Eigen::Matrix2d rotation;
  rotation << a / m, -b / m, b / m, a / m;
  if (mirrored)
    rotation.col(1) = -rotation.col(1);
  const double scale = options.kind == TransformKind::similarity ? m / plan_spread : 1.0;
  return make_estimate(c, scale * rotation, scale);
}

// Normal equations of the centred data: L = H C_pp^{-1}.
std::optional<TransformEstimate> fit_affine(const CentredMoments& c, std::string* reason) {
  const Eigen::Matrix2d& C = c.plan_plan;
  const double half_trace = 0.5 * C.trace();
  const double gap = std::sqrt(std::max(0.0, half_trace * half_trace - C.determinant()));
  const double largest = half_trace + gap;
  const double smallest = half_trace - gap;
  const double tiny = kDistinctRelative * c.position_magnitude;
  if (!(largest > c.weight * tiny * tiny) || !(smallest > kCollinearVarianceRatio * largest)) {
    *reason =
        "the plan points (with positive weight) are collinear: an affine needs 3 "
        "non-collinear points";
    return std::nullopt;
  }
  const Eigen::Matrix2d linear = c.grid_plan * C.inverse();
  return make_estimate(c, linear, std::sqrt(std::abs(linear.determinant())));
}

std::optional<TransformEstimate> solve(const PairMoments& moments,
                                       const TransformEstimationOptions& options,
                                       std::string* reason) {
  if (!(moments.weight > 0.0) || !std::isfinite(moments.weight)) {
    *reason = "no pair has a positive weight";
    return std::nullopt;
  }
  const CentredMoments c = centre(moments);
  if (options.kind == TransformKind::affine)
    return fit_affine(c, reason);
  return fit_orthogonal(c, options, reason);
}

[[noreturn]] void throw_pairs_error(const std::string& message) {
  throw InputError(message, {}, 0, "pairs");
}

}  // namespace

const char* transform_kind_name(TransformKind kind) {
  switch (kind) {
    case TransformKind::similarity:
      return "similarity";
    case TransformKind::rigid:
      return "rigid";
    case TransformKind::affine:
      return "affine";
  }
  return "unknown";
}

int minimal_sample_size(TransformKind kind) {
  return kind == TransformKind::affine ? 3 : 2;
}

void PairMoments::add(const Eigen::Vector2d& point_in_plan, const Eigen::Vector2d& point_in_grid,
                      double w) {
  const Eigen::Vector2d p = point_in_plan - origin_in_plan;
  const Eigen::Vector2d q = point_in_grid - origin_in_grid;
  weight += w;
  plan += w * p;
  grid += w * q;
  plan_plan += w * p * p.transpose();
  grid_plan += w * q * p.transpose();
  grid_grid += w * q.squaredNorm();
}

PairMoments& PairMoments::operator+=(const PairMoments& other) {
  weight += other.weight;
  plan += other.plan;
  grid += other.grid;
  plan_plan += other.plan_plan;
  grid_plan += other.grid_plan;
  grid_grid += other.grid_grid;
  return *this;
}

std::optional<TransformEstimate> fit_transform(const PairMoments& moments,
                                               const TransformEstimationOptions& options) {
  std::string reason;
  return solve(moments, options, &reason);
}

std::string degeneracy_reason(const PairMoments& moments,
                              const TransformEstimationOptions& options) {
  std::string reason;
  solve(moments, options, &reason);
  return reason;
}

TransformEstimate estimate_transform(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                                     const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid,
                                     const Eigen::Ref<const Eigen::VectorXd>& weights,
                                     const TransformEstimationOptions& options) {
  const Eigen::Index n = points_in_plan.cols();
  if (points_in_grid.cols() != n || (weights.size() != 0 && weights.size() != n)) {
    std::ostringstream message;
    message << "mismatched sizes: " << n << " plan points, " << points_in_grid.cols()
            << " grid points, " << weights.size() << " weights";
    throw_pairs_error(message.str());
  }
  const int needed = minimal_sample_size(options.kind);
  if (n < needed) {
    std::ostringstream message;
    message << "a " << transform_kind_name(options.kind) << " needs at least " << needed
            << " pairs (got " << n << ")";
    throw_pairs_error(message.str());
  }
  const auto weight = [&](Eigen::Index i) { return weights.size() == 0 ? 1.0 : weights[i]; };
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!points_in_plan.col(i).allFinite() || !points_in_grid.col(i).allFinite()) {
      throw_pairs_error("pair " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
    if (!(weight(i) >= 0.0) || !std::isfinite(weight(i))) {
      throw_pairs_error("pair " + std::to_string(i) + " has a negative, NaN or infinite weight");
    }
  }

  // Two passes: the centroids first, then the moments about them, so that nothing cancels.
  PairMoments moments;
  double total = 0.0;
  Eigen::Vector2d sum_plan = Eigen::Vector2d::Zero();
  Eigen::Vector2d sum_grid = Eigen::Vector2d::Zero();
  for (Eigen::Index i = 0; i < n; ++i) {
    total += weight(i);
    sum_plan += weight(i) * points_in_plan.col(i);
    sum_grid += weight(i) * points_in_grid.col(i);
  }
  if (total > 0.0) {
    moments.origin_in_plan = sum_plan / total;
    moments.origin_in_grid = sum_grid / total;
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    moments.add(points_in_plan.col(i), points_in_grid.col(i), weight(i));
  }
  std::string reason;
  std::optional<TransformEstimate> estimate = solve(moments, options, &reason);
  if (!estimate)
    throw_pairs_error(reason);

  // The exact rms, free of the moments' rounding.
  const Eigen::Matrix2d linear = estimate->T_grid_plan.topLeftCorner<2, 2>();
  const Eigen::Vector2d translation = estimate->T_grid_plan.topRightCorner<2, 1>();
  double squared = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    squared += weight(i) *
               (linear * points_in_plan.col(i) + translation - points_in_grid.col(i)).squaredNorm();
  }
  estimate->rms = std::sqrt(squared / total);
  return *estimate;
}

TransformEstimate estimate_transform(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                                     const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid,
                                     const TransformEstimationOptions& options) {
  return estimate_transform(points_in_plan, points_in_grid, Eigen::VectorXd(), options);
}

}  // namespace floorgrid
