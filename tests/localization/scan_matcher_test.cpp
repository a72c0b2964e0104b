// Scan matching against analytic walls: a scan of a known room matched from a perturbed pose
// recovers the true pose; a corridor is degenerate along its axis; a scan that does not fit is
// refused.
#include "floorgrid/localization/scan_matcher.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/expect_error.hpp"
#include "tests/support/simulated_room.hpp"

namespace floorgrid {
namespace {

struct Walls {
  VectorFloorplan plan;
  OccupancyGrid grid;
  WallField field;
  explicit Walls(VectorFloorplan p)
      : plan(std::move(p)), grid(test::room_grid(plan)), field(plan, grid.geometry()) {}
};

ScanObservation scan_of(const VectorFloorplan& walls, const Pose2& pose) {
  const RobotLog log = test::log_along(walls, {pose});
  return make_observation(log.scans[0], {.max_beams = 180});
}

TEST(ScanMatcher, RecoversTheTruePoseFromAPerturbedOne) {
  const Walls room(test::asymmetric_room());
  for (const Pose2& truth : {Pose2{3.0, 5.0, 0.2}, Pose2{8.0, 2.0, 2.5}, Pose2{6.0, 6.5, -1.2}}) {
    const ScanObservation scan = scan_of(room.plan, truth);
    const ScanMatch m = match_scan(room.field, scan, truth.compose({0.2, -0.15, 0.06}), 1.0);
    ASSERT_TRUE(m.ok()) << to_string(m.failure);
    EXPECT_LT((m.pose.translation() - truth.translation()).norm(), 0.015);
    EXPECT_LT(std::abs(normalize_angle(m.pose.theta - truth.theta)), 0.005);
    EXPECT_GT(m.inliers, m.endpoints / 2);
  }
}

TEST(ScanMatcher, ACorridorIsDegenerateAlongItsAxis) {
  // Two long parallel walls 2 m apart: nothing fixes the position along them.
  VectorFloorplan corridor;
  corridor.add_segment({-50.0, 0.0}, {50.0, 0.0}, "W");
  corridor.add_segment({-50.0, 2.0}, {50.0, 2.0}, "W");
  const Walls walls(corridor);
  const Pose2 truth{0.0, 1.0, 0.0};
  const ScanMatch m =
      match_scan(walls.field, scan_of(walls.plan, truth), truth.compose({0.1, 0.1, 0.0}), 1.0);
  EXPECT_EQ(m.failure, ScanMatchFailure::degenerate);
  EXPECT_NEAR(std::abs(m.weak_direction.x()), 1.0, 1e-3);
  // Across the corridor the match still found the truth.
  EXPECT_NEAR(m.pose.y, truth.y, 0.02);
}

TEST(ScanMatcher, AScanThatDoesNotFitIsRefused) {
  const Walls room(test::asymmetric_room());
  const Pose2 truth{3.0, 5.0, 0.2};
  // A scan of another place (a round hall of radius 3 m): too few endpoints find a wall.
  VectorFloorplan hall;
  for (int k = 0; k < 36; ++k) {
    const double a = k * M_PI / 18, b = (k + 1) * M_PI / 18;
    hall.add_segment({3.0 + 3.0 * std::cos(a), 5.0 + 3.0 * std::sin(a)},
                     {3.0 + 3.0 * std::cos(b), 5.0 + 3.0 * std::sin(b)}, "W");
  }
  const ScanMatch other = match_scan(room.field, scan_of(hall, truth), truth, 1.0);
  EXPECT_EQ(other.failure, ScanMatchFailure::too_few_inliers);
  // A correction larger than max_correction is refused even when the match converges.
  ScanMatchOptions strict;
  strict.max_correction = 0.05;
  const ScanMatch limited = match_scan(room.field, scan_of(room.plan, truth),
                                       truth.compose({0.2, 0.0, 0.0}), 1.0, strict);
  EXPECT_FALSE(limited.ok());
}

TEST(ScanMatcher, RefusesBadOptions) {
  ScanMatchOptions options;
  options.min_correspondence = 1.0;  // above max_correspondence
  test::expect_input_error([&] { validate(options); }, {"min_correspondence"});
}

}  // namespace
}  // namespace floorgrid
