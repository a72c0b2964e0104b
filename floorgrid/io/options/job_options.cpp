#include "floorgrid/io/options/job_options.hpp"

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/model_selection.hpp"

namespace floorgrid::io {

JobOptions job_options(const JobOverrides& overrides) {
  JobOptions options;
  if (!overrides.config.empty())
    read_options_yaml(overrides.config, job_option_tree(options));
  if (!overrides.options_text.empty())
    read_options_yaml_text(overrides.options_text, overrides.options_source,
                           job_option_tree(options));
  if (overrides.seed) {
    options.align.localization.seed = *overrides.seed;
    options.align.models.mapping.common.seed = *overrides.seed;
  }
  if (overrides.cv) {
    if (*overrides.cv < 0 || *overrides.cv == 1)
      throw InputError("must be 0 or at least 2", {}, 0, "--cv");
    options.align.models.cv_folds = *overrides.cv;
  }
  CrossValidationOptions& cv = options.align.models.mapping.auto_select.cv;
  if (overrides.cv_kind)
    cv.kind = parse_cv_kind(*overrides.cv_kind);
  if (overrides.cv_block) {
    if (!(*overrides.cv_block >= 0.0 && *overrides.cv_block <= kMaxCoordinate))
      throw InputError("must be 0 (chosen from the pairs) or a size in metres", {}, 0,
                       "--cv-block");
    cv.block_size = *overrides.cv_block;
  }
  if (overrides.memory_gb) {
    if (!(*overrides.memory_gb > 0.0 && *overrides.memory_gb < 1e6))
      throw InputError("must be a positive number of GiB", {}, 0, "--memory-limit");
    options.limits.memory_gb = *overrides.memory_gb;
  }
  if (overrides.pairs_from)
    options.align.pairs_from = parse_pair_source(*overrides.pairs_from);
  return options;
}

}  // namespace floorgrid::io
