#include "floorgrid/simulation/room_rotation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid {
namespace {

// S(t) = 6t⁵ - 15t⁴ + 10t³ and S'(t) = 30 t² (1 - t)²: 0 and 1 at the ends, with S' and S''
// vanishing there, so the weight joins the core and the outside without a kink.
double smoothstep(double t) {
  return t * t * t * (t * (6.0 * t - 15.0) + 10.0);
}
double smoothstep_slope(double t) {
  return 30.0 * t * t * (1.0 - t) * (1.0 - t);
}

struct BlendWeight {
  double value = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
};

BlendWeight blend_weight(const RoomRotation& room, const Eigen::Vector2d& p) {
  const Eigen::Vector2d below = room.core.min() - p;
  const Eigen::Vector2d above = p - room.core.max();
  // Offset from the nearest point of the core box; its length is the distance d, its direction
  // the gradient of d.
  const Eigen::Vector2d offset(below.x() > 0.0 ? -below.x() : std::max(above.x(), 0.0),
                               below.y() > 0.0 ? -below.y() : std::max(above.y(), 0.0));
  const double d = offset.norm();
  if (d == 0.0)
    return {1.0, Eigen::Vector2d::Zero()};
  if (d >= room.band)
    return {};
  const double t = 1.0 - d / room.band;
  return {smoothstep(t), -smoothstep_slope(t) / room.band * (offset / d)};
}

}  // namespace

void validate_room_rotation(const RoomRotation& room) {
  if (room.core.isEmpty() || !room.core.min().allFinite() || !room.core.max().allFinite()) {
    throw InputError("must be a non-empty finite box", {}, 0, "room.core");
  }
  if (!(std::isfinite(room.band) && room.band > 0.0)) {
    throw InputError("must be a finite number > 0 " + got(room.band), {}, 0, "room.band");
  }
  if (!room.center.allFinite()) {
    throw InputError("must be finite", {}, 0, "room.center");
  }
  if (!std::isfinite(room.angle)) {
    throw InputError("must be a finite number " + got(room.angle), {}, 0, "room.angle");
  }
}

double room_rotation_weight(const RoomRotation& room, const Eigen::Vector2d& point_in_world) {
  return blend_weight(room, point_in_world).value;
}

Eigen::Vector2d rotate_room_point(const RoomRotation& room, const Eigen::Vector2d& point_in_world) {
  const double w = blend_weight(room, point_in_world).value;
  if (w == 0.0)
    return point_in_world;
  const Eigen::Vector2d r = point_in_world - room.center;
  return point_in_world + w * (rotation_2d(room.angle) * r - r);
}

Eigen::Matrix2d room_rotation_jacobian(const RoomRotation& room,
                                       const Eigen::Vector2d& point_in_world) {
  const BlendWeight w = blend_weight(room, point_in_world);
  const Eigen::Matrix2d turn = rotation_2d(room.angle) - Eigen::Matrix2d::Identity();
  const Eigen::Vector2d displacement = turn * (point_in_world - room.center);
  return Eigen::Matrix2d::Identity() + w.value * turn + displacement * w.gradient.transpose();
}

double min_jacobian_determinant(const RoomRotation& room, double spacing) {
  if (!(std::isfinite(spacing) && spacing > 0.0)) {
    throw InputError("must be a finite number > 0 " + got(spacing), {}, 0, "room.spacing");
  }
  validate_room_rotation(room);
  const Eigen::Vector2d lo = room.core.min().array() - room.band;
  const Eigen::Vector2d size = (room.core.max() - room.core.min()).array() + 2.0 * room.band;
  const int nx = static_cast<int>(std::ceil(size.x() / spacing)) + 1;
  const int ny = static_cast<int>(std::ceil(size.y() / spacing)) + 1;
  double smallest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const Eigen::Vector2d p(lo.x() + size.x() * i / (nx - 1), lo.y() + size.y() * j / (ny - 1));
      smallest = std::min(smallest, room_rotation_jacobian(room, p).determinant());
    }
  }
  return smallest;
}

}  // namespace floorgrid
