#include "floorgrid/geometry/transform_estimation.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <numbers>

#include "floorgrid/core/random.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

constexpr double kExtent = 100.0;  // metres: the plan points lie in [0, 100] x [0, 60]

Eigen::Matrix2Xd random_plan_points(Random& random, int count) {
  Eigen::Matrix2Xd points(2, count);
  for (int i = 0; i < count; ++i) {
    points.col(i) = Eigen::Vector2d(random.uniform(0.0, kExtent), random.uniform(0.0, 60.0));
  }
  return points;
}

// A random transform of `kind`, mirrored (det < 0) when asked.
Eigen::Matrix3d random_transform(Random& random, TransformKind kind, bool mirrored) {
  Eigen::Matrix2d linear;
  if (kind == TransformKind::affine) {
    do {
      linear << random.uniform(-2, 2), random.uniform(-2, 2), random.uniform(-2, 2),
          random.uniform(-2, 2);
    } while (std::abs(linear.determinant()) < 0.3 || (linear.determinant() < 0) != mirrored);
  } else {
    const double angle = random.uniform(-std::numbers::pi, std::numbers::pi);
    const double scale = kind == TransformKind::similarity ? random.uniform(0.5, 2.0) : 1.0;
    linear << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    linear *= scale;
    if (mirrored)
      linear.col(1) = -linear.col(1);
  }
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  T.topLeftCorner<2, 2>() = linear;
  T.topRightCorner<2, 1>() = Eigen::Vector2d(random.uniform(-50, 50), random.uniform(-50, 50));
  return T;
}

Eigen::Matrix2Xd apply(const Eigen::Matrix3d& T, const Eigen::Matrix2Xd& points) {
  return (T.topLeftCorner<2, 2>() * points).colwise() + T.topRightCorner<2, 1>();
}

// The largest distance between the two transforms' images over the box [0, 100] x [0, 60]
// (their difference is affine, so it is largest at a corner).
double transform_error(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  double worst = 0.0;
  for (const Eigen::Vector3d& corner :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(kExtent, 0, 1), Eigen::Vector3d(0, 60, 1),
        Eigen::Vector3d(kExtent, 60, 1)}) {
    worst = std::max(worst, ((a - b) * corner).head<2>().norm());
  }
  return worst;
}

struct Case {
  TransformKind kind;
  bool mirrored;
};

TEST(TransformEstimation, RecoversRandomTransformsExactlyIncludingMirrors) {
  Random random(11);
  for (const Case c :
       {Case{TransformKind::similarity, false}, Case{TransformKind::similarity, true},
        Case{TransformKind::rigid, false}, Case{TransformKind::rigid, true},
        Case{TransformKind::affine, false}, Case{TransformKind::affine, true}}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Matrix3d truth = random_transform(random, c.kind, c.mirrored);
      const Eigen::Matrix2Xd plan = random_plan_points(random, 3 + trial);
      const TransformEstimate e = estimate_transform(plan, apply(truth, plan), {c.kind});
      SCOPED_TRACE(std::string(transform_kind_name(c.kind)) + (c.mirrored ? " mirrored" : ""));
      EXPECT_LT(transform_error(e.T_grid_plan, truth), 1e-10 * kExtent);
      EXPECT_LT(e.rms, 1e-10 * kExtent);
      EXPECT_EQ(e.reflected, c.mirrored);
      EXPECT_NEAR(e.scale, std::sqrt(std::abs(truth.topLeftCorner<2, 2>().determinant())), 1e-12);
      EXPECT_EQ(e.T_grid_plan.row(2), Eigen::RowVector3d(0, 0, 1));
    }
  }
}

