#pragma once

#include <cstdint>
#include <vector>

namespace floorgrid::detail {

/// The insertion kernel of DelaunayTriangulation: an incremental Delaunay triangulation by
/// Bowyer-Watson cavities, with ghost triangles instead of a super triangle. Every convex hull
/// edge (a, b) has a ghost triangle (b, a, ghost) on its outside, so the triangulation of the hull
/// plus its ghosts covers the plane and insertion outside the hull needs no special case. A ghost
/// triangle's "circumcircle" is the open half-plane beyond its edge plus the edge's open segment.
/// All decisions use the exact predicates.
class BowyerWatson {
 public:
  /// Triangle slots hold 3 vertices and 3 neighbours; neighbour i is across the edge opposite
  /// vertex i. A ghost triangle has the ghost vertex (index point_count) at position 2.
  /// `xy` holds point_count (x, y) pairs and must outlive this object.
  BowyerWatson(const double* xy, int point_count);

  /// Starts the triangulation with the non-collinear points a, b, c (any orientation).
  void start(int a, int b, int c);

  /// Inserts point p. Returns -1 when inserted, else the vertex whose coordinates equal p's
  /// (the point is then skipped).
  int insert(int p);

  /// The ghost vertex's index (the number of points).
  int ghost() const { return ghost_; }
  /// Number of triangle slots (real and ghost; none is ever freed).
  int slot_count() const { return static_cast<int>(vertices_.size() / 3); }
  /// Vertex k (0..2) of triangle slot t.
  int vertex(int t, int k) const { return vertices_[3 * t + k]; }
  /// Neighbour k (0..2) of triangle slot t.
  int neighbor(int t, int k) const { return neighbors_[3 * t + k]; }
  /// Whether slot t is a ghost triangle.
  bool is_ghost(int t) const { return vertices_[3 * t + 2] == ghost_; }

 private:
  struct BoundaryEdge {
    int from;  // cavity boundary edge, counter-clockwise seen from inside the cavity
    int to;
    int outside;  // the triangle beyond it, which stays
  };

  const double* point(int v) const { return xy_ + 2 * v; }
  int walk(int t, const double* p);
  bool conflicts(int t, const double* p) const;
  bool strictly_between(int a, int b, const double* p) const;
  void dig_cavity(int t, const double* p);
  int fill_cavity(int p);
  int new_triangle(int a, int b, int c);
  int local_index(int t, int v) const;
  std::uint32_t next_random();

  const double* xy_;
  int ghost_;
  std::vector<int> vertices_;
  std::vector<int> neighbors_;
  std::vector<std::uint32_t> mark_;  // 2*epoch: in the cavity; 2*epoch+1: tested, no conflict
  std::uint32_t epoch_ = 0;
  std::vector<int> cavity_;
  std::vector<int> stack_;
  std::vector<BoundaryEdge> boundary_;
  std::vector<int> new_triangles_;
  std::vector<int> by_start_;  // per vertex: the new triangle whose boundary edge starts there
  int last_ = -1;              // a real triangle made by the latest insertion
  std::uint32_t random_state_ = 0x9e3779b9u;
};

}  // namespace floorgrid::detail
