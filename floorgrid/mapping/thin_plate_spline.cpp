#include "floorgrid/mapping/thin_plate_spline.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/parallel.hpp"

namespace floorgrid {
namespace {

// In normalized units (the centres' rms radius is 1): centres closer than this coincide, and
// a cloud whose minor axis is below 1e-6 of its major axis is a line.
constexpr double kCoincident = 1e-9;
constexpr double kCollinearVarianceRatio = 1e-12;

[[noreturn]] void throw_pairs_error(const std::string& message) {
  throw InputError(message, {}, 0, "pairs");
}

// log x for a positive, finite x >= DBL_MIN, written so that a loop over it vectorizes (no
// table, no branch, no 64-bit integer to double conversion), where a libm call would not and
// Eigen's packet log is three times slower: x = 2^k m with m in [sqrt(1/2), sqrt(2)), and
// log m = 2 atanh(s) = 2 s (1 + z/3 + ... + z^10/21) with s = (m - 1) / (m + 1), z = s^2,
// |s| <= 0.172 (the first term left out, z^11 / 23, is below 1e-18). Within 2 ulp of std::log
// (the tests compare the spline with a std::log sum).
inline double log_positive(double x) {
  const auto bits = std::bit_cast<std::uint64_t>(x);
  double m = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
  // The biased exponent as a double: its bits under 2^52's, minus 2^52 and the bias.
  double k =
      std::bit_cast<double>((bits >> 52) | 0x4330000000000000ull) - (4503599627370496.0 + 1023.0);
  // A select between constants, then arithmetic: GCC if-converts this under -ftrapping-math.
  const double high = m > std::numbers::sqrt2 ? 1.0 : 0.0;
  m -= 0.5 * m * high;
  k += high;
  const double f = m - 1.0;
  const double s = f / (2.0 + f);
  const double z = s * s;
  // 1/3 + z/5 + ... + z^9/21 by Horner.
  double p = 1.0 / 21;
  p = p * z + 1.0 / 19, p = p * z + 1.0 / 17, p = p * z + 1.0 / 15, p = p * z + 1.0 / 13;
  p = p * z + 1.0 / 11, p = p * z + 1.0 / 9, p = p * z + 1.0 / 7, p = p * z + 1.0 / 5;
  p = p * z + 1.0 / 3;
  return k * std::numbers::ln2 + (2.0 * s + 2.0 * s * z * p);
}

// u_i = U(|x - c_i|) = r^2 log(r^2) / 2 for every centre. The log of r^2 + DBL_MIN stays
// finite at a centre, where the factor r^2 = 0 makes U(0) = 0 exactly.
void kernel_values(const Eigen::ArrayXd& cx, const Eigen::ArrayXd& cy, const Eigen::Vector2d& x,
                   Eigen::ArrayXd& u) {
  const Eigen::Index n = cx.size();
  u.resize(n);
  const double* px = cx.data();
  const double* py = cy.data();
  double* out = u.data();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double dx = x.x() - px[i], dy = x.y() - py[i];
    const double r2 = dx * dx + dy * dy;
    out[i] = 0.5 * r2 * log_positive(r2 + DBL_MIN);
  }
}

// The first two centres (by index) closer than kCoincident, or (-1, -1).
std::pair<Eigen::Index, Eigen::Index> find_coincident(const Eigen::ArrayXd& x,
                                                      const Eigen::ArrayXd& y) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(x.size()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index a, Eigen::Index b) { return x[a] < x[b]; });
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Eigen::Index i = order[k];
    for (std::size_t l = k + 1; l < order.size() && x[order[l]] - x[i] <= kCoincident; ++l) {
      const Eigen::Index j = order[l];
      if (std::abs(y[j] - y[i]) <= kCoincident)
        return {std::min(i, j), std::max(i, j)};
    }
  }
  return {-1, -1};
}

