#include "apps/floorgrid/dataset_run.hpp"

#include "floorgrid/core/error.hpp"

namespace floorgrid::app {

std::optional<StartPoses> start_poses(const io::LoadedDataset& dataset) {
  if (!dataset.manifest.initial_pose)
    return std::nullopt;
  return StartPoses{dataset.manifest.initial_pose->plan, dataset.manifest.initial_pose->grid};
}

const RobotLog& dataset_log(const io::LoadedDataset& dataset) {
  if (!dataset.log) {
    throw InputError("the dataset names no log: pairs need a robot run",
                     dataset.manifest.manifest_path.string(), 0, "log");
  }
  return *dataset.log;
}

DualLocalizerInputs dual_inputs(const io::LoadedDataset& dataset) {
  return {.plan = dataset.plan_grid,
          .gridmap = dataset.gridmap,
          .log = dataset_log(dataset),
          .start = start_poses(dataset),
          .plan_scale = dataset.manifest.floorplan_scale,
          .plan_geometry = dataset.plan ? &*dataset.plan : nullptr};
}

void require_localized(const LocalizationStatus& status, const io::LoadedDataset& dataset) {
  if (!status.ok)
    throw InputError(status.message, dataset.manifest.manifest_path.string(), 0, status.field);
}

}  // namespace floorgrid::app
