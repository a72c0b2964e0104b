#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/predicates.hpp"
#include "floorgrid/mapping/delaunay.hpp"

namespace floorgrid::test {

/// n points uniform in [0, width] x [0, height].
inline Eigen::Matrix2Xd uniform_points(Random& random, int n, double width = 100.0,
                                       double height = 100.0) {
  Eigen::Matrix2Xd p(2, n);
  for (int i = 0; i < n; ++i)
    p.col(i) << random.uniform(0, width), random.uniform(0, height);
  return p;
}

/// "Laser pairs along walls": n points densely along `walls` random axis-aligned or slanted
/// segments in a 100 m square, each with normal noise of `noise` metres across the wall: many
/// nearly collinear points.
inline Eigen::Matrix2Xd wall_points(Random& random, int n, int walls, double noise) {
  std::vector<std::array<Eigen::Vector2d, 2>> segments;
  for (int w = 0; w < walls; ++w) {
    const Eigen::Vector2d a(random.uniform(0, 100), random.uniform(0, 100));
    const double length = random.uniform(2, 30);
    const int kind = static_cast<int>(random.integer(0, 2));
    const double angle =
        kind == 0 ? 0.0 : (kind == 1 ? 1.5707963267948966 : random.uniform(0, 3.14));
    segments.push_back({a, a + length * Eigen::Vector2d(std::cos(angle), std::sin(angle))});
  }
  Eigen::Matrix2Xd p(2, n);
  for (int i = 0; i < n; ++i) {
    const auto& s = segments[static_cast<std::size_t>(random.integer(0, walls - 1))];
    const Eigen::Vector2d d = s[1] - s[0];
    const Eigen::Vector2d normal = Eigen::Vector2d(-d.y(), d.x()).normalized();
    p.col(i) = s[0] + random.uniform() * d + random.normal(noise) * normal;
  }
  return p;
}

/// A triangle as its vertex set rotated to start at the smallest index (orientation kept).
inline std::array<int, 3> canonical(std::array<int, 3> t) {
  while (t[0] > t[1] || t[0] > t[2])
    std::rotate(t.begin(), t.begin() + 1, t.end());
  return t;
}

/// The triangles as a sorted set of canonical triples.
inline std::set<std::array<int, 3>> triangle_set(const DelaunayTriangulation& dt) {
  std::set<std::array<int, 3>> s;
  for (const auto& t : dt.triangles())
    s.insert(canonical(t));
  return s;
}

inline const double* at(const DelaunayTriangulation& dt, int v) {
  return dt.points().col(v).data();
}

/// Structure: counter-clockwise triangles (exact), symmetric neighbours sharing the right edge,
/// hull edges exactly where neighbours are -1 and in hull order, every vertex used, no duplicate
/// used, and Euler's count 2n - h - 2. Local Delaunay on every inner edge (the neighbour's far
/// vertex is never strictly inside the circumcircle), which implies the global property.
inline void expect_valid_delaunay(const DelaunayTriangulation& dt) {
  ASSERT_FALSE(dt.degenerate()) << dt.message();
  const auto& tris = dt.triangles();
  const auto& nbrs = dt.neighbors();
  const int n = static_cast<int>(dt.points().cols());
  ASSERT_EQ(tris.size(), nbrs.size());
  const int h = static_cast<int>(dt.hull().size());
  ASSERT_EQ(static_cast<int>(tris.size()), 2 * dt.vertex_count() - h - 2) << "Euler";
  std::vector<int> used(static_cast<std::size_t>(n), 0);
  std::vector<int> hull_position(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < h; ++k)
    hull_position[static_cast<std::size_t>(dt.hull()[static_cast<std::size_t>(k)])] = k;
  int hull_edges = 0;
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const auto& v = tris[t];
    ASSERT_GT(orient2d(at(dt, v[0]), at(dt, v[1]), at(dt, v[2])), 0.0) << "triangle " << t;
    for (int k = 0; k < 3; ++k) {
      const int vk = v[static_cast<std::size_t>(k)];
      ASSERT_EQ(dt.duplicate_of()[static_cast<std::size_t>(vk)], vk) << "duplicate used";
      used[static_cast<std::size_t>(vk)] = 1;
      const int a = v[static_cast<std::size_t>((k + 1) % 3)];
      const int b = v[static_cast<std::size_t>((k + 2) % 3)];
      const int o = nbrs[t][static_cast<std::size_t>(k)];
      if (o < 0) {
        ++hull_edges;
        const int pa = hull_position[static_cast<std::size_t>(a)];
        ASSERT_GE(pa, 0);
        ASSERT_EQ(dt.hull()[static_cast<std::size_t>((pa + 1) % h)], b) << "hull order";
        continue;
      }
      const auto& w = tris[static_cast<std::size_t>(o)];
      int far = -1, far_index = -1;
      for (int m = 0; m < 3; ++m) {
        if (w[static_cast<std::size_t>(m)] != a && w[static_cast<std::size_t>(m)] != b) {
          far = w[static_cast<std::size_t>(m)];
          far_index = m;
        }
      }
      ASSERT_GE(far, 0);
      ASSERT_EQ(w[static_cast<std::size_t>((far_index + 1) % 3)], b) << "shared edge reversed";
      ASSERT_EQ(w[static_cast<std::size_t>((far_index + 2) % 3)], a);
      ASSERT_EQ(nbrs[static_cast<std::size_t>(o)][static_cast<std::size_t>(far_index)],
                static_cast<int>(t))
          << "neighbours symmetric";
      ASSERT_LE(incircle(at(dt, v[0]), at(dt, v[1]), at(dt, v[2]), at(dt, far)), 0.0)
          << "local Delaunay, triangle " << t;
    }
  }
  ASSERT_EQ(hull_edges, h);
  for (int i = 0; i < n; ++i) {
    const bool vertex = dt.duplicate_of()[static_cast<std::size_t>(i)] == i;
    ASSERT_EQ(used[static_cast<std::size_t>(i)] == 1, vertex) << "point " << i;
  }
  // The hull is convex (left or straight turns) and holds every point.
  for (int k = 0; k < h; ++k) {
    const int a = dt.hull()[static_cast<std::size_t>(k)];
    const int b = dt.hull()[static_cast<std::size_t>((k + 1) % h)];
    const int c = dt.hull()[static_cast<std::size_t>((k + 2) % h)];
    ASSERT_GE(orient2d(at(dt, a), at(dt, b), at(dt, c)), 0.0);
  }
}

/// The empty-circumcircle property by brute force: no point strictly inside any triangle's
/// circumcircle (exact incircle), every triangle against every point.
inline void expect_empty_circumcircles(const DelaunayTriangulation& dt) {
  const int n = static_cast<int>(dt.points().cols());
  for (const auto& t : dt.triangles()) {
    for (int p = 0; p < n; ++p) {
      ASSERT_LE(incircle(at(dt, t[0]), at(dt, t[1]), at(dt, t[2]), at(dt, p)), 0.0)
          << "point " << p << " inside the circumcircle of (" << t[0] << ", " << t[1] << ", "
          << t[2] << ")";
    }
  }
  // And every point is inside or on the hull.
  const int h = static_cast<int>(dt.hull().size());
  for (int k = 0; k < h; ++k) {
    const int a = dt.hull()[static_cast<std::size_t>(k)];
    const int b = dt.hull()[static_cast<std::size_t>((k + 1) % h)];
    for (int p = 0; p < n; ++p)
      ASSERT_GE(orient2d(at(dt, a), at(dt, b), at(dt, p)), 0.0) << "point " << p << " outside";
  }
}

}  // namespace floorgrid::test
