#pragma once

#include "floorgrid/io/dataset/dataset_run.hpp"

namespace floorgrid::app {

/// Logs what loading found: the readers' warnings, and the run's say on a DXF's units when it
/// confirmed the drawing's (an overruling is among the warnings).
void report_loading(const io::LoadedDataset& dataset);

using io::dataset_log;
using io::dataset_log_or_none;
using io::dual_inputs;
using io::require_localized;
using io::require_pairs;
using io::require_plan_match;
using io::start_poses;

}  // namespace floorgrid::app
