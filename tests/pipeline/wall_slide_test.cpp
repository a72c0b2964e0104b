// Pairs slid along their gridmap walls: a corridor whose scans are lost along it (the
// aperture problem of real laser pairs), with the exact truth.
#include "floorgrid/pipeline/wall_slide.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/core/random.hpp"
#include "tests/support/expect_error.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

constexpr double kResolution = 0.05;

/// A 30 x 8 m gridmap: a corridor from x = 1 to 29 between walls at y = 2 and y = 4, closed at
/// both ends, with a side wall at x = 15 going up from the corridor.
OccupancyGrid corridor(double yaw = 0.0) {
  GridGeometry g{.width = 600, .height = 160, .resolution = kResolution, .origin = {0.0, 0.0, yaw}};
  OccupancyGrid grid(g, CellState::free);
  const auto wall = [&](double x0, double y0, double x1, double y1) {
    for (double s = 0.0; s <= 1.0; s += 0.001) {
      const int ix = static_cast<int>((x0 + s * (x1 - x0)) / kResolution);
      const int iy = static_cast<int>((y0 + s * (y1 - y0)) / kResolution);
      grid.set_state(ix, iy, CellState::occupied);
    }
  };
  wall(1.0, 2.0, 29.0, 2.0);
  wall(1.0, 4.0, 29.0, 4.0);
  wall(1.0, 2.0, 1.0, 4.0);
  wall(29.0, 2.0, 29.0, 4.0);
  wall(15.0, 4.0, 15.0, 8.0);
  return grid;
}

/// Scans every 0.5 m down the corridor's middle, each seeing the walls within 4 m; a scan far
/// from the corridor's ends is lost along it (`along_sigma`), one near an end is not (both
/// axes `across_sigma`). The truth is
/// the identity: a pair's grid point is the wall point, its plan point is off by the scan's pose
/// error.
ReferencePairs corridor_pairs(std::uint64_t seed, double along_sigma = 0.15,
                              double across_sigma = 0.01) {
  Random random(seed);
  std::vector<Eigen::Vector2d> plan, grid;
  for (double xs = 2.0; xs <= 28.0; xs += 0.5) {
    const bool near_end = xs < 5.0 || xs > 25.0;
    const Eigen::Vector2d error(random.normal(near_end ? across_sigma : along_sigma),
                                random.normal(across_sigma));
    const auto see = [&](const Eigen::Vector2d& wall_point) {
      if ((wall_point - Eigen::Vector2d(xs, 3.0)).norm() > 4.0)
        return;
      grid.push_back(wall_point);
      plan.push_back(wall_point - error);
    };
    for (double x = 1.1; x < 29.0; x += 0.25) {
      see({x, 2.025});
      see({x, 4.025});
    }
    for (double y = 2.2; y < 4.0; y += 0.25) {
      see({1.025, y});
      see({29.025, y});
    }
  }
  return test::pairs_of(plan, grid);
}

TEST(WallDirection, FollowsAStraightWallAndNoneAtACornerOrInTheOpen) {
  const OccupancyGrid grid = corridor();
  const Eigen::Vector2d along = wall_direction(grid, {10.0, 2.02}, 0.25, 0.25);
  EXPECT_NEAR(std::abs(along.x()), 1.0, 1e-9);
  EXPECT_NEAR(along.y(), 0.0, 1e-9);
  const Eigen::Vector2d end = wall_direction(grid, {1.02, 3.0}, 0.25, 0.25);
  EXPECT_NEAR(std::abs(end.y()), 1.0, 1e-9);
  EXPECT_EQ(wall_direction(grid, {1.02, 2.02}, 0.25, 0.25), Eigen::Vector2d::Zero());  // corner
  EXPECT_EQ(wall_direction(grid, {10.0, 3.0}, 0.25, 0.25), Eigen::Vector2d::Zero());   // open
  EXPECT_EQ(wall_direction(grid, {-5.0, 3.0}, 0.25, 0.25), Eigen::Vector2d::Zero());   // off it
  // A grid turned by its yaw turns its walls' directions with it.
  const double yaw = 0.3;
  const OccupancyGrid turned = corridor(yaw);
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  const Eigen::Vector2d t = wall_direction(turned, r * Eigen::Vector2d(10.0, 2.02), 0.25, 0.25);
  EXPECT_NEAR(std::abs(t.dot(r * Eigen::Vector2d::UnitX())), 1.0, 1e-9);
}

