#include "floorgrid/simulation/arc_bend.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>

#include "floorgrid/core/random.hpp"
#include "floorgrid/simulation/warp.hpp"
#include "tests/simulation/warp_test_support.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

Eigen::Vector2d axis_point(const ArcBend& bend, double u, double v) {
  const Eigen::Vector2d along(std::cos(bend.axis_angle), std::sin(bend.axis_angle));
  const Eigen::Vector2d normal(-along.y(), along.x());
  return bend.axis_origin + u * along + v * normal;
}

ArcBend random_bend(Random& random, double curvature) {
  ArcBend bend;
  bend.axis_origin = {random.uniform(-50, 50), random.uniform(-50, 50)};
  bend.axis_angle = random.uniform(-std::numbers::pi, std::numbers::pi);
  bend.curvature = curvature;
  return bend;
}

// The least-squares rigid transform taking `from` onto `to` (2D Kabsch: centroids, then the
// angle of the summed cross and dot products).
Pose2 best_rigid_fit(const Eigen::Matrix2Xd& from, const Eigen::Matrix2Xd& to) {
  const Eigen::Vector2d from_mean = from.rowwise().mean();
  const Eigen::Vector2d to_mean = to.rowwise().mean();
  double cross = 0;
  double dot = 0;
  for (Eigen::Index i = 0; i < from.cols(); ++i) {
    const Eigen::Vector2d a = from.col(i) - from_mean;
    const Eigen::Vector2d b = to.col(i) - to_mean;
    cross += a.x() * b.y() - a.y() * b.x();
    dot += a.dot(b);
  }
  const double angle = std::atan2(cross, dot);
  const Eigen::Vector2d t = to_mean - rotation_2d(angle) * from_mean;
  return {t.x(), t.y(), angle};
}

TEST(WarpBend, ZeroCurvatureIsTheIdentity) {
  Random random(11);
  const ArcBend bend = random_bend(random, 0.0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d p(random.uniform(-100, 100), random.uniform(-100, 100));
    EXPECT_LT((bend_point(bend, p) - p).norm(), 1e-12);
    EXPECT_LT((unbend_point(bend, p) - p).norm(), 1e-12);
    EXPECT_LT((bend_jacobian(bend, p) - Eigen::Matrix2d::Identity()).norm(), 1e-15);
  }
  EXPECT_EQ(curvature_for_deviation(0.0, 40.0), 0.0);
}

TEST(WarpBend, NearEndIsUntouched) {
  Random random(12);
  for (const double k : {1.0 / 800.0, -0.01, 0.05}) {
    const ArcBend bend = random_bend(random, k);
    for (const double v : {-10.0, -1.0, 0.0, 2.5, 9.0}) {
      const Eigen::Vector2d p = axis_point(bend, 0.0, v);
      EXPECT_LT((bend_point(bend, p) - p).norm(), 1e-12) << "k " << k << " v " << v;
    }
    // On the axis itself the near end does not even turn or stretch.
    EXPECT_LT((bend_jacobian(bend, bend.axis_origin) - Eigen::Matrix2d::Identity()).norm(), 1e-15);
  }
}

TEST(WarpBend, MatchesTheArcFormula) {
  // The closed form of the design, evaluated directly where it is well conditioned (k u ~ 1).
  Random random(13);
  const double k = 0.02;
  const ArcBend bend = random_bend(random, k);
  const Eigen::Vector2d along(std::cos(bend.axis_angle), std::sin(bend.axis_angle));
  const Eigen::Vector2d normal(-along.y(), along.x());
  for (int i = 0; i < 100; ++i) {
    const double u = random.uniform(0, 100);
    const double v = random.uniform(-25, 25);
    const double u_bent = (1 / k - v) * std::sin(k * u);
    const double v_bent = 1 / k - (1 / k - v) * std::cos(k * u);
    const Eigen::Vector2d expected = bend.axis_origin + u_bent * along + v_bent * normal;
    EXPECT_LT((bend_point(bend, axis_point(bend, u, v)) - expected).norm(), 1e-10);
  }
}

TEST(WarpBend, AnalyticInverseIsExact) {
  Random random(14);
  for (const double k : {1e-9, 1.0 / 800.0, -1e-4, 0.02, -0.02}) {
    const ArcBend bend = random_bend(random, k);
    double worst = 0;
    for (int i = 0; i < 1000; ++i) {
      // Up to k u = 2 rad and |k v| = 0.5: far beyond any building, still one-to-one.
      const double u = random.uniform(-100, 100);
      const double v = random.uniform(-25, 25);
      const Eigen::Vector2d p = axis_point(bend, u, v);
      worst = std::max(worst, (unbend_point(bend, bend_point(bend, p)) - p).norm());
    }
    EXPECT_LT(worst, 1e-12) << "k " << k;
  }
}

TEST(WarpBend, JacobianMatchesFiniteDifferences) {
  Random random(15);
  const ArcBend bend = random_bend(random, 0.01);
  const auto f = [&](const Eigen::Vector2d& p) { return bend_point(bend, p); };
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector2d p = axis_point(bend, random.uniform(0, 100), random.uniform(-25, 25));
    const Eigen::Matrix2d J = bend_jacobian(bend, p);
    EXPECT_LT((J - test::central_difference_jacobian(f, p)).norm(), 1e-6 * J.norm());
  }
}

