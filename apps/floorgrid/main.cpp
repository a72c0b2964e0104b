// floorgrid: align a building's CAD floorplan with a robot's occupancy gridmap.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"

int main(int argc, char** argv) {
  floorgrid::io::remove_temporaries_on_signals();
  CLI::App root{"floorgrid: align a CAD floorplan with a robot's occupancy gridmap"};
  root.require_subcommand(1);
  root.set_version_flag("--version", "floorgrid 0.1.0");
  // Messages and progress go to stderr; stdout carries only results (text or --json).
  spdlog::set_default_logger(spdlog::stderr_color_st("floorgrid"));
  spdlog::set_pattern("%^%l%$: %v");
  floorgrid::app::add_info_command(root);
  floorgrid::app::add_simulate_command(root);
  floorgrid::app::add_fit_command(root);
  floorgrid::app::add_map_command(root);
  floorgrid::app::add_pairs_command(root);
  floorgrid::app::add_evaluate_command(root);
  floorgrid::app::add_align_command(root);
  floorgrid::app::add_demo_command(root);
  floorgrid::app::add_config_command(root);
  floorgrid::app::add_export_command(root);
  floorgrid::app::add_serve_command(root);
  floorgrid::app::add_migrate_command(root);

  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = root.exit(e);
    return status == 0 ? 0 : 2;
  } catch (const floorgrid::InputError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const floorgrid::AlignmentFailure& e) {
    spdlog::error("{}", e.what());
    return 3;
  } catch (const std::exception& e) {
    spdlog::error("internal failure: {}", e.what());
    return 1;
  }
  return 0;
}
