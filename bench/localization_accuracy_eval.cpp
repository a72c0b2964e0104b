// Accuracy of the dual Monte Carlo localization on a simulated dataset, against its truth.json:
// each filter's pose error over the scans where both were converged, the pair error, the scale,
// the convergence and the timings. Usage: localization_accuracy_eval DATASET [seed]
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "floorgrid/io/dataset_loader.hpp"
#include "floorgrid/localization/dual_localizer.hpp"
#include "floorgrid/localization/scan_matcher.hpp"

using namespace floorgrid;

namespace {

struct Stats {
  std::vector<double> v;
  std::string text(double scale = 1.0) const {
    if (v.empty())
      return "-";
    std::vector<double> s = v;
    std::sort(s.begin(), s.end());
    return fmt::format("median {:.4f} p90 {:.4f} max {:.4f}", scale * s[s.size() / 2],
                       scale * s[s.size() * 9 / 10], scale * s.back());
  }
};

double wrap(double a) { return std::remainder(a, 2.0 * M_PI); }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    fmt::print(stderr, "usage: {} DATASET [seed]\n", argv[0]);
    return 2;
  }
  const io::LoadedDataset d = io::load_dataset(argv[1]);
  DualLocalizerOptions o;
  if (argc > 2)
    o.seed = std::stoull(argv[2]);
  if (const char* e = std::getenv("FG_ESS")) {
    o.plan_filter.convergence.min_ess_ratio = std::atof(e);
    o.grid_filter.convergence.min_ess_ratio = std::atof(e);
  }
  std::optional<StartPoses> start;
  if (d.manifest.initial_pose && !std::getenv("FG_GLOBAL"))
    start = StartPoses{d.manifest.initial_pose->plan, d.manifest.initial_pose->grid};
  const DualLocalization r =
      localize_dual(d.plan_grid, d.gridmap, *d.log, start, d.manifest.floorplan_scale, o, {},
                    d.plan ? &*d.plan : nullptr);

  std::ifstream in(d.manifest.folder() / "truth.json");
  const nlohmann::json truth = nlohmann::json::parse(in);
  const double plan_per_world = truth["plan"]["plan_per_world"];
  const auto& poses = truth["trajectory"]["poses"];
  // time -> row (truth is sampled at the odometry period; scans fall on those times)
  std::map<long, std::vector<double>> by_time;
  for (const auto& p : poses)
    by_time[std::lround(p[0].get<double>() * 1000)] = p.get<std::vector<double>>();
  const WallField grid_walls(d.gridmap);
  const WallField plan_walls = d.plan ? WallField(*d.plan, d.plan_grid.geometry()) : WallField(d.plan_grid);
  Stats tgrid_pos, tgrid_head, tplan_pos, tplan_head;
  Stats plan_pos, plan_head, grid_pos, grid_head, pair, mplan_pos, mplan_head, mgrid_pos, mgrid_head;
  for (const ScanRecord& s : r.scans) {
    if (!(s.plan_converged && s.grid_converged))
      continue;
    const auto it = by_time.find(std::lround(d.log->scans[s.scan].timestamp * 1000));
    if (it == by_time.end())
      continue;
    const auto& t = it->second;
    plan_pos.v.push_back(
        std::hypot(s.plan_pose.x - t[1] * plan_per_world, s.plan_pose.y - t[2] * plan_per_world));
    plan_head.v.push_back(std::abs(wrap(s.plan_pose.theta - t[3])));
    grid_pos.v.push_back(std::hypot(s.grid_pose.x - t[4], s.grid_pose.y - t[5]));
    grid_head.v.push_back(std::abs(wrap(s.grid_pose.theta - t[6])));
    {
      const ScanObservation obs = make_observation(d.log->scans[s.scan], {180});
      const ScanMatch g = match_scan(grid_walls, obs, Pose2{t[4], t[5], t[6]}, 1.0);
      tgrid_pos.v.push_back(std::hypot(g.pose.x - t[4], g.pose.y - t[5]));
      tgrid_head.v.push_back(std::abs(wrap(g.pose.theta - t[6])));
      const ScanMatch p = match_scan(plan_walls, obs,
                                     Pose2{t[1] * plan_per_world, t[2] * plan_per_world, t[3]},
                                     1.0 / plan_per_world);
      tplan_pos.v.push_back(std::hypot(p.pose.x - t[1] * plan_per_world, p.pose.y - t[2] * plan_per_world));
      tplan_head.v.push_back(std::abs(wrap(p.pose.theta - t[3])));
    }
    if (s.plan_match.ok() && s.grid_match.ok()) {
      const Pose2& p = s.plan_match.pose;
      const Pose2& g = s.grid_match.pose;
      mplan_pos.v.push_back(std::hypot(p.x - t[1] * plan_per_world, p.y - t[2] * plan_per_world));
      mplan_head.v.push_back(std::abs(wrap(p.theta - t[3])));
      mgrid_pos.v.push_back(std::hypot(g.x - t[4], g.y - t[5]));
      mgrid_head.v.push_back(std::abs(wrap(g.theta - t[6])));
    }
  }
  const auto tally = [&](bool plan) {
    std::size_t pos = 0, head = 0, ess = 0, beam = 0, scale = 0, not_conv = 0;
    for (const ScanRecord& s : r.scans) {
      const ConvergenceCheck& c = plan ? s.plan_check : s.grid_check;
      if ((plan ? s.plan_converged : s.grid_converged))
        continue;
      ++not_conv;
      pos += !c.position_ok;
      head += !c.heading_ok;
      ess += !c.ess_ok;
      beam += !c.beam_ok;
      scale += !c.scale_ok;
    }
    fmt::print("{} not converged on {} scans: position {} heading {} ess {} beam {} scale {}\n",
               plan ? "plan" : "grid", not_conv, pos, head, ess, beam, scale);
  };
  tally(true);
  tally(false);
  for (Eigen::Index i = 0; i < r.pairs.size(); ++i) {
    pair.v.push_back(
        (d.truth_warp->plan_to_grid(r.pairs.points_in_plan.col(i)) - r.pairs.points_in_grid.col(i))
            .norm());
  }
  if (std::getenv("FG_DUMP")) {
    Eigen::Index k = 0;
    for (const ScanRecord& s : r.scans) {
      double worst = 0.0;
      for (std::size_t j = 0; j < s.pairs; ++j, ++k)
        worst = std::max(worst, pair.v[static_cast<std::size_t>(k)]);
      if (worst > 0.2) {
        fmt::print("scan {} pairs {} worst {:.3f} plan in {} c {:.3f} rms {:.3f} grid in {} c {:.3f} rms {:.3f}\n",
                   s.scan, s.pairs, worst, s.plan_match.inliers, s.plan_match.constraint,
                   s.plan_match.rms, s.grid_match.inliers, s.grid_match.constraint,
                   s.grid_match.rms);
      }
    }
  }
  fmt::print("scale     {:.5f} +- {:.5f} (true {:.5f})\n", r.plan_scale, r.plan_scale_std,
             1.0 / plan_per_world);
  fmt::print("converged {:.3f}, divergences plan {} grid {}, {} periods\n", r.converged_fraction,
             r.plan_divergences, r.grid_divergences, r.converged_periods.size());
  fmt::print("plan pos  {}\nplan head {} deg\n", plan_pos.text(), plan_head.text(180 / M_PI));
  fmt::print("grid pos  {}\ngrid head {} deg\n", grid_pos.text(), grid_head.text(180 / M_PI));
  fmt::print("matched plan pos  {}\nmatched plan head {} deg\n", mplan_pos.text(),
             mplan_head.text(180 / M_PI));
  fmt::print("matched grid pos  {}\nmatched grid head {} deg\n", mgrid_pos.text(),
             mgrid_head.text(180 / M_PI));
  fmt::print("from truth: plan pos {} head {} deg\n", tplan_pos.text(), tplan_head.text(180/M_PI));
  fmt::print("from truth: grid pos {} head {} deg\n", tgrid_pos.text(), tgrid_head.text(180/M_PI));
  fmt::print("pairs     {}: {}\n", r.pairs.size(), pair.text());
  fmt::print("time      global {:.1f} s, scale {:.1f} s, localize {:.1f} s\n",
             r.global_localization_seconds, r.scale_search_seconds, r.localize_seconds);
  for (const auto& n : r.notes)
    fmt::print("note      {}\n", n);
  return 0;
}