TEST(WarpBend, CurvatureForDeviationInvertsTheDeviation) {
  for (const double length : {1.0, 40.0, 100.0}) {
    for (const double ratio : {1e-12, 1e-6, 0.005, 0.025, 0.1, 0.5, 0.72, 0.7246113537767085}) {
      for (const double sign : {1.0, -1.0}) {
        const double deviation = sign * ratio * length;
        const double k = curvature_for_deviation(deviation, length);
        EXPECT_NEAR(bend_deviation(k, length), deviation, 1e-14 * length)
            << "length " << length << " ratio " << ratio;
        EXPECT_EQ(std::signbit(k), sign < 0);
        EXPECT_LE(std::abs(k) * length, 2.3311223704144224 + 1e-12);  // the increasing branch
      }
    }
  }
  // Small bends: k ≈ 2 deviation / L².
  EXPECT_NEAR(curvature_for_deviation(0.2, 40.0), 2 * 0.2 / (40.0 * 40.0), 1e-4 * 2.5e-4);
}

TEST(WarpBend, CurvatureForDeviationRejectsImpossibleBends) {
  test::expect_input_error([] { curvature_for_deviation(30.0, 40.0); }, {"bend.deviation"});
  test::expect_input_error([] { curvature_for_deviation(0.2, 0.0); }, {"bend.length", "got 0"});
  test::expect_input_error(
      [] { curvature_for_deviation(std::numeric_limits<double>::quiet_NaN(), 40.0); },
      {"bend.deviation"});
}

struct BendCase {
  std::string name;
  double length;      // metres along the axis
  double width;       // metres across it
  double deviation;   // metres at the far end
  double max_strain;  // the SPEC's bound for the preset
};

// Names the case in test listings instead of gtest's byte dump.
void PrintTo(const BendCase& c, std::ostream* out) {
  *out << c.name;
}

class WarpBendPreset : public ::testing::TestWithParam<BendCase> {};

// The far end deviates by the requested amount, and the whole warp (rigid + bend) stretches the
// building by no more than the preset allows: measured from the singular values of the
// Jacobian over the whole building, axis through its middle.
TEST_P(WarpBendPreset, DeviationAndStrainAsSpecified) {
  const BendCase& c = GetParam();
  Random random(16);
  WarpParams params;
  params.T_grid_world = {random.uniform(-20, 20), random.uniform(-20, 20),
                         random.uniform(-std::numbers::pi, std::numbers::pi)};
  params.bend = random_bend(random, curvature_for_deviation(c.deviation, c.length));
  const SimulatedWarp warp(params);
  const ArcBend& bend = params.bend;

  // Far end on the axis against where the rigid transform of the near end puts it.
  const Eigen::Vector2d far_end = axis_point(bend, c.length, 0.0);
  const Eigen::Vector2d offset =
      warp.world_to_grid(far_end) - params.T_grid_world.transform(far_end);
  const Eigen::Vector2d normal_in_grid =
      params.T_grid_world.rotation() *
      Eigen::Vector2d(-std::sin(bend.axis_angle), std::cos(bend.axis_angle));
  const double sideways = offset.dot(normal_in_grid);
  EXPECT_NEAR(sideways, c.deviation, 1e-9);

  double strain = 0;
  Eigen::Matrix2Xd points_in_world(2, 0);
  const int nu = static_cast<int>(c.length / 0.5) + 1;
  const int nv = static_cast<int>(c.width / 0.5) + 1;
  points_in_world.resize(2, nu * nv);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const Eigen::Vector2d p = axis_point(bend, 0.5 * i, -0.5 * c.width + 0.5 * j);
      points_in_world.col(i * nv + j) = p;
      strain = std::max(strain, test::principal_strain(warp.jacobian(p)));
    }
  }
  EXPECT_LE(strain, c.max_strain);
  EXPECT_NEAR(strain, max_strain(bend.curvature, 0.5 * c.width), 1e-9);

  // For the record: the far end against the best rigid fit of the whole building.
  const Pose2 fit = best_rigid_fit(points_in_world, warp.world_to_grid_batch(points_in_world));
  const Eigen::Vector2d fitted_far = fit.transform(far_end);
  std::cout << "[ info     ] " << c.name << ": k = " << bend.curvature << " 1/m, far end sideways "
            << sideways << " m, total " << offset.norm() << " m, from the best rigid fit "
            << (warp.world_to_grid(far_end) - fitted_far).norm() << " m, max strain "
            << 100 * strain << " %\n";
}

INSTANTIATE_TEST_SUITE_P(WarpPresets, WarpBendPreset,
                         ::testing::Values(BendCase{"office", 40, 20, 0.2, 0.003},
                                           BendCase{"warehouse", 100, 50, 0.5, 0.003},
                                           BendCase{"bent_office", 40, 20, 1.0, 0.015}),
                         [](const auto& test_info) { return test_info.param.name; });

}  // namespace
}  // namespace floorgrid
