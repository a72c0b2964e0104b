#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace floorgrid {

/// A closed ring of a polygon: its vertices in order, the closing vertex not repeated.
using Ring = std::vector<Eigen::Vector2d>;

/// What a zone is for on the robot (SPEC revision 3, "Plan layers to the robot").
struct ZoneSpeed {
  /// Speed limit in percent of the robot's maximal speed, (0, 100]: nav2 filter type 1.
  std::optional<double> percent;
  /// Speed limit in metres per second, > 0: nav2 filter type 2.
  std::optional<double> metres_per_second;
};

/// A zone drawn on a map: a polygon (outer ring and holes) with a name, in one frame (plan
/// metres, or gridmap metres once mapped). Holes are read with the even-odd rule: a point is
/// inside when a ray from it crosses the rings an odd number of times.
struct Zone {
  std::string name;         ///< as given, or "zone <index>" when the file names none
  std::size_t index = 0;    ///< 0-based position in the file (feature, or entity)
  Ring outer;               ///< the outer boundary, metres
  std::vector<Ring> holes;  ///< rings cut out of it, metres
  ZoneSpeed speed;          ///< for speed masks; empty for keepout zones
};

/// A named pose (a station, a waypoint) drawn on a map, in one frame, metres and radians.
struct Waypoint {
  std::string name;       ///< as given, or "waypoint <index>"
  std::size_t index = 0;  ///< 0-based position in the file (feature or CSV row)
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< metres
  std::optional<double> theta;  ///< heading, radians (counter-clockwise from +x); may be absent
};

/// Zones and waypoints of one file, and what reading them noticed.
struct PlanLayers {
  std::vector<Zone> zones;            ///< polygons, in file order
  std::vector<Waypoint> waypoints;    ///< named poses, in file order
  std::vector<std::string> warnings;  ///< non-fatal oddities (features of other types skipped)
};

/// Checks a zone: every coordinate finite, each ring at least 3 distinct vertices, no ring
/// crossing itself or another ring, a non-zero area, and the speed (when given) in range.
/// Throws InputError naming `where` and the zone ("zone 2 'loading bay'") and saying what and
/// where (the crossing edges and the point).
void validate_zone(const Zone& zone, const std::string& where);

/// Checks a waypoint: finite position and heading; InputError naming `where` and the waypoint.
void validate_waypoint(const Waypoint& waypoint, const std::string& where);

/// "zone 2 'loading bay'": how messages name a zone.
std::string describe(const Zone& zone);
/// "waypoint 0 'dock'": how messages name a waypoint.
std::string describe(const Waypoint& waypoint);

/// Points along the ring's edges (the ring closed), at most `spacing` apart, each vertex kept:
/// what is mapped through a model so that a bent model bends the edges.
Eigen::Matrix2Xd densify_ring(const Ring& ring, double spacing);

/// Where two edges of the rings cross (touching counts), the first found: ring and edge
/// indices and the point. Empty when the rings are simple and disjoint.
struct RingCrossing {
  std::size_t ring_a = 0, edge_a = 0, ring_b = 0, edge_b = 0;  ///< edge i runs from vertex i
  Eigen::Vector2d point = Eigen::Vector2d::Zero();             ///< metres
};
/// The first crossing among `rings` (edges sharing a vertex within one ring are adjacent and
/// not counted), or nullopt.
std::optional<RingCrossing> find_crossing(const std::vector<Ring>& rings);

/// The signed area of a ring (positive counter-clockwise), square metres.
double signed_area(const Ring& ring);

}  // namespace floorgrid
