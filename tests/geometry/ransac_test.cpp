#include "floorgrid/geometry/ransac.hpp"

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <numbers>

#include "floorgrid/core/random.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

// The plan points lie in [0, 100] x [0, 60] metres.
constexpr double kWidth = 100.0;
constexpr double kHeight = 60.0;

Eigen::Matrix3d make_transform(TransformKind kind, bool mirrored, double angle) {
  Eigen::Matrix2d linear;
  linear << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  if (kind == TransformKind::similarity)
    linear *= 1.025;
  if (kind == TransformKind::affine)
    linear *= (Eigen::Matrix2d() << 1.02, 0.03, -0.01, 0.97).finished();
  if (mirrored)
    linear.col(1) = -linear.col(1);
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  T.topLeftCorner<2, 2>() = linear;
  T.topRightCorner<2, 1>() = Eigen::Vector2d(12.5, -40.0);
  return T;
}

struct Synthetic {
  ReferencePairs pairs;
  std::vector<bool> is_outlier;
};

// Inliers: T p plus Gaussian noise of `noise` metres per axis. Outliers: a grid point drawn
// uniformly over the image of the plan box grown by 20 m.
Synthetic make_pairs(const Eigen::Matrix3d& T, int count, double outlier_fraction, double noise,
                     std::uint64_t seed) {
  Random random(seed);
  Synthetic s;
  s.pairs.points_in_plan.resize(2, count);
  s.pairs.points_in_grid.resize(2, count);
  s.is_outlier.resize(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d p(random.uniform(0, kWidth), random.uniform(0, kHeight));
    s.pairs.points_in_plan.col(i) = p;
    const bool outlier = random.bernoulli(outlier_fraction);
    s.is_outlier[static_cast<std::size_t>(i)] = outlier;
    if (outlier) {
      const Eigen::Vector2d elsewhere(random.uniform(-20, kWidth + 20),
                                      random.uniform(-20, kHeight + 20));
      s.pairs.points_in_grid.col(i) =
          T.topLeftCorner<2, 2>() * elsewhere + T.topRightCorner<2, 1>();
    } else {
      s.pairs.points_in_grid.col(i) = T.topLeftCorner<2, 2>() * p + T.topRightCorner<2, 1>() +
                                      Eigen::Vector2d(random.normal(noise), random.normal(noise));
    }
  }
  return s;
}

// The largest distance between the two transforms' images over the plan box.
double transform_error(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  double worst = 0.0;
  for (const Eigen::Vector3d& corner :
       {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(kWidth, 0, 1), Eigen::Vector3d(0, kHeight, 1),
        Eigen::Vector3d(kWidth, kHeight, 1)}) {
    worst = std::max(worst, ((a - b) * corner).head<2>().norm());
  }
  return worst;
}

struct Case {
  TransformKind kind;
  bool mirrored;
};

TEST(Ransac, RecoversEveryKindUnder60PercentOutliersWithin1cm) {
  int seed = 100;
  for (const Case c :
       {Case{TransformKind::similarity, false}, Case{TransformKind::similarity, true},
        Case{TransformKind::rigid, false}, Case{TransformKind::rigid, true},
        Case{TransformKind::affine, false}, Case{TransformKind::affine, true}}) {
    SCOPED_TRACE(std::string(transform_kind_name(c.kind)) + (c.mirrored ? " mirrored" : ""));
    const Eigen::Matrix3d truth = make_transform(c.kind, c.mirrored, 0.3 * ++seed);
    const Synthetic data = make_pairs(truth, 5000, 0.6, 0.01, static_cast<std::uint64_t>(seed));
    RansacOptions options;
    options.kind = c.kind;
    options.inlier_threshold = 0.10;  // given: AdaptiveThreshold* test the default
    const RansacResult result = ransac_transform(data.pairs, options);
    ASSERT_TRUE(result.ok) << result.message;
    EXPECT_LT(transform_error(result.estimate.T_grid_plan, truth), 0.01);
    EXPECT_EQ(result.estimate.reflected, c.mirrored);
    EXPECT_NEAR(result.estimate.rms, 0.01 * std::sqrt(2.0), 0.003);
    // Every true inlier is found (4.5 sigma lies inside 0.10 m); few outliers slip in.
    std::size_t found = 0, false_inliers = 0, inliers = 0;
    for (std::size_t i = 0; i < data.is_outlier.size(); ++i) {
      inliers += !data.is_outlier[i];
      found += !data.is_outlier[i] && result.inlier_mask[i];
      false_inliers += data.is_outlier[i] && result.inlier_mask[i];
    }
    EXPECT_EQ(found, inliers);
    EXPECT_LT(false_inliers, inliers / 100);
    EXPECT_EQ(result.inlier_count, found + false_inliers);
    EXPECT_LE(result.refit_passes, options.max_refit_passes);
    EXPECT_FALSE(result.threshold_adaptive);
    EXPECT_EQ(result.inlier_threshold, 0.10);
  }
}

