#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <set>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/gaussian_process.hpp"
#include "floorgrid/mapping/gp_tuning.hpp"
#include "tests/mapping/gaussian_process_test_support.hpp"

namespace floorgrid {
namespace {

using test::gp_sample;
using test::hyperparameters;
using test::uniform_points;

struct Case {
  GpHyperparameters truth;
  double width, height;
  std::uint64_t seed;
};

void PrintTo(const Case& c, std::ostream* out) {
  *out << c.width << "x" << c.height << "m_l" << c.truth.length_scale.x() << "x"
       << c.truth.length_scale.y() << "_sf" << c.truth.signal_std << "_sn" << c.truth.noise_std;
}

class GaussianProcessTuning : public ::testing::TestWithParam<Case> {};

TEST_P(GaussianProcessTuning, RecoversTheLengthScalesOfItsOwnPrior) {
  const Case c = GetParam();
  Random random(c.seed);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 400, c.width, c.height);
  const Eigen::Matrix2Xd outputs = gp_sample(random, c.truth, inputs);
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs);
  const GpHyperparameters& tuned = fit.summary.hyperparameters;
  for (int d = 0; d < 2; ++d) {
    const double ratio = tuned.length_scale[d] / c.truth.length_scale[d];
    EXPECT_GT(ratio, 1.0 / 1.5) << "axis " << d << ": " << tuned.length_scale.transpose();
    EXPECT_LT(ratio, 1.5) << "axis " << d << ": " << tuned.length_scale.transpose();
  }
  // The noise is well determined by 800 residuals, the signal std less so.
  EXPECT_NEAR(std::log(tuned.noise_std / c.truth.noise_std), 0.0, std::log(1.5));
  EXPECT_NEAR(std::log(tuned.signal_std / c.truth.signal_std), 0.0, std::log(2.0));
  EXPECT_TRUE(fit.summary.at_bounds.empty()) << fit.summary.message;
  // RPROP improved on its start and the reported value is the subsample's likelihood.
  ASSERT_FALSE(fit.summary.history.empty());
  EXPECT_GE(fit.summary.tuning_log_marginal_likelihood, fit.summary.history.front());
  EXPECT_EQ(fit.summary.tuning_points, 400);
  // All 400 points were the subsample: one likelihood, computed on two paths.
  EXPECT_NEAR(fit.summary.tuning_log_marginal_likelihood, fit.summary.log_marginal_likelihood,
              1e-9 * std::abs(fit.summary.log_marginal_likelihood));
}

INSTANTIATE_TEST_SUITE_P(
    GaussianProcess, GaussianProcessTuning,
    ::testing::Values(Case{hyperparameters(3.0, 6.0, 0.5, 0.05), 40.0, 20.0, 1},
                      Case{hyperparameters(4.0, 4.0, 0.2, 0.01), 40.0, 20.0, 2},
                      Case{hyperparameters(8.0, 5.0, 1.0, 0.05), 100.0, 50.0, 3}));

TEST(GaussianProcessTuningReport, SaysWhatWasDone) {
  Random random(31);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 1000, 60.0, 30.0);
  const Eigen::Matrix2Xd outputs = gp_sample(random, hyperparameters(5, 5, 0.3, 0.02), inputs);
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs);
  const GaussianProcessSummary& s = fit.summary;
  EXPECT_TRUE(s.tuned);
  EXPECT_EQ(s.training_points, 1000);
  EXPECT_EQ(s.tuning_points, 400);
  EXPECT_GE(s.iterations, 2);
  EXPECT_LE(s.iterations, 100);
  EXPECT_EQ(s.history.size(), static_cast<std::size_t>(s.iterations));
  EXPECT_TRUE(std::isfinite(s.log_marginal_likelihood));
  EXPECT_NE(s.log_marginal_likelihood, s.tuning_log_marginal_likelihood);
  EXPECT_EQ(s.jitter, 0.0);
  EXPECT_GT(s.lattice_nodes, 0);
  EXPECT_LE(s.lattice_error, 0.5e-3);
  EXPECT_NE(s.message.find("tuned on 400 of 1000 points"), std::string::npos) << s.message;
  // The bounds hold the result, and the converged flag says whether the tolerance was met.
  for (int d = 0; d < 2; ++d) {
    EXPECT_GE(s.hyperparameters.length_scale[d], s.bounds.lower.length_scale[d]);
    EXPECT_LE(s.hyperparameters.length_scale[d], s.bounds.upper.length_scale[d]);
  }
  if (s.converged) {
    ASSERT_GE(s.history.size(), 2u);
    EXPECT_LT(std::abs(s.history[s.history.size() - 1] - s.history[s.history.size() - 2]), 1e-4);
  } else {
    EXPECT_EQ(s.iterations, 100);
  }
}

TEST(GaussianProcessTuningBounds, FollowTheDataAndTheOptions) {
  // A 4 x 4 grid with 2 m spacing over 6 x 6 m; outputs +-1 (RMS 1).
  Eigen::Matrix2Xd points(2, 16), outputs(2, 16);
  for (int i = 0; i < 16; ++i) {
    points.col(i) << 2.0 * (i % 4), 2.0 * (i / 4);
    outputs.col(i) << ((i % 2) ? 1.0 : -1.0), ((i / 2) % 2 ? 1.0 : -1.0);
  }
  const GpTuningOptions options;
  const GpHyperparameterBounds b = gp_hyperparameter_bounds(points, points, outputs, options);
  EXPECT_DOUBLE_EQ(b.lower.length_scale.x(), 2.0);   // the spacing
  EXPECT_DOUBLE_EQ(b.upper.length_scale.y(), 60.0);  // 10 x the extent
  EXPECT_DOUBLE_EQ(b.lower.noise_std, 1e-4);
  EXPECT_DOUBLE_EQ(b.upper.noise_std, 1.0);
  EXPECT_DOUBLE_EQ(b.upper.signal_std, 100.0);
}

TEST(GaussianProcessTuningSubsample, IsSpreadAndDeterministic) {
  // 1000 points in a 1 m cluster and 10 isolated points far apart: a spread subsample of 30
  // takes every isolated point.
  Random random(37);
  Eigen::Matrix2Xd points(2, 1010);
  points.leftCols(1000) = uniform_points(random, 1000, 1.0, 1.0);
  for (int i = 0; i < 10; ++i)
    points.col(1000 + i) << 20.0 + 10.0 * i, (i % 2) ? 30.0 : -30.0;
  const std::vector<Eigen::Index> chosen = gp_spread_subsample(points, 30);
  ASSERT_EQ(chosen.size(), 30u);
  const std::set<Eigen::Index> unique(chosen.begin(), chosen.end());
  EXPECT_EQ(unique.size(), 30u);
  for (Eigen::Index i = 1000; i < 1010; ++i)
    EXPECT_TRUE(unique.count(i)) << i;
  EXPECT_EQ(gp_spread_subsample(points, 30), chosen);
  EXPECT_EQ(gp_spread_subsample(points, 5000).size(), 1010u);
}

}  // namespace
}  // namespace floorgrid
