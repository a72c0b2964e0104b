#pragma once

#include <CLI/CLI.hpp>

namespace floorgrid::app {

/// Each CLI verb registers its subcommand (options and callback) on the root app.
/// The callbacks throw InputError on bad input; main() maps it to exit status 2.
void add_info_command(CLI::App& root);
/// `floorgrid simulate`.
void add_simulate_command(CLI::App& root);
/// `floorgrid fit`.
void add_fit_command(CLI::App& root);
/// `floorgrid map`.
void add_map_command(CLI::App& root);
/// `floorgrid pairs`.
void add_pairs_command(CLI::App& root);
/// `floorgrid evaluate`.
void add_evaluate_command(CLI::App& root);
/// `floorgrid align`.
void add_align_command(CLI::App& root);
/// `floorgrid demo`.
void add_demo_command(CLI::App& root);
/// `floorgrid config`.
void add_config_command(CLI::App& root);
/// `floorgrid export`.
void add_export_command(CLI::App& root);
/// `floorgrid serve`.
void add_serve_command(CLI::App& root);
/// `floorgrid migrate`.
void add_migrate_command(CLI::App& root);

}  // namespace floorgrid::app
