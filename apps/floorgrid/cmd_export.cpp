// `floorgrid export --model FILE --format F [--dataset DIR] [--pairs P.csv] --out FILE`: the
// model in another tool's terms (QGIS, GDAL, Open-RMF traffic-editor, nav2).
#include <fmt/format.h>

#include <cmath>
#include <filesystem>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "apps/floorgrid/dataset_run.hpp"
#include "apps/floorgrid/plan_layers_export.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/export/export_gdal_vrt.hpp"
#include "floorgrid/io/export/export_inputs.hpp"
#include "floorgrid/io/export/export_nav2_map.hpp"
#include "floorgrid/io/export/export_qgis_points.hpp"
#include "floorgrid/io/export/export_rmf.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/mapping/pair_preparation.hpp"

namespace floorgrid::app {

namespace {

namespace fs = std::filesystem;

constexpr const char* kHelp = R"(Formats (every output is written atomically):
  qgis-points  QGIS Georeferencer GCP file (.points) from the pairs: map = grid metres (robot
               map frame, '#CRS: ' left empty: a local frame QGIS leaves untransformed),
               source = the plan raster's pixels as QGIS counts them (x = column, y = -row,
               0 at the image's top-left corner) with --dataset and a raster plan, otherwise
               plan metres (a DXF plan, or no --dataset); dX,dY,residual = model(plan) - grid
               in metres (QGIS's "map units" residuals). Pairs: --pairs P.csv (in the model's
               pair units, as `fit --unit`), else pairs.csv beside the model file (an `align`
               output folder). More than --max-points pairs are binned in the plan (a robust
               mean per cell).
  gdal-vrt     GDAL VRT over the plan raster (--source plan: GCPs to grid metres through the
               model) or the gridmap image (--source gridmap: GCPs to plan metres through the
               inverse). gt, gt-rigid, gt-affine: 9 GCPs reproduce the model exactly with GDAL's
               first-order polynomial: gdalwarp -order 1 (gdaltransform -order 1). Other models:
               a --lattice x --lattice (33) lattice of GCPs for GDAL's thin-plate spline:
               gdalwarp -tps, which follows smooth models (tps, gp, gpgt) within about 1 cm and
               smooths the kinks of piecewise ones (ct, dt, lc: measured up to 6, 19 and 63 cm on
               a simulated bent office; a denser --lattice follows them closer). Pixel/line
               0,0 is the top-left corner of the top-left pixel. Needs --dataset; --source plan
               needs a raster plan.
  rmf          Open-RMF traffic-editor building YAML fragment: the gridmap image as a layer
               (layers: {robot_map: {filename, transform: {scale, translation_x, translation_y,
               yaw}, visible, color}}) on the plan's level. scale = level metres per gridmap
               pixel, translation = level metres of the image's top-left corner, y down, yaw in
               radians, as traffic-editor's Transform reads them; the level is the plan raster at
               its resolution (a DXF plan: its metres with y flipped). From the model's
               similarity: exact for gt and gt-rigid, else the least-squares similarity of the
               model over the pairs (or the plan's walls without pairs), whose rms residual is
               written as a comment and printed. Needs --dataset.
  nav2-map     The plan's walls drawn through the model (densely sampled, so non-rigid models
               bend them) into the gridmap's frame: --out YAML (mode: trinary, the gridmap's
               resolution and origin, negate: 0, occupied_thresh: 0.65, free_thresh: 0.25) and a
               PGM beside it of the gridmap's size; walls occupied (black), the rest free
               (--background free, for keepout masks) or unknown. Needs --dataset.)";

/// The pairs: --pairs, else pairs.csv beside the model file; empty when neither.
ReferencePairs find_pairs(const std::string& pairs_option, const fs::path& model_path, double unit,
                          std::string& from) {
  if (!pairs_option.empty()) {
    from = pairs_option;
    return io::read_pairs_csv(pairs_option, unit);
  }
  const fs::path beside = model_path.parent_path() / "pairs.csv";
  if (fs::exists(beside)) {
    from = beside.string();
    return io::read_pairs_csv(beside, unit);
  }
  return {};
}

void require_dataset(const std::string& dataset, const std::string& format,
                     const std::string& why) {
  if (dataset.empty()) {
    throw InputError(fmt::format("--format {} needs --dataset DIR: {}", format, why), {}, 0,
                     "--dataset");
  }
}

}  // namespace