void validate_inputs(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                     const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid,
                     const ThinPlateSplineOptions& options, const Eigen::VectorXd& weights) {
  if (!(options.regularization >= 0.0) || !std::isfinite(options.regularization)) {
    std::ostringstream message;
    message << "must be >= 0 m^2 (got " << options.regularization << ")";
    throw InputError(message.str(), {}, 0, "tps.regularization");
  }
  const Eigen::Index n = points_in_plan.cols();
  if (weights.size() != 0 &&
      (weights.size() != n || !(weights.array() > 0.0).all() || !weights.allFinite())) {
    throw InputError("must be " + std::to_string(n) + " finite weights > 0, or none", {}, 0,
                     "tps.weights");
  }
  if (points_in_grid.cols() != n) {
    throw_pairs_error("mismatched sizes: " + std::to_string(n) + " plan points, " +
                      std::to_string(points_in_grid.cols()) + " grid points");
  }
  if (n < 3) {
    throw_pairs_error("a thin-plate spline needs at least 3 pairs, not all collinear (got " +
                      std::to_string(n) + ")");
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!points_in_plan.col(i).allFinite() || !points_in_grid.col(i).allFinite()) {
      throw_pairs_error("pair " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
  }
}

// The sums over the centres that evaluation needs, at one normalized point.
struct KernelSums {
  Eigen::Vector2d value = Eigen::Vector2d::Zero();     // sum w U
  Eigen::Matrix2d gradient = Eigen::Matrix2d::Zero();  // row k: sum w_k grad U
  Eigen::Vector2d mixed = Eigen::Vector2d::Zero();     // sum w d^2U / dx dy
};

// Per centre: U, grad U = (log r^2 + 1) (x - c) and d^2 U / dx dy = 2 dx dy / r^2 (0 at the
// centre itself). `__restrict` (a GCC/Clang extension) tells the vectorizer that the six
// arrays do not overlap; without it GCC gives up on this many.
void derivative_terms(Eigen::Index n, const Eigen::Vector2d& x, const double* __restrict cx,
                      const double* __restrict cy, double* __restrict u, double* __restrict slope_x,
                      double* __restrict slope_y, double* __restrict cross) {
  const double x0 = x.x(), y0 = x.y();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double dx = x0 - cx[i], dy = y0 - cy[i];
    const double r2 = dx * dx + dy * dy;
    const double log_r2 = log_positive(r2 + DBL_MIN);
    u[i] = 0.5 * r2 * log_r2;
    slope_x[i] = (log_r2 + 1.0) * dx;
    slope_y[i] = (log_r2 + 1.0) * dy;
    cross[i] = 2.0 * dx * dy / (r2 + DBL_MIN);
  }
}

}  // namespace

