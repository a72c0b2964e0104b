#include "floorgrid/mapping/rprop.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

// f(x) = sum_i a_i (x_i - c_i)^2: minimum 0 at c.
RpropObjective quadratic(const Eigen::VectorXd& a, const Eigen::VectorXd& c) {
  return [a, c](const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
    const Eigen::VectorXd d = x - c;
    gradient = 2.0 * a.cwiseProduct(d);
    return d.dot(a.cwiseProduct(d));
  };
}

// Rosenbrock's banana: minimum 0 at (1, 1) at the end of a long curved valley.
double rosenbrock(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
  const double a = 1.0 - x[0];
  const double b = x[1] - x[0] * x[0];
  gradient.resize(2);
  gradient[0] = -2.0 * a - 400.0 * x[0] * b;
  gradient[1] = 200.0 * b;
  return a * a + 100.0 * b * b;
}

double square(const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
  gradient[0] = 2.0 * x[0];
  return x[0] * x[0];
}

TEST(Rprop, MinimizesAnIllConditionedQuadraticFromSeveralStarts) {
  const Eigen::VectorXd a = Eigen::Vector3d(1.0, 10.0, 100.0);
  const Eigen::VectorXd c = Eigen::Vector3d(0.5, -2.0, 3.0);
  RpropOptions options;
  options.max_iterations = 1000;
  options.min_step = 1e-9;
  options.tolerance = 1e-12;
  for (const Eigen::Vector3d& start :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 10, -10), Eigen::Vector3d(-3, 7, 0.1)}) {
    const RpropResult result = minimize_rprop(quadratic(a, c), start, options);
    EXPECT_TRUE(result.converged) << result.message;
    EXPECT_LT((result.x - c).cwiseAbs().maxCoeff(), 1e-5) << result.x.transpose();
    EXPECT_LT(result.value, 1e-9);
    EXPECT_EQ(result.history.size(), static_cast<std::size_t>(result.iterations));
    EXPECT_LT(result.iterations, options.max_iterations);
  }
}

TEST(Rprop, MinimizesRosenbrockFromSeveralStarts) {
  RpropOptions options;
  options.max_iterations = 20000;
  options.tolerance = 0.0;  // run until no step moves or the budget ends
  options.min_step = 1e-10;
  for (const Eigen::Vector2d& start : {Eigen::Vector2d(-1.2, 1.0), Eigen::Vector2d(2.0, 2.0),
                                       Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(-1.0, -1.0)}) {
    const RpropResult result = minimize_rprop(rosenbrock, start, options);
    EXPECT_LT((result.x - Eigen::Vector2d(1.0, 1.0)).norm(), 1e-4)
        << "from " << start.transpose() << ": " << result.x.transpose() << ", " << result.message;
    EXPECT_LT(result.value, 1e-8);
  }
}

TEST(Rprop, StepsGrowGeometricallyWhileTheSignHolds) {
  // f(x) = x has gradient 1 everywhere: steps 0.1, 0.12, 0.144, ... capped at max_step.
  RpropOptions options;
  options.max_iterations = 20;
  const RpropObjective slope = [](const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
    gradient[0] = 1.0;
    return x[0];
  };
  const RpropResult result = minimize_rprop(slope, Eigen::VectorXd::Zero(1), options);
  double x = 0.0, step = 0.1;
  for (int i = 1; i < options.max_iterations; ++i) {
    x -= step;
    EXPECT_NEAR(result.history[static_cast<std::size_t>(i)], x, 1e-12) << "iteration " << i;
    step = std::min(step * 1.2, 1.0);
  }
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.reverts, 0);
}

TEST(Rprop, RevertsTheLastStepWhenTheSignFlipsAndTheObjectiveGotWorse) {
  // From 0.3 a step of 1 lands on -0.7 (f 0.49 > 0.09, gradient flipped): iRprop+ takes the
  // step back, so the third evaluation is at 0.3 again.
  RpropOptions options;
  options.initial_step = 1.0;
  options.max_iterations = 3;
  const RpropResult result = minimize_rprop(square, Eigen::VectorXd::Constant(1, 0.3), options);
  ASSERT_EQ(result.history.size(), 3u);
  EXPECT_DOUBLE_EQ(result.history[0], 0.09);
  EXPECT_DOUBLE_EQ(result.history[1], 0.49);
  EXPECT_EQ(result.history[2], result.history[0]);
  EXPECT_EQ(result.reverts, 1);
}

