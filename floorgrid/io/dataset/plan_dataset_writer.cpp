#include "floorgrid/io/dataset/plan_dataset_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "floorgrid/evaluation/overlay.hpp"
#include "floorgrid/io/dataset/dataset_manifest.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/formats/truth_json.hpp"
#include "floorgrid/io/logs/carmen_writer.hpp"

namespace floorgrid::io {

namespace {

using nlohmann::json;

constexpr int kMaxWorldPicture = 2400;  // pixels along the world picture's longer side

json vec(const Eigen::Vector2d& v) {
  return json::array({v.x(), v.y()});
}
json pose(const Pose2& p) {
  return json::array({p.x, p.y, p.theta});
}

std::string describe_source(const PlanDrawingFile& f) {
  if (f.kind == "dxf")
    return fmt::format("DXF in {} ({})", f.dxf->units_used, f.dxf->units_source);
  return fmt::format("raster {} x {} px at {} m per px", f.drawing.raster->width(),
                     f.drawing.raster->height(), f.drawing.raster->resolution());
}

json world_json(const PlanDataset& d) {
  const double to_plan = 1.0 / d.statistics.plan_scale;
  const PlanWorld& w = d.world;
  json regions = json::array();
  const auto in = [](const std::vector<int>& list, std::size_t r) {
    return std::find(list.begin(), list.end(), static_cast<int>(r)) != list.end();
  };
  const Eigen::Vector2d* rotated = d.warp.room ? &d.warp.room->center : nullptr;
  for (std::size_t r = 0; r < w.regions.size(); ++r) {
    const WorldRegion& region = w.regions[r];
    regions.push_back({{"name", region.name},
                       {"kind", region.kind},
                       {"area_m2", region.area},
                       {"box_min", vec(region.box.min() * to_plan)},
                       {"box_max", vec(region.box.max() * to_plan)},
                       {"centre", vec(region.centre * to_plan)},
                       {"visited", region.visited},
                       {"skipped", in(d.tour.skipped, r)},
                       {"unreachable", in(d.tour.unreachable, r)},
                       {"rotated", rotated && region.box.center().isApprox(*rotated)}});
  }
  json doors = json::array();
  for (const WorldDoor& door : w.doors) {
    doors.push_back({{"a", vec(door.jamb_a * to_plan)},
                     {"b", vec(door.jamb_b * to_plan)},
                     {"width_m", door.width()},
                     {"state", door.state},
                     {"regions", {door.region_a, door.region_b}}});
  }
  json glass = json::array();
  for (const GlassWall& g : w.glass) {
    glass.push_back({{"a", vec(g.a * to_plan)},
                     {"b", vec(g.b * to_plan)},
                     {"thickness_m", g.thickness},
                     {"mullions", g.mullions}});
  }
  std::map<std::string, int> objects;
  json columns = json::array();
  for (const WorldObject& o : w.objects) {
    ++objects[o.what];
    if (o.kind == SurfaceKind::column) {
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (const auto& p : o.outline)
        c += p / double(o.outline.size());
      columns.push_back(vec(c * to_plan));
    }
  }
  json errors = json::array();
  for (const DrawingError& e : w.errors) {
    errors.push_back({{"kind", e.kind},
                      {"a", vec(e.a * to_plan)},
                      {"b", vec(e.b * to_plan)},
                      {"amount_m", e.amount}});
  }
  return {{"note", "plan metres, except widths, thicknesses and amounts in world metres"},
          {"partition_thickness_m", w.partition_thickness},
          {"exterior_thickness_m", w.exterior_thickness},
          {"regions", regions},
          {"doors", doors},
          {"glass", glass},
          {"columns", columns},
          {"objects", objects},
          {"drawing_errors", errors}};
}

// The world as a picture: what stands where, the drawing under it, the path and the errors.
void write_world_picture(const PlanDataset& d, const std::filesystem::path& path) {
  const PlanWorld& w = d.world;
  GridGeometry g = w.raster;
  const double extent = std::max(g.width, g.height) * g.resolution;
  g.resolution = std::max(0.05, extent / kMaxWorldPicture);
  g.width = static_cast<int>(std::ceil(w.raster.width * w.raster.resolution / g.resolution));
  g.height = static_cast<int>(std::ceil(w.raster.height * w.raster.resolution / g.resolution));
  RgbImage picture{g.width, g.height, std::vector<std::uint8_t>(g.size() * 3, 200)};
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      int wx = 0, wy = 0;
      if (!w.raster.cell_of(g.cell_center(ix, iy), wx, wy))
        continue;
      const std::size_t i = static_cast<std::size_t>(wy) * w.raster.width + wx;
      const int region = w.region_of[i];
      const bool unvisited = region >= 0 && !w.regions[static_cast<std::size_t>(region)].visited;
      if (w.walkable[i] || region >= 0)
        picture.set(ix, g.height - 1 - iy,
                    unvisited ? Colour{255, 215, 225} : Colour{255, 255, 255});
    }
  }
  const auto identity = [](const Eigen::Vector2d& p) { return p; };
  draw_points(picture, g, w.drawn_ink, {170, 200, 240});
  std::map<int, VectorFloorplan> by_kind;
  for (const Segment& s : w.world_segments())
    by_kind[s.layer].add_segment(s.a, s.b, "S");
  const std::map<int, Colour> colours = {{static_cast<int>(SurfaceKind::wall), {0, 0, 0}},
                                         {static_cast<int>(SurfaceKind::furniture), {150, 90, 40}},
                                         {static_cast<int>(SurfaceKind::door_leaf), {240, 140, 0}},
                                         {static_cast<int>(SurfaceKind::column), {140, 40, 170}},
                                         {static_cast<int>(SurfaceKind::mullion), {140, 40, 170}}};
  for (const auto& [kind, plan] : by_kind)
    draw_plan(picture, g, plan, identity, colours.at(kind));
  VectorFloorplan glass, errors;
  for (const GlassWall& pane : w.glass)
    glass.add_segment(pane.a, pane.b, "G");
  for (const DrawingError& e : w.errors)
    errors.add_segment(e.a, e.b, "E");
  if (!glass.empty())
    draw_plan(picture, g, glass, identity, {0, 190, 220});
  Eigen::Matrix2Xd route(2, static_cast<Eigen::Index>(d.true_trajectory.size()));
  for (std::size_t i = 0; i < d.true_trajectory.size(); ++i)
    route.col(static_cast<Eigen::Index>(i)) = d.true_trajectory[i].pose.translation();
  draw_points(picture, g, route, {40, 160, 40});
  if (!errors.empty())
    draw_plan(picture, g, errors, identity, {230, 0, 200});
  write_png_rgb(path, picture.width, picture.height, picture.rgb);
}

