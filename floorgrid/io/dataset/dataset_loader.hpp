#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/evaluation/model_evaluation.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/io/dataset/dataset_manifest.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/pipeline/plan_unit_fit.hpp"
#include "floorgrid/robot/robot_log.hpp"
#include "floorgrid/simulation/plan_truth.hpp"

namespace floorgrid::io {

/// How a dataset's plan becomes a grid the plan filter can localize in.
struct PlanRasterOptions {
  double resolution = 0.05;     ///< metres per cell of a rasterized DXF plan
  double wall_thickness = 0.0;  ///< metres: 0 draws each drawn line one cell wide
  double margin = 2.0;          ///< metres of free border around the plan
};

/// What loading a dataset may cost.
struct DatasetLimits {
  /// GiB the main job may allocate for the maps it derives (0: half of this machine's memory);
  /// maps that would need more are refused at load with the estimate and the limit.
  double memory_gb = 0.0;
  /// Maps of more cells than this are cropped to their known (free or occupied) cells plus
  /// crop_margin metres: a large canvas of unknown around a building costs nothing then.
  std::size_t crop_above_cells = 16'000'000;
  double crop_margin = 5.0;  ///< metres
};

/// Everything a dataset holds, read and prepared.
struct LoadedDataset {
  DatasetManifest manifest;             ///< the manifest read
  OccupancyGrid plan_grid;              ///< the plan as an occupancy grid (plan metres)
  std::optional<VectorFloorplan> plan;  ///< a DXF plan's geometry (layers filtered)
  std::optional<DxfReport> dxf_report;  ///< how the DXF was read
  /// The run's say on a DXF's units, when the drawing left several plausible: the gridmap
  /// registered on the plan under each.
  std::optional<PlanUnitDecision> unit_decision;
  Eigen::Matrix2Xd plan_wall_samples;          ///< plan wall points every ~5 cm (plan metres)
  OccupancyGrid gridmap;                       ///< the robot's map
  MapRaster gridmap_raster;                    ///< its image file, uncropped (for exports)
  std::optional<MapRaster> plan_raster;        ///< a raster plan's image file, uncropped
  std::optional<RobotLog> log;                 ///< the run, odometry noise added when asked
  std::optional<PlanTruth> truth_warp;         ///< a simulator's exact plan -> grid truth
  std::optional<ReferencePairs> manual_pairs;  ///< hand-picked truth pairs (metres)
  std::vector<std::string> warnings;           ///< from the readers
};

/// Reads a dataset (dataset.yaml or its folder): the plan (DXF rasterized, or a raster plan),
/// the gridmap, the log (with the manifest's laser settings, and odometry noise added when
/// `odometry_noise` is given), and the truth it references. Large maps are cropped to their
/// known area, and maps the main job could not localize in within `limits.memory_gb` are
/// refused. A DXF whose units the manifest leaves to `auto` and the drawing leaves ambiguous
/// gets the unit under which the gridmap fits it (see fit_plan_units, with `units`).
/// InputError on bad input.
LoadedDataset load_dataset(const std::filesystem::path& path, const PlanRasterOptions& raster = {},
                           const DatasetLimits& limits = {}, const PlanUnitFitOptions& units = {});

/// A DXF plan's units as metrics.json reports them (`floorplan_units`): the unit used, its
/// source and confidence, the reason, and each candidate with the drawing's probability and,
/// when the run decided, how the gridmap fitted under it. Null for a raster plan.
nlohmann::json floorplan_units_json(const LoadedDataset& dataset);

/// The dataset's exact warp as a GroundTruth (plan to grid; `dataset` must outlive it), or an
/// empty one without it.
GroundTruth warp_truth(const LoadedDataset& dataset);

/// The occupied cell centres of a grid (the "walls" of a raster plan), 2 x N, metres.
Eigen::Matrix2Xd occupied_cell_centres(const OccupancyGrid& grid);

}  // namespace floorgrid::io