TEST(WallSlide, MovesPairsAlongTheirWallOnlyAndTowardsTheTruth) {
  const OccupancyGrid grid = corridor();
  const ReferencePairs pairs = corridor_pairs(7);
  const WallSlide slide = slide_pairs_along_walls(pairs, grid);
  ASSERT_EQ(slide.pairs.size(), pairs.size());
  EXPECT_EQ(slide.iterations, 2u);
  EXPECT_TRUE(slide.applied());
  ASSERT_TRUE(slide.noise);
  EXPECT_GT(slide.noise->along_m2, 4.0 * slide.noise->across_m2);
  EXPECT_GT(slide.pairs_on_walls, static_cast<std::size_t>(pairs.size()) * 8 / 10);
  EXPECT_GT(slide.median_slide_m, 0.01);

  double along_before = 0.0, along_after = 0.0;
  int along_pairs = 0;
  for (Eigen::Index i = 0; i < pairs.size(); ++i) {
    const Eigen::Vector2d g = pairs.points_in_grid.col(i), slid = slide.pairs.points_in_grid.col(i);
    EXPECT_EQ(slide.pairs.points_in_plan.col(i), pairs.points_in_plan.col(i));
    const bool on_side_wall = std::abs(g.y() - 2.025) < 1e-9 || std::abs(g.y() - 4.025) < 1e-9;
    const bool on_end_wall = std::abs(g.x() - 1.025) < 1e-9 || std::abs(g.x() - 29.025) < 1e-9;
    // Never across a straight wall: a side wall's pairs keep their y, an end wall's their x
    // (away from the corners and the side wall's junction, where two walls' cells tilt it).
    const bool at_junction = std::abs(g.y() - 4.025) < 1e-9 && std::abs(g.x() - 15.0) < 0.5;
    if (on_side_wall && g.x() > 1.5 && g.x() < 28.5 && !at_junction) {
      EXPECT_NEAR(slid.y(), g.y(), 1e-12) << "pair " << i;
    }
    if (on_end_wall && g.y() > 2.5 && g.y() < 3.5) {
      EXPECT_NEAR(slid.x(), g.x(), 1e-12) << "pair " << i;
    }
    if (on_side_wall && g.x() > 6.0 && g.x() < 24.0) {
      // The truth is the identity: the error is the grid point less the plan point.
      along_before += std::pow(g.x() - pairs.points_in_plan(0, i), 2);
      along_after += std::pow(slid.x() - pairs.points_in_plan(0, i), 2);
      ++along_pairs;
    }
  }
  ASSERT_GT(along_pairs, 1000);
  const double before = std::sqrt(along_before / along_pairs);
  const double after = std::sqrt(along_after / along_pairs);
  EXPECT_GT(before, 0.10);
  EXPECT_LT(after, 0.6 * before) << before << " -> " << after;

  // A model fitted on the slid pairs is nearer the truth than on the filters' own.
  const auto mean_error = [&](const ReferencePairs& fit_on) {
    MappingOptions o;
    o.model = "tps";
    const std::unique_ptr<PointMapping> m = make_mapping(o);
    m->fit(fit_on);
    double sum = 0.0;
    int n = 0;
    for (double x = 2.0; x <= 28.0; x += 0.1, ++n)
      sum += (m->forward({x, 2.0}) - Eigen::Vector2d(x, 2.0)).norm();
    return sum / n;
  };
  EXPECT_LT(mean_error(slide.pairs), 0.8 * mean_error(pairs));
}

TEST(WallSlide, NoRoundsOrNoWallsLeaveThePairsAsTheyAre) {
  const ReferencePairs pairs = corridor_pairs(3);
  const WallSlide none = slide_pairs_along_walls(pairs, corridor(), {.iterations = 0});
  EXPECT_EQ(none.iterations, 0u);
  EXPECT_EQ(none.pairs.points_in_grid, pairs.points_in_grid);
  GridGeometry g{.width = 600, .height = 160, .resolution = kResolution, .origin = {}};
  const WallSlide open = slide_pairs_along_walls(pairs, OccupancyGrid(g, CellState::free));
  EXPECT_EQ(open.pairs_on_walls, 0u);
  EXPECT_EQ(open.pairs.points_in_grid, pairs.points_in_grid);
}

TEST(WallSlide, PairsAsUnsureAcrossTheirWallsAsAlongThemStay) {
  // Scan errors of 5 cm on both axes everywhere: the revisits show no aperture effect.
  const ReferencePairs pairs = corridor_pairs(5, 0.05, 0.05);
  const WallSlide slide = slide_pairs_along_walls(pairs, corridor());
  ASSERT_TRUE(slide.noise);
  EXPECT_NEAR(std::sqrt(slide.noise->along_m2 / slide.noise->across_m2), 1.0, 0.3);
  EXPECT_FALSE(slide.applied());
  EXPECT_EQ(slide.iterations, 0u);
  EXPECT_EQ(slide.pairs.points_in_grid, pairs.points_in_grid);
}

TEST(WallSlide, PairsTheSmootherCannotFitStay) {
  // Only the lower wall's pairs, none off its line: a spline cannot be fitted to collinear plan
  // points, so nothing slides (and nothing throws), though the noise calls for a slide.
  const ReferencePairs all = corridor_pairs(9, 0.15, 0.0);
  std::vector<Eigen::Vector2d> plan, grid;
  for (Eigen::Index i = 0; i < all.size(); ++i) {
    if (std::abs(all.points_in_grid(1, i) - 2.025) < 1e-9) {
      plan.push_back(all.points_in_plan.col(i));
      grid.push_back(all.points_in_grid.col(i));
    }
  }
  const ReferencePairs pairs = test::pairs_of(plan, grid);
  ASSERT_GT(pairs.size(), 500);
  const WallSlide slide = slide_pairs_along_walls(pairs, corridor(), {.smoother = "tps"});
  ASSERT_TRUE(slide.noise);
  EXPECT_GT(slide.noise->along_m2, 2.25 * slide.noise->across_m2);
  EXPECT_FALSE(slide.applied());
  EXPECT_EQ(slide.iterations, 0u);
  EXPECT_EQ(slide.pairs.points_in_grid, pairs.points_in_grid);
}

TEST(WallSlide, BadOptionsNameTheirField) {
  test::expect_input_error([] { validate(WallSlideOptions{.radius = 0.0}); },
                           {"align.wall_slide.radius"});
  test::expect_input_error([] { validate(WallSlideOptions{.max_flatness = 1.0}); },
                           {"align.wall_slide.max_flatness"});
  test::expect_input_error([] { validate(WallSlideOptions{.smoother = "spline"}); },
                           {"align.wall_slide.smoother", "spline"});
  test::expect_input_error([] { validate(WallSlideOptions{.iterations = 1000}); },
                           {"align.wall_slide.iterations"});
  test::expect_input_error([] { validate(WallSlideOptions{.min_along_ratio = 0.5}); },
                           {"align.wall_slide.min_along_ratio"});
}

}  // namespace
}  // namespace floorgrid
