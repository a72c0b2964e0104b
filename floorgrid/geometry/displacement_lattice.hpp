#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace floorgrid {

/// One observation of a displacement field along a direction: normal . D(point) = offset, with
/// a weight (point-to-plane: how far a point must move across the wall it should lie on).
struct LatticeConstraint {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();    ///< where the field is observed
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();  ///< unit direction observed
  double offset = 0.0;                                ///< normal . D(point), metres
  double weight = 1.0;                                ///< >= 0
};

/// A smooth 2-D displacement field D over a box: displacements at the nodes of a square lattice,
/// bilinear in between (clamped to the box outside it), fitted to directional observations by
/// regularized least squares, the membrane energy of neighbouring nodes' differences keeping
/// the field smooth where observations are few or all along one direction (a corridor's walls
/// say nothing of the motion along them: the field there follows its neighbours).
class DisplacementLattice {
 public:
  /// A zero field over `box` with nodes `spacing` apart (spacing > 0, box not empty).
  DisplacementLattice(const Eigen::AlignedBox2d& box, double spacing);

  /// D(point).
  Eigen::Vector2d at(const Eigen::Vector2d& point) const;

  /// Fits the nodes to `constraints`: minimizes sum w (n . D(p) - offset)^2 + stiffness * m *
  /// sum over lattice edges |u_a - u_b|^2 (m: the constraints' total weight per node, so that
  /// the stiffness does not depend on how many points there are) + a tiny ridge on every node.
  /// Returns false (the field unchanged) when there is no constraint of positive weight.
  bool fit(const std::vector<LatticeConstraint>& constraints, double stiffness);

  double spacing() const { return spacing_; }  ///< metres between nodes
  int columns() const { return columns_; }     ///< nodes along x
  int rows() const { return rows_; }           ///< nodes along y

 private:
  // The four nodes around `point` and their bilinear weights.
  void corners(const Eigen::Vector2d& point, int index[4], double weight[4]) const;

  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double spacing_ = 1.0;
  int columns_ = 2;
  int rows_ = 2;
  std::vector<Eigen::Vector2d> nodes_;
};

}  // namespace floorgrid
