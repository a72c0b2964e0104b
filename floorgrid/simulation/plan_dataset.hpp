#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/robot/robot_log.hpp"
#include "floorgrid/simulation/plan_truth.hpp"
#include "floorgrid/simulation/plan_world.hpp"
#include "floorgrid/simulation/robot_tour.hpp"
#include "floorgrid/simulation/simulation_preset.hpp"
#include "floorgrid/simulation/tour_planner.hpp"

namespace floorgrid {

/// A drawing to build a world from: a raster (its cells as read, occupied = ink, at its stated
/// resolution, which the world keeps: the dataset's plan is the raster with its resolution and
/// origin divided by the plan scale) or vector walls in the drawing's metres (the plan itself:
/// the world is their copy scaled by the plan scale).
struct PlanDrawing {
  std::optional<OccupancyGrid> raster;  ///< a raster drawing; when absent, `vector` is used
  VectorFloorplan vector;               ///< vector walls (a DXF's chosen layers)
};

/// How a dataset is made from a real drawing (`simulate --from-plan`). Unset choices are drawn
/// from the seed.
struct PlanDatasetOptions {
  std::uint64_t seed = 1;  ///< the same drawing and seed give the same dataset
  /// World metres per plan metre (what the dataset's `floorplan_scale` would say). Unset:
  /// log-uniform in [min_plan_scale, max_plan_scale]; for a vector drawing the lower end is
  /// raised so that its median doorway is at least `min_doorway` wide in the world.
  std::optional<double> plan_scale;
  double min_plan_scale = 0.5;  ///< of the default range
  double max_plan_scale = 2.0;  ///< of the default range
  double min_doorway = 0.8;     ///< metres, see plan_scale
  /// Metres the far end of the building's long axis bends sideways. Unset: uniform in
  /// `bend_range`.
  std::optional<double> bend;
  UniformRange bend_range{0.2, 1.0};  ///< metres, of the default bend
  /// Degrees the gridmap is turned against the world. Unset: uniform in [-180, 180).
  std::optional<double> rotation_deg;
  bool drawing_errors = false;  ///< the world differs from the drawing in a few places
  /// The laser, odometry, speeds, scan rate, gridmap resolution, room rotation and manual pairs:
  /// the presets' values (SPEC "Synthetic datasets"); name and building are not used.
  SimulationPreset run;
  PlanWorldOptions world;  ///< how the world is built from the drawing
  TourPlanOptions tour;    ///< where the robot drives
};

/// Figures of a dataset made from a drawing, printed by the CLI and written to truth.json.
struct PlanDatasetStatistics {
  double plan_scale = 1.0;            ///< world metres per plan metre, as used
  double plan_scale_low = 0.5;        ///< the default range's lower end, as used
  double raster_resolution = 0.0;     ///< metres per pixel of the world's raster
  double path_length = 0.0;           ///< metres driven
  double duration = 0.0;              ///< seconds
  std::size_t scans = 0;              ///< laser scans in the log
  std::size_t beams = 0;              ///< readings in all
  std::size_t returns = 0;            ///< readings in (0, max_range)
  std::size_t wall_beams = 0;         ///< beams that truly met a wall
  std::size_t furniture_beams = 0;    ///< beams that met furniture or clutter
  std::size_t door_beams = 0;         ///< beams that met a door leaf
  std::size_t column_beams = 0;       ///< beams that met a column or a glass wall's mullion
  double clutter_fraction = 0.0;      ///< (furniture + door) beams / beams, as the presets count
  double final_odometry_error = 0.0;  ///< metres, odometry drift at the end
  double bend_deviation = 0.0;        ///< metres, signed
  double max_bend_strain = 0.0;       ///< of the bend over the walls
  double rotation_deg = 0.0;          ///< the gridmap's turn against the world
  double room_rotation_deg = 0.0;     ///< the turned room's angle (0: none)
  double min_room_jacobian = 0.0;     ///< smallest det J of the room rotation (> 0: no fold)
  /// The scale of the least-squares similarity from the world to the gridmap over the drawn
  /// walls: 1 without a bend; the plan scale a global fit can find is plan_scale times this.
  double warp_fit_scale = 1.0;
  std::size_t occupied_cells = 0;  ///< gridmap
  std::size_t free_cells = 0;      ///< gridmap
  std::size_t unknown_cells = 0;   ///< gridmap
};

/// A dataset made from a real drawing: the world built from it, a robot's run through that
/// world, a SLAM-like gridmap of the run through a known warp, and the exact truth.
///
/// Frames: the world is the plan times plan_scale (world metres per plan metre), so PlanTruth's
/// plan_per_world is 1 / plan_scale; the gridmap is the world through `warp`.
struct PlanDataset {
  PlanDatasetOptions options;              ///< with every choice made
  PlanWorld world;                         ///< the building the laser sees and the robot drives
  TourPlan tour;                           ///< the waypoints and the rooms they visit
  std::vector<TimedPose> true_trajectory;  ///< the robot's true poses (world), per tick
  RobotLog log;                      ///< noisy odometry and scans, as written to the CARMEN log
  OccupancyGrid gridmap;             ///< the SLAM-like gridmap, grid frame
  WarpParams warp;                   ///< world -> grid
  ReferencePairs manual_pairs;       ///< emulated hand-picked pairs at drawn corners
  Pose2 start_in_plan;               ///< the true start (not in the manifest)
  Pose2 start_in_grid;               ///< the true start (not in the manifest)
  PlanDatasetStatistics statistics;  ///< figures of the run

  /// The exact plan -> grid mapping.
  PlanTruth truth() const { return PlanTruth(warp, 1.0 / statistics.plan_scale); }
};

/// Checks `options`; InputError naming the field (`plan_scale`, `bend`, `rotation`, ...).
void validate_plan_dataset_options(const PlanDatasetOptions& options);

/// Makes a dataset from a drawing: builds the world (plan_world.hpp), plans a tour through it,
/// drives it with the presets' laser and odometry, maps it through a rigid turn, a bend and one
/// room turned by a degree or two, and emulates manual pairs at the drawing's corners.
/// Deterministic for a drawing and options. InputError when the drawing has no walls, no
/// interior a robot can reach, or the options are bad.
PlanDataset simulate_from_plan(const PlanDrawing& drawing, const PlanDatasetOptions& options);

}  // namespace floorgrid
