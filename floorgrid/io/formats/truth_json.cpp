#include "floorgrid/io/formats/truth_json.hpp"

#include <cmath>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/value_json.hpp"

namespace floorgrid::io {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "floorgrid-simulation-truth";
constexpr int kVersion = 1;

json vec(const Eigen::Vector2d& v) {
  return json::array({v.x(), v.y()});
}
json pose(const Pose2& p) {
  return json::array({p.x, p.y, p.theta});
}

/// Reads a field, turning every JSON type error into an InputError naming file and field.
const json& field(const json& j, const std::string& key, const std::string& where,
                  const std::string& path) {
  if (!j.is_object() || !j.contains(key)) {
    throw InputError("missing field", where, 0, path + key);
  }
  return j.at(key);
}

double number(const json& j, const std::string& key, const std::string& where,
              const std::string& path) {
  const json& v = field(j, key, where, path);
  if (!v.is_number() || !std::isfinite(v.get<double>())) {
    throw InputError("expected a finite number", where, 0, path + key);
  }
  return v.get<double>();
}

Eigen::Vector2d vector2(const json& j, const std::string& key, const std::string& where,
                        const std::string& path) {
  const json& v = field(j, key, where, path);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
    throw InputError("expected [x, y]", where, 0, path + key);
  }
  return {v[0].get<double>(), v[1].get<double>()};
}

}  // namespace

json laser_json(const SimulationPreset& p) {
  return {{"beams", p.beams},
          {"field_of_view", p.field_of_view},
          {"max_range", p.max_range},
          {"range_noise_sigma", p.range_noise_sigma},
          {"random_reading_fraction", p.random_reading_fraction},
          {"forward_offset", p.laser_forward_offset},
          {"scan_period", p.scan_period}};
}

json odometry_alpha_json(const SimulationPreset& p) {
  return {p.odometry.alpha1, p.odometry.alpha2, p.odometry.alpha3, p.odometry.alpha4};
}

json warp_json(const WarpParams& warp) {
  json j;
  j["T_grid_world"] = {
      {"x", warp.T_grid_world.x}, {"y", warp.T_grid_world.y}, {"theta", warp.T_grid_world.theta}};
  j["bend"] = {{"axis_origin", vec(warp.bend.axis_origin)},
               {"axis_angle", warp.bend.axis_angle},
               {"curvature", warp.bend.curvature}};
  if (warp.room) {
    j["room_rotation"] = {{"core_min", vec(warp.room->core.min())},
                          {"core_max", vec(warp.room->core.max())},
                          {"band", warp.room->band},
                          {"center", vec(warp.room->center)},
                          {"angle", warp.room->angle}};
  } else {
    j["room_rotation"] = nullptr;
  }
  return j;
}

WarpParams warp_from_json(const json& j, const std::string& where) {
  WarpParams warp;
  const json& t = field(j, "T_grid_world", where, "warp.");
  warp.T_grid_world = {number(t, "x", where, "warp.T_grid_world."),
                       number(t, "y", where, "warp.T_grid_world."),
                       number(t, "theta", where, "warp.T_grid_world.")};
  const json& bend = field(j, "bend", where, "warp.");
  warp.bend.axis_origin = vector2(bend, "axis_origin", where, "warp.bend.");
  warp.bend.axis_angle = number(bend, "axis_angle", where, "warp.bend.");
  warp.bend.curvature = number(bend, "curvature", where, "warp.bend.");
  const json& room = field(j, "room_rotation", where, "warp.");
  if (!room.is_null()) {
    RoomRotation r;
    const std::string p = "warp.room_rotation.";
    r.core = Eigen::AlignedBox2d(vector2(room, "core_min", where, p),
                                 vector2(room, "core_max", where, p));
    r.band = number(room, "band", where, p);
    r.center = vector2(room, "center", where, p);
    r.angle = number(room, "angle", where, p);
    warp.room = r;
  }
  return warp;
}

