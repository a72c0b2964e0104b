#include "apps/floorgrid/plan_layers_export.hpp"

#include <fmt/format.h>

#include "apps/floorgrid/cli_util.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/evaluation/waypoint_mapping.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/formats/nav2_filter_mask.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "floorgrid/io/plans/plan_layers_io.hpp"

namespace floorgrid::app {

namespace fs = std::filesystem;

const char* const kPlanLayersHelp = R"(

Plan layers (zones and waypoints drawn on the plan, carried to the robot's map):
  nav2-keepout  --zones FILE: a nav2 KeepoutFilter mask on the gridmap's grid (same size,
               resolution and origin): --out MASK.yaml (mode trinary, occupied_thresh 0.65,
               free_thresh 0.196, as nav2's keepout tutorial), MASK.pgm beside it (zones black =
               OccupancyGrid 100, the rest 254 = 0) and MASK_filter_info.yaml (ROS 2 params of
               costmap_filter_info_server: type 0, base 0, multiplier 1; and filter_mask_server).
               Each zone edge is sampled densely (4 per cell) and mapped through the model, so a
               bent model bends it; cells are in when their centre is (even-odd rule, holes
               allowed); the zone is widened by --margin-sigma K x the model's std_m at each
               boundary point (default 2: about 95% per point). Zones partly off the gridmap are
               clipped (a warning); a zone wholly off it is refused. Needs --dataset.
  nav2-speed   --zones FILE: a nav2 SpeedFilter mask: mode scale, free_thresh 0.0,
               occupied_thresh 1.0 (the speed tutorial's "no thresholds"), 0 = no limit outside
               the zones; zone properties speed_percent (filter type 1: base 0, multiplier 1,
               mask value = percent) or speed_mps (type 2: base 0, multiplier max(0.01,
               fastest/100), value = speed / multiplier); --speed-percent P for zones without
               their own. Where zones overlap the slowest wins. Widened as nav2-keepout.
  nav2-waypoints --waypoints FILE: poses: a YAML list of geometry_msgs/PoseStamped in the map
               frame, the goal of nav2's FollowWaypoints action; heading through the model's
               Jacobian; a comment per pose with its name, std_m and flag. Extrapolated
               waypoints are kept and flagged, never dropped.
  geojson      --zones and/or --waypoints: the same features in gridmap metres (zones as their
               mapped boundary), each with std_m, extrapolated and flag in its properties.
  Zones: GeoJSON Polygon/MultiPolygon features in plan metres (property name; closed, simple
  rings), or a DXF (--layer GLOB: closed LWPOLYLINE/POLYLINE and HATCH boundaries, in the
  dataset's plan units). Waypoints: GeoJSON Point features (name; theta in radians or
  heading_deg) or CSV name,x,y[,theta]. A GeoJSON in WGS84 degrees is refused: plan metres only.)";

bool is_plan_layers_format(const std::string& format) {
  return format == "nav2-keepout" || format == "nav2-speed" || format == "nav2-waypoints" ||
         format == "geojson";
}

namespace {

/// Metres per drawing unit of a zones DXF: the dataset's plan's when the dataset's plan is DXF,
/// else the unit the zones file's own drawing suggests.
double dxf_metres_per_unit(const fs::path& zones, const std::optional<io::LoadedDataset>& dataset) {
  if (dataset && dataset->dxf_report)
    return dataset->dxf_report->metres_per_unit;
  return io::read_dxf(zones).report.metres_per_unit;
}

PlanLayers read_layers(const std::string& path, const std::string& layer,
                       const std::optional<io::LoadedDataset>& dataset) {
  io::PlanLayersReadOptions options;
  options.layer = layer;
  if (fs::path(path).extension() == ".dxf" || fs::path(path).extension() == ".DXF")
    options.metres_per_unit = dxf_metres_per_unit(path, dataset);
  PlanLayers layers = io::read_plan_layers(path, options);
  for (const std::string& w : layers.warnings)
    fmt::print(stderr, "warning: {}\n", w);
  return layers;
}

void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings)
    fmt::print(stderr, "warning: {}\n", w);
}

}  // namespace

