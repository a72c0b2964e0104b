#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <numbers>
#include <string>
#include <vector>

namespace floorgrid {

/// A straight piece of a drawing, drawing units.
struct PlanLine {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  ///< start
  Eigen::Vector2d b = Eigen::Vector2d::Zero();  ///< end
};

/// A circular arc of a drawing, drawing units, counter-clockwise from `start` to `end`.
struct PlanCircle {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< centre
  double radius = 0.0;                               ///< drawing units
  double start = 0.0;                                ///< radians
  double end = 0.0;                                  ///< radians, > start
};

/// A circular arc of the drawing, as unit evidence.
struct PlanArc {
  double radius = 0.0;  ///< drawing units
  double sweep = 0.0;   ///< radians, (0, 2 pi]
  bool leaf = false;    ///< a straight line runs from its centre to one of its ends: a door leaf
};

/// A dimension whose text states a length with its unit (`12'-6"`, `3.60 m`): the text says
/// what the measured distance is in the real world.
struct StatedLength {
  double measured = 0.0;  ///< the dimension's measurement, drawing units
  double stated_m = 0.0;  ///< what its text says, metres
  std::string text;       ///< the text, formatting codes removed
};

/// How thin bands of parallel lines (the two faces of a wall) are found. The rules are ratios,
/// so they hold in any unit.
struct WallBandOptions {
  double max_angle = std::numbers::pi / 180.0;  ///< radians: lines this close in angle are parallel
  double min_overlap = 0.5;  ///< share of the shorter line the two must overlap side by side
  double min_ratio = 4.0;    ///< a band: the line's far-side neighbour lies this many times farther
  std::size_t max_scan = 64;  ///< neighbours looked at on each side of a line (bounds the cost)
};

/// Wall faces: lines whose nearest parallel neighbour on one side is much closer than on the
/// other, as the two faces of a drawn wall are. Unit-free, in drawing units.
struct WallBandSummary {
  std::size_t faces = 0;         ///< lines found to be a face of such a band
  double thickness = 0.0;        ///< the most common band thickness (length-weighted); 0 if none
  double thickness_share = 0.0;  ///< share of the band faces' length within 25% of `thickness`
  double spacing = 0.0;  ///< length-weighted median distance from a band face to the next parallel
                         ///< line beyond it (the room or corridor on that side); 0 if none
};

/// The arcs as unit evidence (radius, sweep), each with `leaf` set when one of `lines` starts at
/// the arc's centre (within 5% of the radius) and runs towards one of the arc's ends for 80-120%
/// of the radius: the leaf of a door swing symbol. Only arcs sweeping less than a half turn are
/// checked. O((arcs + lines) log lines).
std::vector<PlanArc> find_door_leaves(const std::vector<PlanCircle>& arcs,
                                      const std::vector<PlanLine>& lines);

/// Finds the wall bands among `lines` and summarises their thickness and spacing.
/// O(lines log lines + lines * max_scan).
WallBandSummary measure_wall_bands(const std::vector<PlanLine>& lines,
                                   const WallBandOptions& options = {});

/// The box holding the middle `1 - 2 * tail` of `points` along each axis: the drawing without a
/// few far-off strays (a survey marker at the origin of a georeferenced site). Empty if no points.
Eigen::AlignedBox2d core_extent(std::vector<Eigen::Vector2d> points, double tail = 0.01);

}  // namespace floorgrid
