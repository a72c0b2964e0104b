#include "floorgrid/mapping/gaussian_process.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/gp_likelihood.hpp"
#include "tests/mapping/gaussian_process_test_support.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

using test::gp_sample;
using test::hyperparameters;
using test::uniform_points;

GaussianProcessOptions given(const GpHyperparameters& h) {
  GaussianProcessOptions options;
  options.hyperparameters = h;
  return options;
}

TEST(GaussianProcessKernel, MatchesTheSquaredExponentialWithNoise) {
  const GpHyperparameters h = hyperparameters(2.0, 0.5, 1.5, 0.1);
  const Eigen::Vector2d a(1.0, 2.0), b(2.0, 1.5);
  // dx / lx = 0.5, dy / ly = 1: exponent -1/2 (0.25 + 1).
  EXPECT_NEAR(gp_signal_covariance(h, a, b), 2.25 * std::exp(-0.625), 1e-15);
  Eigen::Matrix2Xd points(2, 2);
  points << a, b;
  const Eigen::MatrixXd k = gp_training_covariance(h, points, 0.5);
  EXPECT_NEAR(k(0, 0), 2.25 + 0.01 + 0.5, 1e-15);
  EXPECT_NEAR(k(0, 1), 2.25 * std::exp(-0.625), 1e-15);
  EXPECT_EQ(k(0, 1), k(1, 0));
  const Eigen::Vector4d log_h = h.to_log();
  const GpHyperparameters back = GpHyperparameters::from_log(log_h);
  EXPECT_NEAR(back.length_scale.x(), 2.0, 1e-15);
  EXPECT_NEAR(back.noise_std, 0.1, 1e-16);
}

TEST(GaussianProcessLikelihood, GradientMatchesCentralDifferences) {
  Random random(7);
  const Eigen::Matrix2Xd points = uniform_points(random, 40, 20.0, 10.0);
  Eigen::Matrix2Xd outputs(2, 40);
  for (Eigen::Index i = 0; i < outputs.size(); ++i)
    outputs.data()[i] = random.normal(0.3);
  outputs = outputs.colwise() - outputs.rowwise().mean();
  const GpMarginalLikelihood likelihood(points, outputs);
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::Vector4d log_h(
        std::log(random.uniform(1.0, 8.0)), std::log(random.uniform(1.0, 8.0)),
        std::log(random.uniform(0.1, 2.0)), std::log(random.uniform(0.01, 0.3)));
    const GpLikelihoodValue analytic = likelihood.value_and_gradient(log_h);
    ASSERT_TRUE(analytic.ok);
    EXPECT_EQ(analytic.value, likelihood.value(log_h).value);
    for (int d = 0; d < 4; ++d) {
      const double step = 1e-5;
      Eigen::Vector4d plus = log_h, minus = log_h;
      plus[d] += step;
      minus[d] -= step;
      const double numeric =
          (likelihood.value(plus).value - likelihood.value(minus).value) / (2.0 * step);
      EXPECT_NEAR(analytic.gradient[d], numeric, 1e-5 * std::max(std::abs(numeric), 1.0))
          << "trial " << trial << ", parameter " << d;
    }
  }
}

