#pragma once

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
/// whose farthest vertex is nearest. The map is piecewise affine and discontinuous where the
/// chosen triangle changes; the inverse is the fixed point of "choose the triangle, invert its
/// affine map".
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
  /// The affine map of a triangle: grid = A plan + t.
  void affine(const Triangle& t, Eigen::Matrix2d& A, Eigen::Vector2d& offset) const;
  void prepare(const ReferencePairs& pairs);

  LinearCombinationOptions options_;
  ReferencePairs pairs_;
  PointIndex2D plan_index_;
  double min_sin_angle_ = 0.17;
};

}  // namespace floorgrid
