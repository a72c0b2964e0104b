#include "floorgrid/mapping/thin_plate_spline_lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/core/random.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

const Eigen::AlignedBox2d kBox(Eigen::Vector2d(0, 0), Eigen::Vector2d(40, 30));

// One pair per 2 m cell (as binned laser pairs), through a bend, with 5 mm of noise.
ThinPlateSpline binned_spline(Random& random, double lambda) {
  Eigen::Matrix2Xd plan(2, 300), grid(2, 300);
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector2d p(2.0 * (i % 20) + random.uniform(0.2, 1.8),
                            2.0 * (i / 20) + random.uniform(0.2, 1.8));
    plan.col(i) = p;
    grid.col(i) = Eigen::Vector2d(0.99 * p.x() - 0.1 * p.y() + 3.0,
                                  0.1 * p.x() + 0.99 * p.y() + 0.4 * std::sin(p.x() / 8.0)) +
                  Eigen::Vector2d(random.normal(0.005), random.normal(0.005));
  }
  return ThinPlateSpline::fit(plan, grid, {lambda});
}

Eigen::Matrix2Xd points_in(Random& random, const Eigen::AlignedBox2d& box, int count) {
  Eigen::Matrix2Xd points(2, count);
  for (int i = 0; i < count; ++i) {
    points.col(i) = Eigen::Vector2d(random.uniform(box.min().x(), box.max().x()),
                                    random.uniform(box.min().y(), box.max().y()));
  }
  return points;
}

TEST(ThinPlateSplineLattice, AddsLessThan1mmOnBinnedPairs) {
  Random random(21);
  for (const double lambda : {0.0, 0.01}) {
    const ThinPlateSpline spline = binned_spline(random, lambda);
    const ThinPlateSplineLattice lattice(spline, kBox);
    EXPECT_EQ(lattice.spacing(), 0.25);
    const Eigen::Matrix2Xd queries = points_in(random, kBox, 20000);
    const Eigen::Matrix2Xd exact = spline.evaluate_batch(queries);
    const Eigen::Matrix2Xd approximate = lattice.evaluate_batch(queries);
    EXPECT_LT((approximate - exact).colwise().norm().maxCoeff(), 0.001) << lambda;
    for (Eigen::Index i = 0; i < queries.cols(); i += 1000) {
      const Eigen::Vector2d p = queries.col(i);
      EXPECT_EQ(lattice.evaluate(p), Eigen::Vector2d(approximate.col(i)));
      EXPECT_LT((lattice.jacobian(p) - spline.jacobian(p)).norm(), 0.01) << lambda;
    }
  }
}

TEST(ThinPlateSplineLattice, IsExactAtNodesAndForAffineMaps) {
  Random random(22);
  const ThinPlateSpline spline = binned_spline(random, 0.0);
  const ThinPlateSplineLattice lattice(spline, kBox, {0.5, 1.0, 1});
  const Eigen::Vector2d corner = lattice.box().min();
  for (const Eigen::Vector2d& node : {corner, Eigen::Vector2d(corner + Eigen::Vector2d(10.0, 7.5)),
                                      Eigen::Vector2d(corner + Eigen::Vector2d(20.5, 31.0))}) {
    EXPECT_LT((lattice.evaluate(node) - spline.evaluate(node)).norm(), 1e-12);
    EXPECT_LT((lattice.jacobian(node) - spline.jacobian(node)).norm(), 1e-12);
  }
  Eigen::Matrix2Xd plan = points_in(random, kBox, 30);
  const Eigen::Matrix2Xd grid = (Eigen::Matrix2d() << 1.1, 0.2, -0.3, 0.9).finished() * plan;
  const ThinPlateSpline affine = ThinPlateSpline::fit(plan, grid);
  const ThinPlateSplineLattice affine_lattice(affine, kBox, {1.3});
  const Eigen::Matrix2Xd queries = points_in(random, kBox, 1000);
  EXPECT_LT((affine_lattice.evaluate_batch(queries) - affine.evaluate_batch(queries))
                .cwiseAbs()
                .maxCoeff(),
            1e-10);
}

TEST(ThinPlateSplineLattice, IsContinuousAcrossCellsAndExactOutside) {
  Random random(23);
  const ThinPlateSpline spline = binned_spline(random, 0.0);
  const ThinPlateSplineLattice lattice(spline, kBox, {0.5});
  const double x = lattice.box().min().x() + 0.5 * 17;  // a cell border
  const double e = 1e-9;
  for (double y = 1.1; y < 29; y += 3.7) {
    EXPECT_LT((lattice.evaluate({x - e, y}) - lattice.evaluate({x + e, y})).norm(), 1e-8);
    EXPECT_LT((lattice.jacobian({x - e, y}) - lattice.jacobian({x + e, y})).norm(), 1e-6);
  }
  for (const Eigen::Vector2d& outside : {Eigen::Vector2d(-5, 10), Eigen::Vector2d(20, 31.2)}) {
    EXPECT_FALSE(lattice.contains(outside));
    EXPECT_EQ(lattice.evaluate(outside), spline.evaluate(outside));
    EXPECT_EQ(lattice.jacobian(outside), spline.jacobian(outside));
  }
  EXPECT_TRUE(lattice.contains({-0.4, 30.4}));  // inside the 0.5 m margin
}

TEST(ThinPlateSplineLattice, BadOptionsNameTheirField) {
  Random random(24);
  const ThinPlateSpline spline = binned_spline(random, 0.0);
  for (const double spacing : {0.0, -1.0, 1e-4, std::nan("")}) {
    test::expect_input_error([&] { ThinPlateSplineLattice(spline, kBox, {spacing}); },
                             {"tps_lattice.spacing"});
  }
  test::expect_input_error([&] { ThinPlateSplineLattice(spline, Eigen::AlignedBox2d()); },
                           {"tps_lattice.box"});
}

}  // namespace
}  // namespace floorgrid
