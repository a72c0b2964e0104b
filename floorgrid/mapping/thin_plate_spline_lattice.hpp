#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/mapping/thin_plate_spline.hpp"

namespace floorgrid {

/// Options of ThinPlateSplineLattice.
struct ThinPlateSplineLatticeOptions {
  /// Metres between lattice nodes, tried first: halved (or quartered, or divided by 8) until the
  /// added error measured (see ThinPlateSplineLattice) is at most tolerance / 2. A smooth spline
  /// keeps it (bench/heat_map_bench.cpp's, over 200 x 200 m: 3 um measured at 1 m); an
  /// interpolant (lambda 0) of raw pairs with 2 cm of noise, whose kernels bend sharply at close
  /// centres, needs 0.125 m or less, or no lattice at all. Build cost grows as 1 / spacing^2.
  double spacing = 1.0;
  double margin = 0.5;            ///< metres added around the box on every side
  int threads = kDefaultThreads;  ///< threads building the nodes (1 or 2)
  /// Metres: the largest acceptable |lattice - spline|; the spacing is refined until the error
  /// measured is at most half of it.
  double tolerance = 1e-3;
  /// Give up (the exact spline everywhere) rather than use more nodes (64 bytes each).
  Eigen::Index max_nodes = 4'000'000;
};

/// Checks `options`; throws InputError naming `tps_lattice.<field>` (spacing and tolerance
/// finite and > 0, margin finite and >= 0, threads 1 or 2, max_nodes >= 4).
void validate(const ThinPlateSplineLatticeOptions& options);

/// A fast approximation of a ThinPlateSpline over a box: exact values, Jacobians and mixed
/// derivatives at lattice nodes, bicubic Hermite interpolation in between (C1, reproduces
/// cubics exactly). Evaluation costs O(1) instead of O(n); outside the box it falls back to the
/// exact spline. Building costs one exact evaluation per node.
///
/// The spacing is chosen by measurement before the nodes are built: the lattice's value is
/// compared with the exact spline at every centre inside the box and at the centre and edge
/// midpoints of its cell (near a centre, where U = r^2 log r is least smooth, a patch errs
/// most: up to about 0.19 |w_i| (h / input_scale)^2, at the centre itself), and at the centre
/// and edge midpoints of 32 x 32 cells spread over the box (the smooth part, error O(h^4)).
/// The spacing is divided by powers of 2 (the coarser nodes stay nodes) while that error
/// exceeds tolerance / 2; when that would take more than max_nodes nodes, there is no lattice
/// and every point is evaluated exactly.
class ThinPlateSplineLattice {
 public:
  /// Samples `spline` over `box_in_plan` grown by options.margin, at the spacing chosen as
  /// above. Throws InputError naming `tps_lattice.<field>` for options out of range (see
  /// validate), `tps_lattice.spacing` when the first spacing gives more than 10^8 nodes, and
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

  /// Whether the point is inside the sampled box (where the lattice is used); never when there
  /// is no lattice.
  bool contains(const Eigen::Vector2d& point_in_plan) const;
  /// Whether there is no lattice (the tolerance needed more than max_nodes nodes).
  bool empty() const { return nodes_.empty(); }
  /// The sampled box (the given one grown by the margin, rounded out to whole cells); empty
  /// when there is no lattice.
  const Eigen::AlignedBox2d& box() const { return box_; }
  /// Metres between nodes (the spacing chosen; 0 when there is no lattice).
  double spacing() const { return spacing_; }
  /// The largest |lattice - spline| (metres, both outputs together) at the points measured for
  /// the spacing chosen; infinity when there is no lattice.
  double measured_error() const { return measured_error_; }
  /// Spacings measured (1: the first was kept).
  int attempts() const { return attempts_; }
  /// What was built, or why there is no lattice.
  const std::string& message() const { return message_; }
  /// The exact spline.
  const ThinPlateSpline& spline() const { return spline_; }

 private:
  // Value (and, when kWithJacobian, the Jacobian in *jacobian) of the interpolant inside the
  // box.
  template <bool kWithJacobian>
  Eigen::Vector2d interpolate(const Eigen::Vector2d& point_in_plan,
                              Eigen::Matrix2d* jacobian) const;

  ThinPlateSpline spline_;
  Eigen::AlignedBox2d box_;
  double spacing_ = 0.0;
  Eigen::Index columns_ = 0, rows_ = 0;  // nodes along x and y
  // Per node (row-major, x fastest): f (2), h f_x (2), h f_y (2), h^2 f_xy (2).
  std::vector<double> nodes_;
  double measured_error_ = 0.0;
  int attempts_ = 0;
  std::string message_;
};

}  // namespace floorgrid
