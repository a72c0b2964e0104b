#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "floorgrid/simulation/log_dataset.hpp"
#include "floorgrid/simulation/plan_truth.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid::io {

/// truth.json of a synthetic dataset: format "floorgrid-simulation-truth", the warp's
/// parameters, the plan's scale and units, the preset's parameters, the run's statistics and
/// the true trajectory (world frame, and in plan and grid frames).
nlohmann::json simulation_truth_json(const SimulatedDataset& dataset);

/// truth.json of a semi-real dataset made from the log `source`: the same format as a preset's
/// (read_plan_truth reads both), with "preset": "from-log", the choices made and the figures,
/// and the corrected trajectory (grid frame, and in the plan's world).
nlohmann::json log_dataset_truth_json(const LogDataset& dataset, const std::string& source);

/// Reads the exact plan -> grid mapping from a truth.json. InputError naming the file and the
/// field for a missing or malformed one.
PlanTruth read_plan_truth(const std::filesystem::path& path);

/// The warp parameters as JSON, and back (`where` names the file for errors).
nlohmann::json warp_json(const WarpParams& warp);
/// truth.json's parameters.laser: the simulated laser of `preset`.
nlohmann::json laser_json(const SimulationPreset& preset);
/// truth.json's parameters.odometry_alpha: the odometry noise of `preset` (alpha1-4).
nlohmann::json odometry_alpha_json(const SimulationPreset& preset);
/// Parses warp_json's output; InputError naming `where` and the field otherwise.
WarpParams warp_from_json(const nlohmann::json& j, const std::string& where);

}  // namespace floorgrid::io
