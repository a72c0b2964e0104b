#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace floorgrid {

/// A straight wall piece from `a` to `b`, in the plan frame (metres).
struct Segment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  ///< start, metres
  Eigen::Vector2d b = Eigen::Vector2d::Zero();  ///< end, metres
  int layer = 0;                                ///< index into VectorFloorplan::layers()

  /// Length in metres.
  double length() const { return (b - a).norm(); }
};

/// A circular arc, counter-clockwise from `start_angle` to `end_angle` (radians, end > start;
/// a full circle spans 2 pi), in the plan frame (metres).
struct Arc {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< metres
  double radius = 0.0;                               ///< metres
  double start_angle = 0.0;                          ///< radians
  double end_angle = 0.0;                            ///< radians, > start_angle
  int layer = 0;                                     ///< index into VectorFloorplan::layers()

  /// The point at `angle` on the circle.
  Eigen::Vector2d point_at(double angle) const;
  /// Whether the direction `angle` lies within the arc's sweep.
  bool sweeps(double angle) const;
  /// Arc length in metres.
  double length() const { return radius * (end_angle - start_angle); }
};

/// A vector floorplan: wall segments and arcs on named layers, in metres. Annotation is not here.
class VectorFloorplan {
 public:
  /// Index of `layer_name`, added when new.
  int layer_index(const std::string& layer_name);
  /// Adds a segment on a layer; zero-length segments are kept (they rasterize to a dot).
  void add_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::string& layer);
  /// Adds an arc on a layer. Angles in radians; the sweep is normalized to (0, 2 pi].
  void add_arc(const Eigen::Vector2d& center, double radius, double start_angle, double end_angle,
               const std::string& layer);

  /// Layer names, indexed by Segment::layer and Arc::layer.
  const std::vector<std::string>& layers() const { return layers_; }
  /// All segments.
  const std::vector<Segment>& segments() const { return segments_; }
  /// All arcs.
  const std::vector<Arc>& arcs() const { return arcs_; }
  /// Whether the plan holds no geometry.
  bool empty() const { return segments_.empty() && arcs_.empty(); }

  /// Axis-aligned bounds of all geometry (arcs by their true extent), metres.
  Eigen::AlignedBox2d bounds() const;
  /// Total length of all geometry, metres.
  double total_length() const;
  /// Points every `spacing` metres along every segment and arc (ends included), 2 x N.
  Eigen::Matrix2Xd sample_points(double spacing) const;
  /// The plan with every coordinate multiplied by `factor` (a unit conversion).
  VectorFloorplan scaled(double factor) const;

 private:
  std::vector<std::string> layers_;
  std::vector<Segment> segments_;
  std::vector<Arc> arcs_;
};

}  // namespace floorgrid