TEST(TransformEstimation, TwoPairsDetermineASimilarity) {
  Random random(12);
  for (const bool mirrored : {false, true}) {
    const Eigen::Matrix3d truth = random_transform(random, TransformKind::similarity, mirrored);
    const Eigen::Matrix2Xd plan = random_plan_points(random, 2);
    const Eigen::Matrix2Xd grid = apply(truth, plan);
    // Two points fit a proper and a mirrored similarity equally: `allow` keeps the proper one.
    const TransformEstimate any = estimate_transform(plan, grid);
    EXPECT_FALSE(any.reflected);
    EXPECT_LT(any.rms, 1e-10 * kExtent);
    const TransformEstimate forced =
        estimate_transform(plan, grid, {TransformKind::similarity, Reflection::require});
    EXPECT_TRUE(forced.reflected);
    EXPECT_LT(forced.rms, 1e-10 * kExtent);
    const TransformEstimate& same_hand = mirrored ? forced : any;
    EXPECT_LT((apply(same_hand.T_grid_plan, plan) - grid).norm(), 1e-10 * kExtent);
  }
}

TEST(TransformEstimation, ForbiddenReflectionFitsTheBestProperTransform) {
  Random random(13);
  const Eigen::Matrix3d truth = random_transform(random, TransformKind::rigid, true);
  const Eigen::Matrix2Xd plan = random_plan_points(random, 30);
  const TransformEstimate e =
      estimate_transform(plan, apply(truth, plan), {TransformKind::rigid, Reflection::forbid});
  EXPECT_FALSE(e.reflected);
  EXPECT_GT(e.rms, 1.0);  // a mirrored building cannot be fitted without the mirror
  EXPECT_NEAR((e.T_grid_plan.topLeftCorner<2, 2>().determinant()), 1.0, 1e-12);
}

TEST(TransformEstimation, RigidIgnoresScaleAndSimilarityRecoversIt) {
  Random random(14);
  Eigen::Matrix3d truth = random_transform(random, TransformKind::rigid, false);
  truth.topLeftCorner<2, 2>() *= 1.03;  // a plan drawn 3% small
  const Eigen::Matrix2Xd plan = random_plan_points(random, 40);
  const Eigen::Matrix2Xd grid = apply(truth, plan);
  const TransformEstimate rigid = estimate_transform(plan, grid, {TransformKind::rigid});
  EXPECT_EQ(rigid.scale, 1.0);
  EXPECT_NEAR((rigid.T_grid_plan.topLeftCorner<2, 2>().determinant()), 1.0, 1e-12);
  EXPECT_GT(rigid.rms, 0.1);
  const TransformEstimate similarity = estimate_transform(plan, grid);
  EXPECT_NEAR(similarity.scale, 1.03, 1e-12);
  EXPECT_LT(similarity.rms, 1e-10 * kExtent);
}

TEST(TransformEstimation, HeavilyWeightedPairsPullTheFit) {
  Random random(15);
  // Rigid, so that every kind can fit each half exactly.
  const Eigen::Matrix3d first = random_transform(random, TransformKind::rigid, false);
  Eigen::Matrix3d second = first;
  second.topRightCorner<2, 1>() += Eigen::Vector2d(1.0, -0.5);  // the other half is shifted
  const Eigen::Matrix2Xd plan = random_plan_points(random, 40);
  Eigen::Matrix2Xd grid(2, 40);
  grid.leftCols(20) = apply(first, plan.leftCols(20));
  grid.rightCols(20) = apply(second, plan.rightCols(20));
  for (const TransformKind kind :
       {TransformKind::similarity, TransformKind::rigid, TransformKind::affine}) {
    Eigen::VectorXd weights = Eigen::VectorXd::Ones(40);
    const double unweighted =
        transform_error(estimate_transform(plan, grid, weights, {kind}).T_grid_plan, first);
    weights.head(20).setConstant(1000.0);
    const double pulled =
        transform_error(estimate_transform(plan, grid, weights, {kind}).T_grid_plan, first);
    EXPECT_GT(unweighted, 0.3);
    EXPECT_LT(pulled, 0.01);
    // A zero weight removes a pair exactly.
    weights.head(20).setConstant(0.0);
    const TransformEstimate only_second = estimate_transform(plan, grid, weights, {kind});
    EXPECT_LT(transform_error(only_second.T_grid_plan, second), 1e-10 * kExtent);
    EXPECT_LT(only_second.rms, 1e-10 * kExtent);
  }
}

