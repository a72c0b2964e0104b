#include "apps/floorgrid/job_options.hpp"

#include "apps/floorgrid/cli_util.hpp"

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

}  // namespace floorgrid::app
