#include "floorgrid/mapping/thin_plate_spline_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/parallel.hpp"

namespace floorgrid {
namespace {

constexpr double kMaxNodes = 1e8;
constexpr int kPerNode = 8;

// Cubic Hermite basis on [0, 1]: values at 0 and 1 (v0, v1), unit slopes at 0 and 1 (d0, d1).
struct Hermite {
  double v[2], d[2];    // basis functions
  double dv[2], dd[2];  // their derivatives

  explicit Hermite(double s) {
    const double s2 = s * s, s3 = s2 * s;
    v[0] = 2 * s3 - 3 * s2 + 1, v[1] = -2 * s3 + 3 * s2;
    d[0] = s3 - 2 * s2 + s, d[1] = s3 - s2;
    dv[0] = 6 * s2 - 6 * s, dv[1] = -6 * s2 + 6 * s;
    dd[0] = 3 * s2 - 4 * s + 1, dd[1] = 3 * s2 - 2 * s;
  }
};

}  // namespace

ThinPlateSplineLattice::ThinPlateSplineLattice(ThinPlateSpline spline,
                                               const Eigen::AlignedBox2d& box_in_plan,
                                               const ThinPlateSplineLatticeOptions& options)
    : spline_(std::move(spline)), spacing_(options.spacing) {
  if (box_in_plan.isEmpty() || !box_in_plan.min().allFinite() || !box_in_plan.max().allFinite() ||
      !(options.margin >= 0.0) || !std::isfinite(options.margin)) {
    throw InputError("must be a finite, non-empty box (with a finite margin >= 0)", {}, 0,
                     "tps_lattice.box");
  }
  const Eigen::Vector2d lo = box_in_plan.min().array() - options.margin;
  const Eigen::Vector2d extent = box_in_plan.sizes().array() + 2.0 * options.margin;
  const double columns = std::max(2.0, std::ceil(extent.x() / spacing_) + 1.0);
  const double rows = std::max(2.0, std::ceil(extent.y() / spacing_) + 1.0);
  if (!(spacing_ > 0.0) || !std::isfinite(spacing_) || !(columns * rows <= kMaxNodes)) {
    std::ostringstream message;
    message << "must be > 0 metres and give at most 1e8 nodes (got " << spacing_ << ")";
    throw InputError(message.str(), {}, 0, "tps_lattice.spacing");
  }
  columns_ = static_cast<Eigen::Index>(columns);
  rows_ = static_cast<Eigen::Index>(rows);
  box_ = Eigen::AlignedBox2d(lo, lo + spacing_ * Eigen::Vector2d(static_cast<double>(columns_ - 1),
                                                                 static_cast<double>(rows_ - 1)));
  nodes_.resize(static_cast<std::size_t>(kPerNode * columns_ * rows_));

  const auto fill_rows = [&](Eigen::Index first, Eigen::Index last) {
    for (Eigen::Index j = first; j < last; ++j) {
      for (Eigen::Index i = 0; i < columns_; ++i) {
        const Eigen::Vector2d p =
            lo + spacing_ * Eigen::Vector2d(static_cast<double>(i), static_cast<double>(j));
        const ThinPlateSplineDerivatives e = spline_.derivatives(p);
        const Eigen::Vector2d& value = e.value;
        const Eigen::Matrix2d& J = e.J_grid_plan;
        const Eigen::Vector2d& mixed = e.mixed;
        double* node = &nodes_[static_cast<std::size_t>(kPerNode * (j * columns_ + i))];
        node[0] = value.x(), node[1] = value.y();
        node[2] = spacing_ * J(0, 0), node[3] = spacing_ * J(1, 0);
        node[4] = spacing_ * J(0, 1), node[5] = spacing_ * J(1, 1);
        node[6] = spacing_ * spacing_ * mixed.x(), node[7] = spacing_ * spacing_ * mixed.y();
      }
    }
  };
  parallel_blocks(static_cast<std::size_t>(rows_), rows_ >= 4 ? options.threads : 1,
                  [&](std::size_t first, std::size_t last) {
                    fill_rows(static_cast<Eigen::Index>(first), static_cast<Eigen::Index>(last));
                  });
}

bool ThinPlateSplineLattice::contains(const Eigen::Vector2d& point_in_plan) const {
  return box_.contains(point_in_plan);
}

Eigen::Vector2d ThinPlateSplineLattice::interpolate(const Eigen::Vector2d& point_in_plan,
                                                    Eigen::Matrix2d* jacobian) const {
  const Eigen::Vector2d cell = (point_in_plan - box_.min()) / spacing_;
  const Eigen::Index i =
      std::clamp(static_cast<Eigen::Index>(cell.x()), Eigen::Index{0}, columns_ - 2);
  const Eigen::Index j =
      std::clamp(static_cast<Eigen::Index>(cell.y()), Eigen::Index{0}, rows_ - 2);
  const Hermite hx(cell.x() - static_cast<double>(i));
  const Hermite hy(cell.y() - static_cast<double>(j));
  Eigen::Vector2d value = Eigen::Vector2d::Zero();
  Eigen::Vector2d along_x = Eigen::Vector2d::Zero(), along_y = Eigen::Vector2d::Zero();
  for (int b = 0; b < 2; ++b) {
    for (int a = 0; a < 2; ++a) {
      const double* n = &nodes_[static_cast<std::size_t>(kPerNode * ((j + b) * columns_ + i + a))];
      const Eigen::Vector2d f(n[0], n[1]), fx(n[2], n[3]), fy(n[4], n[5]), fxy(n[6], n[7]);
      value += f * (hx.v[a] * hy.v[b]) + fx * (hx.d[a] * hy.v[b]) + fy * (hx.v[a] * hy.d[b]) +
               fxy * (hx.d[a] * hy.d[b]);
      if (jacobian) {
        along_x += f * (hx.dv[a] * hy.v[b]) + fx * (hx.dd[a] * hy.v[b]) +
                   fy * (hx.dv[a] * hy.d[b]) + fxy * (hx.dd[a] * hy.d[b]);
        along_y += f * (hx.v[a] * hy.dv[b]) + fx * (hx.d[a] * hy.dv[b]) +
                   fy * (hx.v[a] * hy.dd[b]) + fxy * (hx.d[a] * hy.dd[b]);
      }
    }
  }
  if (jacobian) {
    jacobian->col(0) = along_x / spacing_;
    jacobian->col(1) = along_y / spacing_;
  }
  return value;
}

Eigen::Vector2d ThinPlateSplineLattice::evaluate(const Eigen::Vector2d& point_in_plan) const {
  if (!contains(point_in_plan))
    return spline_.evaluate(point_in_plan);
  return interpolate(point_in_plan, nullptr);
}

Eigen::Matrix2Xd ThinPlateSplineLattice::evaluate_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan, int threads) const {
  const Eigen::Index m = points_in_plan.cols();
  Eigen::Matrix2Xd out(2, m);
  const auto run = [&](Eigen::Index first, Eigen::Index last) {
    for (Eigen::Index k = first; k < last; ++k)
      out.col(k) = evaluate(points_in_plan.col(k));
  };
  parallel_blocks(static_cast<std::size_t>(m), m >= 100000 ? threads : 1,
                  [&](std::size_t first, std::size_t last) {
                    run(static_cast<Eigen::Index>(first), static_cast<Eigen::Index>(last));
                  });
  return out;
}

Eigen::Matrix2d ThinPlateSplineLattice::jacobian(const Eigen::Vector2d& point_in_plan) const {
  if (!contains(point_in_plan))
    return spline_.jacobian(point_in_plan);
  Eigen::Matrix2d J;
  interpolate(point_in_plan, &J);
  return J;
}

}  // namespace floorgrid
