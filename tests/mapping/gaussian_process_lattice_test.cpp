#include <gtest/gtest.h>

#include <cmath>
#include <ostream>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/gaussian_process.hpp"
#include "tests/mapping/gaussian_process_test_support.hpp"

namespace floorgrid {
namespace {

using test::gp_sample;
using test::hyperparameters;
using test::uniform_points;

/// The largest |mean - exact_mean| over `count` random points of the lattice's rectangle and
/// a 5 m band around it.
double lattice_error(const GaussianProcess& gp, Random& random, int count) {
  const GpMeanLattice& lattice = gp.lattice();
  const Eigen::Vector2d lo = lattice.origin().array() - 5.0;
  const Eigen::Vector2d hi =
      lattice.origin() +
      lattice.spacing().cwiseProduct(Eigen::Vector2d(static_cast<double>(lattice.nodes_x() - 1),
                                                     static_cast<double>(lattice.nodes_y() - 1))) +
      Eigen::Vector2d::Constant(5.0);
  Eigen::Matrix2Xd queries(2, count);
  for (int i = 0; i < count; ++i) {
    queries.col(i) << random.uniform(lo.x(), hi.x()), random.uniform(lo.y(), hi.y());
  }
  return (gp.mean_batch(queries) - gp.exact_mean_batch(queries)).cwiseAbs().maxCoeff();
}

struct LatticeCase {
  double width, height;
  Eigen::Vector2d length_scale;
  double signal_std;
};

void PrintTo(const LatticeCase& c, std::ostream* out) {
  *out << c.width << "x" << c.height << "m_l" << c.length_scale.x() << "x" << c.length_scale.y()
       << "_sf" << c.signal_std;
}

class GaussianProcessLattice : public ::testing::TestWithParam<LatticeCase> {};

TEST_P(GaussianProcessLattice, AddsAtMostAMillimetreToTheExactMean) {
  const LatticeCase c = GetParam();
  Random random(41);
  const GpHyperparameters h =
      hyperparameters(c.length_scale.x(), c.length_scale.y(), c.signal_std, 0.02);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 1000, c.width, c.height);
  const Eigen::Matrix2Xd outputs = gp_sample(random, h, inputs);
  GaussianProcessOptions options;
  options.hyperparameters = h;
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs, options);
  ASSERT_FALSE(fit.model.lattice().empty()) << fit.model.lattice().message();
  EXPECT_LE(fit.summary.lattice_error, 0.5e-3);
  EXPECT_LE(lattice_error(fit.model, random, 20000), 1e-3) << fit.model.lattice().message();
}

INSTANTIATE_TEST_SUITE_P(
    GaussianProcess, GaussianProcessLattice,
    ::testing::Values(LatticeCase{40, 20, {2, 2}, 1.0}, LatticeCase{40, 20, {5, 5}, 0.05},
                      LatticeCase{40, 20, {10, 10}, 1.0}, LatticeCase{40, 20, {2, 10}, 0.3},
                      LatticeCase{100, 50, {2, 2}, 0.05}, LatticeCase{100, 50, {2, 2}, 1.0},
                      LatticeCase{100, 50, {5, 5}, 1.0}, LatticeCase{100, 50, {10, 4}, 1.0}));

TEST(GaussianProcessLatticeRaw, AddsAtMostAMillimetreOnRawGridCoordinates) {
  // The `gp` model's case: grid = rotated, shifted, scaled plan plus a smooth bend, tuned.
  Random random(43);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 1000, 100.0, 50.0);
  Eigen::Matrix2Xd outputs(2, inputs.cols());
  const double angle = 0.3;
  for (Eigen::Index i = 0; i < inputs.cols(); ++i) {
    const Eigen::Vector2d p = inputs.col(i);
    outputs.col(i) << 1.01 * (std::cos(angle) * p.x() - std::sin(angle) * p.y()) + 12.0,
        1.01 * (std::sin(angle) * p.x() + std::cos(angle) * p.y()) - 7.0 +
            0.5 * std::pow(p.x() / 100.0, 2) + random.normal(0.02);
  }
  const GaussianProcessFit fit = fit_gaussian_process(inputs, outputs);
  ASSERT_FALSE(fit.model.lattice().empty()) << fit.model.lattice().message();
  EXPECT_LE(lattice_error(fit.model, random, 20000), 1e-3) << fit.summary.message;
  // And the GP reproduces the truth between the data.
  const Eigen::Vector2d p(50.0, 25.0);
  const Eigen::Vector2d truth(
      1.01 * (std::cos(angle) * p.x() - std::sin(angle) * p.y()) + 12.0,
      1.01 * (std::sin(angle) * p.x() + std::cos(angle) * p.y()) - 7.0 + 0.125);
  EXPECT_LT((fit.model.mean(p) - truth).norm(), 0.02) << fit.summary.message;
}

TEST(GaussianProcessLatticeOptions, DisabledOrTooFineMeansExactEverywhere) {
  Random random(47);
  const GpHyperparameters h = hyperparameters(3, 3, 0.5, 0.02);
  const Eigen::Matrix2Xd inputs = uniform_points(random, 200, 30.0, 20.0);
  const Eigen::Matrix2Xd outputs = gp_sample(random, h, inputs);
  GaussianProcessOptions options;
  options.hyperparameters = h;
  options.prediction.lattice.enabled = false;
  const GaussianProcessFit off = fit_gaussian_process(inputs, outputs, options);
  EXPECT_TRUE(off.model.lattice().empty());
  EXPECT_EQ(off.summary.lattice_nodes, 0);
  const Eigen::Matrix2Xd queries = uniform_points(random, 500, 30.0, 20.0);
  EXPECT_EQ(off.model.mean_batch(queries), off.model.exact_mean_batch(queries));

  options.prediction.lattice.enabled = true;
  options.prediction.lattice.max_nodes = 100;
  const GaussianProcessFit coarse = fit_gaussian_process(inputs, outputs, options);
  EXPECT_TRUE(coarse.model.lattice().empty());
  EXPECT_NE(coarse.model.lattice().message().find("max_nodes"), std::string::npos)
      << coarse.model.lattice().message();
  EXPECT_EQ(coarse.model.mean_batch(queries), coarse.model.exact_mean_batch(queries));

  // A tighter tolerance gives a finer lattice that meets it.
  options.prediction.lattice.max_nodes = 1'000'000;
  options.prediction.lattice.tolerance = 1e-6;
  const GaussianProcessFit fine = fit_gaussian_process(inputs, outputs, options);
  ASSERT_FALSE(fine.model.lattice().empty()) << fine.model.lattice().message();
  EXPECT_LE(fine.summary.lattice_error, 0.5e-6);
  EXPECT_LE(lattice_error(fine.model, random, 5000), 1e-6);
}

}  // namespace
}  // namespace floorgrid
