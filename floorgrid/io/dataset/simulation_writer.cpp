#include "floorgrid/io/dataset/simulation_writer.hpp"

#include "floorgrid/core/error.hpp"
#include "floorgrid/evaluation/overlay.hpp"
#include "floorgrid/io/dataset/dataset_manifest.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/formats/truth_json.hpp"
#include "floorgrid/io/logs/carmen_writer.hpp"
#include "floorgrid/io/plans/dxf_writer.hpp"
#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/maps/plan_units.hpp"

namespace floorgrid::io {

SimulationFiles write_simulated_dataset(const SimulatedDataset& d,
                                        const std::filesystem::path& folder, bool preview) {
  prepare_output_folder(folder);
  SimulationFiles out{folder, {}};
  const auto add = [&](const std::filesystem::path& p) {
    out.files.push_back(p);
    return p;
  };

  DxfWriteOptions dxf;
  dxf.header_units = d.preset.header_units;
  dxf.units_per_metre = d.drawing_units_per_metre;
  write_dxf(d.plan, add(folder / "floorplan.dxf"), dxf);

  MapWriteOptions map;
  map.mode = MapMode::trinary;
  const auto image = write_map(d.gridmap, folder / "gridmap.yaml", map);
  add(folder / "gridmap.yaml");
  add(image);

  write_carmen(d.log, add(folder / "log.carmen"));
  write_pairs_csv(d.manual_pairs, add(folder / "manual_pairs.csv"));
  write_file_atomically(add(folder / "truth.json"), simulation_truth_json(d).dump(1) + "\n");

  DatasetManifest manifest;
  manifest.manifest_path = folder / "dataset.yaml";
  manifest.name = d.preset.name + " seed " + std::to_string(d.seed);
  manifest.floorplan = folder / "floorplan.dxf";
  manifest.floorplan_units = "auto";
  manifest.floorplan_scale.reset();  // auto: the true scale is only in truth.json
  manifest.floorplan_layers = {"WALLS", "RACKS"};
  manifest.gridmap = folder / "gridmap.yaml";
  manifest.log = folder / "log.carmen";
  manifest.initial_pose = InitialPoses{d.start_in_plan, d.start_in_grid};
  manifest.truth.warp = folder / "truth.json";
  manifest.truth.manual_pairs = folder / "manual_pairs.csv";
  write_manifest(manifest);
  add(manifest.manifest_path);

  if (preview) {
    RgbImage picture = grid_picture(d.gridmap);
    const PlanTruth truth = d.truth();
    Eigen::Matrix2Xd path(2, static_cast<Eigen::Index>(d.true_trajectory.size()));
    for (std::size_t i = 0; i < d.true_trajectory.size(); ++i) {
      path.col(static_cast<Eigen::Index>(i)) =
          truth.warp().world_to_grid(d.true_trajectory[i].pose.translation());
    }
    draw_points(picture, d.gridmap.geometry(), path, {40, 160, 40});
    draw_plan(picture, d.gridmap.geometry(), filter_layers(d.plan, {{"WALLS", "RACKS"}, {}}),
              [&](const Eigen::Vector2d& p) { return truth.plan_to_grid(p); }, {220, 30, 30});
    draw_points(picture, d.gridmap.geometry(), d.manual_pairs.points_in_grid, {30, 60, 230}, 2);
    write_png_rgb(add(folder / "preview.png"), picture.width, picture.height, picture.rgb);
  }
  return out;
}

SimulationFiles write_log_dataset(const LogDataset& d, const std::string& source,
                                  const std::filesystem::path& folder, bool preview) {
  prepare_output_folder(folder);
  SimulationFiles out{folder, {}};
  const auto add = [&](const std::filesystem::path& p) {
    out.files.push_back(p);
    return p;
  };
  DatasetManifest manifest;
  manifest.manifest_path = folder / "dataset.yaml";
  manifest.name = "from " + std::filesystem::path(source).filename().string() + " seed " +
                  std::to_string(d.options.seed);
  if (!d.plan_vector.empty()) {
    DxfWriteOptions dxf;
    dxf.header_units = d.options.header_units;
    dxf.units_per_metre = 1.0 / metres_per_unit(*plan_unit_from_name(d.options.drawing_units));
    write_dxf(d.plan_vector, add(folder / "floorplan.dxf"), dxf);
    manifest.floorplan = folder / "floorplan.dxf";
  } else {
    MapWriteOptions plan;
    plan.mode = MapMode::trinary;
    plan.image_format = "png";
    add(folder / "floorplan.yaml");
    add(write_map(d.plan_raster, folder / "floorplan.yaml", plan));
    manifest.floorplan = folder / "floorplan.yaml";
  }
  MapWriteOptions map;
  map.mode = MapMode::trinary;
  add(folder / "gridmap.yaml");
  add(write_map(d.gridmap, folder / "gridmap.yaml", map));
  write_carmen(d.log, add(folder / "log.carmen"));
  write_pairs_csv(d.manual_pairs, add(folder / "manual_pairs.csv"));
  write_file_atomically(add(folder / "truth.json"),
                        log_dataset_truth_json(d, source).dump(1) + "\n");

  manifest.floorplan_units = "auto";
  manifest.floorplan_scale.reset();  // auto: the true scale is only in truth.json
  manifest.gridmap = folder / "gridmap.yaml";
  manifest.log = folder / "log.carmen";
  const MotionNoise& a = d.options.odometry;
  manifest.odometry_noise = std::array<double, 4>{a.alpha1, a.alpha2, a.alpha3, a.alpha4};
  manifest.odometry_noise_seed = d.options.seed;
  manifest.truth.warp = folder / "truth.json";
  manifest.truth.manual_pairs = folder / "manual_pairs.csv";
  write_manifest(manifest);
  add(manifest.manifest_path);

  if (preview) {
    RgbImage picture = grid_picture(d.gridmap);
    const PlanTruth truth = d.truth();
    Eigen::Matrix2Xd path(2, static_cast<Eigen::Index>(d.log.scans.size()));
    for (std::size_t i = 0; i < d.log.scans.size(); ++i)
      path.col(static_cast<Eigen::Index>(i)) = d.log.scans[i].robot_pose.translation();
    draw_points(picture, d.gridmap.geometry(), path, {40, 160, 40});
    const GridGeometry& plan = d.plan_raster.geometry();
    std::vector<Eigen::Vector2d> walls;
    for (int iy = 0; iy < plan.height; ++iy) {
      for (int ix = 0; ix < plan.width; ++ix) {
        if (d.plan_raster.state(ix, iy) == CellState::occupied)
          walls.push_back(truth.plan_to_grid(plan.cell_center(ix, iy)));
      }
    }
    Eigen::Matrix2Xd wall_points(2, static_cast<Eigen::Index>(walls.size()));
    for (std::size_t i = 0; i < walls.size(); ++i)
      wall_points.col(static_cast<Eigen::Index>(i)) = walls[i];
    draw_points(picture, d.gridmap.geometry(), wall_points, {220, 30, 30});
    draw_points(picture, d.gridmap.geometry(), d.manual_pairs.points_in_grid, {30, 60, 230}, 2);
    write_png_rgb(add(folder / "preview.png"), picture.width, picture.height, picture.rgb);
  }
  return out;
}

}  // namespace floorgrid::io
