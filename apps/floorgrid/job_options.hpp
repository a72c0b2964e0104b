#pragma once

#include <CLI/CLI.hpp>
#include <memory>

#include "floorgrid/io/options/job_options.hpp"

namespace floorgrid::app {

/// The options a job's verb (`align`, `pairs`) takes on the command line besides the dataset:
/// a config file (config --dump's YAML), and the few options worth a flag of their own, which
/// win over the file when given (io::job_options makes the job's options of them).
using JobArgs = io::JobOverrides;
using io::job_options;

/// Adds --config, --seed, --memory-limit (and --cv, --cv-kind, --cv-block when `with_cv`) to
/// `cmd`.
void add_job_options(CLI::App* cmd, const std::shared_ptr<JobArgs>& args, bool with_cv);

}  // namespace floorgrid::app
