// `floorgrid info PATH [--json]`: what a map, plan, log, pairs file or dataset holds.
#include <fmt/format.h>

#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"

namespace floorgrid::app {

void add_info_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("info", "What a map, plan, log, pairs file or dataset holds");
  auto path = std::make_shared<std::string>();
  cmd->add_option("PATH", *path, "a map YAML or image, DXF, CARMEN log, pairs CSV or dataset")
      ->required();
  cmd->callback([path] { throw InputError("not yet supported", *path); });
}

}  // namespace floorgrid::app
