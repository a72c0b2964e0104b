#include "floorgrid/maps/plan_layers.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/predicates.hpp"

namespace floorgrid {

namespace {

std::string point_text(const Eigen::Vector2d& p) {
  std::ostringstream out;
  out << '(' << p.x() << ", " << p.y() << ')';
  return out.str();
}

/// Distinct consecutive vertices (a repeated vertex is not an edge).
std::size_t distinct_vertices(const Ring& ring) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (i == 0 || ring[i] != ring[i - 1])
      ++n;
  }
  if (n > 1 && ring.front() == ring.back())
    --n;
  return n;
}

struct Edge {
  std::size_t ring = 0, index = 0;
  Eigen::Vector2d a, b;
  double xmin = 0, xmax = 0;
};

int sign(double v) {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

bool on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}

/// Whether segments ab and cd share a point (robust orientation tests).
bool segments_touch(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d) {
  const int o1 = sign(orient2d(a, b, c)), o2 = sign(orient2d(a, b, d));
  const int o3 = sign(orient2d(c, d, a)), o4 = sign(orient2d(c, d, b));
  if (o1 != o2 && o3 != o4)
    return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

Eigen::Vector2d crossing_point(const Edge& e, const Edge& f) {
  const Eigen::Vector2d r = e.b - e.a, s = f.b - f.a;
  const double denominator = r.x() * s.y() - r.y() * s.x();
  if (std::abs(denominator) < 1e-300)
    return on_segment(e.a, e.b, f.a) ? f.a : f.b;  // collinear overlap: a shared point
  const Eigen::Vector2d q = f.a - e.a;
  const double t = (q.x() * s.y() - q.y() * s.x()) / denominator;
  return e.a + std::clamp(t, 0.0, 1.0) * r;
}

void check_ring_values(const Ring& ring, const std::string& what, const std::string& where) {
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (!ring[i].allFinite()) {
      throw InputError(what + ": vertex " + std::to_string(i) + " is not a finite number", where, 0,
                       "coordinates");
    }
  }
  if (distinct_vertices(ring) < 3) {
    throw InputError(what + ": needs at least 3 distinct vertices (got " +
                         std::to_string(distinct_vertices(ring)) + ")",
                     where, 0, "coordinates");
  }
}

}  // namespace

std::string describe(const Zone& zone) {
  return "zone " + std::to_string(zone.index) + (zone.name.empty() ? "" : " '" + zone.name + "'");
}

std::string describe(const Waypoint& waypoint) {
  return "waypoint " + std::to_string(waypoint.index) +
         (waypoint.name.empty() ? "" : " '" + waypoint.name + "'");
}

