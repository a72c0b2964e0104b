#include "floorgrid/io/plans/dxf_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "floorgrid/core/overloaded.hpp"

namespace floorgrid::io {

namespace {

void add_polyline(VectorFloorplan& plan, const std::vector<Eigen::Vector2d>& points, double k,
                  const std::string& layer) {
  for (std::size_t i = 1; i < points.size(); ++i) {
    // Tessellating a finite curve of astronomical size can still overflow.
    if (!points[i - 1].allFinite() || !points[i].allFinite()) {
      continue;
    }
    plan.add_segment(points[i - 1] * k, points[i] * k, layer);
  }
}

}  // namespace

int DrawingGeometry::layer_index(const std::string& layer) {
  const auto [it, added] = index_.emplace(layer, static_cast<int>(layers.size()));
  if (added) {
    layers.push_back(layer);
  }
  return it->second;
}

bool is_physical(const decltype(DrawingItem::curve)& curve) {
  // Finite and within kMaxDrawingCoordinate: NaN fails every comparison.
  const auto near = [](const Eigen::Vector2d& p) {
    return std::abs(p.x()) <= kMaxDrawingCoordinate && std::abs(p.y()) <= kMaxDrawingCoordinate;
  };
  const auto small = [](double v) { return std::abs(v) <= kMaxDrawingCoordinate; };
  const auto all_near = [&](const auto& points) {
    return std::all_of(points.begin(), points.end(), near);
  };
  return std::visit(Overloaded{
                        [&](const DrawingLine& l) { return near(l.a) && near(l.b); },
                        [&](const CircularArc2& a) {
                          return near(a.center) && small(a.radius) && std::isfinite(a.start) &&
                                 std::isfinite(a.end);
                        },
                        [&](const DrawingEllipse& e) {
                          return near(e.center) && near(e.u) && near(e.v) && std::isfinite(e.t0) &&
                                 std::isfinite(e.t1);
                        },
                        [&](const BSpline2& s) { return all_near(s.control); },
                        [&](const DrawingPolyline& p) { return all_near(p.points); },
                    },
                    curve);
}

Eigen::AlignedBox2d drawing_extent(const DrawingGeometry& geometry) {
  Eigen::AlignedBox2d box;
  for (const DrawingItem& item : geometry.items) {
    std::visit(
        Overloaded{
            [&](const DrawingLine& l) {
              box.extend(l.a);
              box.extend(l.b);
            },
            [&](const CircularArc2& a) {
              VectorFloorplan one;
              one.add_arc(a.center, a.radius, a.start, a.end, "");
              box.extend(one.bounds());
            },
            [&](const DrawingEllipse& e) {
              for (int i = 0; i <= 64; ++i) {
                const double t = e.t0 + (e.t1 - e.t0) * i / 64.0;
                box.extend(Eigen::Vector2d(e.center + e.u * std::cos(t) + e.v * std::sin(t)));
              }
            },
            [&](const BSpline2& s) {
              for (const Eigen::Vector2d& p : s.control) {
                box.extend(p);
              }
            },
            [&](const DrawingPolyline& p) {
              for (const Eigen::Vector2d& q : p.points) {
                box.extend(q);
              }
            },
        },
        item.curve);
  }
  return box;
}

PlanUnitEvidence drawing_unit_evidence(const DrawingGeometry& geometry) {
  std::vector<PlanLine> lines;
  std::vector<PlanCircle> arcs;
  std::vector<Eigen::Vector2d> points;
  for (const DrawingItem& item : geometry.items) {
    std::visit(Overloaded{
                   [&](const DrawingLine& l) {
                     lines.push_back({l.a, l.b});
                     points.push_back(l.a);
                     points.push_back(l.b);
                   },
                   [&](const CircularArc2& a) {
                     arcs.push_back({a.center, a.radius, a.start, a.end});
                     points.push_back(a.center + a.radius * Eigen::Vector2d(std::cos(a.start),
                                                                            std::sin(a.start)));
                     points.push_back(a.center +
                                      a.radius * Eigen::Vector2d(std::cos(a.end), std::sin(a.end)));
                   },
                   [&](const DrawingEllipse& e) {
                     points.push_back(e.center + e.u * std::cos(e.t0) + e.v * std::sin(e.t0));
                     points.push_back(e.center + e.u * std::cos(e.t1) + e.v * std::sin(e.t1));
                   },
                   [&](const BSpline2& s) {
                     points.insert(points.end(), s.control.begin(), s.control.end());
                   },
                   [&](const DrawingPolyline& p) {
                     for (std::size_t i = 1; i < p.points.size(); ++i) {
                       lines.push_back({p.points[i - 1], p.points[i]});
                     }
                     points.insert(points.end(), p.points.begin(), p.points.end());
                   },
               },
               item.curve);
  }
  PlanUnitEvidence evidence;
  evidence.extent = drawing_extent(geometry);
  // The core extent only matters when strays stretch the drawing: keep it empty otherwise, so
  // that messages speak of the plain extent.
  const Eigen::AlignedBox2d core = core_extent(std::move(points));
  if (!core.isEmpty() && core.sizes().maxCoeff() < 0.5 * evidence.extent.sizes().maxCoeff()) {
    evidence.core_extent = core;
  }
  evidence.arcs = find_door_leaves(arcs, lines);
  evidence.walls = measure_wall_bands(lines);
  evidence.dimensions = geometry.stated_lengths;
  return evidence;
}

VectorFloorplan drawing_to_floorplan(const DrawingGeometry& geometry, double metres_per_unit,
                                     double tolerance_m) {
  const double k = metres_per_unit;
  const double tolerance = tolerance_m / k;  // drawing units
  VectorFloorplan plan;
  for (const DrawingItem& item : geometry.items) {
    if (!item.kept) {
      continue;
    }
    const std::string& layer = geometry.layers[item.layer];
    std::visit(
        Overloaded{
            [&](const DrawingLine& l) { plan.add_segment(l.a * k, l.b * k, layer); },
            [&](const CircularArc2& a) {
              plan.add_arc(a.center * k, a.radius * k, a.start, a.end, layer);
            },
            [&](const DrawingEllipse& e) {
              add_polyline(plan, ellipse_points(e.center, e.u, e.v, e.t0, e.t1, tolerance), k,
                           layer);
            },
            [&](const BSpline2& s) { add_polyline(plan, bspline_points(s, tolerance), k, layer); },
            [&](const DrawingPolyline& p) { add_polyline(plan, p.points, k, layer); },
        },
        item.curve);
  }
  return plan;
}

}  // namespace floorgrid::io
