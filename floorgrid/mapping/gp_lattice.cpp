#include "floorgrid/mapping/gp_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/parallel.hpp"

namespace floorgrid {
namespace {

/// Cubic Hermite basis on [0, 1]: value weights of the left and right node, and slope
/// weights (for slopes already multiplied by the cell size).
struct Hermite {
  double v0, v1, d0, d1;
};

Hermite hermite(double s) {
  const double s2 = s * s;
  const double s3 = s2 * s;
  return {2.0 * s3 - 3.0 * s2 + 1.0, -2.0 * s3 + 3.0 * s2, s3 - 2.0 * s2 + s, s3 - s2};
}

Hermite hermite_derivative(double s) {
  const double s2 = s * s;
  return {6.0 * s2 - 6.0 * s, -6.0 * s2 + 6.0 * s, 3.0 * s2 - 4.0 * s + 1.0, 3.0 * s2 - 2.0 * s};
}

/// Per-axis factors of the separable kernel: e(a, i) = exp(-(g_a - x_i)^2 / 2l^2) for grid
/// coordinates g (rows) and training coordinates x (columns), and de(a, i) = d e / d g_a.
void axis_factors(const Eigen::VectorXd& grid, const Eigen::VectorXd& coordinates, double l,
                  Eigen::MatrixXd& e, Eigen::MatrixXd* de) {
  e.resize(grid.size(), coordinates.size());
  if (de)
    de->resize(grid.size(), coordinates.size());
  for (Eigen::Index i = 0; i < coordinates.size(); ++i) {
    const Eigen::ArrayXd d = (grid.array() - coordinates[i]) / l;
    // Each factor >= e^-150 or 0, so that no product of two (times alpha) is subnormal.
    e.col(i) = (d.square() > kGpKernelCutoff).select(0.0, (-0.5 * d.square()).exp()).matrix();
    if (de)
      de->col(i) = (-(d / l) * e.col(i).array()).matrix();
  }
}

Eigen::VectorXd axis(double origin, double spacing, Eigen::Index count) {
  return Eigen::VectorXd::LinSpaced(count, 0.0, static_cast<double>(count - 1)) * spacing +
         Eigen::VectorXd::Constant(count, origin);
}

void fail(const std::string& prefix, const char* field, const std::string& what, double value) {
  std::ostringstream message;
  message << what << " (got " << value << ")";
  throw InputError(message.str(), {}, 0, prefix + "." + field);
}

}  // namespace

void validate_gp_lattice_options(const GpLatticeOptions& options, const std::string& prefix) {
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    fail(prefix, "tolerance", "must be finite and > 0 (metres)", options.tolerance);
  }
  if (!(options.initial_spacing > 0.0) || !std::isfinite(options.initial_spacing)) {
    fail(prefix, "initial_spacing", "must be finite and > 0", options.initial_spacing);
  }
  if (!(options.margin >= 0.0) || !std::isfinite(options.margin)) {
    fail(prefix, "margin", "must be finite and >= 0", options.margin);
  }
  if (options.max_nodes < 4) {
    fail(prefix, "max_nodes", "must be >= 4", static_cast<double>(options.max_nodes));
  }
  if (options.max_attempts < 1) {
    fail(prefix, "max_attempts", "must be >= 1", options.max_attempts);
  }
}