double signed_area(const Ring& ring) {
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[(i + 1) % ring.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

std::optional<RingCrossing> find_crossing(const std::vector<Ring>& rings) {
  std::vector<Edge> edges;
  for (std::size_t r = 0; r < rings.size(); ++r) {
    const Ring& ring = rings[r];
    for (std::size_t i = 0; i < ring.size(); ++i) {
      Edge e;
      e.ring = r;
      e.index = i;
      e.a = ring[i];
      e.b = ring[(i + 1) % ring.size()];
      if (e.a == e.b)
        continue;  // a repeated vertex: no edge
      e.xmin = std::min(e.a.x(), e.b.x());
      e.xmax = std::max(e.a.x(), e.b.x());
      edges.push_back(e);
    }
  }
  // Sweep along x: only edges whose x ranges overlap can cross.
  std::sort(edges.begin(), edges.end(),
            [](const Edge& a, const Edge& b) { return a.xmin < b.xmin; });
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Edge& e = edges[i];
    for (std::size_t j = i + 1; j < edges.size() && edges[j].xmin <= e.xmax; ++j) {
      const Edge& f = edges[j];
      if (e.ring == f.ring) {
        // Neighbours share their common vertex; that alone is no crossing.
        const std::size_t n = rings[e.ring].size();
        const bool next = (e.index + 1) % n == f.index, previous = (f.index + 1) % n == e.index;
        if (next || previous) {
          const Eigen::Vector2d shared = next ? e.b : f.b;
          const Edge& first = next ? e : f;
          const Edge& second = next ? f : e;
          // Adjacent edges overlap beyond the shared vertex only when they fold back on a line.
          const bool fold = orient2d(first.a, shared, second.b) == 0.0 &&
                            (first.a - shared).dot(second.b - shared) > 0.0;
          if (!fold)
            continue;
        }
      }
      if (segments_touch(e.a, e.b, f.a, f.b)) {
        RingCrossing c;
        const bool swap = std::make_pair(f.ring, f.index) < std::make_pair(e.ring, e.index);
        const Edge& p = swap ? f : e;
        const Edge& q = swap ? e : f;
        c.ring_a = p.ring;
        c.edge_a = p.index;
        c.ring_b = q.ring;
        c.edge_b = q.index;
        c.point = crossing_point(e, f);
        return c;
      }
    }
  }
  return std::nullopt;
}

void validate_zone(const Zone& zone, const std::string& where) {
  const std::string what = describe(zone);
  check_ring_values(zone.outer, what + " outer ring", where);
  for (std::size_t h = 0; h < zone.holes.size(); ++h)
    check_ring_values(zone.holes[h], what + " hole " + std::to_string(h), where);
  std::vector<Ring> rings{zone.outer};
  rings.insert(rings.end(), zone.holes.begin(), zone.holes.end());
  if (const auto c = find_crossing(rings)) {
    const auto ring_name = [](std::size_t r) {
      return r == 0 ? std::string("outer ring") : "hole " + std::to_string(r - 1);
    };
    throw InputError(what + ": self-intersecting: " + ring_name(c->ring_a) + " edge " +
                         std::to_string(c->edge_a) + " crosses " + ring_name(c->ring_b) + " edge " +
                         std::to_string(c->edge_b) + " at " + point_text(c->point),
                     where, 0, "coordinates");
  }
  if (std::abs(signed_area(zone.outer)) <= 0.0)
    throw InputError(what + ": outer ring has no area", where, 0, "coordinates");
  const ZoneSpeed& s = zone.speed;
  if (s.percent && !(*s.percent > 0.0 && *s.percent <= 100.0)) {
    throw InputError(
        what + ": speed_percent must be in (0, 100] (got " + std::to_string(*s.percent) + ")",
        where, 0, "speed_percent");
  }
  if (s.metres_per_second && !(*s.metres_per_second > 0.0 && std::isfinite(*s.metres_per_second))) {
    throw InputError(
        what + ": speed_mps must be > 0 (got " + std::to_string(*s.metres_per_second) + ")", where,
        0, "speed_mps");
  }
  if (s.percent && s.metres_per_second)
    throw InputError(what + ": give speed_percent or speed_mps, not both", where, 0, "speed");
}

void validate_waypoint(const Waypoint& waypoint, const std::string& where) {
  if (!waypoint.position.allFinite()) {
    throw InputError(
        describe(waypoint) + ": position " + point_text(waypoint.position) + " is not finite",
        where, 0, "position");
  }
  if (waypoint.theta && !std::isfinite(*waypoint.theta))
    throw InputError(describe(waypoint) + ": heading is not finite", where, 0, "theta");
}

Eigen::Matrix2Xd densify_ring(const Ring& ring, double spacing) {
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[(i + 1) % ring.size()];
    const double length = (b - a).norm();
    // At most a million samples per edge: a guard against a spacing far below the edge's scale.
    const double wanted = spacing > 0.0 ? std::ceil(length / spacing) : 1.0;
    const int steps = static_cast<int>(std::clamp(wanted, 1.0, 1e6));
    for (int k = 0; k < steps; ++k)
      points.push_back(a + (b - a) * (static_cast<double>(k) / steps));
  }
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    out.col(static_cast<Eigen::Index>(i)) = points[i];
  return out;
}

}  // namespace floorgrid