void write_preview(const PlanDataset& d, const std::filesystem::path& path) {
  RgbImage picture = grid_picture(d.gridmap);
  const SimulatedWarp warp(d.warp);
  Eigen::Matrix2Xd route(2, static_cast<Eigen::Index>(d.true_trajectory.size()));
  for (std::size_t i = 0; i < d.true_trajectory.size(); ++i)
    route.col(static_cast<Eigen::Index>(i)) =
        warp.world_to_grid(d.true_trajectory[i].pose.translation());
  draw_points(picture, d.gridmap.geometry(), route, {40, 160, 40});
  draw_points(picture, d.gridmap.geometry(), warp.world_to_grid_batch(d.world.drawn_ink),
              {220, 30, 30});
  draw_points(picture, d.gridmap.geometry(), d.manual_pairs.points_in_grid, {30, 60, 230}, 2);
  write_png_rgb(path, picture.width, picture.height, picture.rgb);
}

// A raster drawing as given: its image copied, its map YAML with the plan's resolution.
void write_raster_plan(const PlanDataset& d, const PlanDrawingFile& f,
                       const std::filesystem::path& folder, SimulationFiles& out) {
  const double to_plan = 1.0 / d.statistics.plan_scale;
  std::string ext = f.image.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::filesystem::path image = folder / ("floorplan" + ext);
  write_file_atomically(image, read_whole_file(f.image));
  out.files.push_back(image);
  const MapMetadata& m = f.metadata;
  const GridGeometry& g = f.drawing.raster->geometry();
  write_file_atomically(
      folder / "floorplan.yaml",
      fmt::format("image: {}\nmode: {}\nresolution: {}\norigin: [{}, {}, {}]\nnegate: {}\n"
                  "occupied_thresh: {}\nfree_thresh: {}\n",
                  image.filename().string(), to_string(m.mode), g.resolution * to_plan,
                  g.origin.x * to_plan, g.origin.y * to_plan, g.origin.theta, m.negate ? 1 : 0,
                  m.occupied_thresh, m.free_thresh));
  out.files.push_back(folder / "floorplan.yaml");
}

}  // namespace

