#include "floorgrid/io/jobs/alignment_job.hpp"

#include <chrono>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/memory_usage.hpp"
#include "floorgrid/io/dataset/dataset_run.hpp"
#include "floorgrid/io/export/export_inputs.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/report/report_html.hpp"

namespace floorgrid::io {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The model `auto` chose, or null (no auto among the models, or it failed).
const PointMapping* auto_model(const Alignment& a) {
  for (const ModelAlignment& m : a.models) {
    if (m.report.name == "auto" && m.report.model)
      return m.report.model.get();
  }
  return nullptr;
}

/// AlignmentFailure's message when the run is no alignment (require_pairs, require_plan_match),
/// else empty.
std::string failure_of(const Alignment& a, const LoadedDataset& d, const JobOptions& options) {
  try {
    require_pairs(a.localization, d);
    // Pairs from the maps alone were judged by the maps' own fitness (require_localized).
    if (a.pairs_from != PairSource::maps)
      require_plan_match(a.plan_match, d, options.align.localization.plan_location);
  } catch (const AlignmentFailure& e) {
    return e.what();
  }
  return {};
}

}  // namespace

AlignmentJob::AlignmentJob(LoadedDataset loaded, bool use_log)
    : dataset(std::move(loaded)),
      inputs{dataset.plan_grid,
             dataset.plan ? &*dataset.plan : nullptr,
             dataset.plan_wall_samples,
             dataset.gridmap,
             dataset_log_or_none(dataset, use_log),
             start_poses(dataset),
             dataset.manifest.floorplan_scale,
             warp_truth(dataset),
             dataset.manual_pairs ? &*dataset.manual_pairs : nullptr} {}

std::unique_ptr<AlignmentJob> load_alignment_job(const std::filesystem::path& dataset,
                                                 const JobOptions& options) {
  const auto start = Clock::now();
  // Without a log (or without using it) the pairs come from the maps alone.
  auto job = std::make_unique<AlignmentJob>(
      load_dataset(dataset, options.raster, options.limits, options.units),
      options.align.pairs_from != PairSource::maps);
  job->timings.load = seconds_since(start);
  job->timings.load_peak_mib = peak_resident_mib();
  return job;
}

Alignment run_alignment_job(const AlignmentJob& job, const JobOptions& options,
                            const AlignmentProgressCallback& progress) {
  Alignment a = align(job.inputs, options.align, progress);
  require_localized(a.localization.status, job.dataset);
  return a;
}

AlignmentFolder write_alignment_folder(AlignmentJob& job, const Alignment& a,
                                       const JobOptions& options,
                                       const std::filesystem::path& out) {
  const LoadedDataset& d = job.dataset;
  AlignmentFolder folder;
  // From here files are written: the folder says it is incomplete until the last one is.
  IncompleteMarker incomplete(out, "floorgrid align");
  folder.files = write_alignment(a, job.inputs, d.manifest.display_name(), out, job.timings,
                                 floorplan_units_json(d), d.manifest.manifest_path);
  // What was learnt is written (metrics.json holds the localization's story), but a run that
  // made no pairs is a failure, not a result; its report still tells what happened.
  folder.failure = failure_of(a, d, options);
  // The chosen model in other tools' terms (not for a rejected alignment). A failure here costs
  // the exports, not the job.
  const PointMapping* chosen = auto_model(a);
  if (folder.failure.empty() && chosen) {
    const auto start = Clock::now();
    try {
      folder.exports =
          write_exports(*chosen, a.localization.pairs, export_maps(d), out / "exports");
    } catch (const InputError& e) {
      folder.exports_error = e.what();
    }
    folder.exports_seconds = seconds_since(start);
  }
  const auto report_start = Clock::now();
  try {
    folder.report = write_report_html(out);
  } catch (const std::exception& e) {
    folder.report_error = e.what();
  }
  folder.report_seconds = seconds_since(report_start);
  incomplete.done();
  return folder;
}

nlohmann::json alignment_metrics(const AlignmentJob& job, const Alignment& alignment) {
  nlohmann::json metrics = metrics_json(alignment, job.dataset.manifest.display_name(), job.timings,
                                        floorplan_units_json(job.dataset));
  metrics["dataset_path"] =
      std::filesystem::absolute(job.dataset.manifest.manifest_path).lexically_normal().string();
  return metrics;
}

}  // namespace floorgrid::io
