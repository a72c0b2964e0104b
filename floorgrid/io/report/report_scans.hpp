#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

namespace floorgrid::io {

/// The localization scan by scan, as the report's charts draw it (from scans.csv): per scan or,
/// for long runs, per bucket of `bucket` consecutive scans, whether each filter was converged
/// (1 when at least half the bucket's scans were, else null: a gap in the chart), whether the
/// scan made pairs, and the pairs it made.
struct ScanTrack {
  int scans = 0;                   ///< rows of scans.csv
  int bucket = 1;                  ///< scans per chart point
  int plan_converged = 0;          ///< scans whose plan filter was converged
  int grid_converged = 0;          ///< scans whose gridmap filter was converged
  int with_pairs = 0;              ///< scans that made pairs
  nlohmann::json chart = nullptr;  ///< {scan: [...], grid: [...], plan: [...], paired: [...],
                                   ///< pairs: [...]} for page.js, null without scans
};

/// Reads scans.csv's text (columns found by the header: scan, grid_converged, plan_converged,
/// pairs); at most `max_points` chart points. A text without those columns gives no track
/// (scans = 0): the report says scans.csv could not be read rather than failing.
ScanTrack scan_track(std::string_view scans_csv, int max_points = 2000);

}  // namespace floorgrid::io
