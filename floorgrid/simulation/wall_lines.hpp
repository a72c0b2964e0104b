#pragma once

// Straight walls of a drawing, found on its stroke centres (internal to simulation/).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid::plan_world {

/// A straight stretch of wall: its centre line and the stroke's half width.
struct WallLine {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  ///< one end of the centre line, world metres
  Eigen::Vector2d b = Eigen::Vector2d::Zero();  ///< the other end
  double half_width = 0.0;                      ///< metres, of the stroke (at least half a pixel)

  /// Unit vector from a to b.
  Eigen::Vector2d along() const { return (b - a).normalized(); }
  /// Length, metres.
  double length() const { return (b - a).norm(); }
};

/// The straight walls at least `min_length` metres long (a probabilistic Hough transform of
/// the stroke centres), near-duplicates merged, longest first.
std::vector<WallLine> find_wall_lines(const cv::Mat& ink, const GridGeometry& geometry,
                                      double min_length);

/// Whether the wall has `mask` on both sides (at `offset` metres beyond its stroke) along at
/// least `fraction` of its length: a partition between two pieces of inside.
bool has_on_both_sides(const WallLine& line, const cv::Mat& mask, const GridGeometry& geometry,
                       double offset, double fraction);

/// The fraction of the centre line between `from` and `to` metres along it that lies on ink.
double ink_fraction(const WallLine& line, const cv::Mat& ink, const GridGeometry& geometry,
                    double from, double to);

/// The building's main direction in [0, pi/2): the length-weighted circular mean of the
/// walls' directions modulo a quarter turn.
double dominant_angle(const std::vector<WallLine>& lines);

}  // namespace floorgrid::plan_world
