// Point location in a DelaunayTriangulation: visibility walks, the nearest hull edge of outside
// points, batches along a Hilbert curve.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "floorgrid/geometry/hilbert_curve.hpp"
#include "floorgrid/geometry/predicates.hpp"
#include "floorgrid/mapping/delaunay.hpp"

namespace floorgrid {
namespace {

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  // Beyond an end, the distance to that end itself: the two edges at a hull vertex then give
  // exactly the same distance, and the tie is broken by index, not by rounding.
  const Eigen::Vector2d ab = b - a;
  const double along = (p - a).dot(ab);
  if (along <= 0.0)
    return (p - a).norm();
  const double length_squared = ab.squaredNorm();
  if (along >= length_squared)
    return (p - b).norm();
  return (a + (along / length_squared) * ab - p).norm();
}

}  // namespace

Eigen::Vector3d DelaunayTriangulation::barycentric(int t, const Eigen::Vector2d& point) const {
  // Relative to the first vertex, so that coordinates far from the origin lose nothing to the
  // translation: point = a + l1 (b - a) + l2 (c - a).
  const std::array<int, 3>& tri = triangles_[static_cast<std::size_t>(t)];
  const Eigen::Vector2d a = points_.col(tri[0]);
  const Eigen::Vector2d e1 = points_.col(tri[1]) - a;
  const Eigen::Vector2d e2 = points_.col(tri[2]) - a;
  const Eigen::Vector2d d = point - a;
  const double area = e1.x() * e2.y() - e1.y() * e2.x();
  const double l1 = (d.x() * e2.y() - d.y() * e2.x()) / area;
  const double l2 = (e1.x() * d.y() - e1.y() * d.x()) / area;
  return {1.0 - l1 - l2, l1, l2};
}

int DelaunayTriangulation::walk(int t, const double* p, int& exit_edge) const {
  // Visibility walk (as in the insertion kernel): cross an edge that has p strictly beyond it,
  // never straight back, trying the edges from a random one. Stops in a triangle whose closure
  // holds p, or at a hull edge with p strictly outside (exit_edge).
  exit_edge = -1;
  std::uint32_t random = 0x2545f491u ^ static_cast<std::uint32_t>(t);
  int previous = -1;
  const std::size_t step_limit = 4 * triangles_.size() + 16;
  for (std::size_t step = 0; step < step_limit; ++step) {
    random ^= random << 13;
    random ^= random >> 17;
    random ^= random << 5;
    const int first = static_cast<int>(random % 3u);
    const std::array<int, 3>& tri = walk_triangles_[static_cast<std::size_t>(t)];
    const std::array<int, 3>& across = neighbors_[static_cast<std::size_t>(t)];
    int next = -1;
    for (int j = 0; j < 3; ++j) {
      const int k = (first + j) % 3;
      if (previous >= 0 && across[static_cast<std::size_t>(k)] == previous)
        continue;
      const double* a =
          &walk_xy_[2 * static_cast<std::size_t>(tri[static_cast<std::size_t>((k + 1) % 3)])];
      const double* b =
          &walk_xy_[2 * static_cast<std::size_t>(tri[static_cast<std::size_t>((k + 2) % 3)])];
      if (orient2d(a, b, p) < 0.0) {
        if (across[static_cast<std::size_t>(k)] < 0) {
          exit_edge = k;
          return t;
        }
        next = across[static_cast<std::size_t>(k)];
        break;
      }
    }
    if (next < 0)
      return t;
    previous = t;
    t = next;
  }
  return -1;  // no termination: the caller falls back to a scan
}