TEST(Rprop, KeepsAnImprovingStepAcrossASignFlip) {
  // From 0.3 a step of 0.5 lands on -0.2 (f 0.04 < 0.09): no step back; the halved step 0.25
  // follows at once (the flip clears the derivative's memory), reaching 0.05.
  RpropOptions options;
  options.initial_step = 0.5;
  options.max_iterations = 3;
  const RpropResult result = minimize_rprop(square, Eigen::VectorXd::Constant(1, 0.3), options);
  ASSERT_EQ(result.history.size(), 3u);
  EXPECT_NEAR(result.history[1], 0.04, 1e-15);
  EXPECT_NEAR(result.history[2], 0.0025, 1e-15);
  EXPECT_EQ(result.reverts, 0);
}

TEST(Rprop, StopsAtABoundThatBlocksTheMinimum) {
  RpropOptions options;
  options.upper = Eigen::VectorXd::Constant(1, 2.0);
  options.lower = Eigen::VectorXd::Constant(1, -10.0);
  const RpropObjective objective = [](const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
    gradient[0] = 2.0 * (x[0] - 5.0);
    return (x[0] - 5.0) * (x[0] - 5.0);
  };
  const RpropResult result = minimize_rprop(objective, Eigen::VectorXd::Zero(1), options);
  EXPECT_EQ(result.x[0], 2.0);
  EXPECT_TRUE(result.converged) << result.message;
  // A start outside the box is clipped into it first.
  const RpropResult clipped = minimize_rprop(objective, Eigen::VectorXd::Constant(1, 9.0), options);
  EXPECT_EQ(clipped.x[0], 2.0);
}

TEST(Rprop, BacksOffFromInfeasiblePoints) {
  // (x + 1)^2 defined only for x >= 0: the best feasible point is 0.
  RpropOptions options;
  options.initial_step = 0.4;
  options.max_iterations = 200;
  options.tolerance = 0.0;
  options.min_step = 1e-9;
  const RpropObjective objective = [](const Eigen::VectorXd& x, Eigen::VectorXd& gradient) {
    gradient[0] = 2.0 * (x[0] + 1.0);
    return x[0] < 0.0 ? std::numeric_limits<double>::quiet_NaN() : (x[0] + 1.0) * (x[0] + 1.0);
  };
  const RpropResult result = minimize_rprop(objective, Eigen::VectorXd::Constant(1, 1.0), options);
  EXPECT_GT(result.failures, 0);
  EXPECT_GE(result.x[0], 0.0);
  EXPECT_LT(result.x[0], 1e-6);
  EXPECT_TRUE(std::isfinite(result.value));
}

TEST(Rprop, ReportsAnObjectiveThatFailsAtTheStart) {
  const RpropObjective objective = [](const Eigen::VectorXd&, Eigen::VectorXd&) {
    return std::numeric_limits<double>::infinity();
  };
  const RpropResult result = minimize_rprop(objective, Eigen::VectorXd::Zero(2));
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_NE(result.message.find("not finite"), std::string::npos);
}

TEST(Rprop, RejectsBadOptions) {
  const auto run = [](RpropOptions options) {
    minimize_rprop(square, Eigen::VectorXd::Zero(1), options);
  };
  RpropOptions options;
  options.increase = 0.9;
  test::expect_input_error([&] { run(options); }, {"rprop.increase"});
  options = {};
  options.decrease = 1.0;
  test::expect_input_error([&] { run(options); }, {"rprop.decrease"});
  options = {};
  options.max_step = options.min_step / 2;
  test::expect_input_error([&] { run(options); }, {"rprop.max_step"});
  options = {};
  options.max_iterations = 0;
  test::expect_input_error([&] { run(options); }, {"rprop.max_iterations"});
  options = {};
  options.lower = Eigen::VectorXd::Zero(3);
  test::expect_input_error([&] { run(options); }, {"rprop.lower"});
  options = {};
  options.lower = Eigen::VectorXd::Constant(1, 1.0);
  options.upper = Eigen::VectorXd::Constant(1, 0.0);
  test::expect_input_error([&] { run(options); }, {"rprop.upper"});
  test::expect_input_error(
      [&] { minimize_rprop(square, Eigen::VectorXd::Constant(1, std::nan("")), {}); },
      {"rprop.start"});
}

}  // namespace
}  // namespace floorgrid