ThinPlateSpline ThinPlateSpline::fit(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                                     const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_grid,
                                     const ThinPlateSplineOptions& options,
                                     const Eigen::VectorXd& weights) {
  validate_inputs(points_in_plan, points_in_grid, options, weights);
  const Eigen::Index n = points_in_plan.cols();
  ThinPlateSplineData d;
  d.centres_in_plan = points_in_plan;
  d.regularization = options.regularization;

  // Normalize: centred, unit rms radius.
  d.input_offset = points_in_plan.rowwise().mean();
  Eigen::Matrix2Xd x = points_in_plan.colwise() - d.input_offset;
  d.input_scale = std::sqrt(x.squaredNorm() / static_cast<double>(n));
  if (!(d.input_scale > kCoincident * std::max(1.0, d.input_offset.cwiseAbs().maxCoeff()))) {
    throw_pairs_error("the plan points coincide: a thin-plate spline needs 3 non-collinear");
  }
  x /= d.input_scale;
  const Eigen::Matrix2d spread = x * x.transpose() / static_cast<double>(n);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(spread, Eigen::EigenvaluesOnly);
  if (!(axes.eigenvalues()[0] > kCollinearVarianceRatio * axes.eigenvalues()[1])) {
    throw_pairs_error("the plan points are collinear: a thin-plate spline needs 3 non-collinear");
  }
  const Eigen::ArrayXd cx = x.row(0).transpose().array();
  const Eigen::ArrayXd cy = x.row(1).transpose().array();
  if (options.regularization == 0.0) {
    const auto [i, j] = find_coincident(cx, cy);
    if (i >= 0) {
      throw_pairs_error("plan points " + std::to_string(i) + " and " + std::to_string(j) +
                        " coincide: an interpolating thin-plate spline (regularization 0) needs "
                        "distinct plan points; merge them or set regularization > 0");
    }
  }
  d.output_offset = points_in_grid.rowwise().mean();
  const double lambda = options.regularization / (d.input_scale * d.input_scale);

  // K + lambda W^-1, then B = Q^T (K + lambda W^-1) Q with the QR of P = [1 x y].
  Eigen::MatrixXd B(n, n);
  Eigen::ArrayXd column(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    kernel_values(cx, cy, Eigen::Vector2d(cx[j], cy[j]), column);
    B.col(j) = column.matrix();
    B(j, j) += weights.size() != 0 ? lambda / weights[j] : lambda;
  }
  Eigen::MatrixXd P(n, 3);
  P.col(0).setOnes();
  P.col(1) = cx.matrix();
  P.col(2) = cy.matrix();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(P);
  const auto Q = qr.householderQ();
  Q.adjoint().applyThisOnTheLeft(B);
  Q.applyThisOnTheRight(B);
  Eigen::MatrixXd z = (points_in_grid.colwise() - d.output_offset).transpose();  // n x 2
  Q.adjoint().applyThisOnTheLeft(z);

  // (Q2^T (K + lambda W^-1) Q2) g = Q2^T y, by Cholesky in place.
  const Eigen::Index m = n - 3;
  Eigen::MatrixXd g(m, 2);
  if (m > 0) {
    Eigen::Ref<Eigen::MatrixXd> block = B.bottomRightCorner(m, m);
    const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> cholesky(block);
    if (cholesky.info() != Eigen::Success) {
      throw_pairs_error(
          "the plan points are too close together for an interpolating thin-plate spline: set "
          "regularization > 0");
    }
    g = cholesky.solve(z.bottomRows(m));
  }
  // R a = Q1^T (y - (K + lambda W^-1) w).
  const Eigen::Matrix<double, 3, 2> rhs = z.topRows(3) - B.topRightCorner(3, m) * g;
  const Eigen::Matrix<double, 3, 2> a =
      qr.matrixQR().topLeftCorner(3, 3).triangularView<Eigen::Upper>().solve(rhs);
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(n, 2);
  w.bottomRows(m) = g;
  Q.applyThisOnTheLeft(w);
  d.kernel_weights = w.transpose();
  d.affine = a.transpose();
  if (!d.kernel_weights.allFinite() || !d.affine.allFinite()) {
    throw_pairs_error(
        "the thin-plate spline system is numerically singular: set regularization > 0");
  }
  return ThinPlateSpline(std::move(d));
}

ThinPlateSpline::ThinPlateSpline(ThinPlateSplineData data) : data_(std::move(data)) {
  const Eigen::Index n = data_.centres_in_plan.cols();
  if (data_.kernel_weights.cols() != n) {
    throw InputError("mismatched sizes: " + std::to_string(n) + " centres, " +
                         std::to_string(data_.kernel_weights.cols()) + " kernel weights",
                     {}, 0, "tps");
  }
  if (!data_.centres_in_plan.allFinite() || !data_.kernel_weights.allFinite() ||
      !data_.affine.allFinite() || !data_.input_offset.allFinite() ||
      !data_.output_offset.allFinite() || !std::isfinite(data_.regularization) ||
      !(data_.input_scale > 0.0) || !std::isfinite(data_.input_scale)) {
    throw InputError("a value is NaN or infinite, or input_scale is not > 0", {}, 0, "tps");
  }
  const Eigen::Matrix2Xd x =
      (data_.centres_in_plan.colwise() - data_.input_offset) / data_.input_scale;
  cx_ = x.row(0).transpose().array();
  cy_ = x.row(1).transpose().array();
  wx_ = data_.kernel_weights.row(0).transpose().array();
  wy_ = data_.kernel_weights.row(1).transpose().array();
}

