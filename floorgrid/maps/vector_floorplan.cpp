#include "floorgrid/maps/vector_floorplan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace floorgrid {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Angle of `angle` measured from `start` counter-clockwise, in [0, 2 pi).
double sweep_from(double start, double angle) {
  double d = std::fmod(angle - start, kTwoPi);
  if (d < 0.0)
    d += kTwoPi;
  return d;
}
}  // namespace

Eigen::Vector2d Arc::point_at(double angle) const {
  return center + radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

bool Arc::sweeps(double angle) const {
  return sweep_from(start_angle, angle) <= end_angle - start_angle;
}

int VectorFloorplan::layer_index(const std::string& layer_name) {
  const auto it = std::find(layers_.begin(), layers_.end(), layer_name);
  if (it != layers_.end())
    return static_cast<int>(it - layers_.begin());
  layers_.push_back(layer_name);
  return static_cast<int>(layers_.size()) - 1;
}

void VectorFloorplan::add_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                  const std::string& layer) {
  segments_.push_back({a, b, layer_index(layer)});
}

void VectorFloorplan::add_arc(const Eigen::Vector2d& center, double radius, double start_angle,
                              double end_angle, const std::string& layer) {
  double sweep = sweep_from(start_angle, end_angle);
  if (sweep == 0.0)
    sweep = kTwoPi;  // equal angles: DXF's full circle
  arcs_.push_back({center, std::abs(radius), start_angle, start_angle + sweep, layer_index(layer)});
}

Eigen::AlignedBox2d VectorFloorplan::bounds() const {
  Eigen::AlignedBox2d box;
  for (const Segment& s : segments_) {
    box.extend(s.a);
    box.extend(s.b);
  }
  for (const Arc& arc : arcs_) {
    box.extend(arc.point_at(arc.start_angle));
    box.extend(arc.point_at(arc.end_angle));
    // The extreme points at 0, 90, 180 and 270 degrees count where the arc sweeps them.
    for (int k = 0; k < 4; ++k) {
      const double angle = k * std::numbers::pi / 2.0;
      if (arc.sweeps(angle))
        box.extend(arc.point_at(angle));
    }
  }
  return box;
}

double VectorFloorplan::total_length() const {
  double total = 0.0;
  for (const Segment& s : segments_)
    total += s.length();
  for (const Arc& arc : arcs_)
    total += arc.length();
  return total;
}

Eigen::Matrix2Xd VectorFloorplan::sample_points(double spacing) const {
  std::vector<Eigen::Vector2d> points;
  for (const Segment& s : segments_) {
    const int n = std::max(1, static_cast<int>(std::ceil(s.length() / spacing)));
    for (int i = 0; i <= n; ++i)
      points.push_back(s.a + (s.b - s.a) * (double(i) / n));
  }
  for (const Arc& arc : arcs_) {
    const int n = std::max(1, static_cast<int>(std::ceil(arc.length() / spacing)));
    for (int i = 0; i <= n; ++i) {
      points.push_back(arc.point_at(arc.start_angle + (arc.end_angle - arc.start_angle) * i / n));
    }
  }
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    out.col(static_cast<Eigen::Index>(i)) = points[i];
  return out;
}

VectorFloorplan VectorFloorplan::scaled(double factor) const {
  VectorFloorplan out = *this;
  for (Segment& s : out.segments_) {
    s.a *= factor;
    s.b *= factor;
  }
  for (Arc& arc : out.arcs_) {
    arc.center *= factor;
    arc.radius *= std::abs(factor);
  }
  return out;
}

}  // namespace floorgrid