// How many true inliers and outliers `result` marks as inliers.
struct Classification {
  std::size_t inliers = 0, found = 0, outliers = 0, false_inliers = 0;
};

Classification classify(const Synthetic& data, const RansacResult& result) {
  Classification c;
  for (std::size_t i = 0; i < data.is_outlier.size(); ++i) {
    const bool marked = result.inlier_mask[i] != 0;
    if (data.is_outlier[i]) {
      ++c.outliers;
      c.false_inliers += marked;
    } else {
      ++c.inliers;
      c.found += marked;
    }
  }
  return c;
}

TEST(Ransac, AdaptiveThresholdRecoversEveryKindAtCentimetreAndHalfMetreNoise) {
  // 25% gross outliers. The least-squares fit of ~1500 inliers over the 100 x 60 m box is
  // off by about 0.06 sigma at the corners; 0.25 sigma leaves room for the few pairs the
  // threshold cuts. The threshold is 3 sigma: 98.9% of the inliers lie inside it.
  int seed = 200;
  for (const double sigma : {0.02, 0.5}) {
    for (const Case c : {Case{TransformKind::similarity, false}, Case{TransformKind::rigid, true},
                         Case{TransformKind::affine, false}}) {
      SCOPED_TRACE(std::string(transform_kind_name(c.kind)) + " sigma " + std::to_string(sigma));
      const Eigen::Matrix3d truth = make_transform(c.kind, c.mirrored, 0.4 * ++seed);
      const Synthetic data = make_pairs(truth, 2000, 0.25, sigma, static_cast<std::uint64_t>(seed));
      RansacOptions options;
      options.kind = c.kind;
      const RansacResult result = ransac_transform(data.pairs, options);
      ASSERT_TRUE(result.ok) << result.message;
      EXPECT_TRUE(result.threshold_adaptive);
      EXPECT_LT(transform_error(result.estimate.T_grid_plan, truth), 0.25 * sigma);
      EXPECT_EQ(result.estimate.reflected, c.mirrored);
      EXPECT_NEAR(result.noise_sigma, sigma, 0.1 * sigma);
      EXPECT_NEAR(result.inlier_threshold, 3.0 * sigma, 0.3 * sigma);
      const Classification k = classify(data, result);
      EXPECT_GE(static_cast<double>(k.found), 0.97 * static_cast<double>(k.inliers));
      // Outliers spread over the map: within 3 sigma of T p by chance only (~0.1% at 0.5 m).
      EXPECT_LE(static_cast<double>(k.false_inliers), 0.01 * static_cast<double>(k.outliers));
      EXPECT_GT(result.scale_passes, 0);
    }
  }
}

TEST(Ransac, AdaptiveThresholdScalesWithTheNoise) {
  // The same pairs with ten times the noise: ten times the threshold, within the spread of
  // the estimate (the inlier sets differ by the pairs near the cut).
  const Eigen::Matrix3d truth = make_transform(TransformKind::similarity, false, 0.9);
  const RansacResult quiet = ransac_transform(make_pairs(truth, 3000, 0.3, 0.03, 21).pairs);
  const RansacResult noisy = ransac_transform(make_pairs(truth, 3000, 0.3, 0.3, 21).pairs);
  ASSERT_TRUE(quiet.ok && noisy.ok);
  EXPECT_NEAR(noisy.inlier_threshold / quiet.inlier_threshold, 10.0, 0.5);
  EXPECT_NEAR(noisy.noise_sigma / quiet.noise_sigma, 10.0, 0.5);
  EXPECT_NEAR(quiet.inlier_threshold, 0.09, 0.009);
}