TEST(TransformEstimation, WeightedRmsIsTheWeightedResidual) {
  Eigen::Matrix2Xd plan(2, 4), grid(2, 4);
  plan << 0, 10, 10, 0, 0, 0, 10, 10;
  grid = plan;
  grid(0, 0) += 0.2;  // one pair off by 0.2 m
  Eigen::VectorXd weights(4);
  weights << 3, 1, 1, 1;
  const TransformEstimate e = estimate_transform(plan, grid, weights, {TransformKind::rigid});
  const Eigen::Matrix2Xd residual = apply(e.T_grid_plan, plan) - grid;
  double sum = 0.0;
  for (int i = 0; i < 4; ++i)
    sum += weights[i] * residual.col(i).squaredNorm();
  EXPECT_NEAR(e.rms, std::sqrt(sum / weights.sum()), 1e-14);
  EXPECT_GT(e.rms, 0.01);
}

TEST(TransformEstimation, MomentsAboutAnyOriginGiveTheSameFit) {
  Random random(16);
  const Eigen::Matrix3d truth = random_transform(random, TransformKind::affine, false);
  const Eigen::Matrix2Xd plan = random_plan_points(random, 50);
  Eigen::Matrix2Xd grid = apply(truth, plan);
  for (Eigen::Index i = 0; i < grid.cols(); ++i)
    grid.col(i) += Eigen::Vector2d(random.normal(0.01), random.normal(0.01));
  for (const TransformKind kind :
       {TransformKind::similarity, TransformKind::rigid, TransformKind::affine}) {
    PairMoments moments;
    moments.origin_in_plan = {37.0, -12.0};
    moments.origin_in_grid = {-5.0, 80.0};
    PairMoments second_half = moments;
    for (Eigen::Index i = 0; i < 25; ++i)
      moments.add(plan.col(i), grid.col(i));
    for (Eigen::Index i = 25; i < 50; ++i)
      second_half.add(plan.col(i), grid.col(i));
    moments += second_half;
    const std::optional<TransformEstimate> from_moments = fit_transform(moments, {kind});
    ASSERT_TRUE(from_moments.has_value());
    const TransformEstimate direct = estimate_transform(plan, grid, {kind});
    EXPECT_LT((from_moments->T_grid_plan - direct.T_grid_plan).norm(), 1e-12);
    EXPECT_NEAR(from_moments->rms, direct.rms, 1e-9);
  }
}

TEST(TransformEstimation, FarFromTheOriginStaysAccurate) {
  Random random(17);
  Eigen::Matrix3d truth = random_transform(random, TransformKind::similarity, false);
  truth.topRightCorner<2, 1>() += Eigen::Vector2d(3e5, -2e5);
  const Eigen::Matrix2Xd plan = (random_plan_points(random, 100).array() + 1e5).matrix();
  const TransformEstimate e = estimate_transform(plan, apply(truth, plan));
  const Eigen::Matrix2Xd error = apply(e.T_grid_plan, plan) - apply(truth, plan);
  EXPECT_LT(error.colwise().norm().maxCoeff(), 1e-9 * kExtent);
}