json plan_dataset_truth_json(const PlanDataset& d, const PlanDrawingFile& f) {
  const PlanDatasetOptions& o = d.options;
  const PlanDatasetStatistics& s = d.statistics;
  const SimulationPreset& p = o.run;
  const SimulatedWarp warp(d.warp);
  json j;
  j["format"] = "floorgrid-simulation-truth";
  j["version"] = 1;
  j["preset"] = "from-plan";
  j["seed"] = o.seed;
  j["source_plan"] = f.path.string();
  j["source"] = describe_source(f);
  j["frames"] = {{"world", "metric world the laser sees: the plan times plan.plan_scale"},
                 {"plan", "the drawing's own coordinates, metres: world x plan.plan_per_world"},
                 {"grid", "the gridmap's ROS map frame, metres"}};
  const std::string units = f.dxf ? f.dxf->units_used : "m";
  j["plan"] = {{"plan_per_world", 1.0 / s.plan_scale},
               {"plan_scale", s.plan_scale},
               {"drawing_units", units},
               {"header_units", f.dxf ? f.dxf->header_units : "m"},
               {"drawing_units_per_metre", f.dxf ? 1.0 / f.dxf->metres_per_unit : 1.0},
               {"layers", f.layers}};
  j["warp"] = warp_json(d.warp);
  j["parameters"] = {{"plan_scale", s.plan_scale},
                     {"plan_scale_range", {s.plan_scale_low, o.max_plan_scale}},
                     {"bend_m", *o.bend},
                     {"rotation_deg", *o.rotation_deg},
                     {"drawing_errors", o.drawing_errors ? "some" : "none"},
                     {"raster_resolution", s.raster_resolution},
                     {"gridmap_resolution", p.gridmap_resolution},
                     {"laser", laser_json(p)},
                     {"odometry_alpha", odometry_alpha_json(p)},
                     {"speed", p.tour.speed},
                     {"turn_rate", p.tour.turn_rate},
                     {"odometry_period", p.tour.tick},
                     {"clearance", o.tour.clearance},
                     {"max_tour_length", o.tour.max_length},
                     {"room_rotation_deg", {p.room_rotation_min_deg, p.room_rotation_max_deg}},
                     {"room_rotation_band", p.room_rotation_band},
                     {"manual_pairs", {p.min_manual_pairs, p.max_manual_pairs}},
                     {"manual_pair_noise", p.manual_pair_noise}};
  const PlanWorld& w = d.world;
  std::size_t rooms = 0;
  for (const WorldRegion& r : w.regions)
    rooms += r.kind == "room";
  j["statistics"] = {
      {"regions", w.regions.size()},
      {"rooms", rooms},
      {"regions_visited", d.tour.visited.size()},
      {"regions_unreachable", d.tour.unreachable.size()},
      {"regions_skipped", d.tour.skipped.size()},
      {"reachable_area_m2", d.tour.reachable_area},
      {"doors_open", w.doors_in_state("open")},
      {"doors_closed", w.doors_in_state("closed")},
      {"doorways_without_leaf", w.doors_in_state("none")},
      {"glass_walls", w.glass.size()},
      {"mullions", w.count(SurfaceKind::mullion)},
      {"columns", w.count(SurfaceKind::column)},
      {"furniture_pieces", w.count(SurfaceKind::furniture)},
      {"drawing_errors", w.errors.size()},
      {"wall_segments", w.walls.size()},
      {"path_length_m", s.path_length},
      {"duration_s", s.duration},
      {"scans", s.scans},
      {"beams", s.beams},
      {"returns", s.returns},
      {"wall_beams", s.wall_beams},
      {"furniture_beams", s.furniture_beams},
      {"door_beams", s.door_beams},
      {"column_beams", s.column_beams},
      {"furniture_fraction", s.clutter_fraction},
      {"max_bend_strain", s.max_bend_strain},
      {"bend_deviation_m", s.bend_deviation},
      {"warp_fit_scale", s.warp_fit_scale},
      {"room_rotation_deg", s.room_rotation_deg},
      {"min_room_jacobian", s.min_room_jacobian},
      {"final_odometry_error_m", s.final_odometry_error},
      {"cells",
       {{"occupied", s.occupied_cells}, {"free", s.free_cells}, {"unknown", s.unknown_cells}}}};
  j["world"] = world_json(d);
  j["start"] = {{"plan", pose(d.start_in_plan)}, {"grid", pose(d.start_in_grid)}};
  json poses = json::array();
  for (const TimedPose& tp : d.true_trajectory) {
    const Pose2 g = warp.pose_world_to_grid(tp.pose);
    poses.push_back({tp.time, tp.pose.x, tp.pose.y, tp.pose.theta, g.x, g.y, g.theta});
  }
  j["trajectory"] = {
      {"columns", {"time", "world_x", "world_y", "world_theta", "grid_x", "grid_y", "grid_theta"}},
      {"note", "plan pose = world position x plan.plan_per_world, same heading"},
      {"poses", poses}};
  return j;
}