TEST(Ransac, AdaptiveThresholdRejectsBlundersAmongFewNoisyPairs) {
  // Hand-picked pairs: 30 with 0.4 m of noise, three of them misplaced by 5 to 8 m.
  const Eigen::Matrix3d truth = make_transform(TransformKind::similarity, false, -1.2);
  Synthetic data = make_pairs(truth, 30, 0.0, 0.4, 22);
  const Eigen::Vector2d blunders[] = {{5.0, 0.0}, {-4.0, 6.0}, {0.0, -8.0}};
  for (int i = 0; i < 3; ++i) {
    data.pairs.points_in_grid.col(7 * i + 3) += blunders[i];
    data.is_outlier[static_cast<std::size_t>(7 * i + 3)] = true;
  }
  const RansacResult result = ransac_transform(data.pairs);
  ASSERT_TRUE(result.ok) << result.message;
  const Classification k = classify(data, result);
  EXPECT_EQ(k.false_inliers, 0u);
  EXPECT_GE(k.found, 25u);
  // 27 inliers: the fit is off by about 0.4 sigma at the corners; an equal share of slack.
  EXPECT_LT(transform_error(result.estimate.T_grid_plan, truth), 0.8 * 0.4);
  EXPECT_GT(result.inlier_threshold, 0.8);
  EXPECT_LT(result.inlier_threshold, 2.0);
}

TEST(Ransac, AdaptiveThresholdOnExactPairsStaysAboveRounding) {
  const Eigen::Matrix3d truth = make_transform(TransformKind::affine, false, 0.3);
  Synthetic data = make_pairs(truth, 500, 0.2, 0.0, 23);
  RansacOptions options;
  options.kind = TransformKind::affine;
  const RansacResult result = ransac_transform(data.pairs, options);
  ASSERT_TRUE(result.ok) << result.message;
  const Classification k = classify(data, result);
  EXPECT_EQ(k.found, k.inliers);
  EXPECT_EQ(k.false_inliers, 0u);
  EXPECT_LT(transform_error(result.estimate.T_grid_plan, truth), 1e-6);
  EXPECT_GT(result.inlier_threshold, 0.0);
  EXPECT_LT(result.inlier_threshold, 1e-3);
}

TEST(Ransac, LargeInputGoesThroughTheSubsets) {
  const Eigen::Matrix3d truth = make_transform(TransformKind::similarity, false, -2.0);
  const Synthetic data = make_pairs(truth, 200000, 0.3, 0.01, 7);
  RansacOptions options;            // 200,000 pairs: scoring on 2,000, verification on 50,000
  options.inlier_threshold = 0.10;  // given: 10 sigma, every inlier inside
  const RansacResult result = ransac_transform(data.pairs, options);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_LT(transform_error(result.estimate.T_grid_plan, truth), 0.002);
  EXPECT_NEAR(static_cast<double>(result.inlier_count), 140000.0, 1500.0);
  EXPECT_LE(result.refit_passes, 3);
  EXPECT_EQ(inlier_indices(result).size(), result.inlier_count);

  // Adaptive: sigma measured on the verification subset, 3 sigma keeps 1 - exp(-4.5) = 98.9%.
  const RansacResult adaptive = ransac_transform(data.pairs);
  ASSERT_TRUE(adaptive.ok) << adaptive.message;
  EXPECT_LT(transform_error(adaptive.estimate.T_grid_plan, truth), 0.002);
  EXPECT_NEAR(adaptive.noise_sigma, 0.01, 0.0002);
  EXPECT_NEAR(static_cast<double>(adaptive.inlier_count), 140000.0 * (1.0 - std::exp(-4.5)),
              1500.0);
  EXPECT_LE(adaptive.refit_passes, 3);
}

TEST(Ransac, DeterministicForASeedWhateverTheThreads) {
  const Eigen::Matrix3d truth = make_transform(TransformKind::similarity, false, 1.0);
  const Synthetic data = make_pairs(truth, 300000, 0.5, 0.02, 8);  // two threads from 2^18
  RansacOptions options;
  options.seed = 42;
  const RansacResult a = ransac_transform(data.pairs, options);
  const RansacResult b = ransac_transform(data.pairs, options);
  options.threads = 1;
  const RansacResult one_thread = ransac_transform(data.pairs, options);
  for (const RansacResult* other : {&b, &one_thread}) {
    EXPECT_EQ(a.estimate.T_grid_plan, other->estimate.T_grid_plan);
    EXPECT_EQ(a.estimate.rms, other->estimate.rms);
    EXPECT_EQ(a.inlier_mask, other->inlier_mask);
    EXPECT_EQ(a.iterations, other->iterations);
  }
  options.seed = 43;
  const RansacResult c = ransac_transform(data.pairs, options);
  EXPECT_LT(transform_error(c.estimate.T_grid_plan, truth), 0.01);
}

