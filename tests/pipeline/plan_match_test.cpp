// Whether a plan is of the gridmap's building at all, judged after the pairs: the simulated
// office's plan against its gridmap, and a warehouse's plan given pairs that agree with
// themselves (the office's own, as filters converged on the wrong plan would make).
#include "floorgrid/pipeline/plan_match.hpp"

#include <gtest/gtest.h>

#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/pipeline/dual_localizer.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid {
namespace {

OccupancyGrid walls_raster(const SimulatedDataset& d) {
  return rasterize(filter_layers(d.plan, {{"WALLS"}, {}}), RasterizeOptions{});
}

TEST(PlanMatch, TheRightPlanMatchesAndAnotherBuildingsDoesNot) {
  const SimulatedDataset office = simulate("office", 3);
  ASSERT_GE(office.manual_pairs.size(), 10);
  const PlanMatch right = judge_plan_match(office.gridmap, walls_raster(office),
                                           PlanWalls::vector_lines, office.manual_pairs);
  ASSERT_TRUE(right.judged);
  EXPECT_GT(right.score.score, 0.3);
  // The similarity refined from the pairs' is the truth's scale (plan metres per world metre).
  EXPECT_NEAR(right.score.transform.scale / office.plan_scale, 1.0, 0.01);

  const SimulatedDataset warehouse = simulate("warehouse", 1);
  const PlanMatch wrong = judge_plan_match(office.gridmap, walls_raster(warehouse),
                                           PlanWalls::vector_lines, office.manual_pairs);
  ASSERT_TRUE(wrong.judged);
  EXPECT_LT(wrong.score.score, PlanLocationOptions{}.min_plan_match);

  // The run goes on with the right plan only.
  const PlanLocationOptions o;
  EXPECT_TRUE(plan_match_accepted(right, o.min_plan_match, o.max_plan_walls_in_free_space));
  EXPECT_FALSE(plan_match_accepted(wrong, o.min_plan_match, o.max_plan_walls_in_free_space));
}

TEST(PlanMatch, PlanWallsWhereTheRobotSawFreeSpaceRefuseAPassingScore) {
  // Seattle's DXF plan with pairs 5 m off along its corridor (measured): 47% of the gridmap's
  // walls on the plan's, 25% of the plan's walls in free space, score 0.23 above 0.15.
  PlanMatch off;
  off.judged = true;
  off.score.on_walls = 0.47;
  off.score.in_free_space = 0.245;
  off.score.score = 0.226;
  const PlanLocationOptions o;
  EXPECT_GE(off.score.score, o.min_plan_match);
  EXPECT_FALSE(plan_match_accepted(off, o.min_plan_match, o.max_plan_walls_in_free_space));
  // fr079's drawing (wrong in places): 0.33 with 5% in free space, accepted.
  off.score.in_free_space = 0.05;
  off.score.score = 0.33;
  EXPECT_TRUE(plan_match_accepted(off, o.min_plan_match, o.max_plan_walls_in_free_space));
  // Nothing judged: nothing refused.
  EXPECT_TRUE(plan_match_accepted(PlanMatch{}, o.min_plan_match, o.max_plan_walls_in_free_space));
}

TEST(PlanMatch, PairsThatDetermineNoSimilarityAreNotJudged) {
  const SimulatedDataset office = simulate("office", 3);
  ReferencePairs two;
  two.points_in_plan = office.manual_pairs.points_in_plan.leftCols(2);
  two.points_in_grid = office.manual_pairs.points_in_grid.leftCols(2);
  EXPECT_FALSE(
      judge_plan_match(office.gridmap, walls_raster(office), PlanWalls::vector_lines, two).judged);
  ReferencePairs same_point;
  same_point.points_in_plan = Eigen::Matrix2Xd::Ones(2, 5);
  same_point.points_in_grid = Eigen::Matrix2Xd::Ones(2, 5);
  EXPECT_FALSE(
      judge_plan_match(office.gridmap, walls_raster(office), PlanWalls::vector_lines, same_point)
          .judged);
}

}  // namespace
}  // namespace floorgrid
