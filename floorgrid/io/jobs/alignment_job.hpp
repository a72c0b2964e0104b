#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/export/export_bundle.hpp"
#include "floorgrid/io/jobs/alignment_writer.hpp"
#include "floorgrid/io/options/options_schema.hpp"
#include "floorgrid/pipeline/align.hpp"

namespace floorgrid::io {

/// A dataset read for the main job, with what `align` works on: `inputs` refer into `dataset`,
/// so a job is neither copied nor moved (load_alignment_job hands out a unique_ptr).
struct AlignmentJob {
  /// Takes the dataset read; `use_log` false aligns from the maps alone.
  AlignmentJob(LoadedDataset loaded, bool use_log);
  AlignmentJob(const AlignmentJob&) = delete;
  AlignmentJob& operator=(const AlignmentJob&) = delete;

  LoadedDataset dataset;     ///< the dataset read
  AlignmentInputs inputs;    ///< what align() works on (refers into `dataset`)
  AlignmentTimings timings;  ///< `load` filled; write_alignment_folder fills `write`
};

/// Reads `dataset` (dataset.yaml or its folder) with `options`' loading settings, timed.
/// InputError on bad input.
std::unique_ptr<AlignmentJob> load_alignment_job(const std::filesystem::path& dataset,
                                                 const JobOptions& options);

/// The main job on a dataset read (align() with `options.align`). A localization that failed
/// is bad input: InputError naming the manifest and the field (require_localized).
Alignment run_alignment_job(const AlignmentJob& job, const JobOptions& options,
                            const AlignmentProgressCallback& progress = {});

/// What write_alignment_folder wrote, and whether the result is an alignment at all.
struct AlignmentFolder {
  AlignmentFiles files;                ///< pairs, models, overlays, heat maps, metrics.json
  std::optional<ExportFiles> exports;  ///< the chosen model's exports (when accepted)
  std::string exports_error;           ///< why the exports were not written, or empty
  double exports_seconds = 0.0;        ///< writing them
  std::optional<std::filesystem::path> report;  ///< report.html, unless it failed
  std::string report_error;                     ///< why report.html was not written, or empty
  double report_seconds = 0.0;                  ///< writing it
  /// Why this is no alignment (no pairs, or a plan of another building: AlignmentFailure's
  /// message, which the CLI exits 3 with), or empty. metrics.json and report.html are
  /// written then too; the exports are not.
  std::string failure;
};

/// Writes the main job's folder `out` as `floorgrid align` does, with INCOMPLETE.txt in it
/// until the last file is written: write_alignment (metrics.json last), then, when the run made
/// pairs and its plan matches the gridmap, the chosen model's exports, and report.html.
AlignmentFolder write_alignment_folder(AlignmentJob& job, const Alignment& alignment,
                                       const JobOptions& options, const std::filesystem::path& out);

/// metrics.json of an alignment as write_alignment_folder writes it (its `timings_s.write`
/// and `heat_maps` are 0 when nothing was written).
nlohmann::json alignment_metrics(const AlignmentJob& job, const Alignment& alignment);

}  // namespace floorgrid::io
