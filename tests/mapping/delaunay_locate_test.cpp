#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/predicates.hpp"
#include "floorgrid/mapping/delaunay.hpp"
#include "tests/mapping/delaunay_test_support.hpp"

namespace floorgrid {
namespace {

using Located = DelaunayTriangulation::Located;

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + s * ab - p).norm();
}

// The point mapped back through its barycentric coordinates, and the scale that rounding is
// relative to (the triangle's size and position).
Eigen::Vector2d reproduce(const DelaunayTriangulation& dt, const Located& r) {
  const auto& t = dt.triangles()[static_cast<std::size_t>(r.triangle)];
  return r.barycentric[0] * dt.points().col(t[0]) + r.barycentric[1] * dt.points().col(t[1]) +
         r.barycentric[2] * dt.points().col(t[2]);
}

// An inside answer: the closed triangle holds the point (exact), the coordinates sum to 1 and
// reproduce the point.
void expect_inside(const DelaunayTriangulation& dt, const Eigen::Vector2d& q, const Located& r,
                   double tolerance) {
  ASSERT_TRUE(r.inside);
  ASSERT_GE(r.triangle, 0);
  const auto& t = dt.triangles()[static_cast<std::size_t>(r.triangle)];
  for (int k = 0; k < 3; ++k) {
    ASSERT_GE(orient2d(dt.points().col(t[static_cast<std::size_t>(k)]),
                       dt.points().col(t[static_cast<std::size_t>((k + 1) % 3)]), q),
              0.0);
  }
  EXPECT_NEAR(r.barycentric.sum(), 1.0, 1e-14);
  EXPECT_LE((reproduce(dt, r) - q).norm(), tolerance);
  EXPECT_EQ(r.hull_edge, -1);
  for (int k = 0; k < 3; ++k)
    EXPECT_GE(r.barycentric[k], -1e-12);
}

// An outside answer: the point is strictly outside the hull, the reported edge is the nearest
// hull edge (by brute force), its triangle is the one on that edge, and the (extrapolated)
// coordinates still reproduce the point.
void expect_outside(const DelaunayTriangulation& dt, const Eigen::Vector2d& q, const Located& r,
                    double tolerance) {
  ASSERT_FALSE(r.inside);
  ASSERT_GE(r.hull_edge, 0);
  const auto& hull = dt.hull();
  const int h = static_cast<int>(hull.size());
  bool outside_some_edge = false;
  double nearest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < h; ++k) {
    const Eigen::Vector2d a = dt.points().col(hull[static_cast<std::size_t>(k)]);
    const Eigen::Vector2d b = dt.points().col(hull[static_cast<std::size_t>((k + 1) % h)]);
    outside_some_edge |= orient2d(a, b, q) < 0.0;
    nearest = std::min(nearest, distance_to_segment(q, a, b));
  }
  ASSERT_TRUE(outside_some_edge);
  EXPECT_NEAR(r.hull_distance, nearest, 1e-12 * (1.0 + nearest));
  const int a = hull[static_cast<std::size_t>(r.hull_edge)];
  const int b = hull[static_cast<std::size_t>((r.hull_edge + 1) % h)];
  EXPECT_NEAR(distance_to_segment(q, dt.points().col(a), dt.points().col(b)), r.hull_distance,
              1e-12 * (1.0 + nearest));
  const auto& t = dt.triangles()[static_cast<std::size_t>(r.triangle)];
  int shared = 0;
  for (const int v : t)
    shared += (v == a || v == b);
  EXPECT_EQ(shared, 2) << "the triangle on the nearest hull edge";
  const double magnitude = 1.0 + r.barycentric.cwiseAbs().sum();  // large when extrapolating
  EXPECT_NEAR(r.barycentric.sum(), 1.0, 1e-15 * magnitude);
  EXPECT_LE((reproduce(dt, r) - q).norm(), tolerance * magnitude);
}

TEST(DelaunayLocate, RandomQueriesInsideAndOutside) {
  Random random(21);
  const Eigen::Matrix2Xd p = test::uniform_points(random, 2000, 50.0, 30.0);
  const DelaunayTriangulation dt(p);
  int inside = 0, outside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector2d q(random.uniform(-20, 70), random.uniform(-20, 50));
    const Located r = dt.locate(q);
    if (r.inside) {
      expect_inside(dt, q, r, 1e-12);
      ++inside;
    } else {
      expect_outside(dt, q, r, 1e-12);
      ++outside;
    }
  }
  EXPECT_GT(inside, 4000);  // the hull covers about a quarter of the query box
  EXPECT_GT(outside, 10000);
  // Every input point lies in a triangle at that vertex: one coordinate 1, the others 0.
  for (Eigen::Index i = 0; i < p.cols(); ++i) {
    const Located r = dt.locate(p.col(i));
    expect_inside(dt, p.col(i), r, 1e-13);
    EXPECT_NEAR(r.barycentric.maxCoeff(), 1.0, 1e-12);
  }
}

