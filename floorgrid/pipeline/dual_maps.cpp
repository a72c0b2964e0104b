#include "floorgrid/pipeline/dual_maps.hpp"

#include <fmt/format.h>

#include <chrono>

#include "floorgrid/pipeline/map_alignment.hpp"

namespace floorgrid {

namespace {

// Progress is reported every this many scans: often enough for a live line, rarely enough to
// cost nothing.
constexpr std::size_t kProgressEveryScans = 25;

// A plan whose "rooms" would leave more than this share of its walls unseen is not drawn as
// closed rooms: its walls are all used.
constexpr double kMaxHiddenWallShare = 0.5;

/// The plan as a robot inside sees it (the unseen faces of walls drawn as two lines dropped).
VisibleWalls find_visible_walls(const OccupancyGrid& plan, const PlanLocationOptions& options,
                                std::vector<std::string>& notes) {
  if (!options.visible_walls_only)
    return {};
  VisibleWalls visible = visible_walls(plan, options.visible);
  if (!visible.applied) {
    notes.push_back("the plan has no closed inside: every drawn wall is used");
  } else if (double(visible.hidden) > kMaxHiddenWallShare * double(visible.walls)) {
    // An open, gappy drawing (walls only where someone drew them) has pockets for rooms:
    // hiding most of its walls would leave the filter nothing to see.
    notes.push_back("the plan's rooms are not closed (" + std::to_string(visible.hidden) + " of " +
                    std::to_string(visible.walls) +
                    " wall cells would be unseen from inside): every drawn wall is used");
    return {};
  }
  return visible;
}

/// The plan's walls to match scans onto: a DXF plan's exact walls when given, else the plan
/// grid's occupied cells, met at the ink's edges when `at_ink_edges`; one-sided where the
/// visible walls found the rooms.
WallField plan_wall_field(const DualLocalizerInputs& inputs, const OccupancyGrid& plan,
                          const VisibleWalls& visible, const WallFieldOptions& options,
                          bool at_ink_edges) {
  const std::vector<std::uint8_t>* rooms = visible.applied ? &visible.room : nullptr;
  if (inputs.plan_geometry) {
    return WallField(*inputs.plan_geometry, plan.geometry(), options,
                     visible.applied ? &visible.grid : nullptr, rooms);
  }
  WallField walls(plan, options, rooms);
  if (at_ink_edges)
    walls.set_surface_offset(0.5 * plan.geometry().resolution);
  return walls;
}

}  // namespace

bool plan_walls_at_ink_edges(const DualLocalizerInputs& inputs, const DualLocalizerOptions& options,
                             std::vector<std::string>& notes) {
  if (inputs.plan_geometry || options.plan_wall_line == PlanWallLine::cell_centres)
    return false;
  if (options.plan_wall_line == PlanWallLine::ink_edges)
    return true;
  if (!inputs.maps || inputs.maps->faces.partition_points == 0)
    return false;
  // The faces' offsets are in plan metres; the registration maps world metres to plan metres.
  const double plan_per_world = inputs.maps->registration.best.transform.scale;
  const double offset = inputs.maps->faces.partition_offset / plan_per_world;
  if (!(offset >= options.ink_edge_min_offset))
    return false;
  notes.push_back(fmt::format(
      "the plan's walls are met at the ink's edges: the partitions' faces lie {:.3f} m off their "
      "strokes (walls thicker than their ink)",
      offset));
  return true;
}

MapModel::MapModel(const OccupancyGrid& map, const LikelihoodFieldOptions& likelihood,
                   ObservationModelKind kind, const BeamModelOptions& beam)
    : field_(std::make_unique<LikelihoodFieldModel>(map, likelihood)) {
  if (kind == ObservationModelKind::beam)
    beam_ = std::make_unique<BeamModel>(map, beam);
}

const ObservationModel& MapModel::model() const {
  return beam_ ? static_cast<const ObservationModel&>(*beam_) : *field_;
}

DualMaps::DualMaps(const DualLocalizerInputs& inputs, const DualLocalizerOptions& options,
                   std::vector<std::string>& notes)
    : visible_(find_visible_walls(inputs.plan, options.plan_location, notes)),
      plan_(visible_.applied ? &visible_.grid : &inputs.plan),
      gridmap_(inputs.gridmap),
      plan_model_(*plan_, options.plan.likelihood, options.plan.model, options.beam),
      grid_model_(gridmap_, options.grid.likelihood, options.grid.model, options.beam),
      plan_walls_(plan_wall_field(inputs, *plan_, visible_, options.walls,
                                  plan_walls_at_ink_edges(inputs, options, notes))),
      grid_walls_(gridmap_, options.walls),
      log_(inputs.log),
      plan_observation_(options.plan.observation),
      grid_observation_(options.grid.observation) {
  if (options.plan_beam_consistency)
    plan_rays_.emplace(*plan_);
}

ScanObservation DualMaps::grid_observation(std::size_t i) const {
  return make_observation(log_.scans[i], grid_observation_);
}

void report_progress(const DualProgressCallback& progress, const char* phase, std::size_t done,
                     std::size_t total, bool converged, std::size_t pairs) {
  if (progress && (done % kProgressEveryScans == 0 || done == total))
    progress({phase, done, total, converged, pairs});
}

void count_divergence(DivergenceCount& count, const std::string& reason) {
  ++count.total;
  ++count.by_reason[reason];
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace floorgrid
