#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "floorgrid/maps/vector_floorplan.hpp"

namespace floorgrid {

/// Segments count as extended at both ends by this fraction of their length, so that a ray
/// through the corner shared by two segments hits at least one of them whatever the rounding.
inline constexpr double kRayEndpointTolerance = 1e-9;

/// A ray within this angle (radians) of a segment's direction counts as parallel to it: where
/// it would cross the segment's line is lost in rounding.
inline constexpr double kRayParallelTolerance = 1e-12;

namespace detail {

/// The ray-segment test behind SegmentRayCaster and intersect_ray_segment (one definition, so
/// both give bit-identical ranges). Ray origin (ox, oy) and unit direction (dx, dy); segment
/// start (ax, ay) and (ex, ey) = end - start. Returns the distance along the ray, or +inf.
/// See intersect_ray_segment for the rules. The segment parameter is taken from the hit point
/// itself (not from a second ratio of cross products), so a reported hit always lies on the
/// segment up to rounding, however ill-conditioned the crossing: the caster's cells, which hold
/// the segment's neighbourhood, then always contain it.
inline double ray_segment_range(double ox, double oy, double dx, double dy, double ax, double ay,
                                double ex, double ey) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double wx = ax - ox;
  const double wy = ay - oy;
  const double side = wx * ey - wy * ex;   // cross(a - o, e): zero when o is on the line
  const double denom = dx * ey - dy * ex;  // cross(d, e) = |e| sin(angle between them)
  if (side == 0.0 || denom == 0.0)
    return kInf;
  const double t = side / denom;
  if (!(t > 0.0))
    return kInf;
  const double ee = ex * ex + ey * ey;
  if (denom * denom <= (kRayParallelTolerance * kRayParallelTolerance) * ee)
    return kInf;
  const double along = (t * dx - wx) * ex + (t * dy - wy) * ey;  // u |e|^2 of the hit point
  if (!(along >= -kRayEndpointTolerance * ee && along <= (1.0 + kRayEndpointTolerance) * ee))
    return kInf;
  return t;
}

}  // namespace detail

/// Where a ray meets a segment: metres along the ray's unit `direction`, or nullopt.
///
/// Rules, chosen so that every case has one deterministic answer:
/// - a segment is closed, and extended at both ends by kRayEndpointTolerance of its length: a ray
///   grazing an endpoint hits, and a ray through a corner of a closed polygon never slips through;
/// - a segment whose supporting line passes exactly through the origin is never hit: seen
///   edge-on (the ray runs along it) or from on itself (the ray starts on it and leaves it);
///   zero-length segments are never hit;
/// - a segment parallel to the ray, or within kRayParallelTolerance (1e-12 rad) of it, is never
///   hit (it has no width);
/// - the hit must lie at a distance > 0 and <= `max_range`.
/// `direction` must have unit length; it is not renormalized.
std::optional<double> intersect_ray_segment(const Eigen::Vector2d& origin,
                                            const Eigen::Vector2d& direction,
                                            const Segment& segment, double max_range);

/// The nearest surface a ray meets.
struct RayHit {
  double range = 0.0;       ///< metres from the ray's origin
  std::size_t segment = 0;  ///< index of the segment hit, in the caster's segment list
  int layer = 0;            ///< that segment's Segment::layer (an opaque kind tag)
};

/// Settings of SegmentRayCaster's acceleration grid.
struct SegmentRayCasterOptions {
  double cell_size = 1.0;  ///< metres, edge of the square acceleration cells, finite and > 0
  /// The cell size is doubled until the acceleration grid has at most this many cells
  /// (a memory guard for sparse scenes of huge extent).
  std::size_t max_cells = std::size_t{1} << 24;
};

/// Exact nearest-hit ray casting over line segments in the world frame (metres).
///
/// Every segment is registered in each cell of a uniform acceleration grid that it touches
/// (conservatively: in every cell within a tiny pad of it). A ray walks the cells it crosses
/// (Amanatides and Woo's traversal), tests the segments of each, and stops at the first cell
/// whose far boundary lies beyond the nearest hit found so far. The result is identical to testing
/// every segment with intersect_ray_segment and keeping the smallest range, ties going to the
/// lowest segment index. The grid's cell boundaries lie at integer multiples of the cell size.
///
/// Immutable after construction; `cast` is const and safe to call from several threads.
class SegmentRayCaster {
 public:
  /// Builds the acceleration grid. Throws InputError naming `ray_caster.cell_size` or
  /// `segments` when the cell size is not finite and > 0 or a coordinate is not finite.
  explicit SegmentRayCaster(std::vector<Segment> segments_in_world,
                            const SegmentRayCasterOptions& options = {});

  /// The nearest hit of the ray from `origin` (world, metres) at `angle` (radians, world frame),
  /// with range <= `max_range` (metres), or nullopt. The direction is (cos angle, sin angle).
  std::optional<RayHit> cast(const Eigen::Vector2d& origin, double angle, double max_range) const;

  /// As cast, along a unit `direction` given directly (exactly axis-parallel rays, for instance).
  /// A non-finite origin or direction, or a zero direction, gives nullopt.
  std::optional<RayHit> cast_along(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction,
                                   double max_range) const;

  /// The segments, in the order given (RayHit::segment indexes them).
  const std::vector<Segment>& segments() const { return segments_; }
  /// Edge of the acceleration cells as used (options.cell_size, or larger), metres.
  double cell_size() const { return cell_size_; }
  /// Acceleration cells along x.
  int grid_width() const { return nx_; }
  /// Acceleration cells along y.
  int grid_height() const { return ny_; }
  /// Outer corner of the acceleration grid's lower-left cell, world metres.
  Eigen::Vector2d grid_origin() const { return {x0_, y0_}; }
  /// Segment registrations in all cells (a segment crossing k cells counts k times).
  std::size_t registrations() const { return entries_.size(); }

 private:
  /// A segment as stored in a cell: start, end - start and its index (kept contiguous per cell).
  struct CellEntry {
    double ax, ay, ex, ey;
    std::uint32_t index;
  };

  void build_grid(double requested_cell_size, std::size_t max_cells);
  template <typename Visit>
  void for_each_cell_touched(const Segment& segment, Visit&& visit) const;

  std::vector<Segment> segments_;
  double cell_size_ = 1.0;
  double inv_cell_size_ = 1.0;
  double pad_ = 0.0;  // metres: registration pad and stopping margin
  double x0_ = 0.0, y0_ = 0.0, x1_ = 0.0, y1_ = 0.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> cell_begin_;  // CSR offsets into entries_, nx * ny + 1
  std::vector<CellEntry> entries_;
};

}  // namespace floorgrid