TEST(DelaunayLocate, EveryVertexAndEdgeMidpointIsInside) {
  // Exactly representable midpoints: a grid with co-circular squares and collinear hull sides.
  std::vector<Eigen::Vector2d> list;
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j < 9; ++j)
      list.emplace_back(i * 0.5, j * 0.25);
  }
  Eigen::Matrix2Xd p(2, static_cast<Eigen::Index>(list.size()));
  for (std::size_t i = 0; i < list.size(); ++i)
    p.col(static_cast<Eigen::Index>(i)) = list[i];
  const DelaunayTriangulation dt(p);
  for (Eigen::Index v = 0; v < p.cols(); ++v) {
    const Located r = dt.locate(p.col(v));
    expect_inside(dt, p.col(v), r, 0.0);
    EXPECT_NEAR(r.barycentric.maxCoeff(), 1.0, 1e-15);
  }
  for (const auto& t : dt.triangles()) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d m = 0.5 * (p.col(t[static_cast<std::size_t>(k)]) +
                                       p.col(t[static_cast<std::size_t>((k + 1) % 3)]));
      expect_inside(dt, m, dt.locate(m), 1e-15);
    }
  }
  // Just outside the hull's sides, by one ulp.
  expect_outside(dt, Eigen::Vector2d(1.0, -std::numeric_limits<double>::denorm_min()),
                 dt.locate(Eigen::Vector2d(1.0, -std::numeric_limits<double>::denorm_min())),
                 1e-15);
  const Eigen::Vector2d beyond(std::nextafter(5.5, 6.0), 1.0);
  const Located r = dt.locate(beyond);
  expect_outside(dt, beyond, r, 1e-15);
  EXPECT_LT(r.hull_distance, 1e-15);
}

TEST(DelaunayLocate, FarOutsideQueriesFindTheNearestHullEdge) {
  Random random(22);
  const Eigen::Matrix2Xd p = test::wall_points(random, 3000, 20, 0.01);
  const DelaunayTriangulation dt(p);
  for (int i = 0; i < 2000; ++i) {
    const double angle = random.uniform(0, 6.283185307179586);
    const double radius = random.uniform(80, 1e5);
    const Eigen::Vector2d q =
        Eigen::Vector2d(50, 50) + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    expect_outside(dt, q, dt.locate(q), 1e-9 * radius);
  }
}

TEST(DelaunayLocate, AnyHintGivesTheSameAnswer) {
  Random random(23);
  const Eigen::Matrix2Xd p = test::uniform_points(random, 500);
  const DelaunayTriangulation dt(p);
  const int triangles = static_cast<int>(dt.triangles().size());
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector2d q(random.uniform(-10, 110), random.uniform(-10, 110));
    const Located reference = dt.locate(q);
    const int hint = static_cast<int>(random.integer(-3, triangles + 3));  // some out of range
    const Located r = dt.locate(q, hint);
    EXPECT_EQ(r.inside, reference.inside);
    EXPECT_EQ(r.triangle, reference.triangle);  // random points are on no edge
    EXPECT_EQ(r.hull_edge, reference.hull_edge);
  }
}

TEST(DelaunayLocate, BatchMatchesSingleQueries) {
  Random random(24);
  const Eigen::Matrix2Xd p = test::wall_points(random, 5000, 40, 0.01);
  const DelaunayTriangulation dt(p);
  Eigen::Matrix2Xd queries = test::uniform_points(random, 20000, 110, 110);
  queries.array() -= 5.0;
  const std::vector<Located> batch = dt.locate_all(queries);
  ASSERT_EQ(batch.size(), 20000u);
  for (Eigen::Index i = 0; i < queries.cols(); ++i) {
    const Located single = dt.locate(queries.col(i));
    const Located& b = batch[static_cast<std::size_t>(i)];
    ASSERT_EQ(b.inside, single.inside) << i;
    EXPECT_EQ(b.triangle, single.triangle);
    EXPECT_EQ(b.hull_edge, single.hull_edge);
    EXPECT_EQ(b.barycentric, single.barycentric);  // same triangle, same arithmetic
  }
}

TEST(DelaunayLocate, FarFromTheOriginBarycentricsReproduceThePoint) {
  // Coordinates around 10^6 m (a building in UTM): the coordinates are computed relative to a
  // vertex, so they reproduce the point to the rounding of the coordinates themselves.
  Random random(25);
  Eigen::Matrix2Xd p = test::uniform_points(random, 1000, 100, 100);
  p.row(0).array() += 5.0e5;
  p.row(1).array() += 5.5e6;
  const DelaunayTriangulation dt(p);
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector2d q(5.0e5 + random.uniform(0, 100), 5.5e6 + random.uniform(0, 100));
    const Located r = dt.locate(q);
    if (r.inside)
      expect_inside(dt, q, r, 1e-8);
  }
}

TEST(DelaunayLocate, DegenerateAndNonFiniteQueries) {
  Eigen::Matrix2Xd line(2, 3);
  line << 0, 1, 2, 0, 1, 2;
  const DelaunayTriangulation degenerate(line);
  EXPECT_EQ(degenerate.locate(Eigen::Vector2d(0.5, 0.5)).triangle, -1);
  EXPECT_FALSE(degenerate.locate(Eigen::Vector2d(0.5, 0.5)).inside);
  EXPECT_EQ(degenerate.locate_all(line).size(), 3u);
  Eigen::Matrix2Xd square(2, 4);
  square << 0, 1, 1, 0, 0, 0, 1, 1;
  const DelaunayTriangulation dt(square);
  EXPECT_EQ(dt.locate(Eigen::Vector2d(NAN, 0.5)).triangle, -1);
  EXPECT_EQ(dt.locate(Eigen::Vector2d(0.5, INFINITY)).triangle, -1);
  Eigen::Matrix2Xd queries(2, 3);
  queries << 0.5, NAN, 0.25, 0.5, 0.0, 0.75;
  const std::vector<Located> batch = dt.locate_all(queries);
  EXPECT_TRUE(batch[0].inside);
  EXPECT_EQ(batch[1].triangle, -1);
  EXPECT_TRUE(batch[2].inside);
}

}  // namespace
}  // namespace floorgrid