GpMeanLattice GpMeanLattice::build(const GpHyperparameters& hyperparameters,
                                   Eigen::Ref<const Eigen::Matrix2Xd> points,
                                   Eigen::Ref<const Eigen::Matrix2Xd> alpha,
                                   const GpLatticeOptions& options, int threads) {
  GpMeanLattice lattice;
  if (!options.enabled) {
    lattice.message_ = "disabled: the exact formula everywhere";
    return lattice;
  }
  const Eigen::Vector2d l = hyperparameters.length_scale;
  const double sf2 = hyperparameters.signal_std * hyperparameters.signal_std;
  const double extent = (points.rowwise().maxCoeff() - points.rowwise().minCoeff()).maxCoeff();
  // Length scales far beyond the data (a near-linear mean) would stretch the margin over
  // kilometres nobody queries; the exact formula serves those points.
  const Eigen::Vector2d margin = (options.margin * l).cwiseMin(Eigen::Vector2d::Constant(extent));
  const Eigen::Vector2d lo = points.rowwise().minCoeff() - margin;
  const Eigen::Vector2d hi = points.rowwise().maxCoeff() + margin;
  // At least 8 cells across the data even when the length scales dwarf it.
  Eigen::Vector2d spacing =
      (options.initial_spacing * l).cwiseMin(Eigen::Vector2d::Constant(extent / 8.0));
  const double target = 0.5 * options.tolerance;
  const Eigen::VectorXd xs = points.row(0).transpose();
  const Eigen::VectorXd ys = points.row(1).transpose();

  for (int attempt = 1; attempt <= options.max_attempts; ++attempt) {
    Eigen::Index n[2];
    Eigen::Vector2d h;
    for (int d = 0; d < 2; ++d) {
      const double span = std::max(hi[d] - lo[d], spacing[d]);
      n[d] = std::max<Eigen::Index>(2, static_cast<Eigen::Index>(std::ceil(span / spacing[d])) + 1);
      h[d] = span / static_cast<double>(n[d] - 1);
    }
    const double count = static_cast<double>(n[0]) * static_cast<double>(n[1]);
    if (count > static_cast<double>(options.max_nodes)) {
      std::ostringstream message;
      message << "no lattice: the tolerance " << options.tolerance << " m needs more than "
              << "max_nodes (" << options.max_nodes << ") nodes; the exact formula everywhere";
      GpMeanLattice none;
      none.measured_error_ = std::numeric_limits<double>::infinity();
      none.attempts_ = attempt;
      none.message_ = message.str();
      return none;
    }
    lattice.origin_ = lo;
    lattice.spacing_ = h;
    lattice.nodes_x_ = n[0];
    lattice.nodes_y_ = n[1];
    lattice.attempts_ = attempt;
    lattice.nodes_.assign(static_cast<std::size_t>(8 * n[0] * n[1]), 0.0);

    const Eigen::VectorXd gx = axis(lo.x(), h.x(), n[0]);
    const Eigen::VectorXd gy = axis(lo.y(), h.y(), n[1]);
    const Eigen::VectorXd cx = gx.head(n[0] - 1).array() + 0.5 * h.x();
    const Eigen::VectorXd cy = gy.head(n[1] - 1).array() + 0.5 * h.y();
    Eigen::MatrixXd ex, dex, ey, dey, ecx, ecy;
    axis_factors(gx, xs, l.x(), ex, &dex);
    axis_factors(gy, ys, l.y(), ey, &dey);
    axis_factors(cx, xs, l.x(), ecx, nullptr);
    axis_factors(cy, ys, l.y(), ecy, nullptr);
    Eigen::MatrixXd left(2 * n[0], xs.size());
    left << ex, dex;
    Eigen::MatrixXd check_left(2 * n[0] - 1, xs.size());
    check_left << ecx, ex;

    // One task per output, each a fixed set of products: the thread count changes nothing.
    double errors[2] = {0.0, 0.0};
    parallel_tasks(2, threads, [&](Eigen::Index c) {
      const Eigen::Index nx = n[0], ny = n[1];
      Eigen::MatrixXd right(xs.size(), 2 * ny);
      right << alpha.row(c).transpose().asDiagonal() * ey.transpose(),
          alpha.row(c).transpose().asDiagonal() * dey.transpose();
      const Eigen::MatrixXd r = left * right;
      const double fx = sf2 * h.x(), fy = sf2 * h.y(), fxy = sf2 * h.x() * h.y();
      for (Eigen::Index b = 0; b < ny; ++b) {
        for (Eigen::Index a = 0; a < nx; ++a) {
          double* node = &lattice.nodes_[static_cast<std::size_t>(8 * (a + nx * b))];
          node[c] = sf2 * r(a, b);
          node[2 + c] = fx * r(nx + a, b);
          node[4 + c] = fy * r(a, ny + b);
          node[6 + c] = fxy * r(nx + a, ny + b);
        }
      }
    });
    // Exact values at every cell centre and edge midpoint, where a Hermite patch errs most.
    parallel_tasks(2, threads, [&](Eigen::Index c) {
      const Eigen::Index nx = n[0], ny = n[1];
      Eigen::MatrixXd right(xs.size(), 2 * ny - 1);
      right << alpha.row(c).transpose().asDiagonal() * ecy.transpose(),
          alpha.row(c).transpose().asDiagonal() * ey.transpose();
      const Eigen::MatrixXd exact = sf2 * (check_left * right);
      double worst = 0.0;
      for (Eigen::Index b = 0; b < 2 * ny - 1; ++b) {
        const double y = b < ny - 1 ? cy[b] : gy[b - (ny - 1)];
        for (Eigen::Index a = 0; a < 2 * nx - 1; ++a) {
          if (a >= nx - 1 && b >= ny - 1)
            continue;  // a node: exact by construction
          const double x = a < nx - 1 ? cx[a] : gx[a - (nx - 1)];
          worst = std::max(worst, std::abs(lattice.value({x, y})[c] - exact(a, b)));
        }
      }
      errors[c] = worst;
    });
    lattice.measured_error_ = std::max(errors[0], errors[1]);
    if (lattice.measured_error_ <= target) {
      std::ostringstream message;
      message << n[0] << " x " << n[1] << " nodes, spacing " << h.x() << " x " << h.y()
              << " m, measured error " << lattice.measured_error_ << " m";
      lattice.message_ = message.str();
      return lattice;
    }
    // The Hermite error scales with spacing^4: aim below the target, shrink at least 20%.
    const double factor =
        std::clamp(0.9 * std::pow(target / lattice.measured_error_, 0.25), 0.25, 0.8);
    spacing = h * factor;
  }
  std::ostringstream message;
  message << "no lattice: still " << lattice.measured_error_ << " m off after "
          << options.max_attempts << " attempts; the exact formula everywhere";
  GpMeanLattice none;
  none.measured_error_ = std::numeric_limits<double>::infinity();
  none.attempts_ = options.max_attempts;
  none.message_ = message.str();
  return none;
}

