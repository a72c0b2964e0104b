#include "floorgrid/mapping/delaunay.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "tests/mapping/delaunay_test_support.hpp"
#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

using test::expect_empty_circumcircles;
using test::expect_valid_delaunay;
using test::triangle_set;

Eigen::Matrix2Xd from_list(const std::vector<Eigen::Vector2d>& list) {
  Eigen::Matrix2Xd p(2, static_cast<Eigen::Index>(list.size()));
  for (std::size_t i = 0; i < list.size(); ++i)
    p.col(static_cast<Eigen::Index>(i)) = list[i];
  return p;
}

TEST(DelaunayTriangulation, SmallRandomSetsHaveEmptyCircumcircles) {
  Random random(1);
  for (const int n : {3, 4, 5, 7, 10, 20, 50, 100, 300, 1000}) {
    for (int rep = 0; rep < 3; ++rep) {
      const Eigen::Matrix2Xd p = test::uniform_points(random, n);
      const DelaunayTriangulation dt(p);
      SCOPED_TRACE(n);
      expect_valid_delaunay(dt);
      expect_empty_circumcircles(dt);
      EXPECT_EQ(dt.duplicate_count(), 0);
    }
  }
}

TEST(DelaunayTriangulation, SingleTriangleInEitherOrientation) {
  const DelaunayTriangulation ccw(from_list({{0, 0}, {1, 0}, {0, 1}}));
  ASSERT_EQ(ccw.triangles().size(), 1u);
  EXPECT_EQ(test::canonical(ccw.triangles()[0]), (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(ccw.hull(), (std::vector<int>{0, 1, 2}));
  const DelaunayTriangulation cw(from_list({{0, 0}, {0, 1}, {1, 0}}));
  EXPECT_EQ(test::canonical(cw.triangles()[0]), (std::array<int, 3>{0, 2, 1}));
  EXPECT_EQ(cw.hull(), (std::vector<int>{0, 2, 1}));
  EXPECT_EQ(cw.neighbors()[0], (std::array<int, 3>{-1, -1, -1}));
}

TEST(DelaunayTriangulation, IntegerGridIsDelaunay) {
  // Every unit square has four co-circular corners, and the hull's sides hold many collinear
  // points: the hard case for inexact predicates. Also far from the origin and rotated.
  for (const double offset : {0.0, 1e6}) {
    std::vector<Eigen::Vector2d> list;
    for (int i = 0; i < 25; ++i) {
      for (int j = 0; j < 20; ++j)
        list.emplace_back(offset + i, offset - j);
    }
    const DelaunayTriangulation dt(from_list(list));
    expect_valid_delaunay(dt);
    expect_empty_circumcircles(dt);
    EXPECT_EQ(dt.hull().size(), 2u * (25 + 20) - 4);
    EXPECT_EQ(dt.triangles().size(), 2u * 24 * 19);
  }
  // A grid rotated by a rational rotation (3/5, 4/5): exact integer coordinates.
  std::vector<Eigen::Vector2d> rotated;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j)
      rotated.emplace_back(3.0 * i - 4.0 * j, 4.0 * i + 3.0 * j);
  }
  const DelaunayTriangulation dt(from_list(rotated));
  expect_valid_delaunay(dt);
  expect_empty_circumcircles(dt);
}

TEST(DelaunayTriangulation, UlpPerturbedGridIsDelaunay) {
  // A grid whose points are moved by 0-3 ulps: nearly co-circular and collinear everywhere.
  Random random(5);
  std::vector<Eigen::Vector2d> list;
  for (int i = 0; i < 18; ++i) {
    for (int j = 0; j < 18; ++j) {
      double x = 0.5 + 0.125 * i, y = 0.5 + 0.125 * j;
      for (int k = static_cast<int>(random.integer(0, 3)); k > 0; --k)
        x = std::nextafter(x, random.bernoulli(0.5) ? 10.0 : -10.0);
      for (int k = static_cast<int>(random.integer(0, 3)); k > 0; --k)
        y = std::nextafter(y, random.bernoulli(0.5) ? 10.0 : -10.0);
      list.emplace_back(x, y);
    }
  }
  const DelaunayTriangulation dt(from_list(list));
  expect_valid_delaunay(dt);
  expect_empty_circumcircles(dt);
}

