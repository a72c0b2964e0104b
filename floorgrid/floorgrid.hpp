#pragma once
// floorgrid's integrator surface, one header: load a dataset, align it (options, progress,
// cancelling), load, fit and save a model, and map points and poses both ways with their
// accuracy (std_m), flag and distance to the nearest pair. Link floorgrid::floorgrid:
//
//   find_package(floorgrid REQUIRED)
//   target_link_libraries(app PRIVATE floorgrid::floorgrid)
//
// Bad input from outside throws floorgrid::InputError (file(), line(), field()); an alignment
// that found no answer throws AlignmentFailure; a cancelled one throws Cancelled.

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/io/options/job_options.hpp"
#include "floorgrid/mapping/checked_fit.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

namespace io {
struct AlignmentJob;
}  // namespace io

/// The library's version (the CMake project's, "0.1.0").
std::string version();

/// Every option of `align` with its default, unit and description, as JSON (`config --dump
/// --json`): nested objects whose leaves are {"default", "unit", "description", "choices"}.
std::string options_json();

/// An align() that was cancelled (AlignOptions::cancel set, or the progress callback threw it).
class Cancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Points or poses mapped, one column (or entry) per input point.
struct MappedPoints {
  /// 2 x N points or 3 x N poses (x, y, theta in radians), in the model's units; NaN where not
  /// invertible.
  Eigen::MatrixXd values;
  Eigen::VectorXd std_m;           ///< the error's rms length, metres (NaN: the model has none)
  Eigen::VectorXd nearest_pair_m;  ///< metres from the input point to the nearest pair
  std::vector<MapFlag> flags;      ///< not_invertible, outside_hull, extrapolated, uncertain, ok
};

/// A fitted mapping between a building's plan frame and a robot's gridmap frame (SPEC "Mapping
/// models"). Cheap to copy (copies share the model); safe to use from several threads.
class Model {
 public:
  /// Reads a model file written by `fit`, `align` or save(). `max_error_m` > 0 overrides the
  /// file's bound of an `ok` point (`map --max-error`). InputError naming the file and field.
  static Model load(const std::string& path, double max_error_m = 0.0);
  /// Fits a model to pairs in metres, as `floorgrid fit` does (`request.unit` is recorded: the
  /// model then maps points in that unit); InputError naming `source` and the pair's row for
  /// bad pairs. A `request.memory_limit_gb` of 0 is `fit`'s default: half of this machine's
  /// memory.
  static Model fit(const ReferencePairs& pairs, ModelFitRequest request = {},
                   const std::string& source = "pairs");
  /// Wraps a fitted mapping.
  explicit Model(std::shared_ptr<PointMapping> mapping);

  /// Writes the model file (JSON, atomically); InputError when it cannot be written.
  void save(const std::string& path) const;

  /// The model's name: lc, gt, gt-rigid, gt-affine, ct, gp, gpgt, dt, tps or auto.
  std::string name() const;
  /// For auto: the model it chose; else name().
  std::string chosen() const;
  /// Metres per unit of the points it maps (1 for metres).
  double unit() const;
  /// Metres from every pair beyond which a point is flagged extrapolated.
  double extrapolation_distance() const;
  /// Metres: a point whose 95% bound (2 std_m) exceeds this is flagged uncertain.
  double max_error() const;
  /// Sets max_error() (> 0; InputError otherwise). Shared by the copies of this model.
  void set_max_error(double metres);
  /// The fit's summary as JSON: the model file's `fit` (rms_m, cv_error_m, details, ...) with
  /// its `pairs` (given, merged, used, reduction).
  std::string summary_json() const;

