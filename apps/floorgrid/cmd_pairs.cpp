// `floorgrid pairs DATASET --out pairs.csv`: reference pairs by dual Monte Carlo localization.
#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/dataset_loader.hpp"
#include "floorgrid/io/pairs_csv.hpp"
#include "floorgrid/localization/dual_localizer.hpp"

namespace floorgrid::app {

void add_pairs_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("pairs", "Reference pairs by dual Monte Carlo localization");
  struct Args {
    std::string dataset, out;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("DATASET", args->dataset, "dataset.yaml or its folder")->required();
  cmd->add_option("--out", args->out, "pairs CSV to write")->required();
  cmd->callback([args] {
    const io::LoadedDataset d = io::load_dataset(args->dataset);
    if (!d.log)
      throw InputError("the dataset has no log", d.manifest.manifest_path, 0, "log");
    std::optional<StartPoses> start;
    if (d.manifest.initial_pose)
      start = StartPoses{d.manifest.initial_pose->plan, d.manifest.initial_pose->grid};
    const bool tty = isatty(fileno(stderr));
    const auto progress = [&](const DualProgress& p) {
      if (!tty)
        return;
      fmt::print(stderr, "\r{}: {}/{} {} usable {}    ", p.phase, p.scan, p.scans,
                 p.converged ? "converged" : "--", p.pairs);
    };
    const DualLocalization r =
        localize_dual(d.plan_grid, d.gridmap, *d.log, start, d.manifest.floorplan_scale, {},
                      progress, d.plan ? &*d.plan : nullptr);
    if (tty)
      fmt::print(stderr, "\n");
    io::write_pairs_csv(r.pairs, args->out);
    fmt::print("pairs {} scale {:.4f} +- {:.4f} converged {:.3f}\n", r.pairs.size(), r.plan_scale,
               r.plan_scale_std, r.converged_fraction);
    for (const auto& [k, v] : r.rejections.by_reason())
      fmt::print("  rejected {} {}\n", k, v);
    fmt::print("  global {:.1f} s; scale {:.1f} s; localize {:.1f} s\n",
               r.global_localization_seconds, r.scale_search_seconds, r.localize_seconds);
    if (d.truth_warp) {
      std::vector<double> e;
      for (Eigen::Index i = 0; i < r.pairs.size(); ++i)
        e.push_back((d.truth_warp->plan_to_grid(r.pairs.points_in_plan.col(i)) -
                     r.pairs.points_in_grid.col(i))
                        .norm());
      std::sort(e.begin(), e.end());
      if (!e.empty())
        fmt::print("  pair error median {:.4f} p90 {:.4f} max {:.4f}; true scale {:.5f}\n",
                   e[e.size() / 2], e[e.size() * 9 / 10], e.back(),
                   1.0 / d.truth_warp->plan_scale());
    }
    for (const auto& n : r.notes)
      fmt::print("  note {}\n", n);
  });
}

}  // namespace floorgrid::app
