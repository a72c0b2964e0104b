#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace floorgrid::io {

/// A PNG picture of an output folder, for the report (embedded as a data URL).
struct ReportImage {
  std::string path;  ///< relative to the folder, '/'-separated: "overlays/overlay-gt.png"
  std::string png;   ///< the file's bytes
};

/// What report.html is made of: an output folder's contents (align's or evaluate's), or the
/// same built in memory.
struct ReportInputs {
  nlohmann::json metrics;               ///< metrics.json (required)
  nlohmann::json auto_model = nullptr;  ///< model-auto.json (why auto chose), or null
  std::string scans_csv;                ///< scans.csv's text (scan by scan), or empty
  std::vector<ReportImage> images;      ///< overlays/*.png and heatmaps/*.png, by path
  std::vector<std::string> exports;     ///< files in exports/, by name
};

/// Reads what the report shows from an output folder: metrics.json (InputError naming it when
/// missing or not JSON) and, when present, model-auto.json, scans.csv, overlays/*.png,
/// heatmaps/*.png and the names in exports/.
ReportInputs read_report_inputs(const std::filesystem::path& folder);

/// report.html's text: one self-contained page (uPlot, the page's script and style sheet and
/// every picture inlined; no network), with the summary first (chosen model, its error, pairs,
/// converged share, plan scale), then the models, error histograms, pairs, the localization
/// scan by scan, heat maps, overlays, back-and-forth and timings. Every string from the data is
/// escaped; numbers are formatted by report_format.hpp.
std::string render_report_html(const ReportInputs& inputs);

/// Reads `folder` (read_report_inputs), renders and writes `folder`/report.html atomically;
/// returns its path.
std::filesystem::path write_report_html(const std::filesystem::path& folder);

}  // namespace floorgrid::io
