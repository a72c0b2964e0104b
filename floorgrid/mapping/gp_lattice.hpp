#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "floorgrid/mapping/gp_kernel.hpp"

namespace floorgrid {

/// How the GP mean is tabulated for fast prediction.
struct GpLatticeOptions {
  bool enabled = true;  ///< false: every mean comes from the exact formula (O(N) per point)
  /// metres: the largest acceptable |lattice - exact| of the mean; the lattice is refined until
  /// the error measured at every cell centre and edge midpoint is at most half of it; > 0
  double tolerance = 1e-3;
  /// the first spacing tried, per axis, as a multiple of that axis' length scale (the Hermite
  /// error shrinks with spacing^4); > 0
  double initial_spacing = 0.25;
  /// the lattice covers the training points' bounding box grown by this many length scales
  /// per axis (beyond, the mean is within about sf exp(-margin^2 / 2) of its constant), but by
  /// at most the points' extent (the longer side of their bounding box); >= 0
  double margin = 3.0;
  /// give up (exact formula everywhere) rather than use more nodes (64 bytes each); >= 4
  Eigen::Index max_nodes = 1'000'000;
  /// refinements at most before giving up; >= 1
  int max_attempts = 4;
};

/// Checks `options`; throws InputError naming `<prefix>.<field>`.
void validate_gp_lattice_options(const GpLatticeOptions& options, const std::string& prefix);

/// The noise-free GP mean m(x) = sum_i alpha_ci k_f(x, x_i) of both outputs (without the
/// constant mean) on a regular lattice, with the analytic gradient and cross derivative at
/// every node, interpolated by bicubic Hermite patches: exact at the nodes, C1 everywhere in
/// the lattice, error O(spacing^4). The kernel is separable, so the node values are matrix
/// products exp(-dx^2/2l_1^2) diag(alpha) exp(-dy^2/2l_2^2)^T (one GEMM per output).
class GpMeanLattice {
 public:
  /// An empty lattice: contains() is false everywhere.
  GpMeanLattice() = default;

  /// Builds the lattice for training `points` (2 x N) and `alpha` (2 x N, one row per
  /// output), choosing the spacing as GpLatticeOptions says; empty (with message()) when
  /// disabled or when the tolerance would need more than max_nodes. Uses up to `threads`
  /// threads (1 or 2); the result does not depend on it.
  static GpMeanLattice build(const GpHyperparameters& hyperparameters,
                             Eigen::Ref<const Eigen::Matrix2Xd> points,
                             Eigen::Ref<const Eigen::Matrix2Xd> alpha,
                             const GpLatticeOptions& options, int threads = 1);

  /// Whether there is no lattice.
  bool empty() const { return nodes_.empty(); }
  /// Whether `point` lies in the lattice's rectangle (always false when empty).
  bool contains(const Eigen::Vector2d& point) const;
  /// The interpolated mean of both outputs at `point` (which the lattice must contain).
  Eigen::Vector2d value(const Eigen::Vector2d& point) const;
  /// The derivative of value(): entry (c, d) is d output_c / d input_d.
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point) const;

  /// The lower-left node, metres.
  const Eigen::Vector2d& origin() const { return origin_; }
  /// The node spacing per axis, metres.
  const Eigen::Vector2d& spacing() const { return spacing_; }
  /// Nodes along x and along y.
  Eigen::Index nodes_x() const { return nodes_x_; }
  /// Nodes along y.
  Eigen::Index nodes_y() const { return nodes_y_; }
  /// The largest |lattice - exact| over both outputs at every cell centre and edge midpoint
  /// of the final lattice, metres (infinity when empty).
  double measured_error() const { return measured_error_; }
  /// Lattices built (refinements + 1).
  int attempts() const { return attempts_; }
  /// Why the lattice is empty, or what was built.
  const std::string& message() const { return message_; }

 private:
  template <bool kWithJacobian>
  void interpolate(const Eigen::Vector2d& point, Eigen::Vector2d& value,
                   Eigen::Matrix2d* jacobian) const;

  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d spacing_ = Eigen::Vector2d::Ones();
  Eigen::Index nodes_x_ = 0;
  Eigen::Index nodes_y_ = 0;
  /// 8 numbers per node (x fastest): f_1, f_2, h_x df_1/dx, h_x df_2/dx, h_y df_1/dy,
  /// h_y df_2/dy, h_x h_y d2f_1/dxdy, h_x h_y d2f_2/dxdy
  std::vector<double> nodes_;
  double measured_error_ = 0.0;
  int attempts_ = 0;
  std::string message_;
};

}  // namespace floorgrid