TEST(DelaunayTriangulation, CocircularPointsAreDelaunay) {
  // 44 integer points on the circle x^2 + y^2 = 5^20 (from powers of 3 + 4i) and its centre.
  std::vector<Eigen::Vector2d> list;
  for (int k = 0; k <= 10; ++k) {
    std::int64_t re = 1, im = 0;
    for (int i = 0; i < 10; ++i) {
      const std::int64_t b = i < k ? 4 : -4;
      const std::int64_t r = re * 3 - im * b;
      im = re * b + im * 3;
      re = r;
    }
    const double x = static_cast<double>(re), y = static_cast<double>(im);
    list.emplace_back(x, y);
    list.emplace_back(-y, x);
    list.emplace_back(-x, -y);
    list.emplace_back(y, -x);
  }
  {
    const DelaunayTriangulation dt(from_list(list));
    expect_valid_delaunay(dt);
    expect_empty_circumcircles(dt);
    EXPECT_EQ(dt.hull().size(), list.size());
    EXPECT_EQ(dt.triangles().size(), list.size() - 2);
  }
  list.emplace_back(0.0, 0.0);
  const DelaunayTriangulation dt(from_list(list));
  expect_valid_delaunay(dt);
  expect_empty_circumcircles(dt);
}

TEST(DelaunayTriangulation, PointsOnFewLinesAreDelaunay) {
  // Exactly collinear runs on a few lines (as laser endpoints on walls, without noise), and the
  // same with noise of a micrometre.
  Random random(7);
  for (const double noise : {0.0, 1e-6}) {
    std::vector<Eigen::Vector2d> list;
    const std::vector<std::array<double, 4>> lines = {
        {0, 0, 1, 0}, {0, 0, 0, 1}, {0, 10, 1, 0}, {3, 0, 1, 2}, {0, 7, 2, -1}};
    for (const auto& l : lines) {
      for (int k = 0; k < 60; ++k) {
        const double s = static_cast<double>(random.integer(0, 200)) * 0.0625;
        list.emplace_back(l[0] + s * l[2] + random.normal(noise), l[1] + s * l[3]);
      }
    }
    const DelaunayTriangulation dt(from_list(list));
    SCOPED_TRACE(noise);
    expect_valid_delaunay(dt);
    expect_empty_circumcircles(dt);
  }
}

TEST(DelaunayTriangulation, WallPointsAreDelaunay) {
  Random random(8);
  const Eigen::Matrix2Xd p = test::wall_points(random, 1500, 12, 0.01);
  const DelaunayTriangulation dt(p);
  expect_valid_delaunay(dt);
  expect_empty_circumcircles(dt);
}

TEST(DelaunayTriangulation, LargeSetsAreLocallyDelaunay) {
  // Local Delaunay on every edge (checked by expect_valid_delaunay) implies the global property.
  Random random(9);
  const DelaunayTriangulation uniform(test::uniform_points(random, 100000));
  expect_valid_delaunay(uniform);
  const DelaunayTriangulation walls(test::wall_points(random, 100000, 300, 0.005));
  expect_valid_delaunay(walls);
}

TEST(DelaunayTriangulation, DuplicatesAreSkippedAndReported) {
  Random random(10);
  const int unique = 300;
  Eigen::Matrix2Xd base = test::uniform_points(random, unique);
  // Append copies of random points (some several times), then shuffle everything.
  std::vector<Eigen::Vector2d> list;
  for (int i = 0; i < unique; ++i)
    list.emplace_back(base.col(i));
  for (int k = 0; k < 200; ++k)
    list.emplace_back(base.col(static_cast<Eigen::Index>(random.integer(0, 40))));
  std::vector<int> shuffle(list.size());
  for (std::size_t i = 0; i < shuffle.size(); ++i)
    shuffle[i] = static_cast<int>(i);
  for (std::size_t i = shuffle.size() - 1; i > 0; --i)
    std::swap(shuffle[i],
              shuffle[static_cast<std::size_t>(random.integer(0, static_cast<std::int64_t>(i)))]);
  std::vector<Eigen::Vector2d> mixed;
  for (const int s : shuffle)
    mixed.push_back(list[static_cast<std::size_t>(s)]);
  const Eigen::Matrix2Xd p = from_list(mixed);
  const DelaunayTriangulation dt(p);
  expect_valid_delaunay(dt);
  expect_empty_circumcircles(dt);
  EXPECT_EQ(dt.duplicate_count(), 200);
  EXPECT_EQ(dt.vertex_count(), unique);
  // Each point maps to the lowest index with the same coordinates.
  for (Eigen::Index i = 0; i < p.cols(); ++i) {
    int lowest = static_cast<int>(i);
    for (Eigen::Index j = 0; j < i; ++j) {
      if (p.col(j) == p.col(i)) {
        lowest = static_cast<int>(j);
        break;
      }
    }
    EXPECT_EQ(dt.duplicate_of()[static_cast<std::size_t>(i)], lowest) << i;
  }
  // The same triangulation as without the duplicates (in terms of coordinates).
  const DelaunayTriangulation plain(base);
  EXPECT_EQ(dt.triangles().size(), plain.triangles().size());
}

