#pragma once

#include <Eigen/Geometry>

namespace floorgrid {

/// One room of the simulated gridmap rotated by a small angle about a centre, as a SLAM map shows
/// a room mapped with a heading error, blended smoothly into its unrotated surroundings:
///   p -> p + w(p) (R(angle) (p - c) - (p - c))
/// with w = 1 inside `core` and, outside it, w = S(1 - d/band) for the distance d to the core box
/// (0 beyond the band), S(t) = 6t⁵ - 15t⁴ + 10t³. The blend band lies outside `core`: to keep it
/// inside a room, pass the room shrunk by the band as the core. S is C2 in d, but d itself is only
/// C1 (its curvature jumps where the face regions meet the corner regions), so the map is C1: its
/// Jacobian is continuous everywhere. The band is far from isometric: its displacement gradient
/// reaches about max S' |angle| r / band = 1.875 |angle| r / band at distance r from the centre
/// (measured: 37.5% principal strain for 3 degrees about the centre of a 4 x 5 m core, band
/// 0.8 m, with det J >= 0.69).
struct RoomRotation {
  /// Where the room turns rigidly, world metres.
  Eigen::AlignedBox2d core = Eigen::AlignedBox2d(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero());
  double band = 0.8;                                 ///< metres of blend around the core, > 0
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< rotation centre, world metres
  double angle = 0.0;                                ///< radians, counter-clockwise
};

/// Throws InputError naming the field ("room.core", "room.band", "room.center", "room.angle")
/// unless the core is a non-empty finite box, band > 0 and centre and angle are finite.
void validate_room_rotation(const RoomRotation& room);

/// The blend weight w(p) in [0, 1]: 1 in the core, 0 from `band` metres outside it on.
double room_rotation_weight(const RoomRotation& room, const Eigen::Vector2d& point_in_world);

/// Maps a world point through the room rotation (the result is in the same world frame).
Eigen::Vector2d rotate_room_point(const RoomRotation& room, const Eigen::Vector2d& point_in_world);

/// d rotate_room_point / d point, analytic: I + w (R - I) + (R - I)(p - c) ∇wᵀ.
Eigen::Matrix2d room_rotation_jacobian(const RoomRotation& room,
                                       const Eigen::Vector2d& point_in_world);

/// The smallest Jacobian determinant over a grid of spacing at most `spacing` metres covering the
/// core grown by the band (both edges included); outside that box the map is the identity. A
/// positive value says the map keeps orientation there, i.e. the blend band is wide enough for
/// the angle (the map is then one-to-one: it is the identity outside a compact set). InputError
/// (field "room.spacing") unless spacing > 0, and as validate_room_rotation.
double min_jacobian_determinant(const RoomRotation& room, double spacing);

}  // namespace floorgrid
