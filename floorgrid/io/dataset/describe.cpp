#include "floorgrid/io/dataset/describe.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/dataset/dataset_manifest.hpp"
#include "floorgrid/io/dataset/robot_log_reader.hpp"
#include "floorgrid/io/files/yaml_document.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/logs/bag_log.hpp"
#include "floorgrid/io/logs/carmen_log.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"

namespace floorgrid::io {

namespace {

using nlohmann::json;

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

json box_json(const Eigen::AlignedBox2d& box) {
  if (box.isEmpty())
    return nullptr;
  return {{"min", {box.min().x(), box.min().y()}},
          {"max", {box.max().x(), box.max().y()}},
          {"size", {box.sizes().x(), box.sizes().y()}}};
}

json grid_json(const LoadedMap& map) {
  const OccupancyGrid& grid = map.grid;
  const GridGeometry& g = grid.geometry();
  const CellCounts counts = grid.counts();
  json j = {{"width", g.width},
            {"height", g.height},
            {"resolution_m", g.resolution},
            {"origin", {g.origin.x, g.origin.y, g.origin.theta}},
            {"bounds_m", box_json(g.bounds())},
            {"cells",
             {{"occupied", counts.occupied}, {"free", counts.free}, {"unknown", counts.unknown}}},
            {"mode", to_string(map.metadata.mode)},
            {"negate", map.metadata.negate},
            {"occupied_thresh", map.metadata.occupied_thresh},
            {"free_thresh", map.metadata.free_thresh},
            {"image", map.image_path.string()},
            {"image_format", map.image_description}};
  j["warnings"] = map.warnings;
  return j;
}

json describe_map(const std::filesystem::path& path, const DescribeOptions& options, bool bare) {
  if (!bare)
    return grid_json(read_map_yaml(path));
  MapMetadata settings;
  settings.resolution = options.resolution.value_or(1.0);
  settings.origin = options.origin.value_or(Pose2{});
  json j = grid_json(read_map_image(path, settings));
  if (!options.resolution) {
    // Without a resolution only pixel counts mean anything.
    j.erase("resolution_m");
    j.erase("bounds_m");
    j.erase("origin");
    j["warnings"].push_back("bare image without --resolution: sizes are in pixels only");
  }
  return j;
}

}  // namespace

json unit_candidate_json(const PlanUnitCandidate& c) {
  return {{"unit", unit_name(c.unit)},
          {"metres_per_unit", metres_per_unit(c.unit)},
          {"score", c.score},
          {"probability", c.probability}};
}

namespace {

json describe_dxf(const std::filesystem::path& path, const DxfReadOptions& options = {}) {
  const DxfFloorplan dxf = read_dxf(path, options);
  const DxfReport& r = dxf.report;
  json j = {{"version", r.version},
            {"header_units", r.header_units},
            {"units_used", r.units_used},
            {"metres_per_unit", r.metres_per_unit},
            {"units_reason", r.units_reason},
            {"units_source", r.units_source},
            {"units_confidence", r.units_confidence},
            {"units_evidence", r.units_evidence},
            {"extent_m", box_json(dxf.plan.bounds())},
            {"header_extent_m", box_json(r.header_extent_m)},
            {"segments", dxf.plan.segments().size()},
            {"arcs", dxf.plan.arcs().size()},
            {"wall_length_m", dxf.plan.total_length()},
            {"entities_by_type", r.entities_by_type},
            {"entities_by_layer", r.entities_by_layer},
            {"annotation_skipped", r.annotation_skipped},
            {"unsupported_skipped", r.unsupported_skipped},
            {"excluded_by_layer_filter", r.excluded_by_layer_filter},
            {"inserts_expanded", r.inserts_expanded}};
  json candidates = json::array();
  for (const PlanUnitCandidate& c : r.unit_candidates)
    candidates.push_back(unit_candidate_json(c));
  j["unit_candidates"] = candidates;
  j["warnings"] = r.warnings;
  return j;
}

json setting_json(const UsedSetting& s, double factor) {
  return {{"value", s.value * factor}, {"source", to_string(s.source)}, {"detail", s.detail}};
}

/// The run's summary as `info` shows it, for a CARMEN log or a bag.
json run_json(const RobotLog& log, const RobotLogSummary& s) {
  json messages = json::object();
  std::vector<std::string> unknown_types;
  static const std::vector<std::string> kKnown = {
      "ODOM", "FLASER", "RLASER", "ROBOTLASER1", "ROBOTLASER2", "PARAM", "NEFF", "#", "(empty)"};
  for (const auto& [type, count] : s.messages) {
    messages[type] = {{"lines", count.lines},
                      {"kept", count.kept},
                      {"skipped_zero_timestamp", count.skipped_zero_timestamp},
                      {"skipped_backwards_timestamp", count.skipped_backwards_timestamp},
                      {"not_data", count.not_data}};
    if (std::find(kKnown.begin(), kKnown.end(), type) == kKnown.end())
      unknown_types.push_back(type);
  }
  json lasers = json::array();
  constexpr double kDeg = 180.0 / std::numbers::pi;
  for (const LaserConfigUsage& c : s.laser_configs) {
    lasers.push_back({{"type", c.type},
                      {"scans", c.scans},
                      {"beams", c.beams},
                      {"start_angle_deg", setting_json(c.start_angle, kDeg)},
                      {"angle_increment_deg", setting_json(c.angle_increment, kDeg)},
                      {"max_range_m", setting_json(c.max_range, 1.0)},
                      {"min_range_m", setting_json(c.min_range, 1.0)}});
  }
  json beams = json::object();
  for (const auto& [n, scans] : s.beams_per_scan)
    beams[std::to_string(n)] = scans;
  return {{"lines", s.lines},
          {"messages", messages},
          {"unknown_types", unknown_types},
          {"laser_scans", log.scans.size()},
          {"odometry", log.odometry.size()},
          {"beams_per_scan", beams},
          {"lasers", lasers},
          {"ranges",
           {{"total", s.ranges.total},
            {"hits", s.ranges.hits},
            {"no_return", s.ranges.no_return},
            {"too_close", s.ranges.too_close},
            {"invalid", s.ranges.invalid}}},
          {"params", s.params},
          {"first_timestamp", s.first_timestamp},
          {"last_timestamp", s.last_timestamp},
          {"duration_s", s.duration},
          {"warnings", s.warnings}};
}

json describe_carmen_log(const std::filesystem::path& path, const LaserSettings& laser) {
  CarmenReadOptions options;
  options.laser = laser;
  const CarmenLog log = read_carmen_log(path, options);
  return run_json(log, log.summary);
}

/// A bag's topics as `info` lists them: type, encoding, count and rate.
json topics_json(const BagContents& contents) {
  json topics = json::array();
  for (const BagTopic& t : contents.topics) {
    const double span = static_cast<double>(t.last_ns - t.first_ns) * 1e-9;
    topics.push_back(
        {{"topic", t.topic},
         {"type", t.type},
         {"encoding", t.encoding == MessageEncoding::cdr ? "cdr" : "ros1"},
         {"messages", t.messages},
         {"rate_hz", span > 0.0 && t.messages > 1 ? json(static_cast<double>(t.messages - 1) / span)
                                                  : json(nullptr)}});
  }
  return topics;
}

json describe_bag(const std::filesystem::path& path, BagFormat format,
                  const BagLogOptions& options) {
  // The run, with the contents it read them from; a bag that cannot be read as a run (no scan
  // topic it can tell, say) is still described, from its contents alone.
  std::optional<BagLog> log;
  std::string run_error;
  try {
    log = read_bag_log(path, options);
  } catch (const InputError& e) {
    run_error = e.what();
  }
  const BagContents contents = log ? log->contents : bag_contents(path);
  json j = {{"format", to_string(format)},
            {"topics", topics_json(contents)},
            {"bag_messages", contents.messages},
            {"bag_duration_s", static_cast<double>(contents.end_ns - contents.start_ns) * 1e-9},
            {"bag_warnings", contents.warnings}};
  if (!log) {
    j["run_error"] = run_error;
    return j;
  }
  j.update(run_json(*log, log->summary));
  j["unknown_types"] = json::array();  // a bag's topics are listed above, by type
  j["scan_topic"] = log->scan_topic;
  j["odometry_source"] = log->odometry_source;
  j["laser_frame"] = log->laser_frame;
  j["laser_mount"] = {log->laser_mount.x, log->laser_mount.y, log->laser_mount.theta};
  j["laser_upside_down"] = log->laser_upside_down;
  return j;
}

json describe_log(const std::filesystem::path& path, const BagLogOptions& options = {}) {
  if (const std::optional<BagFormat> format = detect_bag_format(path))
    return describe_bag(path, *format, options);
  return describe_carmen_log(path, options.laser);
}

json describe_pairs(const std::filesystem::path& path) {
  const ReferencePairs pairs = read_pairs_csv(path);
  Eigen::AlignedBox2d plan, grid;
  for (Eigen::Index i = 0; i < pairs.size(); ++i) {
    plan.extend(pairs.points_in_plan.col(i));
    grid.extend(pairs.points_in_grid.col(i));
  }
  return {{"count", pairs.size()},
          {"weighted", pairs.has_weights()},
          {"plan_bounds", box_json(plan)},
          {"grid_bounds", box_json(grid)}};
}

json describe_dataset(const std::filesystem::path& path) {
  const DatasetManifest m = read_manifest(path);
  json j = {{"manifest", m.manifest_path.string()}, {"name", m.name}};
  const bool plan_is_dxf = lower_extension(m.floorplan) == ".dxf";
  if (plan_is_dxf) {
    DxfReadOptions dxf_options;
    dxf_options.units = m.floorplan_units;
    dxf_options.include_layers = m.floorplan_layers;
    dxf_options.exclude_layers = m.floorplan_layers_exclude;
    j["floorplan"] = describe_dxf(m.floorplan, dxf_options);
    j["floorplan"]["kind"] = "dxf";
  } else {
    j["floorplan"] =
        grid_json(read_map(m.floorplan, m.floorplan_resolution, m.floorplan_origin, "floorplan"));
    j["floorplan"]["kind"] = "map";
  }
  j["floorplan"]["path"] = m.floorplan.string();
  j["floorplan_units"] = m.floorplan_units;
  j["floorplan_scale"] = m.floorplan_scale ? json(*m.floorplan_scale) : json("auto");
  j["gridmap"] = grid_json(read_map(m.gridmap, m.gridmap_resolution, m.gridmap_origin, "gridmap"));
  j["gridmap"]["path"] = m.gridmap.string();
  j["gridmap"]["kind"] = "map";
  if (m.log) {
    j["log"] = describe_log(*m.log, bag_log_options(m));
    j["log"]["kind"] = "log";
    j["log"]["path"] = m.log->string();
  }
  j["initial_pose"] =
      m.initial_pose
          ? json{{"plan",
                  {m.initial_pose->plan.x, m.initial_pose->plan.y, m.initial_pose->plan.theta}},
                 {"grid",
                  {m.initial_pose->grid.x, m.initial_pose->grid.y, m.initial_pose->grid.theta}}}
          : json("none: global localization");
  if (m.odometry_noise)
    j["odometry_noise"] = *m.odometry_noise;
  json truth = json::object();
  if (m.truth.manual_pairs) {
    truth["manual_pairs"] = describe_pairs(*m.truth.manual_pairs);
    truth["manual_pairs"]["path"] = m.truth.manual_pairs->string();
  }
  if (m.truth.warp)
    truth["warp"] = m.truth.warp->string();
  j["truth"] = truth;
  return j;
}

/// Whether a YAML file is a map (has `image`) or a dataset (has `floorplan` or `gridmap`).
FileKind yaml_kind(const std::filesystem::path& path) {
  const YAML::Node node = load_yaml_file(path);
  if (node.IsMap() && node["image"])
    return FileKind::map_yaml;
  if (node.IsMap() && (node["floorplan"] || node["gridmap"]))
    return FileKind::dataset;
  throw InputError(
      "a YAML file that is neither a map (no 'image' key) nor a dataset manifest "
      "(no 'floorplan' or 'gridmap' key)",
      path.string());
}

}  // namespace

std::string to_string(FileKind kind) {
  switch (kind) {
    case FileKind::map_yaml:
      return "map";
    case FileKind::image:
      return "image";
    case FileKind::dxf:
      return "dxf";
    case FileKind::log:
      return "log";
    case FileKind::pairs:
      return "pairs";
    case FileKind::dataset:
      return "dataset";
    case FileKind::json:
      return "json";
  }
  return "?";
}

FileKind detect_file_kind(const std::filesystem::path& path) {
  std::error_code ec;
  if (detect_bag_format(path))
    return FileKind::log;
  if (std::filesystem::is_directory(path, ec))
    return FileKind::dataset;
  if (!std::filesystem::exists(path, ec))
    throw InputError("no such file or folder", path.string());
  const std::string ext = lower_extension(path);
  if (ext == ".yaml" || ext == ".yml")
    return yaml_kind(path);
  if (ext == ".pgm" || ext == ".png")
    return FileKind::image;
  if (ext == ".dxf")
    return FileKind::dxf;
  if (ext == ".csv")
    return FileKind::pairs;
  if (ext == ".json")
    return FileKind::json;
  if (ext == ".gz" || ext == ".log" || ext == ".carmen" || ext == ".clf" || ext == ".txt") {
    return FileKind::log;
  }
  // Unknown name: look at the first bytes.
  std::ifstream in(path, std::ios::binary);
  std::string head(64, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.rfind("\x89PNG", 0) == 0 || head.rfind("P5", 0) == 0 || head.rfind("P2", 0) == 0) {
    return FileKind::image;
  }
  if (head.rfind("\x1f\x8b", 0) == 0 || head.rfind("# CARMEN", 0) == 0 ||
      head.rfind("PARAM", 0) == 0 || head.rfind("ODOM", 0) == 0 || head.rfind("FLASER", 0) == 0) {
    return FileKind::log;
  }
  if (head.rfind("plan_x", 0) == 0)
    return FileKind::pairs;
  if (head.find("SECTION") != std::string::npos || head.rfind("AutoCAD Binary DXF", 0) == 0) {
    return FileKind::dxf;
  }
  throw InputError(
      "cannot tell what this file is (expected a map YAML, PGM/PNG image, DXF, "
      "CARMEN log, pairs CSV or dataset)",
      path.string());
}

json describe(const std::filesystem::path& path, const DescribeOptions& options) {
  const FileKind kind = detect_file_kind(path);
  json j;
  switch (kind) {
    case FileKind::map_yaml:
      j = describe_map(path, options, false);
      break;
    case FileKind::image:
      j = describe_map(path, options, true);
      break;
    case FileKind::dxf:
      j = describe_dxf(path);
      break;
    case FileKind::log:
      j = describe_log(path);
      break;
    case FileKind::pairs:
      j = describe_pairs(path);
      break;
    case FileKind::dataset:
      j = describe_dataset(path);
      break;
    case FileKind::json:
      throw InputError("model and truth JSON files are not described yet", path.string());
  }
  j["path"] = path.string();
  j["kind"] = to_string(kind);
  return j;
}

}  // namespace floorgrid::io