TEST(DelaunayTriangulation, DegenerateInputsAreReported) {
  struct Case {
    std::vector<Eigen::Vector2d> points;
    DelaunayStatus status;
    int vertices;
    const char* words;
  };
  const std::vector<Case> cases = {
      {{}, DelaunayStatus::too_few_points, 0, "at least 3 distinct points, got 0"},
      {{{1, 2}}, DelaunayStatus::too_few_points, 1, "got 1"},
      {{{1, 2}, {3, 4}}, DelaunayStatus::too_few_points, 2, "got 2"},
      {{{1, 2}, {1, 2}, {1, 2}, {1, 2}}, DelaunayStatus::too_few_points, 1, "3 duplicates"},
      {{{1, 2}, {3, 4}, {1, 2}, {3, 4}, {3, 4}}, DelaunayStatus::too_few_points, 2, "got 2"},
      {{{0, 0}, {1, 1}, {2, 2}}, DelaunayStatus::collinear, 3, "all 3 distinct points"},
      {{{0.5, 1.5}, {0.25, 0.75}, {8, 24}, {0.5, 1.5}}, DelaunayStatus::collinear, 3, "one line"},
  };
  for (const Case& c : cases) {
    const DelaunayTriangulation dt(from_list(c.points));
    EXPECT_EQ(dt.status(), c.status) << c.words;
    EXPECT_TRUE(dt.degenerate());
    EXPECT_NE(dt.message().find(c.words), std::string::npos) << dt.message();
    EXPECT_TRUE(dt.triangles().empty());
    EXPECT_TRUE(dt.hull().empty());
    EXPECT_EQ(dt.vertex_count(), c.vertices);
    EXPECT_EQ(dt.locate(Eigen::Vector2d(1, 2)).triangle, -1);
  }
  // Collinearity is decided exactly on the doubles as given: (0.1, 0.3), (0.2, 0.6), (0.3, 0.9)
  // are rounded decimals, collinear or not as the exact orientation says.
  const DelaunayTriangulation rounded(from_list({{0.1, 0.3}, {0.2, 0.6}, {0.3, 0.9}}));
  EXPECT_EQ(rounded.status(), orient2d(Eigen::Vector2d(0.1, 0.3), Eigen::Vector2d(0.2, 0.6),
                                       Eigen::Vector2d(0.3, 0.9)) == 0.0
                                  ? DelaunayStatus::collinear
                                  : DelaunayStatus::ok);
  // Many exactly collinear points (with duplicates): collinear, duplicates mapped.
  std::vector<Eigen::Vector2d> line;
  for (int i = 0; i < 1000; ++i)
    line.emplace_back(0.25 * (i % 700), 1.0 + 0.5 * (i % 700));
  const DelaunayTriangulation dt(from_list(line));
  EXPECT_EQ(dt.status(), DelaunayStatus::collinear);
  EXPECT_EQ(dt.vertex_count(), 700);
  EXPECT_EQ(dt.duplicate_of()[750], 50);
  // One point off the line makes it a proper triangulation.
  line.emplace_back(3.0, 0.0);
  const DelaunayTriangulation fan(from_list(line));
  expect_valid_delaunay(fan);
  EXPECT_EQ(fan.triangles().size(), 699u);
}

TEST(DelaunayTriangulation, NonFinitePointsThrow) {
  test::expect_input_error(
      [] {
        DelaunayTriangulation dt(from_list({{0, 0}, {1, NAN}, {0, 1}}));
      },
      {"points", "point 1 is not finite"});
  test::expect_input_error(
      [] {
        DelaunayTriangulation dt(from_list({{0, 0}, {1, 0}, {INFINITY, 1}}));
      },
      {"point 2"});
}

TEST(DelaunayTriangulation, DeterministicAndSeedIndependentInGeneralPosition) {
  Random random(12);
  const Eigen::Matrix2Xd p = test::uniform_points(random, 2000);
  const DelaunayTriangulation a(p), b(p);
  EXPECT_EQ(a.triangles(), b.triangles());
  EXPECT_EQ(a.neighbors(), b.neighbors());
  EXPECT_EQ(a.hull(), b.hull());
  DelaunayOptions other;
  other.seed = 77;
  const DelaunayTriangulation c(p, other);
  EXPECT_EQ(triangle_set(a), triangle_set(c));  // general position: the triangulation is unique
  EXPECT_EQ(a.hull(), c.hull());
  // With co-circular points the seed may choose other diagonals, but a seed repeats itself.
  std::vector<Eigen::Vector2d> grid;
  for (int i = 0; i < 15; ++i) {
    for (int j = 0; j < 15; ++j)
      grid.emplace_back(i, j);
  }
  const DelaunayTriangulation g1(from_list(grid), other), g2(from_list(grid), other);
  EXPECT_EQ(g1.triangles(), g2.triangles());
}

TEST(DelaunayTriangulation, HullStartsAtLowestIndexCounterClockwise) {
  const DelaunayTriangulation dt(
      from_list({{1, 1}, {0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {1, 0.5}}));
  expect_valid_delaunay(dt);
  EXPECT_EQ(dt.hull(), (std::vector<int>{1, 5, 2, 3, 4}));
}

}  // namespace
}  // namespace floorgrid
