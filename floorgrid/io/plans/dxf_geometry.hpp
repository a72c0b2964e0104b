#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "floorgrid/io/plans/dxf_curves.hpp"
#include "floorgrid/maps/plan_unit_choice.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid::io {

/// A straight piece in world XY, drawing units.
struct DrawingLine {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  ///< start
  Eigen::Vector2d b = Eigen::Vector2d::Zero();  ///< end
};

/// `center + u cos t + v sin t` for t in [t0, t1]: an ellipse, or an arc under a non-uniform
/// scale, in world XY, drawing units.
struct DrawingEllipse {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< centre
  Eigen::Vector2d u = Eigen::Vector2d::UnitX();      ///< the point at t = 0, from the centre
  Eigen::Vector2d v = Eigen::Vector2d::UnitY();      ///< the point at t = pi/2, from the centre
  double t0 = 0.0;                                   ///< radians
  double t1 = 0.0;                                   ///< radians, > t0
};

/// Points joined by straight pieces (a spline given by fit points only), drawing units.
struct DrawingPolyline {
  std::vector<Eigen::Vector2d> points;  ///< in order
};

/// One curve of the expanded drawing (world XY, drawing units), with its layer.
struct DrawingItem {
  std::variant<DrawingLine, CircularArc2, DrawingEllipse, BSpline2, DrawingPolyline> curve;
  int layer = 0;     ///< index into DrawingGeometry::layers
  bool kept = true;  ///< false when the layer filters drop it (it still tells the units)
};

/// The drawing after block expansion, before the unit is known.
struct DrawingGeometry {
  std::vector<std::string> layers;  ///< names, by DrawingItem::layer
  std::vector<DrawingItem> items;   ///< every curve, kept or not
  /// Dimensions (on any layer) whose text states a length with its unit: unit evidence.
  std::vector<StatedLength> stated_lengths;

  /// Index of `layer`, added when new.
  int layer_index(const std::string& layer);

 private:
  std::map<std::string, int> index_;
};

/// Drawing units a coordinate may lie from the origin: 1e10 (10,000 km in millimetres). Beyond,
/// an entity is not a building's (stray entities and overflowing transforms are skipped).
inline constexpr double kMaxDrawingCoordinate = 1e10;

/// Whether every number defining `curve` is finite and within kMaxDrawingCoordinate.
bool is_physical(const decltype(DrawingItem::curve)& curve);

/// Bounds of every item (kept or not), drawing units. Ellipses are bounded by sampling and
/// splines by their control points: the bounds tell units, not geometry.
Eigen::AlignedBox2d drawing_extent(const DrawingGeometry& geometry);
/// What every item (kept or not) tells about the units: the extent with and without far-off
/// strays, every circular arc with its door leaf if it has one, the wall bands of the straight
/// pieces, and the stated lengths. The header's part is left for the caller.
PlanUnitEvidence drawing_unit_evidence(const DrawingGeometry& geometry);
/// The kept items as a floorplan in metres: coordinates times `metres_per_unit`; ellipses and
/// splines become segments with chord error at most `tolerance_m` metres.
VectorFloorplan drawing_to_floorplan(const DrawingGeometry& geometry, double metres_per_unit,
                                     double tolerance_m);

}  // namespace floorgrid::io
