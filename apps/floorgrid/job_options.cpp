#include "apps/floorgrid/job_options.hpp"

#include "apps/floorgrid/cli_util.hpp"

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/model_selection.hpp"

namespace floorgrid::app {

void add_job_options(CLI::App* cmd, const std::shared_ptr<JobArgs>& args, bool with_cv) {
  cmd->add_option("--config", args->config,
                  "options file: YAML as `floorgrid config --dump` prints it (keys left out keep "
                  "their defaults)");
  cmd->add_option("--seed", args->seed, "randomness of the filters and the model fits (default 1)")
      ->check(seed_check());
  cmd->add_option("--memory-limit", args->memory_gb,
                  "GiB the maps may take (default: half of this machine's memory)");
  if (with_cv) {
    cmd->add_option("--cv", args->cv, "k of each model's k-fold cross-validation (0: none)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--cv-kind", args->cv_kind,
                    "how auto compares the models: folds of stretches of the run (runs: "
                    "each predicted from the other passes, default), of whole spatial blocks "
                    "(blocked: the error away from the pairs) or of pairs dealt at random "
                    "(random); each model's std_m is fitted on blocked folds unless random")
        ->check(CLI::IsMember({"blocked", "random", "runs"}));
    cmd->add_option("--cv-block", args->cv_block,
                    "metres, side of the blocks of blocked folds (default 0: chosen from the "
                    "pairs)");
  }
}

JobOptions job_options(const JobArgs& args) {
  JobOptions options;
  if (!args.config.empty())
    io::read_options_yaml(args.config, io::job_option_tree(options));
  if (args.seed) {
    options.align.localization.seed = *args.seed;
    options.align.models.mapping.common.seed = *args.seed;
  }
  if (args.cv) {
    if (*args.cv == 1)
      throw InputError("must be 0 or at least 2", {}, 0, "--cv");
    options.align.models.cv_folds = *args.cv;
  }
  CrossValidationOptions& cv = options.align.models.mapping.auto_select.cv;
  if (args.cv_kind)
    cv.kind = parse_cv_kind(*args.cv_kind);
  if (args.cv_block) {
    if (!(*args.cv_block >= 0.0 && *args.cv_block <= kMaxCoordinate))
      throw InputError("must be 0 (chosen from the pairs) or a size in metres", {}, 0,
                       "--cv-block");
    cv.block_size = *args.cv_block;
  }
  if (args.memory_gb) {
    if (!(*args.memory_gb > 0.0 && *args.memory_gb < 1e6))
      throw InputError("must be a positive number of GiB", {}, 0, "--memory-limit");
    options.limits.memory_gb = *args.memory_gb;
  }
  return options;
}

}  // namespace floorgrid::app