// The three-point GP of eq. 3.21-3.23 written out: K by the kernel's definition, its inverse by
// cofactors and its determinant by Sarrus' rule.
TEST(GaussianProcessClosedForm, ThreePointsComputedByHand) {
  const double lx = 1.2, ly = 0.8, sf = 1.5, sn = 0.3;
  const double px[3] = {0.0, 1.0, -0.5}, py[3] = {0.0, 0.5, 2.0};
  const double y[2][3] = {{1.0, 2.0, 4.0}, {-1.0, 0.5, 3.0}};
  const auto kernel = [&](double ax, double ay, double bx, double by) {
    return sf * sf *
           std::exp(-0.5 * ((ax - bx) * (ax - bx) / (lx * lx) + (ay - by) * (ay - by) / (ly * ly)));
  };
  double k[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      k[i][j] = kernel(px[i], py[i], px[j], py[j]) + (i == j ? sn * sn : 0);
  }
  const double det = k[0][0] * k[1][1] * k[2][2] + k[0][1] * k[1][2] * k[2][0] +
                     k[0][2] * k[1][0] * k[2][1] - k[0][2] * k[1][1] * k[2][0] -
                     k[0][0] * k[1][2] * k[2][1] - k[0][1] * k[1][0] * k[2][2];
  double inv[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      // inv = adj / det; adj(i, j) is the cofactor of (j, i).
      const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
      inv[i][j] = (k[r0][c0] * k[r1][c1] - k[r0][c1] * k[r1][c0]) / det;
    }
  }
  const double qx = 0.4, qy = 0.7;
  double ks[3];
  for (int i = 0; i < 3; ++i)
    ks[i] = kernel(qx, qy, px[i], py[i]);

  double expected_mean[2],
      expected_log_likelihood = -std::log(det) - 3.0 * std::log(2 * std::numbers::pi);
  double expected_jacobian[2][2] = {{0, 0}, {0, 0}};
  for (int c = 0; c < 2; ++c) {
    const double m = (y[c][0] + y[c][1] + y[c][2]) / 3.0;
    double alpha[3];
    for (int i = 0; i < 3; ++i) {
      alpha[i] = 0.0;
      for (int j = 0; j < 3; ++j)
        alpha[i] += inv[i][j] * (y[c][j] - m);
    }
    expected_mean[c] = m;
    for (int i = 0; i < 3; ++i) {
      expected_mean[c] += ks[i] * alpha[i];
      expected_log_likelihood -= 0.5 * (y[c][i] - m) * alpha[i];
      expected_jacobian[c][0] -= alpha[i] * ks[i] * (qx - px[i]) / (lx * lx);
      expected_jacobian[c][1] -= alpha[i] * ks[i] * (qy - py[i]) / (ly * ly);
    }
  }
  double expected_variance = sf * sf;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      expected_variance -= ks[i] * inv[i][j] * ks[j];
  }

  Eigen::Matrix2Xd inputs(2, 3), outputs(2, 3);
  inputs << px[0], px[1], px[2], py[0], py[1], py[2];
  outputs << y[0][0], y[0][1], y[0][2], y[1][0], y[1][1], y[1][2];
  const GaussianProcessFit fit =
      fit_gaussian_process(inputs, outputs, given(hyperparameters(lx, ly, sf, sn)));
  const Eigen::Vector2d q(qx, qy);
  const Eigen::Vector2d mean = fit.model.exact_mean(q);
  EXPECT_NEAR(mean[0], expected_mean[0], 1e-12);
  EXPECT_NEAR(mean[1], expected_mean[1], 1e-12);
  EXPECT_NEAR(fit.model.standard_deviation(q), std::sqrt(expected_variance), 1e-12);
  EXPECT_NEAR(fit.model.standard_deviation(q, true), std::sqrt(expected_variance + sn * sn), 1e-12);
  EXPECT_NEAR(fit.summary.log_marginal_likelihood, expected_log_likelihood, 1e-12);
  const Eigen::Matrix2d jacobian = fit.model.exact_mean_jacobian(q);
  for (int c = 0; c < 2; ++c) {
    for (int d = 0; d < 2; ++d)
      EXPECT_NEAR(jacobian(c, d), expected_jacobian[c][d], 1e-12);
  }
  EXPECT_EQ(fit.summary.jitter, 0.0);
  EXPECT_FALSE(fit.summary.tuned);
  // The likelihood class agrees with the closed form too.
  const GpMarginalLikelihood likelihood(inputs, outputs.colwise() - outputs.rowwise().mean());
  EXPECT_NEAR(likelihood.value(hyperparameters(lx, ly, sf, sn).to_log()).value,
              expected_log_likelihood, 1e-12);
}

TEST(GaussianProcessInterpolation, TinyNoisePassesThroughTheTrainingOutputs) {
  Random random(3);
  Eigen::Matrix2Xd inputs(2, 60);
  for (int i = 0; i < 60; ++i) {  // a jittered 10 x 6 grid with 3 m spacing
    inputs.col(i) << 3.0 * (i % 10) + random.uniform(-0.5, 0.5),
        3.0 * (i / 10) + random.uniform(-0.5, 0.5);
  }
  Eigen::Matrix2Xd outputs(2, 60);
  for (Eigen::Index i = 0; i < outputs.size(); ++i)
    outputs.data()[i] = random.normal(1.0);
  GaussianProcessOptions options = given(hyperparameters(2.0, 2.0, 1.0, 1e-5));
  options.prediction.lattice.tolerance = 1e-3;
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs, options);
  const Eigen::Matrix2Xd exact = fit.model.exact_mean_batch(inputs);
  const Eigen::Matrix2Xd fast = fit.model.mean_batch(inputs);
  EXPECT_LT((exact - outputs).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((fast - outputs).cwiseAbs().maxCoeff(), 1e-3);
  // The latent std at a training point is at most the noise (sf^2 - |v|^2 rounds at 1e-16).
  EXPECT_LT(fit.model.standard_deviation_batch(inputs).maxCoeff(), 1.001e-5);
}

