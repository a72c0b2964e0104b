#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/robot/motion_model.hpp"
#include "floorgrid/robot/robot_log.hpp"
#include "floorgrid/simulation/plan_truth.hpp"

namespace floorgrid {

/// How a semi-real dataset is made from a corrected log (`simulate --from-log`). Unset
/// choices are drawn from the seed.
struct LogDatasetOptions {
  std::uint64_t seed = 1;  ///< the same log and seed give the same dataset
  /// The plan's scale as the dataset's `floorplan_scale` would say it: world metres per plan
  /// metre (a laser range divided by it is in plan metres). Unset: log-uniform in [0.5, 2].
  std::optional<double> plan_scale;
  /// Metres the far end of the building's long axis bends sideways. Unset: uniform in [0.2, 1].
  std::optional<double> bend;
  /// Degrees the plan is turned against the gridmap. Unset: uniform in [-180, 180).
  std::optional<double> rotation_deg;
  /// Pixels of a drawn wall stroke behind its surface. Unset: 2, 3 or 4.
  std::optional<int> wall_thickness_px;
  double resolution = 0.05;      ///< metres per gridmap cell and per true plan pixel, > 0
  double mapping_range = 30.0;   ///< metres: longer readings are mapped as free space only
  double min_wall_extent = 1.0;  ///< metres: occupied blobs smaller than this are not drawn
  double margin = 1.0;           ///< metres of white paper around the drawing
  /// Also draw the plan as vector walls (`plan_vector`): the outlines of the wall strokes,
  /// traced on a raster 4x finer and simplified to 0.02 m.
  bool vector_plan = false;
  /// The unit the vector plan's DXF coordinates are in (m, cm, mm, in or ft).
  std::string drawing_units = "m";
  /// What the DXF's `$INSUNITS` says: a unit name, or "none" for no header (a file whose units
  /// a reader must guess, or that lies).
  std::string header_units = "m";
  MotionNoise odometry;  ///< the odometry noise the manifest asks for (SPEC's levels)
};

/// Figures of a semi-real dataset, printed by the CLI and written to truth.json.
struct LogDatasetStatistics {
  std::size_t scans = 0;           ///< laser scans in the log
  double path_length = 0.0;        ///< metres between consecutive scans, summed
  double median_step = 0.0;        ///< metres between consecutive scans, median
  double median_turn_deg = 0.0;    ///< degrees between consecutive scans, median
  std::size_t occupied_cells = 0;  ///< gridmap
  std::size_t free_cells = 0;      ///< gridmap
  std::size_t wall_cells = 0;      ///< occupied cells drawn in the plan
  std::size_t clutter_cells = 0;   ///< occupied cells left out of the plan as clutter
  double bend_deviation = 0.0;     ///< metres, signed
  double max_bend_strain = 0.0;    ///< of the bend over the drawn walls
  /// The scale of the least-squares similarity from the world to the gridmap over the drawn
  /// walls: 1 without a bend; with one, the scale a global fit of the plan can find, so the
  /// plan scale it can find is plan_scale times this.
  double warp_fit_scale = 1.0;
  double rotation_deg = 0.0;      ///< the plan's turn against the gridmap
  int wall_thickness_px = 0;      ///< of the drawn strokes
  std::size_t plan_segments = 0;  ///< vector walls, when drawn
};

/// A semi-real dataset: the real run and its real map, a plan drawn from that map through a
/// known warp, and the exact truth.
///
/// Frames: the gridmap frame is the corrected log's frame. The plan's "world" is the building
/// as the drawing has it in metres: the gridmap is the world through `warp` (a bend of the
/// long axis and a rigid transform), and the plan is the world times `plan_per_world`.
struct LogDataset {
  RobotLog log;                 ///< the corrected log as read (its poses are the truth)
  OccupancyGrid gridmap;        ///< occupancy mapping along the corrected poses, grid frame
  OccupancyGrid plan_raster;    ///< walls occupied, the rest free; plan metres per pixel
  VectorFloorplan plan_vector;  ///< layer WALLS, plan metres (empty unless asked for)
  WarpParams warp;              ///< world -> grid
  double plan_per_world = 1.0;  ///< plan metres per world metre (1 / plan_scale)
  ReferencePairs manual_pairs;  ///< emulated hand-picked pairs at drawn corners
  Pose2 start_in_grid;          ///< the first scan's robot pose
  Pose2 start_in_plan;          ///< the same pose in the plan
  LogDatasetOptions options;    ///< with every choice made
  LogDatasetStatistics statistics;

  /// The exact plan -> grid mapping.
  PlanTruth truth() const { return PlanTruth(warp, plan_per_world); }
};

/// Checks `options`; InputError naming the field (`plan_scale`, `bend`, ...) otherwise.
void validate_log_dataset_options(const LogDatasetOptions& options);

/// Makes a semi-real dataset from a corrected log: the gridmap by occupancy mapping along the
/// log's poses (real laser, real clutter, real people); the plan from that map's occupied cells
/// (blobs under `min_wall_extent` left out, strokes thickened behind the wall surface into
/// space the laser never saw free) drawn through a known bend, rotation and scale error, as a
/// raster with free space white. Deterministic for a log and options. InputError when the log
/// maps no wall or the options are bad.
LogDataset simulate_from_log(const RobotLog& log, const LogDatasetOptions& options);

}  // namespace floorgrid