  /// Maps the columns of `in` (2 x N points or 3 x N poses, model units) plan to grid, or grid
  /// to plan when `inverse`, into the caller's buffers (each of N columns or entries; `out`
  /// has the rows of `in`), on two threads. Writes nothing else; no allocation per point. A
  /// coordinate that is not finite or lies beyond 1e7 m gets no number (NaN) and the flag
  /// not_invertible (`floorgrid map` refuses it).
  void map(const Eigen::Ref<const Eigen::MatrixXd>& in, bool inverse,
           Eigen::Ref<Eigen::MatrixXd> out, Eigen::Ref<Eigen::VectorXd> std_m,
           Eigen::Ref<Eigen::VectorXd> nearest_pair_m,
           Eigen::Ref<Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1>> flags) const;
  /// Plan points (2 x N) or poses (3 x N) in the grid frame.
  MappedPoints forward(const Eigen::Ref<const Eigen::MatrixXd>& in_plan) const;
  /// Grid points (2 x N) or poses (3 x N) in the plan frame.
  MappedPoints inverse(const Eigen::Ref<const Eigen::MatrixXd>& in_grid) const;

  /// The mapping itself (the full library interface).
  const PointMapping& mapping() const { return *mapping_; }

 private:
  std::shared_ptr<PointMapping> mapping_;
};

/// Progress of align(): the stage ("localize", "fit"), what in it, and how far.
struct Progress {
  std::string stage;     ///< "localize" or "fit"
  std::string detail;    ///< the phase or the model
  std::size_t done = 0;  ///< of `total`
  std::size_t total = 0;
};

/// How align() runs, besides the job's options (io::JobOverrides: config file, options text,
/// seed, cv, ...).
struct AlignOptions {
  io::JobOverrides job;  ///< the options, as the CLI's --config and flags give them
  /// Output folder to write as `floorgrid align --out` does (empty: write nothing).
  std::string out;
  /// Called as the job advances, on the calling thread; may throw (Cancelled or its own) to
  /// stop the job.
  std::function<void(const Progress&)> progress;
  /// Set (from any thread) to cancel: align() throws Cancelled at its next progress step.
  const std::atomic<bool>* cancel = nullptr;
};

/// A dataset read (dataset.yaml or its folder) with the job's loading options.
class Dataset {
 public:
  /// Reads the dataset; InputError naming the file, line and field on bad input.
  static Dataset load(const std::string& path, const io::JobOverrides& options = {});
  ~Dataset();
  Dataset(Dataset&&) noexcept;
  Dataset& operator=(Dataset&&) noexcept;

  /// The dataset's name (the manifest's, else its folder's).
  std::string name() const;
  /// The manifest's path.
  std::string manifest_path() const;
  /// Laser scans in the run (0 without a log: aligned from the maps alone).
  std::size_t scans() const;
  /// Whether the dataset has a truth (a simulator's warp or hand-picked pairs).
  bool has_truth() const;

  /// The options it was loaded with (align() uses them too).
  const io::JobOverrides& options() const { return options_; }
  /// The loaded job (the library's full interface).
  io::AlignmentJob& job() { return *job_; }

 private:
  Dataset() = default;
  std::unique_ptr<io::AlignmentJob> job_;
  io::JobOverrides options_;
};

/// What align() found.
struct AlignResult {
  ReferencePairs pairs;  ///< the pairs every model was fitted on (metres)
  /// metrics.json's content (docs/metrics.md): as written into AlignOptions::out, else the
  /// same less the heat maps' keys and write timings.
  std::string metrics_json;
  std::vector<std::string> model_names;  ///< the fitted models, in the order fitted
  std::vector<Model> models;             ///< one per name
  std::string chosen;                    ///< the model `auto` chose ("" without auto)
  std::vector<std::string> files;        ///< written into AlignOptions::out, relative to it
  /// The model named `name` (InputError when none was fitted under it).
  const Model& model(const std::string& name) const;
};

/// The main job on a dataset read (`floorgrid align`) with the options it was loaded with
/// (`options.job` is ignored here). Writes `options.out` when given. InputError for bad input,
/// AlignmentFailure when the run made no pairs or its plan is of another building (after
/// writing metrics.json and report.html), Cancelled when cancelled.
AlignResult align(Dataset& dataset, const AlignOptions& options = {});
/// Reads `dataset` with `options.job`, then aligns it.
AlignResult align(const std::string& dataset, const AlignOptions& options = {});

}  // namespace floorgrid
