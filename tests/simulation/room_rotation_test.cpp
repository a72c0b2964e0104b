#include "floorgrid/simulation/room_rotation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <numbers>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/pose2.hpp"
#include "tests/simulation/warp_test_support.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// A 4 x 5 m room turned about its centre, the blend band around it.
RoomRotation office_room(double angle, double band = 0.8) {
  RoomRotation room;
  room.core = Eigen::AlignedBox2d(Eigen::Vector2d(10, 20), Eigen::Vector2d(14, 25));
  room.center = room.core.center();
  room.angle = angle;
  room.band = band;
  return room;
}

double distance_to_core(const RoomRotation& room, const Eigen::Vector2d& p) {
  return std::sqrt(room.core.squaredExteriorDistance(p));
}

TEST(WarpRoomRotation, CoreTurnsRigidly) {
  const RoomRotation room = office_room(3 * kDegree);
  const Eigen::Matrix2d R = rotation_2d(room.angle);
  Random random(21);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector2d p(random.uniform(10, 14), random.uniform(20, 25));
    const Eigen::Vector2d expected = room.center + R * (p - room.center);
    EXPECT_LT((rotate_room_point(room, p) - expected).norm(), 1e-12);
    EXPECT_LT((room_rotation_jacobian(room, p) - R).norm(), 1e-12);
  }
  // The core's own corners and edges are still the rigid rotation.
  const Eigen::Vector2d corner = room.core.max();
  EXPECT_LT((rotate_room_point(room, corner) - (room.center + R * (corner - room.center))).norm(),
            1e-12);
}

TEST(WarpRoomRotation, IdentityBeyondTheBand) {
  const RoomRotation room = office_room(-3 * kDegree);
  Random random(22);
  int outside = 0;
  int in_band = 0;
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector2d p(random.uniform(7, 17), random.uniform(17, 28));
    const double d = distance_to_core(room, p);
    const double w = room_rotation_weight(room, p);
    if (d >= room.band) {
      ++outside;
      EXPECT_EQ(rotate_room_point(room, p), p);
      EXPECT_EQ(room_rotation_jacobian(room, p), Eigen::Matrix2d::Identity());
      EXPECT_EQ(w, 0.0);
    } else if (d > 0) {
      ++in_band;
      EXPECT_GT(w, 0.0);
      EXPECT_LT(w, 1.0);
    }
  }
  EXPECT_GT(outside, 1000);
  EXPECT_GT(in_band, 500);
  // Right at the band's outer edge the weight has reached 0.
  EXPECT_EQ(room_rotation_weight(room, {14.8, 22.0}), 0.0);
  EXPECT_EQ(room_rotation_weight(room, {14.0, 22.0}), 1.0);
  EXPECT_NEAR(room_rotation_weight(room, {14.4, 22.0}), 0.5, 1e-12);  // S(1/2) = 1/2
}

TEST(WarpRoomRotation, StaysOrientedUpToThreeDegrees) {
  for (const double degrees : {-3.0, -1.0, 0.5, 1.0, 2.0, 3.0}) {
    const double smallest = min_jacobian_determinant(office_room(degrees * kDegree), 0.01);
    EXPECT_GT(smallest, 0.0) << degrees << " degrees";
    if (degrees == 3.0) {
      std::cout << "[ info     ] 4 x 5 m room, band 0.8 m, 3 degrees: min det J " << smallest
                << "\n";
    }
  }
  // The check does detect a fold: a band far too narrow for the angle.
  EXPECT_LT(min_jacobian_determinant(office_room(3 * kDegree, 0.05), 0.005), 0.0);
}

TEST(WarpRoomRotation, JacobianMatchesFiniteDifferences) {
  const RoomRotation room = office_room(2.5 * kDegree);
  const auto f = [&](const Eigen::Vector2d& p) { return rotate_room_point(room, p); };
  Random random(23);
  int checked = 0;
  while (checked < 500) {
    const Eigen::Vector2d p(random.uniform(9, 15), random.uniform(19, 26));
    const double d = distance_to_core(room, p);
    if (d < 1e-3 || d > room.band - 1e-3)
      continue;  // in the band, away from its edges
    const Eigen::Matrix2d J = room_rotation_jacobian(room, p);
    EXPECT_LT((J - test::central_difference_jacobian(f, p)).norm(), 1e-6 * J.norm());
    ++checked;
  }
}

