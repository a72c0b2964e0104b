#include "floorgrid/simulation/building.hpp"

#include "floorgrid/core/error.hpp"
#include "floorgrid/simulation/building_layouts.hpp"

namespace floorgrid {

std::vector<Segment> Building::world_segments() const {
  std::vector<Segment> out;
  out.reserve(walls.size() + racks.size() + furniture.size() + door_leaves.size());
  for (const auto* part : {&walls, &racks, &furniture, &door_leaves}) {
    out.insert(out.end(), part->begin(), part->end());
  }
  return out;
}

VectorFloorplan Building::plan_in_world() const {
  VectorFloorplan plan;
  for (const Segment& s : walls)
    plan.add_segment(s.a, s.b, "WALLS");
  for (const Segment& s : racks)
    plan.add_segment(s.a, s.b, "RACKS");
  for (const Arc& a : door_swings)
    plan.add_arc(a.center, a.radius, a.start_angle, a.end_angle, "DOORS");
  for (const Segment& s : door_lines)
    plan.add_segment(s.a, s.b, "DOORS");
  return plan;
}

Building generate_building(const BuildingOptions& options, Random& random) {
  if (options.kind == "office")
    return make_office(random);
  if (options.kind == "warehouse")
    return make_warehouse(random);
  throw InputError("unknown building kind '" + options.kind + "' (expected office or warehouse)",
                   {}, 0, "building.kind");
}

}  // namespace floorgrid
