#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "floorgrid/io/options_schema.hpp"

namespace floorgrid::app {

/// The options a job's verb (`align`, `pairs`) takes on the command line besides the dataset:
/// a config file (config --dump's YAML), and the few options worth a flag of their own, which
/// win over the file when given.
struct JobArgs {
  std::string config;                  ///< --config FILE, or empty
  std::optional<std::uint64_t> seed;   ///< --seed: the filters' and the model fits' randomness
  std::optional<int> cv;               ///< --cv: k of each model's cross-validation
  std::optional<std::string> cv_kind;  ///< --cv-kind: blocked or random folds
  std::optional<double> cv_block;      ///< --cv-block: side of the blocks, metres (0: chosen)
  std::optional<double> memory_gb;     ///< --memory-limit
};

/// Adds --config, --seed, --memory-limit (and --cv, --cv-kind, --cv-block when `with_cv`) to
/// `cmd`.
void add_job_options(CLI::App* cmd, const std::shared_ptr<JobArgs>& args, bool with_cv);

/// The job's options: the defaults, then the config file, then the flags given.
JobOptions job_options(const JobArgs& args);

}  // namespace floorgrid::app
