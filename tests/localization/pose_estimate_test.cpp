#include "floorgrid/localization/pose_estimate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "floorgrid/core/random.hpp"

namespace floorgrid {
namespace {

constexpr double kPi = std::numbers::pi;

ParticleSet make_set(std::vector<double> x, std::vector<double> y, std::vector<double> theta,
                     std::vector<double> weight = {}) {
  ParticleSet p;
  p.x = std::move(x);
  p.y = std::move(y);
  p.theta = std::move(theta);
  p.weight = std::move(weight);
  return p;
}

TEST(PoseEstimate, CircularMeanAcrossThePiSeam) {
  // Headings just either side of +-pi average to pi (eq. 4.26), not to 0 as their arithmetic
  // mean would.
  const ParticleSet p = make_set({0, 0}, {0, 0}, {kPi - 0.1, -kPi + 0.1});
  const PoseEstimate e = estimate_pose(p);
  EXPECT_NEAR(std::abs(normalize_angle(e.pose.theta - kPi)), 0.0, 1e-12);
  // Their spread is 0.1 rad about the seam: R = cos 0.1.
  EXPECT_NEAR(e.heading_std, std::sqrt(-2.0 * std::log(std::cos(0.1))), 1e-12);
  // Weighted: 3:1 towards -pi + 0.2 moves the mean across the seam to about -pi + 0.1.
  const double w_mean =
      circular_mean(std::vector<double>{kPi - 0.2, -kPi + 0.2}, std::vector<double>{0.25, 0.75});
  const double expected = std::atan2(0.25 * std::sin(kPi - 0.2) + 0.75 * std::sin(-kPi + 0.2),
                                     0.25 * std::cos(kPi - 0.2) + 0.75 * std::cos(-kPi + 0.2));
  EXPECT_NEAR(w_mean, expected, 1e-12);
  EXPECT_LT(w_mean, -kPi + 0.2);
  EXPECT_GT(w_mean, -kPi);
}

TEST(PoseEstimate, WeightedMeanFollowsEquations424To426) {
  const ParticleSet p = make_set({1, 3, 10}, {2, 6, -4}, {0.0, kPi / 2, 1.0}, {0.25, 0.75, 0.0});
  const PoseEstimate e = estimate_pose(p);
  EXPECT_NEAR(e.pose.x, 0.25 * 1 + 0.75 * 3, 1e-12);
  EXPECT_NEAR(e.pose.y, 0.25 * 2 + 0.75 * 6, 1e-12);
  EXPECT_NEAR(e.pose.theta, std::atan2(0.75, 0.25), 1e-12);
  EXPECT_DOUBLE_EQ(e.scale, 1.0);
  EXPECT_EQ(e.scale_std, 0.0);
  EXPECT_EQ(e.particles, 3u);
  // Unnormalized weights give the same estimate.
  const PoseEstimate u =
      estimate_pose(make_set({1, 3, 10}, {2, 6, -4}, {0.0, kPi / 2, 1.0}, {1.0, 3.0, 0.0}));
  EXPECT_NEAR(u.pose.x, e.pose.x, 1e-12);
  EXPECT_NEAR(u.pose.theta, e.pose.theta, 1e-12);
}

TEST(PoseEstimate, EffectiveSampleSizeOfKnownWeights) {
  EXPECT_DOUBLE_EQ(effective_sample_size(std::vector<double>(8, 0.125)), 8.0);    // uniform: N
  EXPECT_DOUBLE_EQ(effective_sample_size(std::vector<double>{0, 1, 0, 0}), 1.0);  // one-hot
  EXPECT_DOUBLE_EQ(effective_sample_size(std::vector<double>{0.5, 0.5, 0, 0}), 2.0);
  // 1 / (0.6^2 + 0.2^2 + 0.2^2) = 1 / 0.44.
  EXPECT_NEAR(effective_sample_size(std::vector<double>{0.6, 0.2, 0.2}), 1.0 / 0.44, 1e-12);
  EXPECT_NEAR(effective_sample_size(std::vector<double>{3, 1, 1}), 1.0 / 0.44, 1e-12);
  EXPECT_EQ(effective_sample_size(std::vector<double>{0, 0}), 0.0);
  const PoseEstimate e = estimate_pose(make_set({0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0.6, 0.2, 0.2}));
  EXPECT_NEAR(e.effective_sample_size, 1.0 / 0.44, 1e-12);
  EXPECT_NEAR(e.ess_ratio, 1.0 / 0.44 / 3.0, 1e-12);
  // No weights: equal weights.
  EXPECT_DOUBLE_EQ(estimate_pose(make_set({0, 1}, {0, 1}, {0, 0})).ess_ratio, 1.0);
}

TEST(PoseEstimate, PositionStdIsTheStdAlongTheWorstDirection) {
  // Four points at (+-2, 0) and (0, +-0.5), rotated by 30 degrees: the covariance has
  // eigenvalues 2 (along the long axis: 2 * 2^2 / 4) and 0.125, whatever the rotation.
  const double c = std::cos(kPi / 6), s = std::sin(kPi / 6);
  std::vector<double> x, y;
  for (const auto& [u, v] :
       std::vector<std::pair<double, double>>{{2, 0}, {-2, 0}, {0, 0.5}, {0, -0.5}}) {
    x.push_back(5.0 + c * u - s * v);
    y.push_back(-3.0 + s * u + c * v);
  }
  const PoseEstimate e = estimate_pose(make_set(x, y, {0, 0, 0, 0}));
  EXPECT_NEAR(e.position_std, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(e.position_covariance.trace(), 2.125, 1e-12);
  EXPECT_NEAR(e.pose.x, 5.0, 1e-12);
  EXPECT_NEAR(e.pose.y, -3.0, 1e-12);
}

TEST(PoseEstimate, SpreadOfGaussianSamples) {
  // 100000 samples of an isotropic Gaussian (sigma 0.3 m) and a wrapped normal heading
  // (sigma 0.2 rad): the estimates' relative standard error is about 1 / sqrt(2 * 100000) =
  // 0.2%; the largest eigenvalue of a sample covariance is biased up by about
  // sigma^2 / sqrt(N) (0.3%), so 2% tolerances are generous.
  Random random(17);
  ParticleSet p;
  for (int i = 0; i < 100000; ++i) {
    p.x.push_back(100.0 + random.normal(0.3));
    p.y.push_back(-50.0 + random.normal(0.3));
    p.theta.push_back(normalize_angle(3.0 + random.normal(0.2)));  // straddles the seam
  }
  const PoseEstimate e = estimate_pose(p);
  EXPECT_NEAR(e.position_std, 0.3, 0.02 * 0.3);
  EXPECT_NEAR(e.heading_std, 0.2, 0.02 * 0.2);  // circular std of a wrapped normal is sigma
  EXPECT_NEAR(normalize_angle(e.pose.theta - 3.0), 0.0, 0.005);
  EXPECT_NEAR(e.pose.x, 100.0, 0.005);
}

TEST(PoseEstimate, UniformHeadingsHaveALargeHeadingStd) {
  ParticleSet p;
  for (int i = 0; i < 360; ++i) {
    p.x.push_back(0);
    p.y.push_back(0);
    p.theta.push_back(normalize_angle(i * kPi / 180.0));
  }
  EXPECT_GT(estimate_pose(p).heading_std, 2.0);
  EXPECT_TRUE(std::isfinite(estimate_pose(p).heading_std));
}

TEST(PoseEstimate, ScaleMeanAndStd) {
  ParticleSet p = make_set({0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0.5, 0.25, 0.25});
  p.scale = {1.0, 1.1, 0.9};
  const PoseEstimate e = estimate_pose(p);
  EXPECT_NEAR(e.scale, 0.5 * 1.0 + 0.25 * 1.1 + 0.25 * 0.9, 1e-12);
  EXPECT_NEAR(e.scale_std, std::sqrt(0.25 * 0.01 + 0.25 * 0.01), 1e-12);
}

TEST(PoseEstimate, EmptySet) {
  const PoseEstimate e = estimate_pose(ParticleSet{});
  EXPECT_EQ(e.particles, 0u);
  EXPECT_EQ(e.ess_ratio, 0.0);
}

}  // namespace
}  // namespace floorgrid
