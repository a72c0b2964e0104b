// The ground truth of a dataset with hand-picked pairs: the Delaunay model through every pair,
// as the thesis, even where the hand pairs fold (dt's untangling would drop them).
#include <gtest/gtest.h>

#include "floorgrid/mapping/piecewise_affine.hpp"
#include "floorgrid/pipeline/align.hpp"

namespace floorgrid {
namespace {

TEST(DatasetTruth, ManualPairsPassThroughEveryPairEvenWhereTheyFold) {
  // A 3 x 3 lattice of hand pairs, 4 m apart, with the centre one clicked 5 m off: the
  // triangles around it flip on the grid.
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, 9);
  pairs.points_in_grid.resize(2, 9);
  for (int i = 0; i < 9; ++i) {
    const Eigen::Vector2d p(4.0 * (i % 3), 4.0 * (i / 3));
    pairs.points_in_plan.col(i) = p;
    pairs.points_in_grid.col(i) = p + Eigen::Vector2d(10.0, -2.0);
  }
  pairs.points_in_grid.col(4) += Eigen::Vector2d(5.0, 0.5);
  // The fitted dt model untangles (so the fold is real), the truth does not.
  PiecewiseAffineMapping dt{MappingCommonOptions{}};
  dt.fit(pairs);
  ASSERT_GT(dt.untangled_pairs(), 0u);

  const OccupancyGrid grid;
  const Eigen::Matrix2Xd no_samples;
  const RobotLog log;
  AlignmentInputs in{.plan_grid = grid,
                     .plan = nullptr,
                     .plan_wall_samples = no_samples,
                     .gridmap = grid,
                     .log = log,
                     .start = std::nullopt,
                     .plan_scale = std::nullopt,
                     .truth_warp = {},
                     .manual_pairs = &pairs};
  const DatasetTruth truth = dataset_truth(in);
  ASSERT_TRUE(truth.plan_to_grid);
  EXPECT_EQ(truth.kind, "manual_pairs_hull");
  for (int i = 0; i < 9; ++i) {
    EXPECT_LE(
        ((*truth.plan_to_grid)(pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i)).norm(),
        1e-9)
        << "pair " << i;
  }
}

}  // namespace
}  // namespace floorgrid
