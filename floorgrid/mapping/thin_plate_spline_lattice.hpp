#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/mapping/thin_plate_spline.hpp"

namespace floorgrid {

/// Options of ThinPlateSplineLattice.
struct ThinPlateSplineLatticeOptions {
  /// Metres between lattice nodes. Measured on 2,000-centre fits over 100 x 60 m
  /// (bench/thin_plate_spline_bench.cpp), the added error at 0.25 m is at most 0.2 mm for
  /// binned pairs (one per cell, 5 mm noise), but up to 7 mm for an interpolant (lambda 0) of
  /// raw pairs with 2 cm noise, whose kernels bend sharply at close centres: 0.125 m brings
  /// that below 1 mm (or smooth with lambda > 0). Build cost grows as 1 / spacing^2.
  double spacing = 0.25;
  double margin = 0.5;            ///< metres added around the box on every side
  int threads = kDefaultThreads;  ///< threads building the nodes (1 or 2)
};

/// A fast approximation of a ThinPlateSpline over a box: exact values, Jacobians and mixed
/// derivatives at lattice nodes, bicubic Hermite interpolation in between (C1, reproduces
/// cubics exactly). Evaluation costs O(1) instead of O(n); outside the box it falls back to the
/// exact spline. Building costs one exact evaluation per node.
class ThinPlateSplineLattice {
 public:
  /// Samples `spline` over `box_in_plan` grown by options.margin. Throws InputError naming
  /// `tps_lattice.spacing` unless it is > 0 and the lattice has at most 10^8 nodes, and
  /// `tps_lattice.box` when the box is empty or not finite.
  ThinPlateSplineLattice(ThinPlateSpline spline, const Eigen::AlignedBox2d& box_in_plan,
                         const ThinPlateSplineLatticeOptions& options = {});

  /// The spline, approximated inside the box (exact outside).
  Eigen::Vector2d evaluate(const Eigen::Vector2d& point_in_plan) const;
  /// evaluate for every column, split over `threads` (1 or 2).
  Eigen::Matrix2Xd evaluate_batch(const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                                  int threads = kDefaultThreads) const;
  /// The Jacobian of the interpolant inside the box (of the spline outside).
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const;

  /// Whether the point is inside the sampled box (where the lattice is used).
  bool contains(const Eigen::Vector2d& point_in_plan) const;
  /// The sampled box (the given one grown by the margin, rounded out to whole cells).
  const Eigen::AlignedBox2d& box() const { return box_; }
  /// Metres between nodes.
  double spacing() const { return spacing_; }
  /// The exact spline.
  const ThinPlateSpline& spline() const { return spline_; }

 private:
  // Value (and, when `jacobian` is set, the Jacobian) of the interpolant inside the box.
  Eigen::Vector2d interpolate(const Eigen::Vector2d& point_in_plan,
                              Eigen::Matrix2d* jacobian) const;

  ThinPlateSpline spline_;
  Eigen::AlignedBox2d box_;
  double spacing_ = 0.0;
  Eigen::Index columns_ = 0, rows_ = 0;  // nodes along x and y
  // Per node (row-major, x fastest): f (2), h f_x (2), h f_y (2), h^2 f_xy (2).
  std::vector<double> nodes_;
};

}  // namespace floorgrid