TEST(Ransac, AdaptiveIterationCountShrinksWhenOutliersAreFew) {
  EXPECT_EQ(required_iterations(0.5, 2, 0.99, 0, 1000), 17);  // log 0.01 / log 0.75 = 16.0
  EXPECT_EQ(required_iterations(1.0, 2, 0.99, 3, 1000), 3);
  EXPECT_EQ(required_iterations(0.0, 2, 0.99, 3, 1000), 1000);
  EXPECT_EQ(required_iterations(0.01, 3, 0.999, 0, 500), 500);
  const Eigen::Matrix3d truth = make_transform(TransformKind::affine, false, 0.5);
  RansacOptions options;
  options.kind = TransformKind::affine;
  options.min_iterations = 0;
  int previous = 0;
  for (const double outliers : {0.05, 0.3, 0.6}) {
    const RansacResult result =
        ransac_transform(make_pairs(truth, 4000, outliers, 0.01, 9).pairs, options);
    ASSERT_TRUE(result.ok);
    EXPECT_GT(result.iterations, previous) << outliers;
    previous = result.iterations;
  }
  EXPECT_GT(previous, 50);  // 60% outliers, samples of 3: about 105
}

TEST(Ransac, WeightsEnterScoringAndRefit) {
  // Two halves 4 cm apart: both inside the threshold, so the weights decide the refit.
  const Eigen::Matrix3d first = make_transform(TransformKind::rigid, false, 0.2);
  Eigen::Matrix3d second = first;
  second(0, 2) += 0.04;
  Synthetic data = make_pairs(first, 2000, 0.0, 0.0, 10);
  const Synthetic other = make_pairs(second, 2000, 0.0, 0.0, 11);
  data.pairs.points_in_plan.conservativeResize(2, 4000);
  data.pairs.points_in_grid.conservativeResize(2, 4000);
  data.pairs.points_in_plan.rightCols(2000) = other.pairs.points_in_plan;
  data.pairs.points_in_grid.rightCols(2000) = other.pairs.points_in_grid;
  RansacOptions options;
  options.kind = TransformKind::rigid;
  const RansacResult even = ransac_transform(data.pairs, options);
  EXPECT_NEAR(even.estimate.T_grid_plan(0, 2), first(0, 2) + 0.02, 0.002);
  data.pairs.weights = Eigen::VectorXd::Ones(4000);
  data.pairs.weights.tail(2000).setConstant(100.0);
  const RansacResult pulled = ransac_transform(data.pairs, options);
  EXPECT_EQ(pulled.inlier_count, 4000u);
  EXPECT_NEAR(pulled.estimate.T_grid_plan(0, 2), second(0, 2), 0.002);
}

TEST(Ransac, FewPairsUseEveryPairForScoring) {
  const Eigen::Matrix3d truth = make_transform(TransformKind::similarity, true, 2.5);
  Synthetic data = make_pairs(truth, 40, 0.0, 0.005, 12);
  for (int i = 0; i < 8; ++i)
    data.pairs.points_in_grid.col(5 * i) += Eigen::Vector2d(3.0, -2.0);
  const RansacResult result = ransac_transform(data.pairs);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_EQ(result.inlier_count, 32u);
  EXPECT_TRUE(result.estimate.reflected);
  EXPECT_LT(transform_error(result.estimate.T_grid_plan, truth), 0.02);
  for (int i = 0; i < 8; ++i)
    EXPECT_EQ(result.inlier_mask[static_cast<std::size_t>(5 * i)], 0);
}

TEST(Ransac, ReportsNotOkWhenNoHypothesisFindsSupport) {
  Synthetic data = make_pairs(Eigen::Matrix3d::Identity(), 300, 1.0, 0.0, 13);  // all outliers
  RansacOptions options;
  options.kind = TransformKind::rigid;
  options.inlier_threshold = 1e-6;
  const RansacResult result = ransac_transform(data.pairs, options);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("inlier_threshold"), std::string::npos) << result.message;
  EXPECT_TRUE(result.estimate.T_grid_plan.allFinite());
}

