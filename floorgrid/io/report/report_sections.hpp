#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "floorgrid/io/report/report_html.hpp"
#include "floorgrid/io/report/report_scans.hpp"

namespace floorgrid::io {

/// What every section of report.html reads: the inputs and what is derived from them once.
struct ReportContext {
  const ReportInputs& inputs;       ///< the folder's contents
  std::string chosen;               ///< metrics.json chosen_model, or empty
  bool has_truth = false;           ///< whether some model was judged against a truth
  std::vector<std::string> models;  ///< fitted models, best first (truth, else cv error)
  ScanTrack track;                  ///< scans.csv, for the localization charts
  const nlohmann::json& metrics() const { return inputs.metrics; }
};

/// The context of `inputs`: chosen model, model order, scan track.
ReportContext report_context(const ReportInputs& inputs);

/// A value of `j` by a path of keys, or null when any is missing.
const nlohmann::json& json_at(const nlohmann::json& j, std::initializer_list<const char*> path);

// The page's sections, each `<section id=...>` with a title and one line on what to look at.
std::string summary_section(const ReportContext& c);         ///< id "summary": what matters
std::string models_section(const ReportContext& c);          ///< id "models": table and why
std::string histogram_section(const ReportContext& c);       ///< id "histograms"
std::string pairs_section(const ReportContext& c);           ///< id "pairs"
std::string localization_section(const ReportContext& c);    ///< id "localization"
std::string heatmaps_section(const ReportContext& c);        ///< id "heatmaps"
std::string overlays_section(const ReportContext& c);        ///< id "overlays"
std::string back_and_forth_section(const ReportContext& c);  ///< id "back-and-forth"
std::string timings_section(const ReportContext& c);         ///< id "timings"
std::string dataset_section(const ReportContext& c);         ///< id "dataset": inputs, exports

/// The charts' data for page.js: error histograms per model, the scan track, the chosen model.
nlohmann::json chart_data(const ReportContext& c);

}  // namespace floorgrid::io
