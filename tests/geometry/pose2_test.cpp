#include "floorgrid/geometry/pose2.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace floorgrid {
namespace {

TEST(NormalizeAngle, WrapsIntoHalfOpenInterval) {
  EXPECT_NEAR(normalize_angle(3.0 * std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(normalize_angle(-std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(normalize_angle(-0.5), -0.5, 1e-15);
  EXPECT_NEAR(normalize_angle(7.0), 7.0 - 2.0 * std::numbers::pi, 1e-12);
}

TEST(Pose2, ComposeWithInverseIsIdentity) {
  const Pose2 a{1.5, -2.0, 0.7};
  const Pose2 id = a.compose(a.inverse());
  EXPECT_NEAR(id.x, 0.0, 1e-12);
  EXPECT_NEAR(id.y, 0.0, 1e-12);
  EXPECT_NEAR(id.theta, 0.0, 1e-12);
}

TEST(Pose2, TransformMatchesMatrix) {
  const Pose2 a{1.0, 2.0, std::numbers::pi / 2.0};
  const Eigen::Vector2d p = a.transform({1.0, 0.0});
  EXPECT_NEAR(p.x(), 1.0, 1e-12);  // x axis turned to +y
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
  const Eigen::Vector3d q = a.matrix() * Eigen::Vector3d(1.0, 0.0, 1.0);
  EXPECT_NEAR(q.x(), p.x(), 1e-12);
  EXPECT_NEAR(q.y(), p.y(), 1e-12);
}

TEST(Pose2, BetweenRecoversRelativeMotion) {
  const Pose2 a{0.3, 0.4, -1.0};
  const Pose2 delta{0.5, -0.1, 0.2};
  const Pose2 b = a.compose(delta);
  const Pose2 back = a.between(b);
  EXPECT_NEAR(back.x, delta.x, 1e-12);
  EXPECT_NEAR(back.y, delta.y, 1e-12);
  EXPECT_NEAR(back.theta, delta.theta, 1e-12);
}

}  // namespace
}  // namespace floorgrid