TEST(Ransac, DegenerateInputsNamePairs) {
  ReferencePairs same;
  same.points_in_plan = Eigen::Matrix2Xd::Ones(2, 2);
  same.points_in_grid = Eigen::Matrix2Xd::Ones(2, 2);
  test::expect_input_error([&] { ransac_transform(same); }, {"pairs", "distinct"});
  ReferencePairs many_same;  // a thousand copies of one pair
  many_same.points_in_plan = Eigen::Matrix2Xd::Constant(2, 1000, 3.0);
  many_same.points_in_grid = Eigen::Matrix2Xd::Constant(2, 1000, -1.0);
  test::expect_input_error([&] { ransac_transform(many_same); }, {"pairs", "distinct"});
  ReferencePairs one;
  one.points_in_plan = Eigen::Matrix2Xd::Ones(2, 1);
  one.points_in_grid = Eigen::Matrix2Xd::Ones(2, 1);
  test::expect_input_error([&] { ransac_transform(one); }, {"pairs", "at least 2"});

  ReferencePairs line;
  line.points_in_plan.resize(2, 50);
  for (int i = 0; i < 50; ++i)
    line.points_in_plan.col(i) = Eigen::Vector2d(i, 2.0 * i);
  line.points_in_grid = line.points_in_plan;
  RansacOptions affine;
  affine.kind = TransformKind::affine;
  test::expect_input_error([&] { ransac_transform(line, affine); }, {"pairs", "collinear"});
  test::expect_input_error(
      [&] {
        ReferencePairs two = line;
        two.points_in_plan.conservativeResize(2, 2);
        two.points_in_grid.conservativeResize(2, 2);
        ransac_transform(two, affine);
      },
      {"pairs", "at least 3"});

  for (const int count : {30, 100000}) {
    Synthetic data = make_pairs(Eigen::Matrix3d::Identity(), count, 0.2, 0.01, 14);
    data.pairs.points_in_grid(1, count - 3) = std::numeric_limits<double>::quiet_NaN();
    test::expect_input_error([&] { ransac_transform(data.pairs); },
                             {"pairs", "pair " + std::to_string(count - 3), "NaN"});
    data.pairs.points_in_grid(1, count - 3) = 0.0;
    data.pairs.weights = Eigen::VectorXd::Ones(count);
    data.pairs.weights[count - 2] = -1.0;
    test::expect_input_error([&] { ransac_transform(data.pairs); },
                             {"pairs", "pair " + std::to_string(count - 2), "weight"});
    data.pairs.weights.resize(count - 1);
    test::expect_input_error([&] { ransac_transform(data.pairs); }, {"pairs", "mismatched"});
  }
}

TEST(Ransac, BadOptionsNameTheirField) {
  const Synthetic data = make_pairs(Eigen::Matrix3d::Identity(), 30, 0.0, 0.0, 15);
  const auto expect_field = [&](auto change, const char* field) {
    RansacOptions options;
    change(options);
    test::expect_input_error([&] { ransac_transform(data.pairs, options); }, {field});
  };
  expect_field([](RansacOptions& o) { o.inlier_threshold = -1; }, "ransac.inlier_threshold");
  expect_field([](RansacOptions& o) { o.inlier_threshold = std::nan(""); },
               "ransac.inlier_threshold");
  expect_field([](RansacOptions& o) { o.inlier_threshold = 0.0; }, "ransac.inlier_threshold");
  expect_field([](RansacOptions& o) { o.threshold_sigmas = 0.0; }, "ransac.threshold_sigmas");
  expect_field([](RansacOptions& o) { o.search_threshold_fraction = 2.0; },
               "ransac.search_threshold_fraction");
  expect_field([](RansacOptions& o) { o.confidence = 1.0; }, "ransac.confidence");
  expect_field([](RansacOptions& o) { o.max_iterations = 0; }, "ransac.max_iterations");
  expect_field([](RansacOptions& o) { o.min_iterations = 20000; }, "ransac.min_iterations");
  expect_field([](RansacOptions& o) { o.threads = 3; }, "ransac.threads");
  expect_field([](RansacOptions& o) { o.max_refit_passes = 0; }, "ransac.max_refit_passes");
  expect_field([](RansacOptions& o) { o.min_sample_separation = 1.0; },
               "ransac.min_sample_separation");
}

}  // namespace
}  // namespace floorgrid
