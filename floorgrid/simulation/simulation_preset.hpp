#pragma once

#include <numbers>
#include <string>
#include <vector>

#include "floorgrid/robot/motion_model.hpp"
#include "floorgrid/simulation/robot_tour.hpp"

namespace floorgrid {

/// Everything fixed per synthetic-dataset preset (SPEC "Synthetic datasets"); written into
/// truth.json so a dataset says how it was made.
struct SimulationPreset {
  std::string name;                  ///< office, warehouse, bent-office, office-inches
  std::string building = "office";   ///< building generator: office or warehouse
  double gridmap_resolution = 0.05;  ///< metres per cell
  // The laser.
  int beams = 361;                          ///< readings per scan over the field of view
  double field_of_view = std::numbers::pi;  ///< radians (180 degrees)
  double max_range = 30.0;                  ///< metres
  double range_noise_sigma = 0.02;          ///< metres
  double random_reading_fraction = 0.01;    ///< share of readings that are random
  double laser_forward_offset = 0.15;       ///< metres, laser ahead of the robot's centre
  double scan_period = 0.2;                 ///< seconds between scans
  // The odometry (alpha1..alpha4).
  MotionNoise odometry{.alpha1 = 0.05, .alpha2 = 0.01, .alpha3 = 0.02, .alpha4 = 0.05};
  // The gridmap's distortion.
  double bend_deviation = 0.2;         ///< metres: far end off the near end's rigid transform
  double max_bend_strain = 0.003;      ///< bound the bend must respect (checked)
  double room_rotation_min_deg = 1.0;  ///< degrees, the rotated room
  double room_rotation_max_deg = 3.0;  ///< degrees
  double room_rotation_band = 1.5;     ///< metres of blend around the rotated room
  // The plan's errors.
  double max_plan_scale_error = 0.03;  ///< the plan's units are off by up to this fraction
  std::string drawing_units = "m";     ///< the unit the DXF's coordinates are really in
  std::string header_units = "m";      ///< the unit its $INSUNITS claims
  // The robot.
  TourOptions tour;                      ///< speeds and odometry rate
  double min_furniture_fraction = 0.20;  ///< of all beams, checked
  // Manual pairs.
  int min_manual_pairs = 30;        ///< emulated hand-picked pairs, at least
  int max_manual_pairs = 60;        ///< at most
  double manual_pair_noise = 0.05;  ///< metres (about one pixel), radial standard deviation
};

/// The preset called `name`; InputError naming the field and the known presets otherwise.
SimulationPreset simulation_preset(const std::string& name);

/// The known preset names.
std::vector<std::string> simulation_preset_names();

}  // namespace floorgrid
