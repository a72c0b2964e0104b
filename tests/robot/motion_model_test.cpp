#include "floorgrid/robot/motion_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace floorgrid {
namespace {

TEST(MotionModel, DecomposeThenApplyReturnsTheTarget) {
  Random random(5);
  for (int i = 0; i < 1000; ++i) {
    const Pose2 from{random.uniform(-10, 10), random.uniform(-10, 10), random.uniform(-3, 3)};
    const Pose2 to{from.x + random.uniform(-1, 1), from.y + random.uniform(-1, 1),
                   random.uniform(-3, 3)};
    const Pose2 back = apply_motion(from, odometry_motion(from, to));
    EXPECT_NEAR(back.x, to.x, 1e-12);
    EXPECT_NEAR(back.y, to.y, 1e-12);
    EXPECT_NEAR(normalize_angle(back.theta - to.theta), 0.0, 1e-12);
  }
}

TEST(MotionModel, KnownDecomposition) {
  // From the origin facing +x to (0, 2) facing -x: turn left 90, drive 2, turn left 90.
  const OdometryMotion m = odometry_motion({0, 0, 0}, {0, 2, std::numbers::pi});
  EXPECT_NEAR(m.rot1, std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(m.trans, 2.0, 1e-12);
  EXPECT_NEAR(std::abs(m.rot2), std::numbers::pi / 2, 1e-12);
  // A turn on the spot is all rot2.
  const OdometryMotion turn = odometry_motion({1, 1, 0.2}, {1, 1, 0.7});
  EXPECT_EQ(turn.rot1, 0.0);
  EXPECT_EQ(turn.trans, 0.0);
  EXPECT_NEAR(turn.rot2, 0.5, 1e-12);
  // Reversing stays a reverse.
  const OdometryMotion reverse = odometry_motion({0, 0, 0}, {-0.1, 0, 0});
  EXPECT_NEAR(reverse.trans, -0.1, 1e-12);
  EXPECT_NEAR(reverse.rot1, 0.0, 1e-12);
}

TEST(MotionModel, NoiseVariancesFollowTheAlphas) {
  const MotionNoise noise{0.05, 0.01, 0.02, 0.05};
  const OdometryMotion m{0.3, 1.0, 0.2};  // an arc: both turns the same way
  Random random(11);
  const int n = 100000;
  double s1 = 0, st = 0, s2 = 0, m1 = 0;
  for (int i = 0; i < n; ++i) {
    const OdometryMotion x = sample_noisy_motion(m, noise, random);
    s1 += (x.rot1 - m.rot1) * (x.rot1 - m.rot1);
    st += (x.trans - m.trans) * (x.trans - m.trans);
    s2 += (x.rot2 - m.rot2) * (x.rot2 - m.rot2);
    m1 += x.rot1 - m.rot1;
  }
  EXPECT_NEAR(m1 / n, 0.0, 0.002);
  EXPECT_NEAR(s1 / n, 0.05 * 0.09 + 0.01 * 1.0, 0.02 * (0.05 * 0.09 + 0.01));
  EXPECT_NEAR(st / n, 0.02 * 1.0 + 0.05 * (0.09 + 0.04), 0.02 * (0.02 + 0.05 * 0.13));
  EXPECT_NEAR(s2 / n, 0.05 * 0.04 + 0.01 * 1.0, 0.02 * (0.05 * 0.04 + 0.01));
}

TEST(MotionModel, SidewaysJumpAddsNoRotationNoiseBeyondTheNetTurn) {
  // 5 cm sideways with no net turn: rot1 = pi/2, rot2 = -pi/2 are artefacts of the
  // decomposition; only the translation's share of the noise remains.
  const MotionNoise noise{0.05, 0.01, 0.02, 0.05};
  const OdometryMotion m = odometry_motion({0, 0, 0}, {0, 0.05, 0});
  ASSERT_NEAR(std::abs(m.rot1), std::numbers::pi / 2, 1e-12);
  Random random(3);
  const int n = 100000;
  double s1 = 0, st = 0;
  for (int i = 0; i < n; ++i) {
    const OdometryMotion x = sample_noisy_motion(m, noise, random);
    s1 += (x.rot1 - m.rot1) * (x.rot1 - m.rot1);
    st += (x.trans - m.trans) * (x.trans - m.trans);
  }
  EXPECT_NEAR(s1 / n, 0.01 * 0.0025, 0.03 * 0.01 * 0.0025);
  EXPECT_NEAR(st / n, 0.02 * 0.0025, 0.03 * 0.02 * 0.0025);
}

}  // namespace
}  // namespace floorgrid