void export_plan_layers(const std::string& format, const PlanLayersExportArgs& args,
                        const PointMapping& model, const std::optional<io::LoadedDataset>& dataset,
                        const std::optional<GridGeometry>& gridmap, const fs::path& out) {
  const bool masks = format == "nav2-keepout" || format == "nav2-speed";
  if (masks && args.zones.empty())
    throw InputError("--format " + format + " needs --zones FILE", {}, 0, "--zones");
  if (format == "nav2-waypoints" && args.waypoints.empty())
    throw InputError("--format nav2-waypoints needs --waypoints FILE", {}, 0, "--waypoints");
  if (format == "geojson" && args.zones.empty() && args.waypoints.empty())
    throw InputError("--format geojson needs --zones FILE or --waypoints FILE", {}, 0, "--zones");
  if (masks && !gridmap) {
    throw InputError("--format " + format +
                         " needs --dataset DIR: the mask takes the gridmap's size, resolution "
                         "and origin",
                     {}, 0, "--dataset");
  }
  for (const std::string& input : {args.zones, args.waypoints}) {
    if (!input.empty())
      refuse_overwriting_input(input, out.string(), "--out");
  }
  std::vector<Zone> zones;
  std::vector<Waypoint> waypoints;
  if (!args.zones.empty()) {
    PlanLayers layers = read_layers(args.zones, args.layer, dataset);
    zones = std::move(layers.zones);
    if (args.waypoints.empty() && format != "nav2-keepout" && format != "nav2-speed")
      waypoints = std::move(layers.waypoints);
    if (zones.empty() && (masks || args.waypoints.empty()))
      throw InputError("holds no zone (Polygon or MultiPolygon feature)", args.zones, 0, "--zones");
  }
  if (!args.waypoints.empty()) {
    PlanLayers layers = read_layers(args.waypoints, args.layer, dataset);
    waypoints = std::move(layers.waypoints);
    if (waypoints.empty())
      throw InputError("holds no waypoint (Point feature or CSV row)", args.waypoints, 0,
                       "--waypoints");
  }
  ZoneMaskOptions options;
  options.margin_sigma = args.margin_sigma;
  if (masks) {
    const ZoneMaskKind kind =
        format == "nav2-keepout" ? ZoneMaskKind::keepout : ZoneMaskKind::speed;
    if (kind == ZoneMaskKind::speed && args.speed_percent) {
      for (Zone& z : zones) {
        if (!z.speed.percent && !z.speed.metres_per_second)
          z.speed.percent = *args.speed_percent;
      }
    }
    const ZoneMask mask = map_zones_to_mask(model, zones, *gridmap, kind, options, args.zones);
    print_warnings(mask.warnings);
    const std::string stem = out.stem().string();
    const io::Nav2MaskFiles files = io::nav2_mask_files(mask, stem);
    fs::path folder = out.parent_path();
    if (folder.empty())
      folder = ".";
    for (const std::string& name : {files.image_name, files.params_name}) {
      for (const std::string& input : {args.zones, args.waypoints}) {
        if (!input.empty())
          refuse_overwriting_input(input, (folder / name).string(), "--out");
      }
    }
    if (out.extension() != ".yaml")
      throw InputError("--out must name the mask's YAML (NAME.yaml)", {}, 0, "--out");
    io::write_nav2_mask_files(files, folder);
    fmt::print(
        "wrote {} ({} x {} cells at {} m), {} and {}: filter type {}, base {}, "
        "multiplier {}\n",
        out.string(), gridmap->width, gridmap->height, gridmap->resolution,
        (folder / files.image_name).string(), (folder / files.params_name).string(),
        mask.filter.type, mask.filter.base, mask.filter.multiplier);
    for (const MappedZone& z : mask.zones) {
      fmt::print(
          "  {} '{}': value {}, {} cells ({} inside its mapped boundary), std_m {}, "
          "margin {:.3f} m{}{}\n",
          z.index, z.name, z.mask_value ? static_cast<int>(*z.mask_value) : 0, z.cells,
          z.cells_inside,
          z.has_std ? fmt::format("{:.3f}-{:.3f}", z.mean_std_m, z.max_std_m) : "none",
          options.margin_sigma * z.max_std_m, z.clipped ? ", clipped" : "",
          z.extrapolated_points ? ", EXTRAPOLATED in part" : "");
    }
    if (gridmap->origin.theta != 0.0) {
      fmt::print(stderr,
                 "warning: the gridmap's origin has a yaw ({} rad): nav2's costmaps ignore it, "
                 "as they do for the map itself\n",
                 gridmap->origin.theta);
    }
    return;
  }
  const std::vector<MappedWaypoint> mapped = map_waypoints(
      model, waypoints, gridmap, args.waypoints.empty() ? args.zones : args.waypoints);
  std::size_t extrapolated = 0;
  for (const MappedWaypoint& m : mapped)
    extrapolated += m.extrapolated;
  if (format == "nav2-waypoints") {
    io::write_file_atomically(out, io::nav2_waypoints_yaml(mapped));
    fmt::print("wrote {}: {} waypoints, {} extrapolated (kept, flagged)\n", out.string(),
               mapped.size(), extrapolated);
    return;
  }
  std::vector<MappedZone> mapped_zones;
  if (!zones.empty()) {
    const double spacing = gridmap
                               ? zone_sample_spacing(model, *gridmap, options)
                               : zone_sample_spacing(model, GridGeometry{0, 0, 0.05, {}}, options);
    for (const Zone& z : zones)
      mapped_zones.push_back(map_zone(model, z, spacing));
  }
  io::write_file_atomically(
      out, io::mapped_layers_geojson(mapped_zones, mapped, "gridmap", options.margin_sigma));
  fmt::print(
      "wrote {}: {} zones, {} waypoints ({} extrapolated, kept and flagged) in gridmap "
      "metres\n",
      out.string(), mapped_zones.size(), mapped.size(), extrapolated);
}

}  // namespace floorgrid::app