Eigen::Vector2d ThinPlateSpline::normalize(const Eigen::Vector2d& point_in_plan) const {
  return (point_in_plan - data_.input_offset) / data_.input_scale;
}

Eigen::Vector2d ThinPlateSpline::value_at(const Eigen::Vector2d& x, Eigen::ArrayXd& u) const {
  kernel_values(cx_, cy_, x, u);
  return data_.output_offset + data_.affine.col(0) + data_.affine.rightCols<2>() * x +
         Eigen::Vector2d((wx_ * u).sum(), (wy_ * u).sum());
}

Eigen::Vector2d ThinPlateSpline::evaluate(const Eigen::Vector2d& point_in_plan) const {
  Eigen::ArrayXd u;
  return value_at(normalize(point_in_plan), u);
}

Eigen::Matrix2Xd ThinPlateSpline::evaluate_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan, int threads) const {
  const Eigen::Index m = points_in_plan.cols();
  Eigen::Matrix2Xd out(2, m);
  const auto run = [&](Eigen::Index first, Eigen::Index last) {
    Eigen::ArrayXd u(size());
    for (Eigen::Index i = first; i < last; ++i) {
      out.col(i) = value_at(normalize(points_in_plan.col(i)), u);
    }
  };
  // A second thread pays off from a few hundred thousand kernel terms.
  const bool parallel = m >= 2 && m * size() >= 200000;
  parallel_blocks(static_cast<std::size_t>(m), parallel ? threads : 1,
                  [&](std::size_t first, std::size_t last) {
                    run(static_cast<Eigen::Index>(first), static_cast<Eigen::Index>(last));
                  });
  return out;
}

ThinPlateSplineDerivatives ThinPlateSpline::derivatives(
    const Eigen::Vector2d& point_in_plan) const {
  const Eigen::Vector2d x = normalize(point_in_plan);
  const Eigen::Index n = size();
  Eigen::ArrayXd u(n), slope_x(n), slope_y(n), cross(n);
  derivative_terms(n, x, cx_.data(), cy_.data(), u.data(), slope_x.data(), slope_y.data(),
                   cross.data());
  ThinPlateSplineDerivatives out;
  out.value = data_.output_offset + data_.affine.col(0) + data_.affine.rightCols<2>() * x +
              Eigen::Vector2d((wx_ * u).sum(), (wy_ * u).sum());
  Eigen::Matrix2d gradient;
  gradient << (wx_ * slope_x).sum(), (wx_ * slope_y).sum(), (wy_ * slope_x).sum(),
      (wy_ * slope_y).sum();
  out.J_grid_plan = (data_.affine.rightCols<2>() + gradient) / data_.input_scale;
  out.mixed = Eigen::Vector2d((wx_ * cross).sum(), (wy_ * cross).sum()) /
              (data_.input_scale * data_.input_scale);
  return out;
}

Eigen::Matrix2d ThinPlateSpline::jacobian(const Eigen::Vector2d& point_in_plan) const {
  return derivatives(point_in_plan).J_grid_plan;
}

double ThinPlateSpline::bending_energy() const {
  double quadratic = 0.0;  // sum over both outputs of w^T K w
  Eigen::ArrayXd u;
  for (Eigen::Index j = 0; j < size(); ++j) {
    kernel_values(cx_, cy_, Eigen::Vector2d(cx_[j], cy_[j]), u);
    quadratic += wx_[j] * (wx_ * u).sum() + wy_[j] * (wy_ * u).sum();
  }
  // The kernel's fundamental solution: Delta^2 U = 8 pi delta, so E = 8 pi w^T K w (normalized
  // units); the energy of f(p) = g((p - o) / s) is that of g over s^2.
  return 8.0 * std::numbers::pi * quadratic / (data_.input_scale * data_.input_scale);
}

}  // namespace floorgrid