TEST(GaussianProcessPrediction, RevertsToTheOutputMeanFarFromData) {
  Random random(5);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 50, 10.0, 10.0);
  const Eigen::Matrix2Xd outputs = inputs * 1.1 + Eigen::Matrix2Xd::Constant(2, 50, 3.0);
  const GaussianProcessFit fit =
      fit_gaussian_process(inputs, outputs, given(hyperparameters(2, 2, 1, 0.01)));
  const Eigen::Vector2d far(500.0, -400.0);
  EXPECT_LT((fit.model.mean(far) - outputs.rowwise().mean()).norm(), 1e-12);
  EXPECT_FALSE(fit.model.lattice().contains(far));
}

TEST(GaussianProcessStd, IsSmallNearDataAndApproachesTheSignalStdFarAway) {
  Random random(11);
  const GpHyperparameters h = hyperparameters(3.0, 3.0, 0.5, 0.01);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 300, 30.0, 20.0);
  const Eigen::Matrix2Xd outputs = gp_sample(random, h, inputs);
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs, given(h));
  const Eigen::VectorXd at_data = fit.model.standard_deviation_batch(inputs);
  EXPECT_LT(at_data.maxCoeff(), 0.01);  // at most about the noise std
  EXPECT_GT(at_data.minCoeff(), 0.0);
  Eigen::Matrix2Xd far(2, 3);
  far << -100.0, 300.0, 15.0, 0.0, 10.0, 1000.0;
  const Eigen::VectorXd far_std = fit.model.standard_deviation_batch(far);
  for (Eigen::Index i = 0; i < far.cols(); ++i) {
    EXPECT_NEAR(far_std[i], 0.5, 1e-9);
    EXPECT_NEAR(fit.model.standard_deviation(far.col(i), true), std::hypot(0.5, 0.01), 1e-9);
  }
  // Growing with the distance from the data: 1, 2, 4 length scales beyond its bounding box.
  double previous = 0.0;
  for (const double d : {3.0, 6.0, 12.0}) {
    const double std = fit.model.standard_deviation(Eigen::Vector2d(30.0 + d, 10.0));
    EXPECT_GT(std, previous);
    previous = std;
  }
  // The batch agrees with single points to rounding.
  const Eigen::Matrix2Xd queries = uniform_points(random, 700, 40.0, 30.0);
  const Eigen::VectorXd batch = fit.model.standard_deviation_batch(queries, true);
  for (Eigen::Index i = 0; i < queries.cols(); i += 37) {
    EXPECT_NEAR(batch[i], fit.model.standard_deviation(queries.col(i), true), 1e-12);
  }
}

TEST(GaussianProcessJacobian, MatchesCentralDifferences) {
  Random random(13);
  const GpHyperparameters h = hyperparameters(3.0, 5.0, 0.8, 0.02);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 200, 30.0, 20.0);
  const Eigen::Matrix2Xd outputs = gp_sample(random, h, inputs);
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs, given(h));
  const GaussianProcess& gp = fit.model;
  const double step = 1e-5;
  // Inside the lattice, near its border, and outside it.
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(10.3, 7.7), Eigen::Vector2d(25.1, 2.2),
                                   Eigen::Vector2d(-5.0, 19.0), Eigen::Vector2d(60.0, -12.0)}) {
    Eigen::Matrix2d exact_numeric, numeric;
    for (int d = 0; d < 2; ++d) {
      const Eigen::Vector2d e = Eigen::Vector2d::Unit(d) * step;
      exact_numeric.col(d) = (gp.exact_mean(p + e) - gp.exact_mean(p - e)) / (2 * step);
      numeric.col(d) = (gp.mean(p + e) - gp.mean(p - e)) / (2 * step);
    }
    EXPECT_LT((gp.exact_mean_jacobian(p) - exact_numeric).cwiseAbs().maxCoeff(), 1e-8)
        << p.transpose();
    EXPECT_LT((gp.mean_jacobian(p) - numeric).cwiseAbs().maxCoeff(), 1e-8) << p.transpose();
    // The lattice's derivative stays close to the exact one (O(spacing^3)).
    EXPECT_LT((gp.mean_jacobian(p) - gp.exact_mean_jacobian(p)).cwiseAbs().maxCoeff(), 2e-3)
        << p.transpose();
  }
}

