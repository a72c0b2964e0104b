// `floorgrid config --dump [--json]`: every option with its default and unit.
#include <fmt/format.h>

#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/options/options_schema.hpp"

namespace floorgrid::app {

void add_config_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "config", "Print every option of align and pairs with its default and unit (--dump)");
  struct Args {
    bool dump = false;
    bool json = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_flag("--dump", args->dump, "print every option as YAML that --config FILE reads back");
  cmd->add_flag("--json", args->json, "as JSON: each option's default, unit and description");
  cmd->callback([args] {
    if (!args->dump)
      throw InputError("say --dump (the only thing config does)", {}, 0, "--dump");
    JobOptions defaults;
    if (args->json) {
      fmt::print("{}", io::options_json(io::job_option_tree(defaults)));
      return;
    }
    fmt::print("{}", io::options_yaml(io::job_option_tree(defaults),
                                      "# floorgrid options: every setting of `align` and `pairs` "
                                      "with its default.\n# Keep the ones you change and pass the "
                                      "file back: floorgrid align DATASET --config FILE.\n"));
  });
}

}  // namespace floorgrid::app
