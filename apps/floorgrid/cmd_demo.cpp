// `floorgrid demo [--out DIR]`: the main job on the built-in default building.
#include <fmt/format.h>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "apps/floorgrid/job_options.hpp"
#include "floorgrid/io/dataset/simulation_writer.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid::app {

void run_align(const std::string& dataset, const std::string& out, const JobOptions& options);

void add_demo_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "demo", "The main job on the built-in default: simulate an office, align it, write results");
  struct Args {
    std::string out = "demo-out";
    std::string preset = "office";
    std::uint64_t seed = 1;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--out", args->out, "output folder (created if needed)")->capture_default_str();
  cmd->add_option("--preset", args->preset, "building preset to simulate")->capture_default_str();
  cmd->add_option("--seed", args->seed, "random seed")->check(seed_check())->capture_default_str();
  cmd->callback([args] {
    simulation_preset(args->preset);  // a bad preset fails before any work
    const std::filesystem::path out(args->out);
    const io::OutputFolder out_folder(out);
    fmt::print("simulating {} (seed {}) into {}\n", args->preset, args->seed,
               (out / "dataset").string());
    const SimulatedDataset d = simulate(args->preset, args->seed);
    io::write_simulated_dataset(d, out / "dataset", true);
    fmt::print("aligning it into {}\n\n", (out / "align").string());
    JobArgs job;
    job.seed = args->seed;
    run_align((out / "dataset").string(), (out / "align").string(), job_options(job));
    fmt::print(
        "\ndemo: the dataset is in {} (preview.png: the plan's walls through the exact "
        "warp), the results in {} (report.html tells it all; overlays/ show the plan's walls "
        "through each model in red, through the truth in green)\n",
        (out / "dataset").string(), (out / "align").string());
  });
}

}  // namespace floorgrid::app