json simulation_truth_json(const SimulatedDataset& d) {
  const PlanTruth truth = d.truth();
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["preset"] = d.preset.name;
  j["seed"] = d.seed;
  j["frames"] = {{"world", "metric world the laser sees, metres"},
                 {"plan", "the plan's own coordinates in metres: world x plan.plan_per_world"},
                 {"grid", "the gridmap's ROS map frame, metres"}};
  // Two views of the plan's scale error: plan metres per world metre, and SPEC's plan_scale
  // (world metres per plan metre: a laser range divided by it is in plan metres).
  j["plan"] = {{"plan_per_world", d.plan_scale},
               {"plan_scale", 1.0 / d.plan_scale},
               {"drawing_units", d.preset.drawing_units},
               {"header_units", d.preset.header_units},
               {"drawing_units_per_metre", d.drawing_units_per_metre}};
  j["warp"] = warp_json(d.warp);
  const SimulationPreset& p = d.preset;
  j["parameters"] = {{"building", p.building},
                     {"gridmap_resolution", p.gridmap_resolution},
                     {"laser", laser_json(p)},
                     {"odometry_alpha", odometry_alpha_json(p)},
                     {"bend_deviation", p.bend_deviation},
                     {"max_bend_strain", p.max_bend_strain},
                     {"room_rotation_deg", {p.room_rotation_min_deg, p.room_rotation_max_deg}},
                     {"room_rotation_band", p.room_rotation_band},
                     {"max_plan_scale_error", p.max_plan_scale_error},
                     {"speed", p.tour.speed},
                     {"turn_rate", p.tour.turn_rate},
                     {"odometry_period", p.tour.tick},
                     {"manual_pairs", {p.min_manual_pairs, p.max_manual_pairs}},
                     {"manual_pair_noise", p.manual_pair_noise}};
  const SimulationStatistics& s = d.statistics;
  j["statistics"] = {
      {"rooms", s.rooms},
      {"rooms_visited", s.rooms_visited},
      {"path_length_m", s.path_length},
      {"duration_s", s.duration},
      {"scans", s.scans},
      {"beams", s.beams},
      {"returns", s.returns},
      {"furniture_beams", s.furniture_beams},
      {"furniture_fraction", s.furniture_fraction},
      {"max_bend_strain", s.max_bend_strain},
      {"bend_deviation_m", s.bend_deviation},
      {"room_rotation_deg", s.room_rotation_deg},
      {"min_room_jacobian", s.min_room_jacobian},
      {"final_odometry_error_m", s.final_odometry_error},
      {"cells",
       {{"occupied", s.occupied_cells}, {"free", s.free_cells}, {"unknown", s.unknown_cells}}}};
  json rooms = json::array();
  for (std::size_t i = 0; i < d.building.rooms.size(); ++i) {
    const Room& r = d.building.rooms[i];
    rooms.push_back({{"name", r.name},
                     {"interior_min", vec(r.interior.min() * d.plan_scale)},
                     {"interior_max", vec(r.interior.max() * d.plan_scale)},
                     {"visited", r.visited},
                     {"rotated", static_cast<int>(i) == d.building.rotated_room}});
  }
  j["rooms_in_plan"] = rooms;
  j["start"] = {{"plan", pose(d.start_in_plan)}, {"grid", pose(d.start_in_grid)}};
  json poses = json::array();
  for (const TimedPose& tp : d.true_trajectory) {
    const Pose2 g = truth.warp().pose_world_to_grid(tp.pose);
    poses.push_back({tp.time, tp.pose.x, tp.pose.y, tp.pose.theta, g.x, g.y, g.theta});
  }
  j["trajectory"] = {
      {"columns", {"time", "world_x", "world_y", "world_theta", "grid_x", "grid_y", "grid_theta"}},
      {"note", "plan pose = world position x plan.scale, same heading"},
      {"poses", poses}};
  return j;
}

json log_dataset_truth_json(const LogDataset& d, const std::string& source) {
  const LogDatasetOptions& o = d.options;
  const LogDatasetStatistics& s = d.statistics;
  const SimulatedWarp warp(d.warp);
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["preset"] = "from-log";
  j["seed"] = o.seed;
  j["source_log"] = source;
  j["frames"] = {{"world", "the building as the plan draws it, metres"},
                 {"plan", "the plan's own coordinates in metres: world x plan.plan_per_world"},
                 {"grid", "the corrected log's frame, metres (the gridmap's)"}};
  j["plan"] = {{"plan_per_world", d.plan_per_world},
               {"plan_scale", 1.0 / d.plan_per_world},
               {"drawing_units", "m"},
               {"header_units", "m"},
               {"drawing_units_per_metre", 1.0}};
  j["warp"] = warp_json(d.warp);
  j["parameters"] = {
      {"plan_scale", *o.plan_scale},
      {"bend_m", *o.bend},
      {"rotation_deg", *o.rotation_deg},
      {"wall_thickness_px", *o.wall_thickness_px},
      {"resolution", o.resolution},
      {"mapping_range", o.mapping_range},
      {"min_wall_extent", o.min_wall_extent},
      {"odometry_alpha",
       {o.odometry.alpha1, o.odometry.alpha2, o.odometry.alpha3, o.odometry.alpha4}}};
  j["statistics"] = {{"scans", s.scans},
                     {"path_length_m", s.path_length},
                     {"median_step_m", s.median_step},
                     {"median_turn_deg", s.median_turn_deg},
                     {"bend_deviation_m", s.bend_deviation},
                     {"max_bend_strain", s.max_bend_strain},
                     {"warp_fit_scale", s.warp_fit_scale},
                     {"wall_cells", s.wall_cells},
                     {"clutter_cells", s.clutter_cells},
                     {"plan_segments", s.plan_segments},
                     {"cells", {{"occupied", s.occupied_cells}, {"free", s.free_cells}}}};
  j["start"] = {{"plan", pose(d.start_in_plan)}, {"grid", pose(d.start_in_grid)}};
  json poses = json::array();
  for (const LaserScan& scan : d.log.scans) {
    const Pose2& g = scan.robot_pose;
    const Pose2 w = warp.pose_grid_to_world(g).pose;
    poses.push_back({scan.timestamp, w.x, w.y, w.theta, g.x, g.y, g.theta});
  }
  j["trajectory"] = {
      {"columns", {"time", "world_x", "world_y", "world_theta", "grid_x", "grid_y", "grid_theta"}},
      {"note", "one pose per scan, in line order; plan pose = world position x plan_per_world"},
      {"poses", poses}};
  return j;
}

PlanTruth read_plan_truth(const std::filesystem::path& path) {
  const std::string where = path.string();
  const json j = parse_json_document(read_whole_file(path), where);
  if (!j.is_object() || j.value("format", "") != kFormat) {
    throw InputError(std::string("not a floorgrid truth file (format must be '") + kFormat + "')",
                     where, 0, "format");
  }
  if (j.value("version", 0) != kVersion) {
    throw InputError(
        "unsupported version (this floorgrid reads version " + std::to_string(kVersion) + ")",
        where, 0, "version");
  }
  const double scale = number(field(j, "plan", where, ""), "plan_per_world", where, "plan.");
  try {
    return PlanTruth(warp_from_json(field(j, "warp", where, ""), where), scale);
  } catch (const InputError& e) {
    if (!e.file().empty())
      throw;
    throw InputError(e.message(), where, 0, e.field());
  }
}

}  // namespace floorgrid::io
