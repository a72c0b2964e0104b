#pragma once

#include <optional>

#include "floorgrid/evaluation/model_evaluation.hpp"
#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/pipeline/dual_localizer.hpp"
#include "floorgrid/pipeline/plan_match.hpp"

namespace floorgrid::io {

// What a job on a dataset (`align`, `pairs`, `evaluate`; the CLI and the Python module) needs
// of it besides loading, and how it refuses a run that found nothing.

/// The manifest's initial poses, when it gives them.
std::optional<StartPoses> start_poses(const LoadedDataset& dataset);

/// The dataset's log; InputError naming the manifest when it has none.
const RobotLog& dataset_log(const LoadedDataset& dataset);

/// The dataset's log, or an empty one when it has none (or `use` is false): a job that can do
/// without a run (evaluate, align from the maps alone).
const RobotLog& dataset_log_or_none(const LoadedDataset& dataset, bool use = true);

/// What the dual localization of a dataset works on (`dataset` must outlive it).
DualLocalizerInputs dual_inputs(const LoadedDataset& dataset);

/// A localization that failed is bad input at the CLI (a wrong map resolution or origin, a
/// wrong initial pose, a log of another building): InputError naming the manifest and the
/// field the status blames.
void require_localized(const LocalizationStatus& status, const LoadedDataset& dataset);

/// Throws AlignmentFailure when the localization made no pairs: which filter failed, where
/// they were, the plan scale used, the localizer's notes, and what to try.
void require_pairs(const DualLocalization& localization, const LoadedDataset& dataset);

/// Throws AlignmentFailure (with what the maps show and what to try) when the plan does not
/// match the gridmap under the pairs' similarity (plan_match_accepted with the options'
/// min_plan_match and max_plan_walls_in_free_space): a plan of another building or floor on
/// which the filters converged anyway.
void require_plan_match(const PlanMatch& match, const LoadedDataset& dataset,
                        const PlanLocationOptions& options);

}  // namespace floorgrid::io
