#include "floorgrid/io/dataset/dataset_run.hpp"

#include <fmt/format.h>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

std::optional<StartPoses> start_poses(const LoadedDataset& dataset) {
  if (!dataset.manifest.initial_pose)
    return std::nullopt;
  return StartPoses{dataset.manifest.initial_pose->plan, dataset.manifest.initial_pose->grid};
}

const RobotLog& dataset_log_or_none(const LoadedDataset& dataset, bool use) {
  static const RobotLog none;
  return dataset.log && use ? *dataset.log : none;
}

const RobotLog& dataset_log(const LoadedDataset& dataset) {
  if (!dataset.log) {
    throw InputError("the dataset names no log: pairs need a robot run",
                     dataset.manifest.manifest_path.string(), 0, "log");
  }
  return *dataset.log;
}

DualLocalizerInputs dual_inputs(const LoadedDataset& dataset) {
  return {.plan = dataset.plan_grid,
          .gridmap = dataset.gridmap,
          .log = dataset_log(dataset),
          .start = start_poses(dataset),
          .plan_scale = dataset.manifest.floorplan_scale,
          .plan_geometry = dataset.plan ? &*dataset.plan : nullptr};
}

void require_localized(const LocalizationStatus& status, const LoadedDataset& dataset) {
  if (!status.ok)
    throw InputError(status.message, dataset.manifest.manifest_path.string(), 0, status.field);
}

void require_pairs(const DualLocalization& l, const LoadedDataset& dataset) {
  if (l.pairs.size() > 0)
    return;
  const DatasetManifest& m = dataset.manifest;
  std::size_t grid_converged = 0, plan_converged = 0;
  for (const ScanRecord& r : l.scans) {
    grid_converged += r.grid.converged;
    plan_converged += r.plan.converged;
  }
  const std::size_t scans = l.scans.size();
  const auto share = [&](std::size_t n) { return scans ? 100.0 * double(n) / double(scans) : 0.0; };
  std::string message = fmt::format(
      "{}: no reference pairs, so no alignment: the two filters were never converged together "
      "on matching scans. The gridmap filter was converged on {:.0f}% of the {} scans (first at "
      "scan {}, at {:.2f}, {:.2f}, {:.3f}), the plan filter on {:.0f}% (started at scan {}, at "
      "{:.2f}, {:.2f}, {:.3f}); plan scale {:.4f} ({}).",
      m.manifest_path.string(), share(grid_converged), scans, l.grid_start_scan, l.start.grid.x,
      l.start.grid.y, l.start.grid.theta, share(plan_converged), l.plan_start_scan, l.start.plan.x,
      l.start.plan.y, l.start.plan.theta, l.plan_scale,
      l.plan_scale_estimated ? "estimated" : "given");
  for (const std::string& note : l.notes)
    message += " " + note + ".";
  std::vector<std::string> tries;
  if (!m.floorplan_scale)
    tries.push_back("give floorplan_scale if the plan's scale is known");
  if (!m.initial_pose)
    tries.push_back("give initial_pose (plan and grid) if the start is known");
  tries.push_back("check the maps' walls with `floorgrid info` (and the plan with --preview)");
  message += " Try: " + fmt::format("{}", fmt::join(tries, "; ")) + ".";
  throw AlignmentFailure(message);
}

void require_plan_match(const PlanMatch& match, const LoadedDataset& dataset,
                        const PlanLocationOptions& options) {
  const double min_score = options.min_plan_match;
  if (plan_match_accepted(match, min_score, options.max_plan_walls_in_free_space))
    return;
  const DatasetManifest& m = dataset.manifest;
  throw AlignmentFailure(fmt::format(
      "{}: the plan does not look like a drawing of the gridmap's building: under the similarity "
      "the pairs give (refined on the two maps, plan scale {:.4f}), {:.0f}% of the gridmap's "
      "walls lie on the plan's walls and {:.0f}% of the plan's walls lie where the robot saw free "
      "space (score {:.2f}, needs {:.2f}; plan walls in free space at most {:.0f}%; the right "
      "plan scored 0.33-0.90 with 0-5% on the datasets measured). The filters converged "
      "on places that agree only locally, so the pairs would be confidently wrong. Check that {} "
      "is this building and floor (`floorgrid info` on it and on {}); if it is, give "
      "floorplan_scale and initial_pose, or set plan_location.min_plan_match to -1 and "
      "max_plan_walls_in_free_space to 1 to accept it.",
      m.manifest_path.string(), 1.0 / match.score.transform.scale, 100.0 * match.score.on_walls,
      100.0 * match.score.in_free_space, match.score.score, min_score,
      100.0 * options.max_plan_walls_in_free_space, m.floorplan.string(), m.gridmap.string()));
}

}  // namespace floorgrid::io
