#include "floorgrid/mapping/thin_plate_spline_lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

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

// Raw laser-like pairs (no binning) in a 40 x 30 m box, 2 cm of noise: close centres that
// disagree by centimetres give an interpolant (lambda 0) large, opposite kernel weights, whose
// kernels bend sharply right at the centres (the hardest case for a lattice).
ThinPlateSpline raw_spline(Random& random, int count) {
  Eigen::Matrix2Xd plan(2, count), grid(2, count);
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d p(random.uniform(0.0, 40.0), random.uniform(0.0, 30.0));
    plan.col(i) = p;
    grid.col(i) = Eigen::Vector2d(0.99 * p.x() - 0.1 * p.y() + 3.0,
                                  0.1 * p.x() + 0.99 * p.y() + 0.4 * std::sin(p.x() / 8.0)) +
                  Eigen::Vector2d(random.normal(0.02), random.normal(0.02));
  }
  return ThinPlateSpline::fit(plan, grid);
}

Eigen::Matrix2Xd points_in(Random& random, const Eigen::AlignedBox2d& box, int count) {
  Eigen::Matrix2Xd points(2, count);
  for (int i = 0; i < count; ++i) {
    points.col(i) = Eigen::Vector2d(random.uniform(box.min().x(), box.max().x()),
                                    random.uniform(box.min().y(), box.max().y()));
  }
  return points;
}

// The largest |lattice - spline| over `count` random points of the box and as many within
// 0.3 m of the spline's centres (where the error concentrates), metres.
double added_error(Random& random, const ThinPlateSplineLattice& lattice, int count) {
  const Eigen::Matrix2Xd& centres = lattice.spline().data().centres_in_plan;
  Eigen::Matrix2Xd queries(2, 2 * count);
  queries.leftCols(count) = points_in(random, kBox, count);
  for (int i = 0; i < count; ++i) {
    queries.col(count + i) = centres.col(i % centres.cols()) +
                             Eigen::Vector2d(random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3));
  }
  return (lattice.evaluate_batch(queries) - lattice.spline().evaluate_batch(queries))
      .colwise()
      .norm()
      .maxCoeff();
}

TEST(ThinPlateSplineLattice, AddsLessThan1mmOnBinnedPairs) {
  Random random(21);
  for (const double lambda : {0.0, 0.01}) {
    const ThinPlateSpline spline = binned_spline(random, lambda);
    const ThinPlateSplineLattice lattice(spline, kBox);
    EXPECT_LE(lattice.spacing(), 1.0);
    EXPECT_LE(lattice.measured_error(), 0.5e-3) << lambda;
    EXPECT_LT(added_error(random, lattice, 20000), 0.001) << lambda;
    const Eigen::Matrix2Xd queries = points_in(random, kBox, 20000);
    const Eigen::Matrix2Xd approximate = lattice.evaluate_batch(queries);
    for (Eigen::Index i = 0; i < queries.cols(); i += 1000) {
      const Eigen::Vector2d p = queries.col(i);
      EXPECT_EQ(lattice.evaluate(p), Eigen::Vector2d(approximate.col(i)));
      EXPECT_LT((lattice.jacobian(p) - spline.jacobian(p)).norm(), 0.01) << lambda;
    }
  }
}

TEST(ThinPlateSplineLattice, RefinesTheSpacingUntilTheAddedErrorIsWithinTolerance) {
  Random random(25);
  const ThinPlateSpline spline = raw_spline(random, 200);
  // Kept at its first spacing (any error tolerated), the lattice errs by millimetres near the
  // centres: the case is one that refinement has to catch.
  ThinPlateSplineLatticeOptions coarse;
  coarse.tolerance = 1e9;
  const ThinPlateSplineLattice first(spline, kBox, coarse);
  EXPECT_EQ(first.spacing(), 1.0);
  EXPECT_GT(added_error(random, first, 20000), 0.002);
  for (const double tolerance : {1e-3, 1e-4}) {
    ThinPlateSplineLatticeOptions options;
    options.tolerance = tolerance;
    const ThinPlateSplineLattice lattice(spline, kBox, options);
    ASSERT_FALSE(lattice.empty()) << lattice.message();
    EXPECT_GT(lattice.attempts(), 1);
    EXPECT_LT(lattice.spacing(), 1.0);
    EXPECT_LE(lattice.measured_error(), 0.5 * tolerance);
    // Measured independently of the lattice's own test points: within the tolerance.
    EXPECT_LE(added_error(random, lattice, 50000), tolerance) << lattice.message();
  }
}

TEST(ThinPlateSplineLattice, GivesUpForTheExactSplineBeyondMaxNodes) {
  Random random(26);
  const ThinPlateSpline spline = raw_spline(random, 200);
  ThinPlateSplineLatticeOptions options;
  // The 1 m lattice over the box has 1,344 nodes and errs by centimetres; the spacings that
  // would do need more than 5,000.
  options.max_nodes = 5000;
  const ThinPlateSplineLattice lattice(spline, kBox, options);
  EXPECT_TRUE(lattice.empty());
  EXPECT_EQ(lattice.attempts(), 1);  // one spacing measured
  EXPECT_NE(lattice.message().find("no lattice"), std::string::npos) << lattice.message();
  EXPECT_EQ(lattice.measured_error(), std::numeric_limits<double>::infinity());
  const Eigen::Matrix2Xd queries = points_in(random, kBox, 100);
  EXPECT_FALSE(lattice.contains(queries.col(0)));
  EXPECT_EQ(lattice.evaluate_batch(queries), spline.evaluate_batch(queries));
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
  const auto expect_refused = [&](const ThinPlateSplineLatticeOptions& options, const char* field) {
    test::expect_input_error([&] { ThinPlateSplineLattice(spline, kBox, options); }, {field});
  };
  for (const double tolerance :
       {0.0, -1e-3, std::numeric_limits<double>::infinity(), std::nan("")}) {
    ThinPlateSplineLatticeOptions options;
    options.tolerance = tolerance;
    expect_refused(options, "tps_lattice.tolerance");
  }
  ThinPlateSplineLatticeOptions options;
  options.margin = -0.1;
  expect_refused(options, "tps_lattice.margin");
  options = {};
  options.threads = 0;
  expect_refused(options, "tps_lattice.threads");
  options = {};
  options.max_nodes = 3;
  expect_refused(options, "tps_lattice.max_nodes");
  test::expect_input_error([&] { ThinPlateSplineLattice(spline, Eigen::AlignedBox2d()); },
                           {"tps_lattice.box"});
}

}  // namespace
}  // namespace floorgrid
