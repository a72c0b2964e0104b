#include "floorgrid/io/dataset/dataset_loader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/dataset/describe.hpp"
#include "floorgrid/io/dataset/robot_log_reader.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/files/system_memory.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/formats/truth_json.hpp"
#include "floorgrid/maps/crop.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/pipeline/memory_estimate.hpp"
#include "floorgrid/robot/odometry_noise.hpp"

namespace floorgrid::io {

Eigen::Matrix2Xd occupied_cell_centres(const OccupancyGrid& grid) {
  std::vector<Eigen::Vector2d> points;
  for (int iy = 0; iy < grid.height(); ++iy) {
    for (int ix = 0; ix < grid.width(); ++ix) {
      if (grid.state(ix, iy) == CellState::occupied)
        points.push_back(grid.geometry().cell_center(ix, iy));
    }
  }
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    out.col(static_cast<Eigen::Index>(i)) = points[i];
  return out;
}

namespace {

/// A map of more than limits.crop_above_cells cells cropped to its known area (a warning
/// says so); smaller maps are left as they are, so that their results do not move.
void crop_large_map(OccupancyGrid& grid, const std::string& what, const DatasetLimits& limits,
                    std::vector<std::string>& warnings) {
  if (grid.geometry().size() <= limits.crop_above_cells)
    return;
  const int margin = static_cast<int>(std::ceil(limits.crop_margin / grid.resolution()));
  const CellBox box = known_cells_box(grid, margin);
  if (box.cells() >= grid.geometry().size())
    return;
  warnings.push_back(fmt::format(
      "{}: cropped from {} x {} to {} x {} cells (its known area and "
      "{:g} m around it)",
      what, grid.width(), grid.height(), box.x1 - box.x0, box.y1 - box.y0, limits.crop_margin));
  grid = crop(grid, box);
}

// A map needs at least this many occupied cells, and this share of its known cells, to
// localize in.
constexpr std::size_t kMinOccupiedCells = 10;
constexpr double kMinOccupiedShare = 5e-4;

/// Refuses a map without a free cell: no filter could be placed on it.
void require_free_space(const OccupancyGrid& grid, const std::filesystem::path& file,
                        const std::string& field) {
  if (grid.counts().free == 0) {
    throw InputError(
        "the map has no free cell: nowhere to localize (check its thresholds, "
        "negate and mode)",
        file.string(), 0, field);
  }
}

/// Refuses a map in which the occupancy rule finds (almost) no occupied cell: no filter could
/// tell one place from another. Names the file, the darkest pixel's occupancy and the rule's
/// thresholds (a real SLAM map saved with thresholds above its walls' grey was blamed on its
/// resolution and origin before).
void require_walls(const LoadedMap& map, const std::string& field) {
  const CellCounts cells = map.grid.counts();
  const std::size_t known = cells.occupied + cells.free;
  if (cells.occupied >= kMinOccupiedCells &&
      double(cells.occupied) >= kMinOccupiedShare * double(known)) {
    return;
  }
  const MapMetadata& meta = map.metadata;
  std::string darkest;
  try {
    const GreyImage image = read_grey_image(map.image_path);
    double most = -1.0;
    for (std::size_t i = 0; i < image.level.size(); ++i) {
      if (!image.alpha.empty() && image.alpha[i] == 0)
        continue;
      const double brightness = double(image.level[i]) / double(image.max_level);
      most = std::max(most, meta.negate ? brightness : 1.0 - brightness);
    }
    if (most >= 0.0) {
      darkest = fmt::format("; its {} pixel has occupancy {:.3f}",
                            meta.negate ? "brightest" : "darkest", most);
    }
  } catch (const InputError&) {
    // The counts alone still say what is wrong.
  }
  throw InputError(
      fmt::format("the occupancy rule finds {} occupied cells of {} known ({} x {}){}, and "
                  "a cell is occupied above occupied_thresh {} (free below free_thresh {}, "
                  "mode {}, negate {}): check the thresholds, negate and mode, not the "
                  "resolution or origin",
                  cells.occupied, known, map.grid.width(), map.grid.height(), darkest,
                  meta.occupied_thresh, meta.free_thresh, to_string(meta.mode),
                  meta.negate ? 1 : 0),
      (map.yaml_path.empty() ? map.image_path : map.yaml_path).string(), 0, field);
}

/// Refuses maps the main job could not localize in within the memory limit.
void check_memory(const LoadedDataset& d, const DatasetLimits& limits) {
  const double limit = limits.memory_gb > 0.0 ? limits.memory_gb : default_memory_limit_gb();
  std::size_t readings = 0;
  if (d.log) {
    for (const LaserScan& scan : d.log->scans)
      readings += scan.ranges.size();
  }
  const double needed = static_cast<double>(alignment_memory_bytes(
                            d.plan_grid.geometry().size(), d.gridmap.geometry().size(), readings)) /
                        (1u << 30);
  if (needed > limit) {
    throw InputError(
        fmt::format("the plan ({} x {} cells) and the gridmap ({} x {} cells) would need about "
                    "{:.1f} GiB to localize in, more than the limit of {:.1f} GiB: crop the maps "
                    "to the building, or give a coarser resolution",
                    d.plan_grid.width(), d.plan_grid.height(), d.gridmap.width(),
                    d.gridmap.height(), needed, limit),
        d.manifest.manifest_path.string(), 0, "gridmap");
  }
}

/// How the job draws a DXF plan.
RasterizeOptions rasterize_options(const PlanRasterOptions& raster) {
  RasterizeOptions r;
  r.resolution = raster.resolution;
  r.wall_thickness = raster.wall_thickness;
  r.margin = raster.margin;
  return r;
}

/// Whether the run decides the DXF's unit: none was asked for, and the drawing left more than
/// one plausible.
bool units_left_to_the_run(const DatasetManifest& m, const DxfReport& report) {
  return m.floorplan_units == "auto" && report.units_source != "requested" &&
         report.units_confidence != "high" && report.unit_candidates.size() >= 2;
}

/// The run's decision on the drawing's unit; the plan converted and the report updated when it
/// overrules the drawing.
PlanUnitDecision decide_units(const OccupancyGrid& gridmap, DxfFloorplan& dxf,
                              const DatasetManifest& m, const RasterizeOptions& raster,
                              const PlanUnitFitOptions& options) {
  DxfReport& report = dxf.report;
  const PlanUnit drawn = plan_unit_from_name(report.units_used).value_or(PlanUnit::m);
  PlanUnitDecision decision = fit_plan_units(gridmap, dxf.plan, drawn, report.unit_candidates,
                                             m.floorplan_scale, raster, options);
  if (decision.overruled()) {
    dxf.plan = dxf.plan.scaled(metres_per_unit(decision.unit) / metres_per_unit(drawn));
    report.units_used = std::string(unit_name(decision.unit));
    report.metres_per_unit = metres_per_unit(decision.unit);
    report.units_source = "run";
    report.extent_m = dxf.plan.bounds();
  }
  if (decision.overruled() || decision.confirmed)
    report.units_confidence = "medium";
  report.units_reason += "; " + decision.reason;
  return decision;
}

/// The manifest's log (a bag or a CARMEN log, told by content), a bag's chunks bounded by the
/// memory limit. Warnings of the reading join `warnings`, prefixed with the file.
RobotLog read_run(const DatasetManifest& m, const DatasetLimits& limits,
                  std::vector<std::string>& warnings) {
  BagLogOptions options = bag_log_options(m);
  options.limits = bag_read_limits(limits.memory_gb);
  ReadRobotLog read = read_robot_log(*m.log, options);
  for (const std::string& warning : read.summary.warnings)
    warnings.push_back(m.log->string() + ": " + warning);
  return read;
}

}  // namespace

LoadedDataset load_dataset(const std::filesystem::path& path, const PlanRasterOptions& raster,
                           const DatasetLimits& limits, const PlanUnitFitOptions& units) {
  LoadedDataset d;
  d.manifest = read_manifest(path);
  const DatasetManifest& m = d.manifest;
  std::string ext = m.floorplan.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::optional<DxfFloorplan> dxf;
  if (ext == ".dxf") {
    DxfReadOptions options;
    options.units = m.floorplan_units;
    options.include_layers = m.floorplan_layers;
    options.exclude_layers = m.floorplan_layers_exclude;
    dxf = read_dxf(m.floorplan, options);
    d.warnings.insert(d.warnings.end(), dxf->report.warnings.begin(), dxf->report.warnings.end());
  } else {
    LoadedMap plan = read_map(m.floorplan, m.floorplan_resolution, m.floorplan_origin, "floorplan");
    require_walls(plan, "floorplan");
    d.warnings.insert(d.warnings.end(), plan.warnings.begin(), plan.warnings.end());
    d.plan_raster = MapRaster{plan.image_path, plan.grid.geometry()};
    d.plan_grid = std::move(plan.grid);
    d.plan_wall_samples = occupied_cell_centres(d.plan_grid);
  }
  LoadedMap grid = read_map(m.gridmap, m.gridmap_resolution, m.gridmap_origin, "gridmap");
  require_walls(grid, "gridmap");
  d.warnings.insert(d.warnings.end(), grid.warnings.begin(), grid.warnings.end());
  d.gridmap_raster = MapRaster{grid.image_path, grid.grid.geometry()};
  d.gridmap = std::move(grid.grid);
  crop_large_map(d.gridmap, "gridmap " + m.gridmap.string(), limits, d.warnings);
  if (dxf) {
    const RasterizeOptions r = rasterize_options(raster);
    if (units_left_to_the_run(m, dxf->report)) {
      d.unit_decision = decide_units(d.gridmap, *dxf, m, r, units);
      if (d.unit_decision->overruled())
        d.warnings.push_back(m.floorplan.string() + ": " + d.unit_decision->reason);
    }
    try {
      d.plan_grid = rasterize(dxf->plan, r);
    } catch (const InputError& e) {
      throw InputError(e.message(), m.floorplan.string(), 0, "floorplan");
    }
    d.plan_wall_samples = dxf->plan.sample_points(0.05);
    d.plan = std::move(dxf->plan);
    d.dxf_report = std::move(dxf->report);
  }
  if (!d.plan)
    crop_large_map(d.plan_grid, "floorplan " + m.floorplan.string(), limits, d.warnings);
  if (m.log) {
    RobotLog log = read_run(m, limits, d.warnings);
    if (m.odometry_noise) {
      const auto& a = *m.odometry_noise;
      const MotionNoise noise{.alpha1 = a[0], .alpha2 = a[1], .alpha3 = a[2], .alpha4 = a[3]};
      log = add_odometry_noise(log, noise, m.odometry_noise_seed);
    }
    d.log = std::move(log);
  }
  require_free_space(d.gridmap, m.gridmap, "gridmap");
  require_free_space(d.plan_grid, m.floorplan, "floorplan");
  check_memory(d, limits);
  if (m.truth.warp)
    d.truth_warp = read_plan_truth(*m.truth.warp);
  if (m.truth.manual_pairs)
    d.manual_pairs = read_pairs_csv(*m.truth.manual_pairs);
  return d;
}

nlohmann::json floorplan_units_json(const LoadedDataset& d) {
  if (!d.dxf_report)
    return nullptr;
  const DxfReport& r = *d.dxf_report;
  nlohmann::json candidates = nlohmann::json::array();
  for (const PlanUnitCandidate& c : r.unit_candidates) {
    nlohmann::json j = unit_candidate_json(c);
    if (d.unit_decision) {
      for (const PlanUnitFit& f : d.unit_decision->fits) {
        if (f.unit == c.unit && f.tried) {
          j["fit_score"] = f.score;
          j["fit_floorplan_scale"] = f.floorplan_scale;
        }
      }
    }
    candidates.push_back(std::move(j));
  }
  return {{"unit", r.units_used},
          {"metres_per_unit", r.metres_per_unit},
          {"header", r.header_units},
          {"source", r.units_source},
          {"confidence", r.units_confidence},
          {"decided_by_run", d.unit_decision.has_value()},
          {"reason", r.units_reason},
          {"candidates", std::move(candidates)}};
}

GroundTruth warp_truth(const LoadedDataset& dataset) {
  if (!dataset.truth_warp)
    return {};
  return [&warp = *dataset.truth_warp](const Eigen::Vector2d& p) { return warp.plan_to_grid(p); };
}

}  // namespace floorgrid::io
