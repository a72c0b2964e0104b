#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "floorgrid/io/options/options_schema.hpp"

namespace floorgrid::io {

/// What a caller may change of a job's options (`align`, `pairs`, `evaluate`) besides the
/// defaults: the CLI's --config and flags, the Python module's keyword arguments. Applied in
/// this order: the defaults, `config`, `options_text`, then each flag given.
struct JobOverrides {
  std::string config;        ///< options file (YAML as `config --dump` prints it), or empty
  std::string options_text;  ///< options as YAML (or JSON) text, or empty
  std::string options_source = "options";  ///< what errors in `options_text` name as the file
  std::optional<std::uint64_t> seed;       ///< the filters' and the model fits' randomness
  std::optional<int> cv;                   ///< k of each model's cross-validation (0: none)
  std::optional<std::string> cv_kind;      ///< blocked, random or runs
  std::optional<double> cv_block;          ///< side of the blocks, metres (0: chosen)
  std::optional<double> memory_gb;         ///< GiB the maps may take
  std::optional<std::string> pairs_from;   ///< run, maps or both
};

/// The job's options: the defaults, then `overrides` (see JobOverrides). InputError naming the
/// file and line of a bad option, or the flag (`--cv`, `--seed`, ...) of a bad value.
JobOptions job_options(const JobOverrides& overrides);

}  // namespace floorgrid::io
