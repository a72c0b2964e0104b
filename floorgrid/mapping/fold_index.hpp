#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace floorgrid {

class PointMapping;

/// A regular lattice of plan points over a box: nodes (column, row) at origin + spacing (c, r).
struct PlanLattice {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< node (0, 0), metres
  double spacing = 1.0;                              ///< metres between nodes
  int columns = 0;
  int rows = 0;

  /// A lattice over `box` grown by `margin` on every side, spaced at least `min_spacing` and
  /// coarse enough to hold at most `max_nodes` nodes.
  static PlanLattice over(const Eigen::AlignedBox2d& box, double margin, double min_spacing,
                          std::size_t max_nodes);
  /// Node (c, r) in the plan.
  Eigen::Vector2d node(int column, int row) const {
    return origin + spacing * Eigen::Vector2d(column, row);
  }
  /// Every node, row by row (column fastest).
  Eigen::Matrix2Xd nodes() const;
};

/// The points of `points` that differ, each kept once: a point within `tolerance` of one kept
/// before is the same (the plan points an inverse found twice, on a shared edge or a seam).
std::vector<Eigen::Vector2d> distinct_points(const std::vector<Eigen::Vector2d>& points,
                                             double tolerance);

/// Grid boxes bucketed for point queries: which boxes hold a grid point.
class GridBoxIndex {
 public:
  /// Indexes `boxes` (empty boxes are skipped).
  explicit GridBoxIndex(std::vector<Eigen::AlignedBox2d> boxes = {});
  /// The indices of the boxes holding `point`, appended to `out`.
  void holding(const Eigen::Vector2d& point, std::vector<int>& out) const;
  /// Whether any box holds `point`.
  bool any_holds(const Eigen::Vector2d& point) const;
  /// The boxes indexed.
  std::size_t size() const { return boxes_.size(); }

 private:
  /// The bucket holding `point`, or null outside every bucket.
  const std::vector<int>* bucket_of(const Eigen::Vector2d& point) const;

  std::vector<Eigen::AlignedBox2d> boxes_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1.0;
  int columns_ = 0, rows_ = 0;
  std::vector<std::vector<int>> buckets_;
};

/// Where a smooth mapping folds, seen from the grid: the grid points with more than one plan
/// point. A mapping that is a similarity far away has degree 1, so a grid point with a plan
/// point where the Jacobian keeps the similarity's orientation has another one only if it also
/// has one where the orientation flips. The index samples the mapping on a plan lattice, marks
/// the cells whose image turns over (either triangle of the cell flipped), grows them by one cell
/// and keeps each marked cell's grid box (its corners' box grown by a cell's image): a grid point
/// in none of them has one plan point. Folds smaller than a cell can escape it.
class FoldIndex {
 public:
  FoldIndex() = default;
  /// Samples `mapping` (forward_batch) on `lattice`; `orientation` is the sign of the
  /// similarity's determinant (+1 or -1).
  FoldIndex(const PointMapping& mapping, const PlanLattice& lattice, double orientation);
  /// Whether `point_in_grid` may have more than one plan point.
  bool covers(const Eigen::Vector2d& point_in_grid) const {
    return boxes_.any_holds(point_in_grid);
  }
  /// Lattice cells that turn over (before growing).
  std::size_t folded_cells() const { return folded_cells_; }

 private:
  GridBoxIndex boxes_;
  std::size_t folded_cells_ = 0;
};

}  // namespace floorgrid