void add_export_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "export",
      "Write a model in another tool's terms: QGIS GCPs, a GDAL VRT, an Open-RMF "
      "traffic-editor layer, or the plan's walls as a nav2 map; zones and waypoints drawn on "
      "the plan as nav2 keepout/speed masks, nav2 waypoints or GeoJSON on the gridmap");
  cmd->footer(std::string(kHelp) + kPlanLayersHelp);
  struct Args {
    std::string model, format, dataset, pairs, source = "plan", background = "free", out;
    std::size_t max_points = io::QgisPointsOptions{}.max_points;
    int lattice = io::GdalVrtOptions{}.lattice_points;
    PlanLayersExportArgs layers;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--model", args->model, "model file written by `fit` or `align`")->required();
  cmd->add_option("--format", args->format,
                  "qgis-points, gdal-vrt, rmf, nav2-map, nav2-keepout, nav2-speed, "
                  "nav2-waypoints or geojson")
      ->required()
      ->check(CLI::IsMember({"qgis-points", "gdal-vrt", "rmf", "nav2-map", "nav2-keepout",
                             "nav2-speed", "nav2-waypoints", "geojson"}));
  cmd->add_option("--zones", args->layers.zones,
                  "nav2-keepout, nav2-speed, geojson: zones on the plan (GeoJSON polygons in "
                  "plan metres, or a DXF with --layer)");
  cmd->add_option("--waypoints", args->layers.waypoints,
                  "nav2-waypoints, geojson: named poses on the plan (GeoJSON points or CSV "
                  "name,x,y,theta; plan metres, radians)");
  cmd->add_option("--layer", args->layers.layer,
                  "--zones DXF: the layer (glob) holding the zones' closed polylines or hatches");
  cmd->add_option("--margin-sigma", args->layers.margin_sigma,
                  "masks: widen each zone by K x the model's std_m along its boundary")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--speed-percent", args->layers.speed_percent,
                  "nav2-speed: the speed limit (% of the robot's maximal speed) of zones without "
                  "speed_percent or speed_mps")
      ->check(CLI::Range(1.0, 100.0));
  cmd->add_option("--dataset", args->dataset,
                  "dataset.yaml or its folder: the maps (needed by gdal-vrt, rmf, nav2-map)");
  cmd->add_option("--pairs", args->pairs,
                  "pairs CSV (qgis-points; rmf of non-similarity models); default: pairs.csv "
                  "beside the model file");
  cmd->add_option("--source", args->source, "gdal-vrt: the raster to wrap, plan or gridmap")
      ->check(CLI::IsMember({"plan", "gridmap"}))
      ->capture_default_str();
  cmd->add_option("--max-points", args->max_points,
                  "qgis-points: control points at most (pairs beyond are binned)")
      ->capture_default_str();
  cmd->add_option("--lattice", args->lattice,
                  "gdal-vrt, non-affine models: GCPs per side of the raster (more follow "
                  "piecewise models closer; GDAL's -tps solve grows with the cube of the count)")
      ->check(CLI::Range(3, 129))
      ->capture_default_str();
  cmd->add_option("--background", args->background, "nav2-map: what is not wall, free or unknown")
      ->check(CLI::IsMember({"free", "unknown"}))
      ->capture_default_str();
  cmd->add_option("--out", args->out,
                  "file to write (nav2-map, nav2-keepout, nav2-speed: the YAML; the image and "
                  "filter info go beside)")
      ->required();
  cmd->callback([args] {
    const fs::path model_path = args->model;
    refuse_overwriting_input(args->model, args->out, "--out");
    if (!args->pairs.empty())
      refuse_overwriting_input(args->pairs, args->out, "--out");
    const auto model = io::read_model(model_path);
    const std::string& format = args->format;
    if (format == "gdal-vrt")
      require_dataset(args->dataset, format, "the VRT wraps the plan raster or gridmap image");
    if (format == "rmf")
      require_dataset(args->dataset, format, "the layer is the gridmap image on the plan's level");
    if (format == "nav2-map")
      require_dataset(args->dataset, format,
                      "the map takes the gridmap's frame and the plan's walls");
    if (format == "nav2-keepout" || format == "nav2-speed")
      require_dataset(args->dataset, format,
                      "the mask takes the gridmap's size, resolution and origin");
    std::optional<io::LoadedDataset> dataset;
    io::ExportMaps maps;
    if (!args->dataset.empty()) {
      dataset = io::load_dataset(args->dataset);
      report_loading(*dataset);
      maps = io::export_maps(*dataset);
    }
    if (is_plan_layers_format(format)) {
      std::optional<GridGeometry> gridmap;
      if (maps.gridmap)
        gridmap = maps.gridmap->geometry;
      export_plan_layers(format, args->layers, *model, dataset, gridmap, fs::path(args->out));
      return;
    }
    std::string pairs_from;
    const ReferencePairs pairs = find_pairs(args->pairs, model_path, model->unit(), pairs_from);
    const std::optional<GridGeometry> plan_raster =
        maps.plan_raster ? std::optional<GridGeometry>(maps.plan_raster->geometry) : std::nullopt;
    const fs::path out = args->out;
    if (format == "qgis-points") {
      if (pairs.empty()) {
        throw InputError(fmt::format("qgis-points needs the pairs: give --pairs P.csv (no "
                                     "pairs.csv beside {})",
                                     model_path.string()),
                         {}, 0, "--pairs");
      }
      io::QgisPointsOptions options;
      options.max_points = args->max_points;
      const io::QgisPoints points = io::qgis_points(*model, pairs, plan_raster, options);
      io::write_file_atomically(out, points.text);
      fmt::print(
          "wrote {} control points ({} pairs from {}) to {}: source in {}, residual rms "
          "{:.4f} m\n",
          points.points, points.pairs, pairs_from, out.string(),
          points.source_in_pixels ? "plan raster pixels (y negative downwards)"
                                  : "plan metres (no plan raster)",
          points.rms_m);
      return;
    }
    if (format == "gdal-vrt") {
      const bool from_plan = args->source == "plan";
      if (from_plan && !maps.plan_raster) {
        throw InputError(fmt::format("--source plan needs a raster plan, and {} is DXF: use "
                                     "--source gridmap (the gridmap into plan metres)",
                                     dataset->manifest.floorplan.string()),
                         {}, 0, "--source");
      }
      const io::MapRaster& raster = from_plan ? *maps.plan_raster : *maps.gridmap;
      io::GdalVrtOptions options;
      options.lattice_points = args->lattice;
      const io::GdalVrt vrt = io::gdal_vrt(
          *model, raster, from_plan ? io::VrtSource::plan : io::VrtSource::gridmap, out, options);
      io::write_file_atomically(out, vrt.text);
      fmt::print(
          "wrote {} with {} GCPs ({} image -> {} metres){}; reproduce with GDAL's {}: "
          "gdalwarp {} {} OUT.tif\n",
          out.string(), vrt.gcps.size(), from_plan ? "plan" : "gridmap",
          from_plan ? "grid" : "plan",
          vrt.not_invertible ? fmt::format(", {} lattice points not invertible", vrt.not_invertible)
                             : "",
          vrt.exact ? "first-order polynomial (exact)" : "thin-plate spline", vrt.transformer,
          out.string());
      return;
    }
    if (format == "rmf") {
      Eigen::Matrix2Xd points = dataset->plan_wall_samples;
      std::string points_from = "the plan's walls";
      if (!pairs.empty()) {
        ReductionOptions reduction;
        reduction.budget = 2000;
        points = reduce_pairs(pairs, reduction).points_in_plan;
        points_from = "the pairs of " + pairs_from;
      }
      std::error_code error;
      fs::path filename =
          fs::relative(fs::absolute(maps.gridmap->image), fs::absolute(out).parent_path(), error);
      if (error || filename.empty())
        filename = fs::absolute(maps.gridmap->image);
      const io::RmfLayer layer =
          io::rmf_layer(*model, points, *maps.gridmap, plan_raster, filename.generic_string());
      io::write_file_atomically(out, layer.text);
      const io::RmfLayerTransform& t = layer.transform;
      fmt::print(
          "wrote {}: scale {:.6g} m/pixel, translation ({:.4f}, {:.4f}) m, yaw {:.6f} "
          "rad\n  similarity: {}{}\n  level frame: {}\n",
          out.string(), t.scale, t.translation_x, t.translation_y, t.yaw, layer.similarity.source,
          layer.similarity.exact ? "" : " (over " + points_from + ")", layer.level_frame);
      return;
    }
    // nav2-map
    io::Nav2MapOptions options;
    options.background = args->background == "free" ? CellState::free : CellState::unknown;
    const GridGeometry& geometry = maps.gridmap->geometry;
    const OccupancyGrid walls =
        maps.plan_vector ? io::plan_walls_in_grid(*model, *maps.plan_vector, geometry, options)
                         : io::plan_walls_in_grid(*model, *maps.plan_grid, geometry, options);
    const fs::path image = io::write_nav2_map(walls, out);
    fmt::print("wrote {} and {}: {} x {} cells at {} m, {} wall cells, the rest {}\n", out.string(),
               image.string(), geometry.width, geometry.height, geometry.resolution,
               walls.counts().occupied, args->background);
  });
}

}  // namespace floorgrid::app
