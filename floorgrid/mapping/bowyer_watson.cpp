#include "floorgrid/mapping/bowyer_watson.hpp"

#include <cassert>
#include <cstddef>

#include "floorgrid/geometry/predicates.hpp"

namespace floorgrid::detail {

BowyerWatson::BowyerWatson(const double* xy, int point_count)
    : xy_(xy), ghost_(point_count), by_start_(static_cast<std::size_t>(point_count) + 1, -1) {
  const std::size_t expected_slots = 2 * static_cast<std::size_t>(point_count) + 4;
  vertices_.reserve(3 * expected_slots);
  neighbors_.reserve(3 * expected_slots);
  mark_.reserve(expected_slots);
}

void BowyerWatson::start(int a, int b, int c) {
  if (orient2d(point(a), point(b), point(c)) < 0.0)
    std::swap(b, c);
  const int t = new_triangle(a, b, c);
  // One ghost per edge, on its outside: edge (a, b) of t gets ghost (b, a, ghost), and so on.
  const int g_ab = new_triangle(b, a, ghost_);
  const int g_bc = new_triangle(c, b, ghost_);
  const int g_ca = new_triangle(a, c, ghost_);
  auto link = [this](int t1, int k1, int t2, int k2) {
    neighbors_[3 * t1 + k1] = t2;
    neighbors_[3 * t2 + k2] = t1;
  };
  link(t, 2, g_ab, 2);  // edge a-b
  link(t, 0, g_bc, 2);  // edge b-c
  link(t, 1, g_ca, 2);  // edge c-a
  // Ghost (p, q, ghost): neighbour 0 (edge q-ghost) is the ghost of the hull edge leaving q,
  // neighbour 1 (edge ghost-p) the ghost of the hull edge entering p.
  link(g_ab, 0, g_ca, 1);  // edge a-ghost
  link(g_ab, 1, g_bc, 0);  // edge b-ghost
  link(g_bc, 1, g_ca, 0);  // edge c-ghost
  last_ = t;
}

std::uint32_t BowyerWatson::next_random() {
  // xorshift32: cheap, deterministic, good enough to break the walk's cycles.
  random_state_ ^= random_state_ << 13;
  random_state_ ^= random_state_ >> 17;
  random_state_ ^= random_state_ << 5;
  return random_state_;
}

int BowyerWatson::new_triangle(int a, int b, int c) {
  // Keep the ghost vertex, if any, at position 2 (same cyclic order).
  if (a == ghost_) {
    a = b;
    b = c;
    c = ghost_;
  } else if (b == ghost_) {
    b = a;
    a = c;
    c = ghost_;
  }
  const int t = slot_count();
  vertices_.insert(vertices_.end(), {a, b, c});
  neighbors_.insert(neighbors_.end(), {-1, -1, -1});
  mark_.push_back(0);
  return t;
}

int BowyerWatson::local_index(int t, int v) const {
  if (vertices_[3 * t] == v)
    return 0;
  if (vertices_[3 * t + 1] == v)
    return 1;
  assert(vertices_[3 * t + 2] == v);
  return 2;
}

int BowyerWatson::walk(int t, const double* p) {
  // Visibility walk: cross any edge that has p strictly on its far side, never straight back;
  // the edge tried first is random, which rules out cycles. It ends in a real triangle whose
  // closure holds p, or in a ghost triangle (p strictly outside that hull edge).
  int previous = -1;
  const std::size_t step_limit = vertices_.size() + 16;
  for (std::size_t step = 0; step < step_limit; ++step) {
    if (is_ghost(t))
      return t;
    const int first = static_cast<int>(next_random() % 3u);
    int next = -1;
    for (int j = 0; j < 3; ++j) {
      const int k = (first + j) % 3;
      const int across = neighbors_[3 * t + k];
      if (across == previous)
        continue;
      const int a = vertices_[3 * t + (k + 1) % 3];
      const int b = vertices_[3 * t + (k + 2) % 3];
      if (orient2d(point(a), point(b), p) < 0.0) {
        next = across;
        break;
      }
    }
    if (next < 0)
      return t;
    previous = t;
    t = next;
  }
  // Unreachable in a Delaunay triangulation (the visibility walk terminates there); kept as a
  // safety net: scan for a triangle in conflict.
  assert(false && "Delaunay walk did not terminate");
  for (int s = 0; s < slot_count(); ++s) {
    if (conflicts(s, p))
      return s;
  }
  return t;
}

bool BowyerWatson::strictly_between(int a, int b, const double* p) const {
  // p is collinear with a and b: compare along the axis on which they differ (exact).
  const double* pa = point(a);
  const double* pb = point(b);
  const int axis = pa[0] != pb[0] ? 0 : 1;
  const double lo = pa[axis] < pb[axis] ? pa[axis] : pb[axis];
  const double hi = pa[axis] < pb[axis] ? pb[axis] : pa[axis];
  return lo < p[axis] && p[axis] < hi;
}

bool BowyerWatson::conflicts(int t, const double* p) const {
  const int a = vertices_[3 * t];
  const int b = vertices_[3 * t + 1];
  const int c = vertices_[3 * t + 2];
  if (c == ghost_) {
    const double side = orient2d(point(a), point(b), p);
    return side > 0.0 || (side == 0.0 && strictly_between(a, b, p));
  }
  return incircle(point(a), point(b), point(c), p) > 0.0;
}

void BowyerWatson::dig_cavity(int t, const double* p) {
  // Depth-first search from t over the triangles whose circumcircle strictly contains p. Their
  // union is star-shaped from p with no vertex inside; its boundary edges are recorded with the
  // triangles beyond them.
  ++epoch_;
  const std::uint32_t inside = 2 * epoch_;
  const std::uint32_t outside = 2 * epoch_ + 1;
  cavity_.clear();
  boundary_.clear();
  stack_.clear();
  mark_[t] = inside;
  cavity_.push_back(t);
  stack_.push_back(t);
  while (!stack_.empty()) {
    const int c = stack_.back();
    stack_.pop_back();
    for (int k = 0; k < 3; ++k) {
      const int o = neighbors_[3 * c + k];
      if (mark_[o] == inside)
        continue;
      if (mark_[o] != outside) {
        if (conflicts(o, p)) {
          mark_[o] = inside;
          cavity_.push_back(o);
          stack_.push_back(o);
          continue;
        }
        mark_[o] = outside;
      }
      boundary_.push_back({vertices_[3 * c + (k + 1) % 3], vertices_[3 * c + (k + 2) % 3], o});
    }
  }
}

int BowyerWatson::fill_cavity(int p) {
  // One new triangle (from, to, p) per boundary edge: the cavity's slots first, then two more
  // (a cavity of k triangles without inner vertices has k + 2 boundary edges).
  assert(boundary_.size() == cavity_.size() + 2);
  new_triangles_.clear();
  int real = -1;
  std::size_t reuse = 0;
  for (const BoundaryEdge& e : boundary_) {
    int t = -1;
    if (reuse < cavity_.size()) {
      t = cavity_[reuse++];
      int a = e.from, b = e.to, c = p;
      if (a == ghost_) {
        a = b;
        b = c;
        c = ghost_;
      } else if (b == ghost_) {
        b = a;
        a = c;
        c = ghost_;
      }
      vertices_[3 * t] = a;
      vertices_[3 * t + 1] = b;
      vertices_[3 * t + 2] = c;
      mark_[t] = 0;
    } else {
      t = new_triangle(e.from, e.to, p);
    }
    new_triangles_.push_back(t);
    // Across (from, to): the triangle that stays, whose matching edge is opposite its vertex
    // that is neither `from` nor `to`.
    const int o = e.outside;
    int k_out = 0;
    while (vertices_[3 * o + k_out] == e.from || vertices_[3 * o + k_out] == e.to)
      ++k_out;
    neighbors_[3 * o + k_out] = t;
    neighbors_[3 * t + local_index(t, p)] = o;
    by_start_[e.from] = t;
    if (e.from != ghost_ && e.to != ghost_)
      real = t;
  }
  // Neighbours among the new triangles: (from, to, p) meets (to, next, p) across edge to-p,
  // which is opposite `from` in the first and opposite `next` in the second.
  for (std::size_t i = 0; i < boundary_.size(); ++i) {
    const BoundaryEdge& e = boundary_[i];
    const int t = new_triangles_[i];
    const int s = by_start_[e.to];
    neighbors_[3 * t + local_index(t, e.from)] = s;
    int next = -1;
    for (int k = 0; k < 3; ++k) {
      const int v = vertices_[3 * s + k];
      if (v != p && v != e.to)
        next = v;
    }
    neighbors_[3 * s + local_index(s, next)] = t;
  }
  return real;
}

int BowyerWatson::insert(int p) {
  const double* xy = point(p);
  const int t = walk(last_, xy);
  if (!is_ghost(t)) {
    for (int k = 0; k < 3; ++k) {
      const int v = vertices_[3 * t + k];
      if (point(v)[0] == xy[0] && point(v)[1] == xy[1])
        return v;
    }
  }
  dig_cavity(t, xy);
  last_ = fill_cavity(p);
  assert(last_ >= 0);
  return -1;
}

}  // namespace floorgrid::detail
