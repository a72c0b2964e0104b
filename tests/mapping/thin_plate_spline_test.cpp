#include "floorgrid/mapping/thin_plate_spline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

// Plan points over a 100 x 60 m building.
Eigen::Matrix2Xd random_points(Random& random, int count, double width = 100.0,
                               double height = 60.0) {
  Eigen::Matrix2Xd points(2, count);
  for (int i = 0; i < count; ++i) {
    points.col(i) = Eigen::Vector2d(random.uniform(0, width), random.uniform(0, height));
  }
  return points;
}

// A smooth, SLAM-like distortion: a rotation, a shift and a gentle bend of about 0.5 m.
Eigen::Vector2d warp(const Eigen::Vector2d& p) {
  const double c = std::cos(0.3), s = std::sin(0.3);
  const Eigen::Vector2d bent(p.x(),
                             p.y() + 0.5 * std::sin(p.x() / 30.0) + 0.002 * p.x() * p.y() / 60.0);
  return Eigen::Vector2d(c * bent.x() - s * bent.y() + 12.0, s * bent.x() + c * bent.y() - 7.0);
}

Eigen::Matrix2Xd apply_warp(const Eigen::Matrix2Xd& points) {
  Eigen::Matrix2Xd out(2, points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    out.col(i) = warp(points.col(i));
  return out;
}

double max_error(const Eigen::Matrix2Xd& a, const Eigen::Matrix2Xd& b) {
  return (a - b).colwise().norm().maxCoeff();
}

TEST(ThinPlateSpline, ZeroRegularizationInterpolatesTheCentres) {
  Random random(1);
  const Eigen::Matrix2Xd plan = random_points(random, 300);
  const Eigen::Matrix2Xd grid = apply_warp(plan);
  const ThinPlateSpline spline = ThinPlateSpline::fit(plan, grid);
  EXPECT_EQ(spline.size(), 300);
  EXPECT_LT(max_error(spline.evaluate_batch(plan), grid), 1e-9 * 100.0);
  for (Eigen::Index i = 0; i < 10; ++i) {
    EXPECT_LT((spline.evaluate(Eigen::Vector2d(plan.col(i))) - grid.col(i)).norm(), 1e-9 * 100.0);
  }
  // Between the centres it follows the smooth warp closely.
  const Eigen::Matrix2Xd between = random_points(random, 200, 80.0, 40.0).array() + 10.0;
  EXPECT_LT(max_error(spline.evaluate_batch(between), apply_warp(between)), 0.01);
}

// f from its plain data with std::log (the engine has its own vectorized log), and the sum of
// the kernel terms' magnitudes, which bounds the rounding of a sum that cancels far away.
Eigen::Vector2d reference_value(const ThinPlateSplineData& d, const Eigen::Vector2d& p,
                                double& magnitude) {
  const Eigen::Vector2d x = (p - d.input_offset) / d.input_scale;
  Eigen::Vector2d f = d.output_offset + d.affine.col(0) + d.affine.rightCols<2>() * x;
  magnitude = f.norm();
  for (Eigen::Index i = 0; i < d.centres_in_plan.cols(); ++i) {
    const double r = (x - (d.centres_in_plan.col(i) - d.input_offset) / d.input_scale).norm();
    if (r == 0.0)
      continue;
    f += d.kernel_weights.col(i) * (r * r * std::log(r));
    magnitude += d.kernel_weights.col(i).norm() * std::abs(r * r * std::log(r));
  }
  return f;
}

TEST(ThinPlateSpline, EvaluationMatchesTheDefinitionWithStdLog) {
  Random random(20);
  const Eigen::Matrix2Xd plan = random_points(random, 200);
  const Eigen::Matrix2Xd grid = apply_warp(plan) + 0.03 * Eigen::Matrix2Xd::Random(2, 200);
  const ThinPlateSpline spline = ThinPlateSpline::fit(plan, grid);
  // Inside, around (up to 500 km away), exactly at a centre and 1 nm from one.
  Eigen::Matrix2Xd queries = random_points(random, 300, 1e6, 1e6).array() - 5e5;
  queries.leftCols(100) = random_points(random, 100);
  queries.col(100) = plan.col(7);
  queries.col(101) = plan.col(8) + Eigen::Vector2d(1e-9, 0);
  const Eigen::Matrix2Xd batch = spline.evaluate_batch(queries);
  for (Eigen::Index i = 0; i < queries.cols(); ++i) {
    double magnitude = 0.0;
    const Eigen::Vector2d expected = reference_value(spline.data(), queries.col(i), magnitude);
    EXPECT_LT((Eigen::Vector2d(batch.col(i)) - expected).norm(), 1e-14 * magnitude) << i;
    if (i < 102) {
      EXPECT_LT((Eigen::Vector2d(batch.col(i)) - expected).norm(), 1e-11) << i;  // 1e-13 of 100 m
    }
  }
}

TEST(ThinPlateSpline, BatchEvaluationMatchesSinglePoints) {
  Random random(2);
  const Eigen::Matrix2Xd plan = random_points(random, 150);
  const ThinPlateSpline spline = ThinPlateSpline::fit(plan, apply_warp(plan));
  const Eigen::Matrix2Xd queries = random_points(random, 3001);
  const Eigen::Matrix2Xd two = spline.evaluate_batch(queries, 2);
  const Eigen::Matrix2Xd one = spline.evaluate_batch(queries, 1);
  EXPECT_EQ(one, two);
  for (Eigen::Index i = 0; i < queries.cols(); i += 97) {
    EXPECT_EQ(Eigen::Vector2d(two.col(i)), spline.evaluate(Eigen::Vector2d(queries.col(i))));
  }
}

TEST(ThinPlateSpline, ReproducesAnAffineMapEverywhere) {
  Random random(3);
  Eigen::Matrix2d A;
  A << 1.02, -0.31, 0.29, 0.97;
  const Eigen::Vector2d t(-40.0, 15.0);
  const Eigen::Matrix2Xd plan = random_points(random, 60);
  const Eigen::Matrix2Xd grid = (A * plan).colwise() + t;
  for (const double lambda : {0.0, 1.0, 1e4}) {
    const ThinPlateSpline spline = ThinPlateSpline::fit(plan, grid, {lambda});
    EXPECT_LT(spline.data().kernel_weights.cwiseAbs().maxCoeff(), 1e-10) << lambda;
    EXPECT_LT(spline.bending_energy(), 1e-18) << lambda;
    const Eigen::Matrix2Xd far = random_points(random, 50, 1000.0, 1000.0).array() - 500.0;
    EXPECT_LT(max_error(spline.evaluate_batch(far), (A * far).colwise() + t), 1e-9 * 1000.0);
    EXPECT_LT((spline.jacobian({3.0, -2.0}) - A).norm(), 1e-12);
  }
}

// The bending energy from its definition, on a fine grid, with the analytic second derivatives
// of U: U_xx = log r^2 + 1 + 2 dx^2 / r^2, U_yy = log r^2 + 1 + 2 dy^2 / r^2, U_xy = 2 dx dy / r^2.
double integrated_bending_energy(const ThinPlateSpline& spline, double half_width, double step) {
  const ThinPlateSplineData& d = spline.data();
  const double s = d.input_scale;
  double energy = 0.0;
  for (double y = -half_width + step / 2; y < half_width; y += step) {
    for (double x = -half_width + step / 2; x < half_width; x += step) {
      Eigen::Matrix2d f_xx = Eigen::Matrix2d::Zero();  // rows: outputs; (f_xx, f_yy) per output
      Eigen::Vector2d f_xy = Eigen::Vector2d::Zero();
      for (Eigen::Index i = 0; i < spline.size(); ++i) {
        const Eigen::Vector2d c = (d.centres_in_plan.col(i) - d.input_offset) / s;
        const double dx = x - c.x(), dy = y - c.y(), r2 = dx * dx + dy * dy;
        const double common = std::log(r2) + 1.0;
        f_xx.col(0) += d.kernel_weights.col(i) * (common + 2 * dx * dx / r2);
        f_xx.col(1) += d.kernel_weights.col(i) * (common + 2 * dy * dy / r2);
        f_xy += d.kernel_weights.col(i) * (2 * dx * dy / r2);
      }
      energy += (f_xx.squaredNorm() + 2 * f_xy.squaredNorm()) * step * step;
    }
  }
  return energy / (s * s);  // the integral in normalized units, back to the plan's metres
}

TEST(ThinPlateSpline, BendingEnergyMatchesItsDefinition) {
  // Four centres on a square with a saddle-like target: the simplest spline that bends.
  Eigen::Matrix2Xd plan(2, 5), grid(2, 5);
  plan << 0, 10, 10, 0, 5, 0, 0, 10, 10, 5;
  grid = plan;
  grid(1, 4) += 1.0;  // the middle raised by 1 m
  const ThinPlateSpline spline = ThinPlateSpline::fit(plan, grid);
  const double energy = spline.bending_energy();
  EXPECT_GT(energy, 0.01);
  // Grid midpoints never hit a centre (they sit at odd multiples of step / 2).
  const double numeric = integrated_bending_energy(spline, 40.0, 0.0125 * 4);
  EXPECT_NEAR(numeric / energy, 1.0, 0.02) << numeric << " vs " << energy;
  // Scaling plan and grid by 7 leaves the energy unchanged.
  const ThinPlateSpline scaled = ThinPlateSpline::fit(7.0 * plan, 7.0 * grid);
  EXPECT_NEAR(scaled.bending_energy() / energy, 1.0, 1e-9);
}

TEST(ThinPlateSpline, InterpolantHasTheLeastBendingEnergy) {
  Random random(4);
  const Eigen::Matrix2Xd plan = random_points(random, 40);
  const Eigen::Matrix2Xd grid = apply_warp(plan) + 0.05 * Eigen::Matrix2Xd::Random(2, 40);
  const ThinPlateSpline spline = ThinPlateSpline::fit(plan, grid);
  const double least = spline.bending_energy();
  // Any other interpolant of the same pairs (here: splines through 10 more points) bends more,
  // unless the extra points take the spline's own values.
  Eigen::Matrix2Xd more_plan(2, 50), more_grid(2, 50);
  more_plan << plan, random_points(random, 10);
  more_grid << grid, spline.evaluate_batch(more_plan.rightCols(10));
  EXPECT_NEAR(ThinPlateSpline::fit(more_plan, more_grid).bending_energy() / least, 1.0, 1e-6);
  for (int trial = 0; trial < 5; ++trial) {
    more_grid.rightCols(10) += 0.02 * Eigen::Matrix2Xd::Random(2, 10);
    EXPECT_GT(ThinPlateSpline::fit(more_plan, more_grid).bending_energy(), least * (1 + 1e-6));
  }
}

TEST(ThinPlateSpline, LargerRegularizationIsSmoother) {
  Random random(5);
  const Eigen::Matrix2Xd plan = random_points(random, 200);
  Eigen::Matrix2Xd grid = apply_warp(plan);
  for (Eigen::Index i = 0; i < grid.cols(); ++i) {
    grid.col(i) += Eigen::Vector2d(random.normal(0.05), random.normal(0.05));
  }
  double previous_rms = -1.0, previous_energy = std::numeric_limits<double>::infinity();
  for (const double lambda : {0.0, 1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e4}) {
    const ThinPlateSpline spline = ThinPlateSpline::fit(plan, grid, {lambda});
    const double rms = std::sqrt((spline.evaluate_batch(plan) - grid).squaredNorm() /
                                 static_cast<double>(plan.cols()));
    const double energy = spline.bending_energy();
    if (lambda == 0.0) {
      EXPECT_LT(rms, 1e-9);
    }
    EXPECT_GT(rms, previous_rms) << lambda;
    EXPECT_LT(energy, previous_energy) << lambda;
    previous_rms = rms, previous_energy = energy;
  }
  // Smoothing noise of 5 cm brings the fit closer to the truth than interpolating it.
  const Eigen::Matrix2Xd queries = random_points(random, 300, 80.0, 40.0).array() + 10.0;
  const double interpolating =
      max_error(ThinPlateSpline::fit(plan, grid).evaluate_batch(queries), apply_warp(queries));
  const double smoothing = max_error(
      ThinPlateSpline::fit(plan, grid, {10.0}).evaluate_batch(queries), apply_warp(queries));
  EXPECT_LT(smoothing, interpolating);
}

TEST(ThinPlateSpline, RegularizationIsInSquareMetres) {
  // The same building drawn in centimetres: lambda scales by 100^2 and the fit by 100.
  Random random(6);
  const Eigen::Matrix2Xd plan = random_points(random, 80);
  const Eigen::Matrix2Xd grid = apply_warp(plan) + 0.05 * Eigen::Matrix2Xd::Random(2, 80);
  const ThinPlateSpline metres = ThinPlateSpline::fit(plan, grid, {3.0});
  const ThinPlateSpline centimetres = ThinPlateSpline::fit(100.0 * plan, 100.0 * grid, {3e4});
  const Eigen::Matrix2Xd queries = random_points(random, 50);
  EXPECT_LT(max_error(100.0 * metres.evaluate_batch(queries),
                      centimetres.evaluate_batch(100.0 * queries)),
            1e-7 * 100.0 * 100.0);
}

TEST(ThinPlateSpline, FarFromTheOriginStaysAccurate) {
  Random random(7);
  const Eigen::Matrix2Xd plan = random_points(random, 100);
  const Eigen::Matrix2Xd grid = apply_warp(plan);
  const Eigen::Vector2d offset(4.0e5, -2.5e6);  // UTM-like coordinates
  const ThinPlateSpline near = ThinPlateSpline::fit(plan, grid);
  const ThinPlateSpline far =
      ThinPlateSpline::fit(plan.colwise() + offset, grid.colwise() + offset);
  const Eigen::Matrix2Xd queries = random_points(random, 50);
  EXPECT_LT(max_error((near.evaluate_batch(queries).colwise() + offset),
                      far.evaluate_batch(queries.colwise() + offset)),
            1e-6);
}

TEST(ThinPlateSpline, JacobianMatchesFiniteDifferences) {
  Random random(8);
  const Eigen::Matrix2Xd plan = random_points(random, 120);
  const ThinPlateSpline spline =
      ThinPlateSpline::fit(plan, apply_warp(plan) + 0.1 * Eigen::Matrix2Xd::Random(2, 120), {0.5});
  const double h = 1e-4;
  const Eigen::Matrix2Xd queries = random_points(random, 100);
  for (Eigen::Index i = 0; i < queries.cols() + 3; ++i) {
    // Also at three centres, where the kernel's second derivative is singular.
    const Eigen::Vector2d p = i < queries.cols() ? Eigen::Vector2d(queries.col(i))
                                                 : Eigen::Vector2d(plan.col(i - queries.cols()));
    Eigen::Matrix2d numeric;
    numeric.col(0) = (spline.evaluate(Eigen::Vector2d(p + Eigen::Vector2d(h, 0))) -
                      spline.evaluate(Eigen::Vector2d(p - Eigen::Vector2d(h, 0)))) /
                     (2 * h);
    numeric.col(1) = (spline.evaluate(Eigen::Vector2d(p + Eigen::Vector2d(0, h))) -
                      spline.evaluate(Eigen::Vector2d(p - Eigen::Vector2d(0, h)))) /
                     (2 * h);
    const ThinPlateSplineDerivatives d = spline.derivatives(p);
    const Eigen::Vector2d& value = d.value;
    const Eigen::Matrix2d& J = d.J_grid_plan;
    const Eigen::Vector2d& mixed = d.mixed;
    EXPECT_LT((J - numeric).norm(), 1e-7) << i;
    EXPECT_EQ(J, spline.jacobian(p));
    EXPECT_EQ(value, spline.evaluate(p));
    if (i < queries.cols()) {
      const Eigen::Vector2d numeric_mixed =
          (spline.jacobian(Eigen::Vector2d(p + Eigen::Vector2d(0, h))).col(0) -
           spline.jacobian(Eigen::Vector2d(p - Eigen::Vector2d(0, h))).col(0)) /
          (2 * h);
      EXPECT_LT((mixed - numeric_mixed).norm(), 1e-6) << i;
    }
  }
}

TEST(ThinPlateSpline, DegenerateInputsNamePairs) {
  Eigen::Matrix2Xd two(2, 2), line(2, 10);
  two << 0, 1, 0, 1;
  for (int i = 0; i < 10; ++i)
    line.col(i) = Eigen::Vector2d(3.0 * i, 1.0 - 2.0 * i);
  test::expect_input_error([&] { ThinPlateSpline::fit(two, two); }, {"pairs", "at least 3"});
  test::expect_input_error([&] { ThinPlateSpline::fit(line, line); }, {"pairs", "collinear"});
  test::expect_input_error([&] { ThinPlateSpline::fit(line, line, {5.0}); },
                           {"pairs", "collinear"});
  const Eigen::Matrix2Xd same = Eigen::Matrix2Xd::Ones(2, 5);
  test::expect_input_error([&] { ThinPlateSpline::fit(same, same); }, {"pairs", "coincide"});
  Eigen::Matrix2Xd plan(2, 4);
  plan << 0, 1, 0, 1, 0, 0, 1, 1;
  Eigen::Matrix2Xd bad = plan;
  bad(1, 2) = std::numeric_limits<double>::quiet_NaN();
  test::expect_input_error([&] { ThinPlateSpline::fit(bad, plan); }, {"pairs", "pair 2", "NaN"});
  test::expect_input_error([&] { ThinPlateSpline::fit(plan, bad); }, {"pairs", "pair 2"});
  test::expect_input_error([&] { ThinPlateSpline::fit(plan, plan.leftCols(3)); },
                           {"pairs", "mismatched"});
  test::expect_input_error([&] { ThinPlateSpline::fit(plan, plan, {-1.0}); },
                           {"tps.regularization"});
  test::expect_input_error([&] { ThinPlateSpline::fit(plan, plan, {std::nan("")}); },
                           {"tps.regularization"});
  for (const Eigen::VectorXd& weights :
       {Eigen::VectorXd(Eigen::VectorXd::Ones(3)), Eigen::VectorXd(Eigen::Vector4d(1, 0, 1, 1)),
        Eigen::VectorXd(Eigen::Vector4d(1, std::nan(""), 1, 1))}) {
    test::expect_input_error([&] { ThinPlateSpline::fit(plan, plan, {1.0}, weights); },
                             {"tps.weights"});
  }
}

TEST(ThinPlateSpline, WeightsScaleEachPairsPenalty) {
  Random random(12);
  const Eigen::Matrix2Xd plan = random_points(random, 40);
  Eigen::Matrix2Xd grid = apply_warp(plan);
  grid.col(7) += Eigen::Vector2d(2.0, -1.0);  // a mis-clicked pair
  const ThinPlateSpline plain = ThinPlateSpline::fit(plan, grid, {5.0});
  // Unit weights are no weights.
  const ThinPlateSpline ones = ThinPlateSpline::fit(plan, grid, {5.0}, Eigen::VectorXd::Ones(40));
  EXPECT_LT(max_error(plain.evaluate_batch(plan), ones.evaluate_batch(plan)), 1e-9);
  // A small weight on the mis-clicked pair: the spline follows it far less, there and around.
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(40);
  weights[7] = 1e-3;
  const ThinPlateSpline weighted = ThinPlateSpline::fit(plan, grid, {5.0}, weights);
  const Eigen::Vector2d truth = warp(plan.col(7));
  const Eigen::Vector2d at = plan.col(7);
  EXPECT_GT((plain.evaluate(at) - truth).norm(), 0.5);
  EXPECT_LT((weighted.evaluate(at) - truth).norm(), 0.2);
  // The same as the least-squares optimum: lambda / w_i is pair i's penalty (a uniform scale
  // of lambda and the weights changes nothing).
  const ThinPlateSpline scaled = ThinPlateSpline::fit(plan, grid, {10.0}, 2.0 * weights);
  EXPECT_LT(max_error(weighted.evaluate_batch(plan), scaled.evaluate_batch(plan)), 1e-6);
}

TEST(ThinPlateSpline, DuplicateCentresNeedRegularization) {
  Random random(9);
  Eigen::Matrix2Xd plan = random_points(random, 30);
  Eigen::Matrix2Xd grid = apply_warp(plan);
  plan.col(17) = plan.col(4);                            // the same plan point twice,
  grid.col(17) = grid.col(4) + Eigen::Vector2d(0.2, 0);  // with conflicting grid points
  test::expect_input_error([&] { ThinPlateSpline::fit(plan, grid); },
                           {"pairs", "plan points 4 and 17 coincide", "regularization > 0"});
  // Smoothing accepts them and lands between the two.
  const ThinPlateSpline smooth = ThinPlateSpline::fit(plan, grid, {1e-3});
  const Eigen::Vector2d at = smooth.evaluate(Eigen::Vector2d(plan.col(4)));
  ASSERT_TRUE(at.allFinite());
  EXPECT_NEAR(at.x(), grid(0, 4) + 0.1, 0.01);
  EXPECT_TRUE(smooth.evaluate_batch(plan).allFinite());
  // Identical duplicates too.
  grid.col(17) = grid.col(4);
  EXPECT_LT((ThinPlateSpline::fit(plan, grid, {1e-6}).evaluate(Eigen::Vector2d(plan.col(4))) -
             grid.col(4))
                .norm(),
            1e-4);
}

TEST(ThinPlateSpline, ThreeNonCollinearPairsGiveTheirAffineMap) {
  Eigen::Matrix2Xd plan(2, 3), grid(2, 3);
  plan << 0, 4, 0, 0, 0, 3;
  grid << 1, 5, 1, 2, 2, 5;
  const ThinPlateSpline spline = ThinPlateSpline::fit(plan, grid);
  EXPECT_LT(max_error(spline.evaluate_batch(plan), grid), 1e-12);
  EXPECT_LT((spline.evaluate(Eigen::Vector2d(4, 3)) - Eigen::Vector2d(5, 5)).norm(), 1e-12);
}

TEST(ThinPlateSpline, RoundTripsThroughItsPlainData) {
  Random random(10);
  const Eigen::Matrix2Xd plan = random_points(random, 50);
  const ThinPlateSpline spline = ThinPlateSpline::fit(plan, apply_warp(plan), {0.2});
  const ThinPlateSpline copy(spline.data());
  const Eigen::Matrix2Xd queries = random_points(random, 20);
  EXPECT_EQ(copy.evaluate_batch(queries), spline.evaluate_batch(queries));
  EXPECT_EQ(copy.data().regularization, 0.2);
  ThinPlateSplineData broken = spline.data();
  broken.kernel_weights.conservativeResize(2, 49);
  test::expect_input_error([&] { ThinPlateSpline{broken}; }, {"tps", "mismatched"});
  broken = spline.data();
  broken.input_scale = 0.0;
  test::expect_input_error([&] { ThinPlateSpline{broken}; }, {"tps", "input_scale"});
  broken = spline.data();
  broken.affine(1, 1) = std::numeric_limits<double>::infinity();
  test::expect_input_error([&] { ThinPlateSpline{broken}; }, {"tps", "NaN or infinite"});
}

TEST(ThinPlateSplineMapping, HandPickedPairsAreRefittedRobustly) {
  // 40 hand-picked pairs with 1 cm of noise, three of them mis-clicked by 1.5-2 m.
  Random random(21);
  ReferencePairs pairs;
  pairs.points_in_plan = random_points(random, 40);
  pairs.points_in_grid = apply_warp(pairs.points_in_plan) + 0.01 * Eigen::Matrix2Xd::Random(2, 40);
  const std::vector<Eigen::Index> wrong = {3, 17, 30};
  for (const Eigen::Index i : wrong)
    pairs.points_in_grid.col(i) += Eigen::Vector2d(1.5, -1.2);
  MappingOptions options;
  options.model = "tps";
  options.tps.regularization = 5.0;
  const auto error_at_wrong = [&](const PointMapping& model) {
    double worst = 0.0;
    for (const Eigen::Index i : wrong)
      worst = std::max(
          worst,
          (model.forward(pairs.points_in_plan.col(i)) - warp(pairs.points_in_plan.col(i))).norm());
    return worst;
  };
  auto robust = make_mapping(options);
  robust->fit(pairs);
  options.tps.robust_max_pairs = 0;
  auto plain = make_mapping(options);
  plain->fit(pairs);
  std::int64_t downweighted = 0;
  ASSERT_TRUE(robust->summary().details.find("robust_downweighted")->as_integer(downweighted));
  EXPECT_GE(downweighted, 3);
  EXPECT_TRUE(plain->summary().details.find("robust_downweighted")->is_null());
  EXPECT_GT(error_at_wrong(*plain), 0.5);
  EXPECT_LT(error_at_wrong(*robust), 0.5 * error_at_wrong(*plain));
}

}  // namespace
}  // namespace floorgrid
