#pragma once

#include <Eigen/Core>

#include "floorgrid/core/parallel.hpp"

namespace floorgrid {

/// Options of ThinPlateSpline::fit.
struct ThinPlateSplineOptions {
  /// lambda >= 0, in m^2. The fit solves (K + lambda I) w + P a = y with P^T w = 0, which
  /// minimizes sum_i |y_i - f(c_i)|^2 + lambda / (8 pi) * E(f), E the bending energy (see
  /// ThinPlateSpline::bending_energy). 0 interpolates the pairs exactly; larger is smoother.
  double regularization = 0.0;
};

/// Everything that defines a fitted spline, as plain data (what a model file stores).
/// With x = (p - input_offset) / input_scale and U(r) = r^2 log r (U(0) = 0):
///   f(p) = output_offset + affine * (1, x) + sum_i kernel_weights.col(i) * U(|x - c_i|),
/// where c_i = (centres_in_plan.col(i) - input_offset) / input_scale.
struct ThinPlateSplineData {
  Eigen::Matrix2Xd centres_in_plan;  ///< n centres (the plan points fitted), metres
  Eigen::Matrix2Xd kernel_weights;   ///< 2 x n weights of U, metres (normalized kernel)
  Eigen::Matrix<double, 2, 3> affine = Eigen::Matrix<double, 2, 3>::Zero();  ///< [a0 | A], m
  double regularization = 0.0;                             ///< lambda of the fit, m^2
  Eigen::Vector2d input_offset = Eigen::Vector2d::Zero();  ///< metres: the centres' centroid
  double input_scale = 1.0;  ///< metres: the centres' rms distance from their centroid
  Eigen::Vector2d output_offset = Eigen::Vector2d::Zero();  ///< metres: the targets' centroid
};

/// f and its derivatives at one point (what a bicubic Hermite lattice needs).
struct ThinPlateSplineDerivatives {
  Eigen::Vector2d value = Eigen::Vector2d::Zero();        ///< f, metres
  Eigen::Matrix2d J_grid_plan = Eigen::Matrix2d::Zero();  ///< df/dp
  /// d^2 f / dx dy, 1/m (that of a kernel is taken as 0 at its centre, where it has no limit).
  Eigen::Vector2d mixed = Eigen::Vector2d::Zero();
};

/// A thin-plate spline f: plan -> grid (both output coordinates share one kernel system), as in
/// the QGIS/GDAL georeferencers, with optional smoothing.
///
/// Solver: the affine part is eliminated with a Householder QR of P = [1 x y] = [Q1 Q2] R;
/// w = Q2 g with Q2^T (K + lambda W^-1) Q2 g = Q2^T y solved by Cholesky (positive definite
/// for distinct centres, or any centres when lambda > 0), then R a = Q1^T (y - (K + lambda
/// W^-1) w), W the pairs' weights (the identity without). The plan
/// coordinates are centred and divided by their rms radius s first, for conditioning: as
/// U(s r) = s^2 U(r) + s^2 log(s) r^2, and the r^2 part sums to a constant when P^T w = 0
/// (absorbed by the affine part), the normalized problem with lambda / s^2 is exactly the
/// metric one. Cost O(n^3) time and 8 n^2 bytes: reduce the pairs to a budget (a few
/// thousand) first.
class ThinPlateSpline {
 public:
  /// Fits f with f(points_in_plan.col(i)) ~ points_in_grid.col(i). Throws InputError naming
  /// `pairs` on mismatched sizes, fewer than 3 pairs, NaN/infinite coordinates, collinear plan
  /// points, and (with regularization 0) coinciding plan points, which an interpolant cannot
  /// honour (merge them or set regularization > 0); naming `tps.regularization` when it is
  /// negative or not finite. `weights` (w_i > 0, one per pair, or empty for all 1) make pair
  /// i's penalty lambda / w_i: a pair of small weight is followed less (a robust refit's
  /// down-weighted pairs); no effect with regularization 0. InputError naming `tps.weights`
  /// when they are not n finite numbers > 0.
  static ThinPlateSpline fit(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                             const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid,
                             const ThinPlateSplineOptions& options = {},
                             const Eigen::VectorXd& weights = {});

  /// A spline from its plain data (a model file). Throws InputError naming `tps` when the sizes
  /// disagree, a value is not finite, or input_scale <= 0.
  explicit ThinPlateSpline(ThinPlateSplineData data);

  /// The plain data.
  const ThinPlateSplineData& data() const { return data_; }
  /// The number of centres.
  Eigen::Index size() const { return data_.centres_in_plan.cols(); }

  /// f at one plan point (metres in, metres out): O(n).
  Eigen::Vector2d evaluate(const Eigen::Vector2d& point_in_plan) const;
  /// f at every column (2 x m in, 2 x m out), exactly: O(n m), split over `threads` (1 or 2).
  Eigen::Matrix2Xd evaluate_batch(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                                  int threads = kDefaultThreads) const;
  /// The analytic Jacobian J_grid_plan = df/dp at a plan point.
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const;
  /// f, its Jacobian and its mixed derivative at a plan point, in one sum over the centres.
  ThinPlateSplineDerivatives derivatives(const Eigen::Vector2d& point_in_plan) const;

  /// The bending energy E = sum over both outputs of the integral over the plane of
  /// f_xx^2 + 2 f_xy^2 + f_yy^2 (dimensionless): 8 pi w^T K w / input_scale^2. O(n^2).
  double bending_energy() const;

 private:
  Eigen::Vector2d normalize(const Eigen::Vector2d& point_in_plan) const;
  // f at a normalized point; `u` is workspace for the n kernel values.
  Eigen::Vector2d value_at(const Eigen::Vector2d& x, Eigen::ArrayXd& u) const;

  ThinPlateSplineData data_;
  Eigen::ArrayXd cx_, cy_;  // normalized centres
  Eigen::ArrayXd wx_, wy_;  // kernel weights per output, contiguous
};

}  // namespace floorgrid