// C1: the Jacobian has no jump where the core meets the band, where the band meets the
// outside, and where the band's face regions meet its corner regions.
TEST(WarpRoomRotation, JacobianIsContinuousAcrossTheBandEdges) {
  const RoomRotation room = office_room(3 * kDegree);
  const double eps = 1e-7;
  struct Crossing {
    Eigen::Vector2d point;
    Eigen::Vector2d direction;
  };
  const Crossing crossings[] = {
      {{14.0, 22.0}, {1, 0}},   // core face, right
      {{12.0, 25.0}, {0, 1}},   // core face, top
      {{10.0, 20.3}, {-1, 0}},  // core face, left, near a corner
      {{14.8, 22.0}, {1, 0}},   // band edge, right
      {{12.0, 19.2}, {0, -1}},  // band edge, bottom
      {{14.0 + 0.8 * std::cos(0.7), 25.0 + 0.8 * std::sin(0.7)},
       {std::cos(0.7), std::sin(0.7)}},  // band edge, around a corner
      {{14.0, 25.3}, {1, 0}},            // face region to corner region
      {{13.5, 25.0}, {1, 1}},            // core face to the corner region, diagonally
  };
  double largest_jump = 0;
  for (const Crossing& c : crossings) {
    const Eigen::Vector2d n = c.direction.normalized();
    const Eigen::Matrix2d jump = room_rotation_jacobian(room, c.point + eps * n) -
                                 room_rotation_jacobian(room, c.point - eps * n);
    EXPECT_LT(jump.norm(), 1e-5) << "at " << c.point.transpose();
    largest_jump = std::max(largest_jump, jump.norm());
  }
  // Where the weight varies fastest, the Jacobian is far from the identity, so a jump would show.
  const Eigen::Matrix2d mid_band = room_rotation_jacobian(room, {12.0, 25.4});
  EXPECT_GT((mid_band - Eigen::Matrix2d::Identity()).norm(), 0.1);
  std::cout << "[ info     ] largest Jacobian jump across the band edges over 2e-7 m: "
            << largest_jump << "\n";
}

TEST(WarpRoomRotation, StrainInTheBandIsBounded) {
  // |J - I| <= |R - I| (1 + r max S' / band) with max S' = 30/16 and r the distance from the
  // centre: the band shears the room's surroundings, much more than the bend stretches.
  const RoomRotation room = office_room(3 * kDegree);
  const double r_max = (room.core.max() - room.center).norm() + room.band;
  const double bound = 2 * std::sin(room.angle / 2) * (1 + r_max * 1.875 / room.band);
  double strain = 0;
  for (double x = 9.0; x <= 15.0; x += 0.01) {
    for (double y = 19.0; y <= 26.0; y += 0.01) {
      strain = std::max(strain, test::principal_strain(room_rotation_jacobian(room, {x, y})));
    }
  }
  EXPECT_LE(strain, bound);
  EXPECT_GT(strain, 0.01);
  std::cout << "[ info     ] 4 x 5 m room, band 0.8 m, 3 degrees: max principal strain "
            << 100 * strain << " % (bound " << 100 * bound << " %)\n";
}

TEST(WarpRoomRotation, RejectsMalformedRooms) {
  RoomRotation room = office_room(kDegree);
  test::expect_input_error([&] { min_jacobian_determinant(room, 0.0); }, {"room.spacing"});
  room.band = 0.0;
  test::expect_input_error([&] { validate_room_rotation(room); }, {"room.band", "got 0"});
  room = office_room(kDegree);
  room.core = Eigen::AlignedBox2d();  // empty
  test::expect_input_error([&] { validate_room_rotation(room); }, {"room.core"});
  room = office_room(std::nan(""));
  test::expect_input_error([&] { validate_room_rotation(room); }, {"room.angle"});
}

}  // namespace
}  // namespace floorgrid
