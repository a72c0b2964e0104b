#pragma once

#include <Eigen/Core>
#include <vector>

namespace floorgrid {

/// The convex hull of the columns of `points`, counter-clockwise, without repeated or collinear
/// vertices (Andrew's monotone chain). Fewer than 3 vertices when the points are collinear.
std::vector<Eigen::Vector2d> convex_hull(const Eigen::Matrix2Xd& points);

/// Whether `point` lies inside or on a counter-clockwise convex polygon (within `tolerance`
/// metres). A polygon of fewer than 3 vertices contains nothing.
bool inside_convex_polygon(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& point,
                           double tolerance = 1e-9);

}  // namespace floorgrid
