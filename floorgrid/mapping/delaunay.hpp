#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace floorgrid {

namespace detail {
class BowyerWatson;
}  // namespace detail

/// Settings of DelaunayTriangulation.
struct DelaunayOptions {
  /// Seed of the biased randomized insertion order (BRIO: random rounds, each sorted along a
  /// Hilbert curve). Points in general position have one Delaunay triangulation whatever the
  /// seed; among four or more co-circular points the seed picks the diagonals. Same seed, same
  /// output.
  std::uint64_t seed = 1;
};

/// Whether a point set has a triangulation.
enum class DelaunayStatus {
  ok,              ///< at least 3 distinct points, not all on one line
  too_few_points,  ///< fewer than 3 distinct points
  collinear,       ///< 3 or more distinct points, all on one line (decided exactly)
};

/// The Delaunay triangulation of a set of 2D points, with exact predicates (orient2d, incircle),
/// and point location. Built by incremental Bowyer-Watson insertion with ghost triangles for the
/// outside of the convex hull, in a biased randomized insertion order with Hilbert-sorted rounds,
/// each point located by a walk from the previous one's triangles: expected O(n log n).
///
/// Exactly equal points are kept once: the lowest input index of each group of equal points is
/// the vertex, the others are reported by duplicate_of(). Degenerate input (fewer than 3 distinct
/// points, or all collinear) is not an error here: status() says which and message() says it in
/// words; the triangulation then has no triangles and locate() finds nothing. A caller that needs
/// triangles (the `dt` mapping model) turns that into an InputError naming its own field
/// (`pairs`). Only a non-finite coordinate throws (InputError naming the field `points`).
///
/// Triangles are counter-clockwise triples of input indices. Neighbour i of a triangle lies across
/// the edge opposite its vertex i (from vertex i+1 to vertex i+2, indices mod 3), or is -1 on the
/// convex hull. With n distinct points, h of them on the hull boundary (hull corners and points
/// on hull edges alike), there are 2n - h - 2 triangles.
class DelaunayTriangulation {
 public:
  /// Where a point lies: the result of locate().
  struct Located {
    /// The triangle containing the point (closed: boundary included; for a point on an edge or
    /// vertex shared by several triangles, one of them, which may depend on the hint); when the
    /// point is outside the convex hull, the triangle on the nearest hull edge; -1 for a
    /// degenerate triangulation or a non-finite point.
    int triangle = -1;
    /// Whether the point lies in the closed triangle (inside the hull or on its boundary).
    bool inside = false;
    /// Barycentric coordinates of the point with respect to triangles()[triangle], in vertex
    /// order: they sum to 1 and reproduce the point to rounding. Outside the hull they
    /// extrapolate (some are negative).
    Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
    /// Outside only: the nearest hull edge, from hull()[hull_edge] to the next hull vertex;
    /// else -1.
    int hull_edge = -1;
    /// Outside only: distance from the point to that edge (units of the points); else 0.
    double hull_distance = 0.0;
  };

  /// Triangulates the columns of `points` (any number, up to millions). Throws InputError
  /// (field `points`) when a coordinate is NaN or infinite.
  explicit DelaunayTriangulation(const Eigen::Matrix2Xd& points,
                                 const DelaunayOptions& options = {});

  /// ok, or why there are no triangles.
  DelaunayStatus status() const { return status_; }
  /// Whether there are no triangles (status() is not ok).
  bool degenerate() const { return status_ != DelaunayStatus::ok; }
  /// What status() means for these points, in words (empty when ok).
  const std::string& message() const { return message_; }

  /// The input points (one per column).
  const Eigen::Matrix2Xd& points() const { return points_; }
  /// Counter-clockwise triangles as triples of input indices.
  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
  /// neighbors()[t][i]: the triangle across the edge opposite vertex i of triangle t, or -1.
  const std::vector<std::array<int, 3>>& neighbors() const { return neighbors_; }
  /// The convex hull boundary, counter-clockwise, starting at its lowest input index: every
  /// vertex on the boundary, including those lying on a hull edge. Empty when degenerate.
  const std::vector<int>& hull() const { return hull_; }
  /// For each input point, the index of the vertex with exactly its coordinates: itself for a
  /// vertex, the lowest index of its group for a duplicate.
  const std::vector<int>& duplicate_of() const { return duplicate_of_; }
  /// Number of input points that are duplicates of a lower index.
  int duplicate_count() const { return duplicate_count_; }
  /// Number of distinct points (vertices).
  int vertex_count() const { return static_cast<int>(points_.cols()) - duplicate_count_; }

  /// Locates `point` by a visibility walk (exact orientation tests, stochastic edge order, never
  /// back across the edge it came through) from triangle `hint`, or when hint is -1 (or not a
  /// triangle) from the start triangle of a bucket grid over the points. O(1) expected steps
  /// from a nearby hint.
  Located locate(const Eigen::Vector2d& point, int hint = -1) const;

  /// Locates every column of `queries`: visits them along a Hilbert curve, each walk starting
  /// from the previous answer. Results in the order of the columns.
  std::vector<Located> locate_all(const Eigen::Matrix2Xd& queries) const;

  /// Barycentric coordinates of `point` with respect to triangle t (see Located::barycentric).
  Eigen::Vector3d barycentric(int t, const Eigen::Vector2d& point) const;

 private:
  void build(const DelaunayOptions& options);
  void mark_degenerate();
  std::vector<int> record_duplicates(const std::vector<int>& inserted_twin);
  void adopt_triangles(const detail::BowyerWatson& kernel, const std::vector<std::uint64_t>& keys,
                       const std::vector<int>& representative);
  void build_walk_index();
  void build_start_grid();
  int start_cell(const Eigen::Vector2d& point) const;
  int walk(int t, const double* p, int& exit_edge) const;
  Located outside(const Eigen::Vector2d& point, int t, int edge) const;
  Located brute_force_locate(const Eigen::Vector2d& point) const;

  Eigen::Matrix2Xd points_;
  DelaunayStatus status_ = DelaunayStatus::ok;
  std::string message_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<std::array<int, 3>> neighbors_;
  std::vector<int> hull_;
  std::vector<int> duplicate_of_;
  int duplicate_count_ = 0;

  // Hull edge k runs from hull_[k] to hull_[k+1]: the triangle on it and the edge's local index
  // there; hull_position_[v] is v's index in hull_, or -1.
  std::vector<int> hull_triangle_;
  std::vector<int> hull_local_edge_;
  std::vector<int> hull_position_;

  // The walks' own copy of the geometry: vertex coordinates in the order the (curve-ordered)
  // triangles first use them, and each triangle's vertices as indices into it.
  std::vector<double> walk_xy_;
  std::vector<std::array<int, 3>> walk_triangles_;

  // Start triangles of the walks: a grid of cells over the bounding box.
  Eigen::Vector2d grid_origin_ = Eigen::Vector2d::Zero();
  double grid_cell_ = 1.0;
  int grid_columns_ = 0;
  int grid_rows_ = 0;
  std::vector<int> grid_triangle_;
};

}  // namespace floorgrid