SimulationFiles write_plan_dataset(const PlanDataset& d, const PlanDrawingFile& f,
                                   const std::filesystem::path& folder, bool preview) {
  prepare_output_folder(folder);
  SimulationFiles out{folder, {}};
  DatasetManifest manifest;
  manifest.manifest_path = folder / "dataset.yaml";
  manifest.name = "from " + f.path.filename().string() + " seed " + std::to_string(d.options.seed);
  if (f.kind == "dxf") {
    manifest.floorplan = folder / "floorplan.dxf";
    write_file_atomically(manifest.floorplan, read_whole_file(f.path));
    out.files.push_back(manifest.floorplan);
    manifest.floorplan_layers = f.layers;
  } else {
    write_raster_plan(d, f, folder, out);
    manifest.floorplan = folder / "floorplan.yaml";
  }
  MapWriteOptions map;
  map.mode = MapMode::trinary;
  out.files.push_back(folder / "gridmap.yaml");
  out.files.push_back(write_map(d.gridmap, folder / "gridmap.yaml", map));
  write_carmen(d.log, folder / "log.carmen");
  out.files.push_back(folder / "log.carmen");
  write_pairs_csv(d.manual_pairs, folder / "manual_pairs.csv");
  out.files.push_back(folder / "manual_pairs.csv");
  write_file_atomically(folder / "truth.json", plan_dataset_truth_json(d, f).dump(1) + "\n");
  out.files.push_back(folder / "truth.json");

  manifest.floorplan_units = "auto";
  manifest.floorplan_scale.reset();  // auto: the true scale is only in truth.json
  manifest.gridmap = folder / "gridmap.yaml";
  manifest.log = folder / "log.carmen";
  manifest.truth.warp = folder / "truth.json";
  manifest.truth.manual_pairs = folder / "manual_pairs.csv";
  write_manifest(manifest);
  out.files.push_back(manifest.manifest_path);
  if (preview) {
    write_preview(d, folder / "preview.png");
    out.files.push_back(folder / "preview.png");
    write_world_picture(d, folder / "world.png");
    out.files.push_back(folder / "world.png");
  }
  return out;
}

}  // namespace floorgrid::io
