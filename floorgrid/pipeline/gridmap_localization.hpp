#pragma once

#include <optional>

#include "floorgrid/pipeline/dual_maps.hpp"

namespace floorgrid {

/// What step 1 found.
struct GridmapLocalization {
  /// The scan the gridmap filter first converged on; none when it never did (then
  /// DualLocalization::status says why).
  std::optional<std::size_t> first_converged;
  /// The given start, when the gridmap filter kept to it (did not diverge before converging).
  std::optional<StartPoses> start;
};

/// Step 1 of localize_dual: the gridmap filter localizes globally from its best hypotheses for
/// the first scan (or tracks from the given start) and runs through the log, re-seeded
/// whenever it diverges: around its last converged pose first, globally from the scan's best
/// hypotheses when that fails (GridmapLocalizationOptions::restart_near_scans). Fills every
/// ScanRecord::grid, the gridmap's divergences, corrections and timings of `result`; a filter not
/// converged within GridmapLocalizationOptions::max_global_scans sets `result.status`.
GridmapLocalization localize_on_gridmap(const DualMaps& maps, const DualLocalizerInputs& inputs,
                                        const DualLocalizerOptions& options,
                                        DualLocalization& result,
                                        const DualProgressCallback& progress);

}  // namespace floorgrid
