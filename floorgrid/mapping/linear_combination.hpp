#pragma once

#include <cstdint>

#include "floorgrid/mapping/fold_index.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// The most neighbours lc may search first (its cost per point grows with their cube).
inline constexpr int kMaxNeighbours = 64;

/// Options of the `lc` model.
struct LinearCombinationOptions {
  int neighbours = 12;          ///< nearest plan points searched for a triangle (first round)
  double min_angle_deg = 10.0;  ///< smallest angle a usable triangle may have, degrees
  /// Pairs kept after spatial binning. Lower than the other models' budget: lc passes exactly
  /// through its pairs, so binning more averages their noise and makes the gaps between
  /// neighbouring triangles' maps (where an inverse can land on the other side) smaller.
  std::size_t budget = 600;
};

/// `lc` (thesis 4.1): a plan point expressed in the affine frame of a nearby non-degenerate
/// triangle of plan points (smallest angle >= min_angle_deg), the same combination applied to
/// their grid partners. The thesis's eq. 4.5/4.6 mix normalized and unnormalized vectors; here
/// the 2x2 system is solved in one basis. Laser pairs lie densely along walls, so the three
/// nearest points are nearly collinear: the triangle is chosen among the nearest `neighbours`
/// (widening the search when none qualifies): one containing the point if any, else the one
/// whose farthest vertex is nearest.
///
/// The triangle is chosen once per cell of a plan lattice over the pairs' box grown by the
/// extrapolation distance (cells 10 cm or more, 50 per pair, at most 250,000), at the cell's
/// centre; every point of the cell maps by that triangle's affine map (beyond the lattice, where
/// every point is flagged extrapolated, by the pairs' similarity). The map is piecewise affine and
/// discontinuous where the triangle changes from cell to cell: beside such a seam a grid point can
/// have two plan points, or none. The inverse is exact: it collects every cell whose image holds
/// the grid point and whose own map takes it back into the cell (and the similarity's inverse, if
/// beyond the lattice), and is invertible only when there is exactly one plan point, so that it
/// never returns another plan point than the one a point came from.
class LinearCombinationMapping : public PointMapping {
 public:
  /// An lc model.
  LinearCombinationMapping(MappingCommonOptions common, LinearCombinationOptions options);

  std::string name() const override { return "lc"; }
  std::size_t min_pairs() const override { return 3; }
  bool needs_non_collinear() const override { return true; }
  bool reduces_pairs() const override { return true; }
  std::size_t reduction_budget() const override { return options_.budget; }

  Eigen::Vector2d forward(const Eigen::Vector2d& point_in_plan) const override;
  /// Each column mapped forward, on two threads.
  Eigen::Matrix2Xd forward_batch(
      const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const override;
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const override;
  InverseMapping inverse(const Eigen::Vector2d& point_in_grid) const override;

 protected:
  void fit_model(const ReferencePairs& pairs, FitSummary& summary) override;
  Value parameters() const override;
  void load_parameters(const Value& parameters, const std::string& where) override;

 private:
  /// A chosen triangle: three pair indices (-1 when none qualifies).
  struct Triangle {
    Eigen::Index a = -1, b = -1, c = -1;
    bool valid() const { return a >= 0; }
    bool operator==(const Triangle&) const = default;
  };
  Triangle choose(const Eigen::Vector2d& point_in_plan) const;
  /// The affine map of a triangle: grid = A plan + t (the similarity when `t` is not valid).
  void affine(const Triangle& t, Eigen::Matrix2d& A, Eigen::Vector2d& offset) const;
  /// Takes the pairs and builds the cells: `cell_m` metres apart (> 0), the default (0), or
  /// none (< 0: files of earlier builds, which chose the triangle at every point).
  void prepare(const ReferencePairs& pairs, double cell_m);
  /// Chooses the triangle of every lattice cell and indexes the cells' grid images (see
  /// prepare() for `cell_m`).
  void build_cells(double cell_m);
  /// The lattice cell holding a plan point (row-major), or -1 outside the lattice.
  long cell_of(const Eigen::Vector2d& point_in_plan) const;
  /// The affine map a plan point maps by.
  void affine_at(const Eigen::Vector2d& point_in_plan, Eigen::Matrix2d& A,
                 Eigen::Vector2d& offset) const;

  /// One affine map of the lattice: a triangle's.
  struct Piece {
    Eigen::Matrix2d A = Eigen::Matrix2d::Identity();
    Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  };

  LinearCombinationOptions options_;
  ReferencePairs pairs_;
  PointIndex2D plan_index_;
  /// Sets min_angle_deg and the sines derived from it.
  void set_min_angle(double degrees);

  double min_sin_angle_ = 0.17;  ///< sine of the smallest angle a triangle may have
  double half_sin2_ = 0.0;       ///< squared sine of half of it (a little less: see choose)
  PlanLattice cells_;            ///< nodes are the cells' corners
  std::vector<std::int32_t> cell_piece_;  ///< per cell: its index into pieces_
  std::vector<Piece> pieces_;             ///< the distinct maps of the cells
  GridBoxIndex cell_images_;              ///< per cell: the grid box of its image
};

}  // namespace floorgrid
