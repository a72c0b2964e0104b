#include "floorgrid/evaluation/waypoint_mapping.hpp"

namespace floorgrid {

std::vector<MappedWaypoint> map_waypoints(const PointMapping& model,
                                          const std::vector<Waypoint>& waypoints,
                                          const std::optional<GridGeometry>& gridmap,
                                          const std::string& where) {
  for (const Waypoint& w : waypoints)
    validate_waypoint(w, where);
  std::vector<MappedWaypoint> out;
  out.reserve(waypoints.size());
  for (const Waypoint& w : waypoints) {
    MappedWaypoint m;
    const MappedPoint p = model.map_forward(w.position);
    m.waypoint = w;
    m.waypoint.position = p.point;
    if (w.theta && p.point.allFinite())
      m.waypoint.theta = model.heading_in_grid(w.position, *w.theta);
    m.std_m = p.std_m;
    m.nearest_pair_m = p.nearest_pair_m;
    m.flag = p.flag;
    m.extrapolated = p.flag == MapFlag::extrapolated || p.flag == MapFlag::outside_hull ||
                     p.flag == MapFlag::not_invertible;
    if (gridmap) {
      int ix = 0, iy = 0;
      m.on_gridmap = p.point.allFinite() && gridmap->cell_of(p.point, ix, iy);
    }
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace floorgrid