TEST(GaussianProcessState, RebuildsTheSamePredictions) {
  Random random(17);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 300, 40.0, 20.0);
  const Eigen::Matrix2Xd outputs = gp_sample(random, hyperparameters(4, 4, 0.3, 0.02), inputs);
  GaussianProcessOptions options;
  options.tuning.max_points = 150;
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs, options);
  const GaussianProcess rebuilt(fit.model.state(), options.prediction);
  const Eigen::Matrix2Xd queries = uniform_points(random, 2000, 60.0, 40.0).array() - 10.0;
  EXPECT_EQ(rebuilt.mean_batch(queries), fit.model.mean_batch(queries));
  EXPECT_EQ(rebuilt.standard_deviation_batch(queries), fit.model.standard_deviation_batch(queries));
  EXPECT_EQ(rebuilt.lattice().measured_error(), fit.model.lattice().measured_error());
}

TEST(GaussianProcessState, RejectsAnInconsistentState) {
  Random random(19);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 20, 10.0, 10.0);
  const GaussianProcessFit fit =
      fit_gaussian_process(inputs, inputs, given(hyperparameters(2, 2, 1, 0.1)));
  GaussianProcessState state = fit.model.state();
  state.alpha = state.alpha.leftCols(19).eval();  // a copy: assigning a block of itself aliases
  test::expect_input_error([&] { GaussianProcess gp(state); }, {"gaussian_process.alpha"});
  state = fit.model.state();
  state.hyperparameters.noise_std = -1.0;
  test::expect_input_error([&] { GaussianProcess gp(state); },
                           {"gaussian_process.hyperparameters.noise_std"});
  state = fit.model.state();
  state.output_mean.x() = std::nan("");
  test::expect_input_error([&] { GaussianProcess gp(state); }, {"gaussian_process.output_mean"});
}

TEST(GaussianProcessDeterminism, SameDataSameBitsWhateverTheThreads) {
  Random random(23);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 700, 50.0, 30.0);
  const Eigen::Matrix2Xd outputs = gp_sample(random, hyperparameters(5, 3, 0.4, 0.03), inputs);
  const Eigen::Matrix2Xd queries = uniform_points(random, 9000, 80.0, 60.0).array() - 15.0;
  GaussianProcessOptions options;
  options.tuning.max_points = 200;
  options.prediction.threads = 1;
  const GaussianProcessFit one = fit_gaussian_process(inputs, outputs, options);
  const GaussianProcessFit again = fit_gaussian_process(inputs, outputs, options);
  options.prediction.threads = 2;
  const GaussianProcessFit two = fit_gaussian_process(inputs, outputs, options);
  for (const GaussianProcessFit* other : {&again, &two}) {
    EXPECT_EQ(other->model.state().alpha, one.model.state().alpha);
    EXPECT_EQ(other->model.hyperparameters().to_log(), one.model.hyperparameters().to_log());
    EXPECT_EQ(other->summary.history, one.summary.history);
    EXPECT_EQ(other->model.mean_batch(queries), one.model.mean_batch(queries));
    EXPECT_EQ(other->model.exact_mean_batch(queries.leftCols(500)),
              one.model.exact_mean_batch(queries.leftCols(500)));
    EXPECT_EQ(other->model.standard_deviation_batch(queries),
              one.model.standard_deviation_batch(queries));
    EXPECT_EQ(other->model.lattice().measured_error(), one.model.lattice().measured_error());
  }
}

