// Where models are judged and how errors are summarized, against hand-computed sets and
// numpy's figures.
#include "floorgrid/evaluation/domain.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace floorgrid {
namespace {

/// A 10 m x 10 m grid at 0.1 m, unknown but for a known block x in [2, 5), y in [2, 5).
OccupancyGrid partly_known_grid() {
  GridGeometry g;
  g.width = 100;
  g.height = 100;
  g.resolution = 0.1;
  OccupancyGrid grid(g);
  for (int iy = 20; iy < 50; ++iy)
    for (int ix = 20; ix < 50; ++ix)
      grid.set_state(ix, iy, CellState::free);
  return grid;
}

TEST(WarpDomain, KeepsTheWallSamplesWhoseTruePlaceWasObserved) {
  // A wall along y = 3.5 from x = 0 to 9: the truth shifts it by (1, 0). Observed near the
  // known block x in [2, 5) (within radius 0.5 m): true x in [1.5, 5.5], plan x in [0.5, 4.5].
  VectorFloorplan plan;
  plan.add_segment({0.0, 3.5}, {9.0, 3.5}, "W");
  const auto shift = [](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(p + Eigen::Vector2d(1, 0));
  };
  const EvaluationDomain d = warp_domain(plan, partly_known_grid(), shift, 0.05, 0.5);
  EXPECT_EQ(d.kind, "warp");
  ASSERT_GT(d.points_in_plan.cols(), 0);
  EXPECT_NEAR(d.points_in_plan.row(0).minCoeff(), 0.5, 0.1);
  EXPECT_NEAR(d.points_in_plan.row(0).maxCoeff(), 4.5, 0.1);
  // Samples every 5 cm along the 4 m that qualify.
  EXPECT_NEAR(static_cast<double>(d.points_in_plan.cols()), 4.0 / 0.05 + 1, 3);
}

TEST(HullDomain, KeepsTheWallSamplesInsideThePairsHull) {
  VectorFloorplan plan;
  plan.add_segment({-5.0, 1.0}, {5.0, 1.0}, "W");
  Eigen::Matrix2Xd pairs(2, 4);
  pairs << -2.0, 2.0, 2.0, -2.0,  //
      0.0, 0.0, 2.0, 2.0;
  const EvaluationDomain d = hull_domain(plan, pairs, 0.05);
  EXPECT_EQ(d.kind, "manual_pairs_hull");
  EXPECT_NEAR(d.points_in_plan.row(0).minCoeff(), -2.0, 0.05 + 1e-9);
  EXPECT_NEAR(d.points_in_plan.row(0).maxCoeff(), 2.0, 0.05 + 1e-9);
  EXPECT_NEAR(static_cast<double>(d.points_in_plan.cols()), 81, 1);
}

TEST(TruthPlanScale, IsTheScaleOfTheTruthsSimilarityWhereTheDomainLies) {
  // Wall samples of a 4 m x 3 m room's four walls, every 0.5 m.
  EvaluationDomain d;
  std::vector<Eigen::Vector2d> points;
  for (double t = 0.0; t <= 4.0; t += 0.5) {
    points.emplace_back(t, 0.0);
    points.emplace_back(t, 3.0);
  }
  for (double t = 0.5; t < 3.0; t += 0.5) {
    points.emplace_back(0.0, t);
    points.emplace_back(4.0, t);
  }
  d.points_in_plan.resize(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    d.points_in_plan.col(static_cast<Eigen::Index>(i)) = points[i];
  // A similarity: scale 1.3, turned 0.4 rad, shifted; its scale is the answer exactly.
  const Eigen::Rotation2Dd turn(0.4);
  const auto similarity = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(1.3 * (turn * p) + Eigen::Vector2d(-7.0, 2.5));
  };
  ASSERT_TRUE(truth_plan_scale(d, similarity).has_value());
  EXPECT_NEAR(*truth_plan_scale(d, similarity), 1.3, 1e-12);
  // A bent truth: 1.1 over the room (x < 6), 0.9 beyond it. Judged where the room is, the
  // scale is the room's, not the 1.0 a fit over the whole drawing would average to.
  const auto bent = [](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(p.x() < 6.0 ? 1.1 * p
                                       : Eigen::Vector2d(6.6 + 0.9 * (p.x() - 6.0), 0.9 * p.y()));
  };
  EXPECT_NEAR(*truth_plan_scale(d, bent), 1.1, 1e-12);
  // One wall along a line still gives it; one point, or points all at one place, do not.
  EvaluationDomain line;
  line.points_in_plan.resize(2, 5);
  line.points_in_plan << 0, 1, 2, 3, 4,  //
      0, 0, 0, 0, 0;
  EXPECT_NEAR(*truth_plan_scale(line, similarity), 1.3, 1e-12);
  EvaluationDomain one;
  one.points_in_plan = Eigen::Matrix2Xd::Zero(2, 1);
  EXPECT_FALSE(truth_plan_scale(one, similarity).has_value());
  EvaluationDomain same;
  same.points_in_plan = Eigen::Matrix2Xd::Ones(2, 4);
  EXPECT_FALSE(truth_plan_scale(same, similarity).has_value());
}

TEST(ErrorStatistics, MatchesNumpy) {
  // numpy: mean 2.5, median 2.5, percentile(95) 4.75 (linear), max 5 of [1, 2, 3, 4, 5, 0].
  const ErrorStatistics s = error_statistics({1, 2, 3, 4, 5, 0});
  EXPECT_EQ(s.count, 6u);
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_NEAR(s.p95, 4.75, 1e-12);
  EXPECT_DOUBLE_EQ(s.max, 5.0);
  const ErrorStatistics none = error_statistics({});
  EXPECT_EQ(none.count, 0u);
  EXPECT_EQ(none.mean, 0.0);
}

}  // namespace
}  // namespace floorgrid
