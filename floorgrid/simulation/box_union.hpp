#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid {

/// The outline of a union of axis-aligned boxes: what a laser sees of solid walls and what a
/// CAD plan draws of them.
struct BoxUnionOutline {
  std::vector<Segment> edges;            ///< boundary edges, collinear pieces merged, layer 0
  std::vector<Eigen::Vector2d> corners;  ///< boundary vertices where the outline turns
};

/// Computes the exact outline of the union of `boxes` by coordinate compression: the distinct
/// box edges cut the plane into cells, each inside or outside the union, and the outline is
/// every cell side between an inside and an outside cell. Touching boxes merge seamlessly.
BoxUnionOutline box_union_outline(const std::vector<Eigen::AlignedBox2d>& boxes);

/// Whether `point` lies inside (or on) any of `boxes`.
bool inside_any(const std::vector<Eigen::AlignedBox2d>& boxes, const Eigen::Vector2d& point);

}  // namespace floorgrid
