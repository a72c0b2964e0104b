#include "floorgrid/mapping/pair_preparation.hpp"

#include <gtest/gtest.h>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/convex_hull.hpp"
#include "floorgrid/geometry/point_index.hpp"
#include "floorgrid/mapping/pair_extent.hpp"

namespace floorgrid {
namespace {

ReferencePairs shifted_pairs(int n, std::uint64_t seed, const Eigen::Vector2d& shift) {
  Random r(seed);
  ReferencePairs p;
  p.points_in_plan.resize(2, n);
  for (int i = 0; i < n; ++i)
    p.points_in_plan.col(i) << r.uniform(0, 100), r.uniform(0, 50);
  p.points_in_grid = p.points_in_plan.colwise() + shift;
  return p;
}

TEST(PairPreparation, ReductionKeepsTheBudgetAndTheMapping) {
  const ReferencePairs pairs = shifted_pairs(100000, 1, {2.0, -1.0});
  ReductionSummary s;
  const ReferencePairs reduced = reduce_pairs(pairs, {1500}, &s);
  EXPECT_TRUE(s.applied);
  EXPECT_LE(reduced.size(), 1500);
  EXPECT_GT(reduced.size(), 1000);  // the smallest cells within the budget
  EXPECT_EQ(s.pairs_after, static_cast<std::size_t>(reduced.size()));
  // Averages of pairs related by a shift are related by the same shift; weights sum up.
  EXPECT_LT(
      ((reduced.points_in_grid - reduced.points_in_plan).colwise() - Eigen::Vector2d(2.0, -1.0))
          .cwiseAbs()
          .maxCoeff(),
      1e-9);
  EXPECT_NEAR(reduced.weights.sum(), 100000.0, 1e-6);
  // Within the budget nothing changes.
  const ReferencePairs small = shifted_pairs(100, 2, {0, 0});
  ReductionSummary none;
  EXPECT_EQ(reduce_pairs(small, {1500}, &none).points_in_plan, small.points_in_plan);
  EXPECT_FALSE(none.applied);
}

TEST(PairPreparation, AStrayPairDoesNotDragItsCell) {
  // One cell: 20 pairs shifted by (1, 0) and one wild pair.
  ReferencePairs p;
  p.points_in_plan.resize(2, 21);
  p.points_in_grid.resize(2, 21);
  for (int i = 0; i < 21; ++i) {
    p.points_in_plan.col(i) << 0.01 * i, 0.005 * i;
    p.points_in_grid.col(i) = p.points_in_plan.col(i) + Eigen::Vector2d(1.0, 0.0);
  }
  p.points_in_grid.col(20) << 50.0, 50.0;
  const ReferencePairs reduced = reduce_pairs(p, {3});
  ASSERT_LE(reduced.size(), 3);
  for (Eigen::Index k = 0; k < reduced.size(); ++k) {
    EXPECT_NEAR(
        (reduced.points_in_grid.col(k) - reduced.points_in_plan.col(k) - Eigen::Vector2d(1, 0))
            .norm(),
        0.0, 1e-12);
  }
  EXPECT_DOUBLE_EQ(reduced.weights.sum(), 20.0);  // the stray pair was left out
}

TEST(PairPreparation, OneFarPairDoesNotCollapseTheRest) {
  // Issue 31, defect 3: a pair at (1e6, 1e6) beside 100,000 pairs over 100 x 50 m made cells
  // from the full extent, so every other pair fell into one or two cells.
  ReferencePairs pairs = shifted_pairs(100000, 4, {2.0, -1.0});
  pairs.points_in_plan.col(77) << 1e6, 1e6;
  pairs.points_in_grid.col(77) << 1e6 + 2.0, 1e6 - 1.0;
  ReductionSummary s;
  const ReferencePairs reduced = reduce_pairs(pairs, {1500}, &s);
  EXPECT_LE(reduced.size(), 1500);
  EXPECT_GT(reduced.size(), 1000) << "cells of " << s.cell_size << " m";
  EXPECT_LT(s.cell_size, 10.0);
  // The far pair stays a pair of its own; the others still carry the shift.
  EXPECT_LT(
      ((reduced.points_in_grid - reduced.points_in_plan).colwise() - Eigen::Vector2d(2.0, -1.0))
          .cwiseAbs()
          .maxCoeff(),
      1e-9);
  EXPECT_NEAR(reduced.weights.sum(), 100000.0, 1e-6);
  // A far pair on the other side (below the others' origin), and the extremes of the
  // coordinate range on both: still within the budget, no cell key overflowing.
  pairs.points_in_plan.col(78) << -1e7, -1e7;
  pairs.points_in_grid.col(78) << -1e7 + 2.0, -1e7 - 1.0;
  pairs.points_in_plan.col(79) << 1e7, -1e7;
  pairs.points_in_grid.col(79) << 1e7 + 2.0, -1e7 - 1.0;
  const ReferencePairs both = reduce_pairs(pairs, {1500}, &s);
  EXPECT_LE(both.size(), 1500);
  EXPECT_GT(both.size(), 1000) << "cells of " << s.cell_size << " m";
  EXPECT_NEAR(both.weights.sum(), 100000.0, 1e-6);
}

TEST(PairPreparation, FarPairsAreFoundByThePairsOwnExtent) {
  ReferencePairs pairs = shifted_pairs(1000, 5, {2.0, -1.0});
  EXPECT_TRUE(far_pairs(pairs).empty());
  pairs.points_in_plan.col(10) << 1e6, 1e6;     // a typo on the plan side
  pairs.points_in_grid.col(20) << -5e4, 3.0;    // and one on the grid side
  pairs.points_in_plan.col(30) << 150.0, 60.0;  // near: not far
  const std::vector<FarPair> far = far_pairs(pairs);
  ASSERT_EQ(far.size(), 2u);
  EXPECT_EQ(far[0].index, 10);
  EXPECT_EQ(far[0].side, "plan");
  EXPECT_GT(far[0].distance, 1e5);
  EXPECT_EQ(far[1].index, 20);
  EXPECT_EQ(far[1].side, "grid");
  EXPECT_EQ(far[1].axis, 0);
  EXPECT_NEAR(far[0].extent, 100.0, 5.0);  // the 1st to 99th percentiles' box: about 100 x 50
  // Too few pairs to judge: none is far.
  EXPECT_TRUE(far_pairs(select_pairs(pairs, std::vector<Eigen::Index>{9, 10, 11, 12})).empty());
}

TEST(PairPreparation, DuplicatesMergeAndConflictsAreCounted) {
  ReferencePairs p;
  p.points_in_plan.resize(2, 4);
  p.points_in_grid.resize(2, 4);
  p.points_in_plan << 0, 1, 0, 0, 0, 1, 0, 0;
  p.points_in_grid << 0, 1, 0.002, 4, 0, 1, 0, 0;
  DuplicateMerge m;
  const ReferencePairs merged = merge_duplicates(p, &m);
  EXPECT_EQ(merged.size(), 2);
  EXPECT_EQ(m.merged, 2u);
  EXPECT_EQ(m.conflicting, 1u);
  EXPECT_NEAR(merged.points_in_grid(0, 0), (0 + 0.002 + 4) / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(merged.weights[0], 3.0);
}

TEST(PairPreparation, ValidationNamesThePair) {
  ReferencePairs p = shifted_pairs(10, 3, {0, 0});
  p.points_in_plan(0, 4) = std::numeric_limits<double>::infinity();
  try {
    validate_pairs(p);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "pairs");
    EXPECT_NE(std::string(e.what()).find("pair 5"), std::string::npos);
  }
}

TEST(ConvexHull, SquareWithInteriorAndCollinearPoints) {
  Eigen::Matrix2Xd p(2, 7);
  p << 0, 2, 2, 0, 1, 1, 2, 0, 0, 2, 2, 1, 0, 1;
  const auto hull = convex_hull(p);
  EXPECT_EQ(hull.size(), 4u);
  EXPECT_TRUE(inside_convex_polygon(hull, {1.0, 1.0}));
  EXPECT_TRUE(inside_convex_polygon(hull, {2.0, 1.0}));  // on an edge
  EXPECT_FALSE(inside_convex_polygon(hull, {2.1, 1.0}));
}

TEST(PointIndex, NearestMatchesBruteForce) {
  Random r(4);
  Eigen::Matrix2Xd p(2, 500);
  for (int i = 0; i < 500; ++i)
    p.col(i) << r.uniform(-10, 10), r.uniform(-10, 10);
  const PointIndex2D index(p);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector2d q(r.uniform(-12, 12), r.uniform(-12, 12));
    Eigen::Index best = 0;
    (p.colwise() - q).colwise().squaredNorm().minCoeff(&best);
    const auto n = index.nearest(q);
    EXPECT_EQ(n.index, best);
    EXPECT_NEAR(n.distance, (p.col(best) - q).norm(), 1e-12);
    const auto within = index.within(q, 2.0);
    EXPECT_EQ(static_cast<long>(within.size()),
              ((p.colwise() - q).colwise().norm().array() <= 2.0).count());
  }
  PointIndex2D moved = std::move(const_cast<PointIndex2D&>(index));
  EXPECT_EQ(moved.nearest({0, 0}).index >= 0, true);
}

}  // namespace
}  // namespace floorgrid