bool GpMeanLattice::contains(const Eigen::Vector2d& point) const {
  if (empty())
    return false;
  const double x_max = origin_.x() + spacing_.x() * static_cast<double>(nodes_x_ - 1);
  const double y_max = origin_.y() + spacing_.y() * static_cast<double>(nodes_y_ - 1);
  return point.x() >= origin_.x() && point.x() <= x_max && point.y() >= origin_.y() &&
         point.y() <= y_max;
}

Eigen::Vector2d GpMeanLattice::value(const Eigen::Vector2d& point) const {
  Eigen::Vector2d value;
  interpolate<false>(point, value, nullptr);
  return value;
}

Eigen::Matrix2d GpMeanLattice::jacobian(const Eigen::Vector2d& point) const {
  Eigen::Vector2d value;
  Eigen::Matrix2d jacobian;
  interpolate<true>(point, value, &jacobian);
  return jacobian;
}

template <bool kWithJacobian>
void GpMeanLattice::interpolate(const Eigen::Vector2d& point, Eigen::Vector2d& value,
                                Eigen::Matrix2d* jacobian) const {
  const double tx = (point.x() - origin_.x()) / spacing_.x();
  const double ty = (point.y() - origin_.y()) / spacing_.y();
  const Eigen::Index a =
      std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::floor(tx)), 0, nodes_x_ - 2);
  const Eigen::Index b =
      std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::floor(ty)), 0, nodes_y_ - 2);
  const double s = tx - static_cast<double>(a);
  const double u = ty - static_cast<double>(b);
  const double* n00 = &nodes_[static_cast<std::size_t>(8 * (a + nodes_x_ * b))];
  const double* n10 = n00 + 8;
  const double* n01 = n00 + 8 * nodes_x_;
  const double* n11 = n01 + 8;
  const Hermite bx = hermite(s);
  const Hermite by = hermite(u);
  for (int c = 0; c < 2; ++c) {
    // Along x on the cell's lower (0) and upper (1) edge: the value g and h_y * d/dy q.
    const double g0 = bx.v0 * n00[c] + bx.v1 * n10[c] + bx.d0 * n00[2 + c] + bx.d1 * n10[2 + c];
    const double g1 = bx.v0 * n01[c] + bx.v1 * n11[c] + bx.d0 * n01[2 + c] + bx.d1 * n11[2 + c];
    const double q0 =
        bx.v0 * n00[4 + c] + bx.v1 * n10[4 + c] + bx.d0 * n00[6 + c] + bx.d1 * n10[6 + c];
    const double q1 =
        bx.v0 * n01[4 + c] + bx.v1 * n11[4 + c] + bx.d0 * n01[6 + c] + bx.d1 * n11[6 + c];
    value[c] = by.v0 * g0 + by.v1 * g1 + by.d0 * q0 + by.d1 * q1;
    if constexpr (kWithJacobian) {
      const Hermite dx = hermite_derivative(s);
      const Hermite dy = hermite_derivative(u);
      const double dg0 = dx.v0 * n00[c] + dx.v1 * n10[c] + dx.d0 * n00[2 + c] + dx.d1 * n10[2 + c];
      const double dg1 = dx.v0 * n01[c] + dx.v1 * n11[c] + dx.d0 * n01[2 + c] + dx.d1 * n11[2 + c];
      const double dq0 =
          dx.v0 * n00[4 + c] + dx.v1 * n10[4 + c] + dx.d0 * n00[6 + c] + dx.d1 * n10[6 + c];
      const double dq1 =
          dx.v0 * n01[4 + c] + dx.v1 * n11[4 + c] + dx.d0 * n01[6 + c] + dx.d1 * n11[6 + c];
      (*jacobian)(c, 0) = (by.v0 * dg0 + by.v1 * dg1 + by.d0 * dq0 + by.d1 * dq1) / spacing_.x();
      (*jacobian)(c, 1) = (dy.v0 * g0 + dy.v1 * g1 + dy.d0 * q0 + dy.d1 * q1) / spacing_.y();
    }
  }
}

}  // namespace floorgrid