DelaunayTriangulation::Located DelaunayTriangulation::outside(const Eigen::Vector2d& point, int t,
                                                              int edge) const {
  // The hull edges that see the point (the point strictly outside their line) form one chain
  // around the exit edge, and the nearest point of the hull lies on it: scan it both ways. Equal
  // distances go to the lower hull index, so the answer does not depend on where the walk left.
  const int h = static_cast<int>(hull_.size());
  const int start = hull_position_[static_cast<std::size_t>(
      triangles_[static_cast<std::size_t>(t)][static_cast<std::size_t>((edge + 1) % 3)])];
  auto vertex = [this, h](int k) { return hull_[static_cast<std::size_t>(((k % h) + h) % h)]; };
  auto sees = [&](int k) {
    return orient2d(points_.col(vertex(k)).data(), points_.col(vertex(k + 1)).data(),
                    point.data()) < 0.0;
  };
  auto distance = [&](int k) {
    return distance_to_segment(point, points_.col(vertex(k)), points_.col(vertex(k + 1)));
  };
  auto wrap = [h](int k) { return ((k % h) + h) % h; };
  int best = wrap(start);
  double best_distance = distance(start);
  auto consider = [&](int k) {
    const double d = distance(k);
    if (d < best_distance || (d == best_distance && wrap(k) < best)) {
      best_distance = d;
      best = wrap(k);
    }
  };
  int forward = 1;
  for (; forward < h && sees(start + forward); ++forward)
    consider(start + forward);
  for (int back = 1; back < h - forward + 1 && sees(start - back); ++back)
    consider(start - back);
  Located result;
  result.triangle = hull_triangle_[static_cast<std::size_t>(best)];
  result.inside = false;
  result.barycentric = barycentric(result.triangle, point);
  result.hull_edge = best;
  result.hull_distance = best_distance;
  return result;
}

DelaunayTriangulation::Located DelaunayTriangulation::brute_force_locate(
    const Eigen::Vector2d& point) const {
  for (std::size_t h = 0; h < hull_.size(); ++h) {
    const int a = hull_[h];
    const int b = hull_[(h + 1) % hull_.size()];
    if (orient2d(points_.col(a).data(), points_.col(b).data(), point.data()) < 0.0)
      return outside(point, hull_triangle_[h], hull_local_edge_[h]);
  }
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const std::array<int, 3>& tri = triangles_[t];
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) {
      inside = orient2d(points_.col(tri[static_cast<std::size_t>(k)]).data(),
                        points_.col(tri[static_cast<std::size_t>((k + 1) % 3)]).data(),
                        point.data()) >= 0.0;
    }
    if (inside) {
      Located result;
      result.triangle = static_cast<int>(t);
      result.inside = true;
      result.barycentric = barycentric(result.triangle, point);
      return result;
    }
  }
  return {};
}

DelaunayTriangulation::Located DelaunayTriangulation::locate(const Eigen::Vector2d& point,
                                                             int hint) const {
  if (degenerate() || !point.allFinite())
    return {};
  int t = hint;
  if (t < 0 || t >= static_cast<int>(triangles_.size()))
    t = grid_triangle_[static_cast<std::size_t>(start_cell(point))];
  int exit_edge = -1;
  t = walk(t, point.data(), exit_edge);
  if (t < 0)
    return brute_force_locate(point);
  if (exit_edge >= 0)
    return outside(point, t, exit_edge);
  Located result;
  result.triangle = t;
  result.inside = true;
  result.barycentric = barycentric(t, point);
  return result;
}

std::vector<DelaunayTriangulation::Located> DelaunayTriangulation::locate_all(
    const Eigen::Matrix2Xd& queries) const {
  std::vector<Located> results(static_cast<std::size_t>(queries.cols()));
  if (degenerate())
    return results;
  const std::vector<std::uint64_t> keys = hilbert_keys(queries);
  std::vector<int> order(static_cast<std::size_t>(queries.cols()));
  std::iota(order.begin(), order.end(), 0);
  sort_by_hilbert_key(order.begin(), order.end(), keys);
  // Gather the queries in curve order and scatter the answers afterwards: independent memory
  // accesses in tight loops, instead of a cache miss inside every walk.
  Eigen::Matrix2Xd sorted(2, queries.cols());
  for (Eigen::Index k = 0; k < queries.cols(); ++k)
    sorted.col(k) = queries.col(order[static_cast<std::size_t>(k)]);
  std::vector<Located> sorted_results(results.size());
  int hint = -1;
  for (Eigen::Index k = 0; k < sorted.cols(); ++k) {
    Located& r = sorted_results[static_cast<std::size_t>(k)];
    r = locate(sorted.col(k), hint);
    if (r.triangle >= 0)
      hint = r.triangle;
  }
  for (std::size_t k = 0; k < order.size(); ++k)
    results[static_cast<std::size_t>(order[k])] = sorted_results[k];
  return results;
}

}  // namespace floorgrid
