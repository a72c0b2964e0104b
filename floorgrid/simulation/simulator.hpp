#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/vector_floorplan.hpp"
#include "floorgrid/robot/robot_log.hpp"
#include "floorgrid/simulation/building.hpp"
#include "floorgrid/simulation/plan_truth.hpp"
#include "floorgrid/simulation/robot_tour.hpp"
#include "floorgrid/simulation/simulation_preset.hpp"

namespace floorgrid {

/// How a preset's run is made; the defaults drive the preset's tour once at its own rates.
struct SimulationOptions {
  /// Seconds the run lasts (SPEC `simulate --duration`): the tour is driven over and over,
  /// forth and back, until then, with a scan and an odometry reading every 1/scan_rate
  /// seconds. Unset: the tour once, a scan every preset scan_period.
  std::optional<double> duration;
  double scan_rate = 15.0;  ///< scans (and odometry readings) a second with a duration
  /// Seconds: the longest duration accepted (4 hours: about 216,000 scans, a log of 1.5 GB
  /// of text and a few GB of memory to make it).
  double max_duration = 4.0 * 3600.0;
};

/// Checks `options`; throws InputError naming the field ("duration", ...).
void validate(const SimulationOptions& options);

/// Figures of a simulated run, checked by the tests and printed by the CLI.
struct SimulationStatistics {
  std::size_t rooms = 0;              ///< rooms in the building
  std::size_t rooms_visited = 0;      ///< rooms the tour enters
  double path_length = 0.0;           ///< metres driven
  double duration = 0.0;              ///< seconds
  std::size_t scans = 0;              ///< laser scans
  std::size_t beams = 0;              ///< readings in all
  std::size_t returns = 0;            ///< readings that hit something
  std::size_t furniture_beams = 0;    ///< readings whose beam hit furniture or a door leaf
  double furniture_fraction = 0.0;    ///< furniture_beams / beams
  double max_bend_strain = 0.0;       ///< of the bend over the building
  double bend_deviation = 0.0;        ///< metres, far end from the near end's rigid transform
  double room_rotation_deg = 0.0;     ///< the rotated room's angle
  double min_room_jacobian = 0.0;     ///< smallest det J of the room rotation (> 0: no fold)
  double final_odometry_error = 0.0;  ///< metres, odometry drift at the end (after aligning start)
  std::size_t occupied_cells = 0;     ///< gridmap cells occupied
  std::size_t free_cells = 0;         ///< gridmap cells free
  std::size_t unknown_cells = 0;      ///< gridmap cells unknown
};

/// A whole synthetic dataset in memory: what `simulate` writes, plus the exact truth.
struct SimulatedDataset {
  SimulationPreset preset;  ///< the parameters used
  std::uint64_t seed = 0;   ///< the seed
  Building building;        ///< the metric world
  VectorFloorplan plan;     ///< the plan in plan metres (world x plan_scale), layers WALLS,
                            ///< DOORS, RACKS
  double plan_scale = 1.0;  ///< plan metres per world metre (the plan's unit error)
  double drawing_units_per_metre = 1.0;  ///< what the DXF's coordinates are, per plan metre
  OccupancyGrid gridmap;                 ///< the SLAM-like gridmap
  RobotLog log;                          ///< noisy odometry and scans, as written to the CARMEN log
  std::vector<TimedPose>
      true_trajectory;              ///< the robot's true poses (world), one per odometry tick
  Pose2 start_in_plan;              ///< the true start in the plan frame
  Pose2 start_in_grid;              ///< the true start in the grid frame
  ReferencePairs manual_pairs;      ///< emulated hand-picked pairs (plan metres, grid metres)
  WarpParams warp;                  ///< the exact distortion world -> grid
  SimulationStatistics statistics;  ///< figures of the run

  /// The exact plan -> grid mapping.
  PlanTruth truth() const { return PlanTruth(warp, plan_scale); }
};

/// Simulates the preset's building, run and maps for a seed. Deterministic: the same preset,
/// seed and options give the same dataset (without a duration, the same as before durations
/// existed). Throws InputError for an unknown preset or bad options.
SimulatedDataset simulate(const std::string& preset, std::uint64_t seed,
                          const SimulationOptions& options = {});

}  // namespace floorgrid
