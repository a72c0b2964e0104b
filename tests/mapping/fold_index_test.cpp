// Where a mapping folds: the fold index of the Newton inverse against an analytic fold, and the
// dt model's untangling of pairs as dense as their noise.
#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/mapping/fold_index.hpp"
#include "floorgrid/mapping/piecewise_affine.hpp"
#include "tests/mapping/mapping_test_data.hpp"

namespace floorgrid {
namespace {

/// x' = 20 + u^3 / 100 - u with u = x - 20, y' = y: the slope 3 u^2 / 100 - 1 is negative for
/// |u| < 10 / sqrt(3), so a grid point with |x' - 20| below fold_half_width() (3.849 m) has
/// three plan points and every other grid point has one.
class CubicFold : public PointMapping {
 public:
  CubicFold() : PointMapping(MappingCommonOptions{}) {}
  std::string name() const override { return "cubic-fold"; }
  std::size_t min_pairs() const override { return 3; }
  bool needs_non_collinear() const override { return true; }
  bool reduces_pairs() const override { return false; }
  Eigen::Vector2d forward(const Eigen::Vector2d& p) const override {
    const double u = p.x() - 20.0;
    return {20.0 + u * u * u / 100.0 - u, p.y()};
  }
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& p) const override {
    const double u = p.x() - 20.0;
    Eigen::Matrix2d j;
    j << 3.0 * u * u / 100.0 - 1.0, 0.0, 0.0, 1.0;
    return j;
  }

 protected:
  void fit_model(const ReferencePairs&, FitSummary&) override {}
  Value parameters() const override { return Value::object(); }
  void load_parameters(const Value&, const std::string&) override {}
};

/// The fold's half-width on the grid: |x' - 20| below it has three plan points.
double fold_half_width() {
  const double u = 10.0 / std::sqrt(3.0);
  return u - u * u * u / 100.0;
}

TEST(FoldIndex, CoversTheGridImageOfAFoldAndNothingFarFromIt) {
  CubicFold fold;
  ReferencePairs pairs;
  pairs.points_in_plan = test::random_points(500, 1);
  pairs.points_in_grid = fold.forward_batch(pairs.points_in_plan);
  fold.fit(pairs);
  ASSERT_GT(fold.fold_index().folded_cells(), 0u);
  Random r(2);
  int far = 0, found = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d g(r.uniform(0.0, test::kWidth), r.uniform(0.0, test::kHeight));
    const double off = std::abs(g.x() - 20.0);
    if (off < fold_half_width() - 1e-6) {
      // Three plan points: never invertible, whichever the Newton iterations found.
      EXPECT_TRUE(fold.fold_index().covers(g)) << g.transpose();
      EXPECT_FALSE(fold.inverse(g).invertible) << g.transpose();
    } else if (off > fold_half_width() + 1.0) {
      // One plan point: not covered, and the Newton iterations find it (from the similarity's
      // guess, or else from the nearest pair).
      ++far;
      EXPECT_FALSE(fold.fold_index().covers(g)) << g.transpose();
      const InverseMapping back = fold.inverse(g);
      if (back.invertible) {
        ++found;
        EXPECT_LE((fold.forward(back.point) - g).norm(), 1e-9);
      }
    }
  }
  // 99.3% when written; 87% from the similarity's guess alone, before the second start.
  EXPECT_GE(found, 0.98 * far);
}

TEST(FoldIndex, ASmoothMapWithoutFoldsHasNone) {
  CubicFold fold;  // fitted where |u| > 10: no fold there
  ReferencePairs pairs;
  Random r(3);
  pairs.points_in_plan.resize(2, 300);
  for (int i = 0; i < 300; ++i)
    pairs.points_in_plan.col(i) = Eigen::Vector2d(r.uniform(33.0, 60.0), r.uniform(0.0, 20.0));
  pairs.points_in_grid = fold.forward_batch(pairs.points_in_plan);
  fold.fit(pairs);
  EXPECT_EQ(fold.fold_index().folded_cells(), 0u);
}

TEST(PlanLattice, CoversTheBoxWithinItsNodeBudget) {
  const Eigen::AlignedBox2d box(Eigen::Vector2d(-3.0, 2.0), Eigen::Vector2d(97.0, 62.0));
  const PlanLattice lattice = PlanLattice::over(box, 2.0, 0.05, 250'000);
  EXPECT_LE(static_cast<double>(lattice.columns) * lattice.rows, 250'000 * 1.02);
  EXPECT_LE(lattice.node(0, 0).x(), -5.0);
  EXPECT_LE(lattice.node(0, 0).y(), 0.0);
  EXPECT_GE(lattice.node(lattice.columns - 1, lattice.rows - 1).x(), 99.0);
  EXPECT_GE(lattice.node(lattice.columns - 1, lattice.rows - 1).y(), 64.0);
  // A small box keeps the finest spacing.
  const PlanLattice fine =
      PlanLattice::over(Eigen::AlignedBox2d(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(1.0, 1.0)),
                        0.0, 0.05, 250'000);
  EXPECT_DOUBLE_EQ(fine.spacing, 0.05);
  EXPECT_EQ(fine.columns, 21);
}

TEST(PiecewiseAffine, UntanglesPairsAsDenseAsTheirNoise) {
  // 3,000 pairs over 40 x 20 m (about 0.5 m apart) with 0.15 m noise: many grid triangles flip.
  const ReferencePairs pairs =
      test::make_pairs(test::random_points(3000, 4), test::bent(), 0.15, 5);
  PiecewiseAffineMapping dt{MappingCommonOptions{}};
  const FitSummary summary = dt.fit(pairs);
  EXPECT_GT(dt.untangled_pairs(), 0u);
  EXPECT_LE(dt.untangled_pairs(), 3000u / 4);
  EXPECT_EQ(dt.folded_triangles(), 0u);
  EXPECT_GT(summary.rms_m, 0.0);  // the dropped pairs are no longer interpolated
  // Untangling drops noise: the map is nearer the truth than the raw interpolant's noise.
  const test::Truth truth = test::bent();
  double error = 0.0;
  const Eigen::Matrix2Xd probes = test::random_points(2000, 6);
  for (Eigen::Index i = 0; i < probes.cols(); ++i)
    error += (dt.forward(probes.col(i)) - truth(probes.col(i))).norm();
  EXPECT_LT(error / 2000.0, 0.15);
  // Fold-free inside: every probe comes back exactly.
  for (Eigen::Index i = 0; i < probes.cols(); ++i) {
    const InverseMapping back = dt.inverse(dt.forward(probes.col(i)));
    if (dt.inside_plan_hull(probes.col(i))) {
      ASSERT_TRUE(back.invertible) << probes.col(i).transpose();
      EXPECT_LE((back.point - probes.col(i)).norm(), 1e-9);
    }
  }
}

}  // namespace
}  // namespace floorgrid