TEST(GaussianProcessJitter, IsAddedAndReportedWhenCholeskyFails) {
  // Dense points, a huge signal and almost no noise: K is singular in double precision.
  Random random(29);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 200, 1.0, 1.0);
  const Eigen::Matrix2Xd outputs = inputs * 2.0;
  GaussianProcessOptions options = given(hyperparameters(100.0, 100.0, 1000.0, 1e-6));
  options.prediction.lattice.enabled = false;
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs, options);
  EXPECT_GT(fit.summary.jitter, 0.0);
  EXPECT_EQ(fit.model.state().jitter, fit.summary.jitter);
  EXPECT_NE(fit.summary.message.find("jitter"), std::string::npos);
  EXPECT_TRUE(fit.model.mean_batch(inputs).allFinite());
  EXPECT_LT((fit.model.mean_batch(inputs) - outputs).cwiseAbs().maxCoeff(), 1e-3);
  const GaussianProcess rebuilt(fit.model.state(), options.prediction);  // same jitter works
  EXPECT_EQ(rebuilt.mean_batch(inputs), fit.model.mean_batch(inputs));
}

TEST(GaussianProcessInput, StaysFiniteOnConflictingDuplicates) {
  Eigen::Matrix2Xd inputs(2, 4), outputs(2, 4);
  inputs << 0, 0, 5, 10, 0, 0, 5, 0;
  outputs << 1, 3, 5, 10, 0, 0, 5, 0;
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs);
  const Eigen::Vector2d at_duplicate = fit.model.mean(Eigen::Vector2d::Zero());
  EXPECT_TRUE(at_duplicate.allFinite());
  EXPECT_GT(at_duplicate.x(), 1.0 - 1e-6);  // between the two conflicting outputs
  EXPECT_LT(at_duplicate.x(), 3.0 + 1e-6);
  EXPECT_TRUE(std::isfinite(fit.model.standard_deviation(Eigen::Vector2d::Zero())));
}

TEST(GaussianProcessInput, RejectsBadPairsNamingThem) {
  Eigen::Matrix2Xd two(2, 2);
  two << 0, 1, 0, 1;
  test::expect_input_error([&] { fit_gaussian_process(two, two); }, {"pairs", "at least 3"});
  Eigen::Matrix2Xd nan(2, 5);
  nan << 0, 1, 2, 3, 4, 0, 1, std::nan(""), 3, 4;
  test::expect_input_error([&] { fit_gaussian_process(nan, Eigen::Matrix2Xd::Zero(2, 5)); },
                           {"pairs", "pair 2", "not finite"});
  test::expect_input_error(
      [&] {
        fit_gaussian_process(Eigen::Matrix2Xd::Zero(2, 5),
                             nan.cwiseAbs());  // plan side fine, other side NaN
      },
      {"pairs", "not finite"});
  const Eigen::Matrix2Xd equal = Eigen::Matrix2Xd::Constant(2, 6, 3.5);
  test::expect_input_error([&] { fit_gaussian_process(equal, equal); }, {"pairs", "equal"});
  test::expect_input_error(
      [&] { fit_gaussian_process(Eigen::Matrix2Xd::Random(2, 5), Eigen::Matrix2Xd::Zero(2, 4)); },
      {"pairs"});
  GaussianProcessOptions options;
  options.max_points = 10;
  test::expect_input_error(
      [&] {
        fit_gaussian_process(Eigen::Matrix2Xd::Random(2, 11), Eigen::Matrix2Xd::Zero(2, 11),
                             options);
      },
      {"pairs", "max_points"});
}

TEST(GaussianProcessInput, RejectsBadOptionsNamingThem) {
  const Eigen::Matrix2Xd points = Eigen::Matrix2Xd::Random(2, 10);
  const auto expect = [&](const GaussianProcessOptions& options, const char* field) {
    test::expect_input_error([&] { fit_gaussian_process(points, points, options); }, {field});
  };
  GaussianProcessOptions options;
  options.prediction.threads = 3;
  expect(options, "gaussian_process.prediction.threads");
  options = {};
  options.tuning.max_points = 2;
  expect(options, "gaussian_process.tuning.max_points");
  options = {};
  options.tuning.rprop.increase = 0.5;
  expect(options, "gaussian_process.tuning.rprop.increase");
  options = {};
  options.tuning.min_noise_std = 0.0;
  expect(options, "gaussian_process.tuning.min_noise_std");
  options = {};
  options.prediction.lattice.tolerance = -1.0;
  expect(options, "gaussian_process.prediction.lattice.tolerance");
  options = given(hyperparameters(1, std::nan(""), 1, 1));
  expect(options, "gaussian_process.hyperparameters.length_scale");
}

}  // namespace
}  // namespace floorgrid
