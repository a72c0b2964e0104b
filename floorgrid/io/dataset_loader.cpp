#include "floorgrid/io/dataset_loader.hpp"

#include <algorithm>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/carmen_log.hpp"
#include "floorgrid/io/map_io.hpp"
#include "floorgrid/io/pairs_csv.hpp"
#include "floorgrid/io/truth_json.hpp"
#include "floorgrid/maps/rasterize.hpp"
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

LoadedDataset load_dataset(const std::filesystem::path& path, const PlanRasterOptions& raster) {
  LoadedDataset d;
  d.manifest = read_manifest(path);
  const DatasetManifest& m = d.manifest;
  std::string ext = m.floorplan.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".dxf") {
    DxfReadOptions options;
    options.units = m.floorplan_units;
    options.include_layers = m.floorplan_layers;
    options.exclude_layers = m.floorplan_layers_exclude;
    DxfFloorplan dxf = read_dxf(m.floorplan, options);
    d.warnings.insert(d.warnings.end(), dxf.report.warnings.begin(), dxf.report.warnings.end());
    RasterizeOptions r;
    r.resolution = raster.resolution;
    r.wall_thickness = raster.wall_thickness;
    r.margin = raster.margin;
    d.plan_grid = rasterize(dxf.plan, r);
    d.plan_wall_samples = dxf.plan.sample_points(0.05);
    d.plan = std::move(dxf.plan);
    d.dxf_report = std::move(dxf.report);
  } else {
    LoadedMap plan = read_map(m.floorplan, m.floorplan_resolution, m.floorplan_origin, "floorplan");
    d.warnings.insert(d.warnings.end(), plan.warnings.begin(), plan.warnings.end());
    d.plan_grid = std::move(plan.grid);
    d.plan_wall_samples = occupied_cell_centres(d.plan_grid);
  }
  LoadedMap grid = read_map(m.gridmap, m.gridmap_resolution, m.gridmap_origin, "gridmap");
  d.warnings.insert(d.warnings.end(), grid.warnings.begin(), grid.warnings.end());
  d.gridmap = std::move(grid.grid);
  if (m.log) {
    CarmenReadOptions options;
    options.laser = m.laser;
    RobotLog log = read_carmen(*m.log, options);
    if (m.odometry_noise) {
      const auto& a = *m.odometry_noise;
      log = add_odometry_noise(log, MotionNoise{a[0], a[1], a[2], a[3]}, m.odometry_noise_seed);
    }
    d.log = std::move(log);
  }
  if (m.truth.warp)
    d.truth_warp = read_plan_truth(*m.truth.warp);
  if (m.truth.manual_pairs)
    d.manual_pairs = read_pairs_csv(*m.truth.manual_pairs);
  return d;
}

}  // namespace floorgrid::io