TEST(TransformEstimation, DegenerateInputNamesPairs) {
  Eigen::Matrix2Xd same(2, 2), line(2, 3), grid3(2, 3);
  same << 1, 1, 2, 2;
  line << 0, 1, 2, 0, 1, 2;
  grid3 << 0, 1, 0, 0, 0, 1;
  for (const TransformKind kind : {TransformKind::similarity, TransformKind::rigid}) {
    test::expect_input_error([&] { estimate_transform(same, same, {kind}); },
                             {"pairs", "distinct"});
    test::expect_input_error(
        [&] { estimate_transform(same.leftCols(1), same.leftCols(1), {kind}); },
        {"pairs", "at least 2"});
  }
  test::expect_input_error([&] { estimate_transform(line, grid3, {TransformKind::affine}); },
                           {"pairs", "collinear"});
  test::expect_input_error(
      [&] { estimate_transform(line.leftCols(2), grid3.leftCols(2), {TransformKind::affine}); },
      {"pairs", "at least 3"});
  // The grid points coincide: no similarity or rotation.
  Eigen::Matrix2Xd one_point = Eigen::Matrix2Xd::Zero(2, 3);
  test::expect_input_error([&] { estimate_transform(grid3, one_point); }, {"pairs", "coincide"});

  Eigen::Matrix2Xd with_nan = grid3;
  with_nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  test::expect_input_error([&] { estimate_transform(with_nan, grid3); },
                           {"pairs", "pair 2", "NaN"});
  test::expect_input_error([&] { estimate_transform(grid3, with_nan, {TransformKind::affine}); },
                           {"pairs", "NaN"});
  Eigen::Matrix2Xd with_inf = grid3;
  with_inf(0, 0) = std::numeric_limits<double>::infinity();
  test::expect_input_error([&] { estimate_transform(with_inf, grid3); }, {"pairs", "pair 0"});

  Eigen::VectorXd weights(3);
  weights << 1, -1, 1;
  test::expect_input_error([&] { estimate_transform(grid3, grid3, weights); },
                           {"pairs", "pair 1", "weight"});
  weights << 0, 0, 0;
  test::expect_input_error([&] { estimate_transform(grid3, grid3, weights); },
                           {"pairs", "positive weight"});
  weights << 0, 0, 1;  // one point left with weight: too few for a similarity
  test::expect_input_error([&] { estimate_transform(grid3, grid3, weights); },
                           {"pairs", "distinct"});
  test::expect_input_error([&] { estimate_transform(grid3, grid3, Eigen::VectorXd::Ones(2)); },
                           {"pairs", "mismatched"});
  test::expect_input_error([&] { estimate_transform(grid3, grid3.leftCols(2)); },
                           {"pairs", "mismatched"});
}

TEST(TransformEstimation, DegeneracyReasonIsEmptyForGoodMoments) {
  PairMoments moments;
  moments.add({0, 0}, {1, 1});
  EXPECT_NE(degeneracy_reason(moments, {}), "");
  EXPECT_FALSE(fit_transform(moments, {}).has_value());
  moments.add({1, 0}, {2, 1});
  EXPECT_EQ(degeneracy_reason(moments, {}), "");
  EXPECT_NE(degeneracy_reason(moments, {TransformKind::affine}), "");
  moments.add({0, 1}, {1, 2});
  EXPECT_EQ(degeneracy_reason(moments, {TransformKind::affine}), "");
  const std::optional<TransformEstimate> e = fit_transform(moments, {TransformKind::affine});
  ASSERT_TRUE(e.has_value());
  EXPECT_LT((e->T_grid_plan.topRightCorner<2, 1>() - Eigen::Vector2d(1, 1)).norm(), 1e-12);
}

TEST(TransformEstimation, KindNamesAndSampleSizes) {
  EXPECT_STREQ(transform_kind_name(TransformKind::similarity), "similarity");
  EXPECT_STREQ(transform_kind_name(TransformKind::rigid), "rigid");
  EXPECT_STREQ(transform_kind_name(TransformKind::affine), "affine");
  EXPECT_EQ(minimal_sample_size(TransformKind::similarity), 2);
  EXPECT_EQ(minimal_sample_size(TransformKind::rigid), 2);
  EXPECT_EQ(minimal_sample_size(TransformKind::affine), 3);
}

}  // namespace
}  // namespace floorgrid
