// Accuracy of the dual Monte Carlo localization on a dataset. On a simulated dataset (with a
// truth.json): each filter's pose error over the scans where both were converged, the refined
// poses' errors, the pair error and the scale against the truth. On real data: where the plan
// filter stands against the whole gridmap registered on the plan (one similarity, a rough
// reference). Always: the convergence timeline, why filters were not converged, divergences,
// timings. Usage: localization_accuracy_eval DATASET [--global] [--pictures PREFIX]
//   [--from S --to S --every K]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>

#include "floorgrid/evaluation/overlay.hpp"
#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/logs/carmen_writer.hpp"
#include "floorgrid/pipeline/dual_localizer.hpp"

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

double wrap(double a) {
  return std::remainder(a, 2.0 * M_PI);
}

/// One character per 10 scans.
void print_line(const std::string& title, const std::string& line) {
  fmt::print("{}\n", title);
  for (std::size_t i = 0; i < line.size(); i += 100)
    fmt::print("  {:5d} {}\n", i * 10, line.substr(i, 100));
}

std::string timeline(const DualLocalization& r,
                     const std::function<char(std::size_t, std::size_t)>& of_block) {
  std::string line;
  for (std::size_t i = 0; i < r.scans.size(); i += 10)
    line += of_block(i, std::min(r.scans.size(), i + 10));
  return line;
}

void why_not_converged(const DualLocalization& r, bool plan) {
  std::size_t pos = 0, head = 0, ess = 0, beam = 0, scale = 0, count = 0;
  for (const ScanRecord& s : r.scans) {
    const FilterRecord& f = plan ? s.plan : s.grid;
    if (f.converged || f.state == FilterState::uninitialized)
      continue;
    ++count;
    pos += !f.check.position_ok;
    head += !f.check.heading_ok;
    ess += !f.check.ess_ok;
    beam += !f.check.beam_ok;
    scale += !f.check.scale_ok;
  }
  fmt::print("{} not converged on {} scans: position {} heading {} ess {} fit {} scale {}\n",
             plan ? "plan" : "grid", count, pos, head, ess, beam, scale);
}

/// The gridmap's occupied cells registered on the plan (a rough reference for real data).
PlanRegistration register_whole_map(const io::LoadedDataset& d) {
  const GridGeometry& g = d.gridmap.geometry();
  std::map<std::pair<int, int>, Eigen::Vector2d> bins;
  const Pose2 centre{g.bounds().center().x(), g.bounds().center().y(), 0.0};
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix)
      if (d.gridmap.state(ix, iy) == CellState::occupied) {
        const Eigen::Vector2d p = g.cell_center(ix, iy) - centre.translation();
        bins.emplace(std::pair<int, int>(static_cast<int>(std::floor(p.x() / 0.25)),
                                         static_cast<int>(std::floor(p.y() / 0.25))),
                     p);
      }
  ScanObservation cloud;
  for (const auto& [k, p] : bins) {
    cloud.angle.push_back(0.0f);
    cloud.range.push_back(static_cast<float>(p.norm()));
    cloud.end_x.push_back(static_cast<float>(p.x()));
    cloud.end_y.push_back(static_cast<float>(p.y()));
    cloud.beam.push_back(0);
  }
  LikelihoodFieldOptions lo;
  lo.sigma_hit = 0.3;
  const LikelihoodFieldModel model(d.plan_grid, lo);
  PlanRegistrationOptions ro;
  ro.seeding.position_step = 0.5;
  const PlanRegistrationResult result = register_on_plan(
      d.plan_grid, model, cloud, centre, ScaleRange{.min = 0.8, .max = 1.3}, 1.0, ro);
  return result.registration;
}

void pictures(const io::LoadedDataset& d, const DualLocalization& r, const std::string& prefix,
              std::size_t from, std::size_t to, std::size_t every) {
  // Each filter's trajectory (green converged, red not) and every k-th scan's endpoints.
  for (const bool plan : {true, false}) {
    const OccupancyGrid& map = plan ? d.plan_grid : d.gridmap;
    RgbImage picture = grid_picture(map);
    for (const ScanRecord& s : r.scans) {
      if (s.scan < from || s.scan >= to)
        continue;
      const FilterRecord& f = plan ? s.plan : s.grid;
      if (f.state == FilterState::uninitialized)
        continue;
      Eigen::Matrix2Xd at(2, 1);
      at.col(0) = f.pose.translation();
      draw_points(picture, map.geometry(), at, f.converged ? Colour{0, 160, 0} : Colour{220, 0, 0},
                  0);
      if (s.scan % every == 0) {
        const ScanObservation obs = make_observation(d.log->scans[s.scan], {180});
        Eigen::Matrix2Xd ends(2, static_cast<Eigen::Index>(obs.size()));
        const double k = plan ? 1.0 / r.plan_scale : 1.0;
        for (std::size_t j = 0; j < obs.size(); ++j)
          ends.col(static_cast<Eigen::Index>(j)) =
              f.pose.transform(k * Eigen::Vector2d(obs.end_x[j], obs.end_y[j]));
        draw_points(picture, map.geometry(), ends, Colour{0, 0, 255}, 0);
      }
    }
    io::write_png_rgb(prefix + (plan ? "_plan.png" : "_grid.png"), picture.width, picture.height,
                      picture.rgb);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    fmt::print(stderr,
               "usage: {} DATASET [--global] [--pictures PREFIX] [--from S --to S --every K]\n",
               argv[0]);
    return 2;
  }
  bool global = false;
  std::string picture_prefix;
  std::size_t from = 0, to = SIZE_MAX, every = 50;
  bool plan_beam = false;
  std::size_t plan_particles = 0;
  int plan_beams = 0;
  double plan_sigma = 0.0, beam_sigma = 0.0, beam_temp = 0.0;
  bool no_proposal = false, bad_pairs = false;
  double local_d = 0, local_h = 0;
  std::optional<Pose2> grid_offset;
  std::size_t max_scans = 0;
  int search_scans = 0;
  std::string export_log, poses_out, trace_out;
  bool search_lf = false;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--global")
      global = true;
    else if (a == "--pictures" && i + 1 < argc)
      picture_prefix = argv[++i];
    else if (a == "--from" && i + 1 < argc)
      from = std::stoul(argv[++i]);
    else if (a == "--to" && i + 1 < argc)
      to = std::stoul(argv[++i]);
    else if (a == "--every" && i + 1 < argc)
      every = std::stoul(argv[++i]);
    else if (a == "--plan-beam")
      plan_beam = true;
    else if (a == "--plan-particles" && i + 1 < argc)
      plan_particles = std::stoul(argv[++i]);
    else if (a == "--plan-beams" && i + 1 < argc)
      plan_beams = std::stoi(argv[++i]);
    else if (a == "--plan-sigma" && i + 1 < argc)
      plan_sigma = std::stod(argv[++i]);
    else if (a == "--beam-sigma" && i + 1 < argc)
      beam_sigma = std::stod(argv[++i]);
    else if (a == "--beam-weight" && i + 1 < argc)
      beam_temp = std::stod(argv[++i]);
    else if (a == "--local" && i + 2 < argc) {
      local_d = std::stod(argv[++i]);
      local_h = std::stod(argv[++i]);
    } else if (a == "--grid-offset" && i + 3 < argc) {
      grid_offset = Pose2{std::stod(argv[i + 1]), std::stod(argv[i + 2]), std::stod(argv[i + 3])};
      i += 3;
    } else if (a == "--scans" && i + 1 < argc) {
      max_scans = std::stoul(argv[++i]);
    } else if (a == "--search-scans" && i + 1 < argc) {
      search_scans = std::stoi(argv[++i]);
    } else if (a == "--search-lf") {
      search_lf = true;
    } else if (a == "--export-log" && i + 1 < argc) {
      export_log = argv[++i];
    } else if (a == "--trace" && i + 1 < argc) {
      trace_out = argv[++i];
    } else if (a == "--poses" && i + 1 < argc) {
      poses_out = argv[++i];
    } else if (a == "--bad-pairs")
      bad_pairs = true;
    else if (a == "--no-proposal")
      no_proposal = true;
  }
  const io::LoadedDataset d = io::load_dataset(argv[1]);
  DualLocalizerOptions options;
  if (plan_beam)
    options.plan.model = ObservationModelKind::beam;
  if (plan_particles)
    options.plan.filter.tracking_particles = plan_particles;
  if (plan_beams)
    options.plan.observation.max_beams = plan_beams;
  if (plan_sigma > 0)
    options.plan.likelihood.sigma_hit = plan_sigma;
  if (beam_sigma > 0)
    options.beam.sigma_hit = beam_sigma;
  if (beam_temp > 0)
    options.beam.beam_weight = beam_temp;
  if (local_d > 0) {
    options.dual_check.local_distance = local_d;
    options.dual_check.local_heading = local_h;
  }
  if (search_scans)
    options.scale_search.scans = search_scans;
  if (search_lf)
    options.scale_search.model = ObservationModelKind::likelihood_field;
  if (no_proposal)
    options.plan.runner.improved_proposal = options.grid.runner.improved_proposal = false;
  std::optional<StartPoses> start;
  if (d.manifest.initial_pose && !global)
    start = StartPoses{d.manifest.initial_pose->plan, d.manifest.initial_pose->grid};
  if (start && grid_offset)
    start->grid = start->grid.compose(*grid_offset);
  RobotLog log = *d.log;
  if (max_scans)
    log.scans.resize(std::min(max_scans, log.scans.size()));
  if (!export_log.empty())
    io::write_carmen(log, export_log);
  const auto t0 = std::chrono::steady_clock::now();
  const DualLocalization r = localize_dual({.plan = d.plan_grid,
                                            .gridmap = d.gridmap,
                                            .log = log,
                                            .start = start,
                                            .plan_scale = d.manifest.floorplan_scale,
                                            .plan_geometry = d.plan ? &*d.plan : nullptr},
                                           options);
  if (!r.status.ok) {
    fmt::print("localization failed: {}\n", r.status.message);
    return 1;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  print_line("converged (# both, p plan only, g grid only, . neither)",
             timeline(r, [&](std::size_t a, std::size_t b) {
               int both = 0, plan = 0, grid = 0;
               for (std::size_t k = a; k < b; ++k) {
                 both += r.scans[k].plan.converged && r.scans[k].grid.converged;
                 plan += r.scans[k].plan.converged;
                 grid += r.scans[k].grid.converged;
               }
               return both >= 5 ? '#' : plan >= 5 ? 'p' : grid >= 5 ? 'g' : '.';
             }));
  for (const bool plan : {false, true}) {
    print_line(std::string(plan ? "plan" : "grid") + " fit (tenths; - no information)",
               timeline(r, [&](std::size_t a, std::size_t b) {
                 double f = 0;
                 int n = 0;
                 for (std::size_t k = a; k < b; ++k) {
                   const double v = plan ? r.scans[k].plan.fit : r.scans[k].grid.fit;
                   if (std::isfinite(v)) {
                     f += v;
                     ++n;
                   }
                 }
                 return n == 0 ? '-'
                               : static_cast<char>('0' + std::min(9, static_cast<int>(10 * f / n)));
               }));
    why_not_converged(r, plan);
  }
  std::size_t reinit = 0;
  for (const ScanRecord& s : r.scans)
    reinit += s.plan_reinitialized;
  fmt::print(
      "start     grid scan {} at {:.2f},{:.2f},{:.2f}; plan scan {} at {:.2f},{:.2f},{:.2f}\n",
      r.grid_start_scan, r.start.grid.x, r.start.grid.y, r.start.grid.theta, r.plan_start_scan,
      r.start.plan.x, r.start.plan.y, r.start.plan.theta);
  if (r.registration)
    fmt::print(
        "registration: {} points, {} hypotheses, ll {:.1f} (runner-up {:.1f}), plan origin "
        "{:.2f},{:.2f},{:.2f} scale {:.4f}\n",
        r.registration->points, r.registration->hypotheses, r.registration->log_likelihood,
        r.registration->runner_up_log_likelihood, r.registration->registration.origin_in_plan().x,
        r.registration->registration.origin_in_plan().y,
        r.registration->registration.origin_in_plan().theta, r.registration->registration.scale());
  fmt::print("scale     {:.5f} +- {:.5f} (search {:.5f} +- {:.5f})\n", r.plan_scale,
             r.plan_scale_std, r.plan_scale_search, r.plan_scale_search_std);
  fmt::print(
      "converged {:.3f} in {} periods; plan re-initialized {} times; corrections plan {} grid {}\n",
      r.converged_fraction, r.converged_periods.size(), reinit, r.plan_corrections,
      r.grid_corrections);
  for (const auto* dc : {&r.plan_divergences, &r.grid_divergences})
    for (const auto& [k, v] : dc->by_reason)
      fmt::print("  {} diverged: {} x {}\n", dc == &r.plan_divergences ? "plan" : "grid", v, k);
  for (const auto& [k, v] : r.rejections.by_reason())
    fmt::print("  rejected {}: {}\n", k, v);
  fmt::print(
      "time      {:.1f} s: global {:.1f} s, scale {:.1f} s, localize {:.1f} s, pairs {:.1f} s\n",
      seconds, r.global_localization_seconds, r.scale_search_seconds, r.localize_seconds,
      r.pairs_seconds);
  if (!poses_out.empty()) {
    std::ofstream out(poses_out);
    out << "scan,timestamp,grid_x,grid_y,grid_theta,grid_converged\n";
    for (const ScanRecord& s : r.scans)
      out << fmt::format("{},{:.6f},{:.6f},{:.6f},{:.6f},{}\n", s.scan, log.scans[s.scan].timestamp,
                         s.grid.pose.x, s.grid.pose.y, s.grid.pose.theta, s.grid.converged ? 1 : 0);
  }
  fmt::print("gridmap   filter pass {:.1f} s (global localization included)\n", r.grid_seconds);
  fmt::print("tracking  {:.0f} M particle-beam evaluations in {:.1f} s: {:.0f} M/s end to end\n",
             r.tracking_evaluations / 1e6, r.localize_seconds,
             r.tracking_evaluations / 1e6 / std::max(1e-9, r.localize_seconds));
  for (const auto& n : r.notes)
    fmt::print("note      {}\n", n);
  if (!picture_prefix.empty())
    pictures(d, r, picture_prefix, from, to, every);

  if (!d.truth_warp) {
    const PlanRegistration whole = register_whole_map(d);
    print_line(
        "plan pose vs the whole gridmap registered on the plan (0 <0.25, 1 <0.5, 2 <1, 3 <2, 9 "
        "more m)",
        timeline(r, [&](std::size_t a, std::size_t b) {
          double e = 0;
          int n = 0;
          for (std::size_t k = a; k < b; ++k) {
            if (!r.scans[k].grid.converged || !r.scans[k].plan.converged)
              continue;
            e += (whole.plan_pose(r.scans[k].grid.pose).translation() -
                  r.scans[k].plan.pose.translation())
                     .norm();
            ++n;
          }
          if (n == 0)
            return '-';
          e /= n;
          return e < 0.25 ? '0' : e < 0.5 ? '1' : e < 1.0 ? '2' : e < 2.0 ? '3' : '9';
        }));
    fmt::print("pairs     {}\n", r.pairs.size());
    return 0;
  }

  std::ifstream in(d.manifest.folder() / "truth.json");
  const nlohmann::json truth = nlohmann::json::parse(in);
  const double plan_per_world = truth["plan"]["plan_per_world"];
  std::map<long, std::vector<double>> by_time;  // truth at the odometry period, by time
  for (const auto& p : truth["trajectory"]["poses"])
    by_time[std::lround(p[0].get<double>() * 1000)] = p.get<std::vector<double>>();
  Stats plan_pos, plan_head, grid_pos, grid_head, mplan_pos, mplan_head, mgrid_pos, mgrid_head,
      pair;
  for (const ScanRecord& s : r.scans) {
    if (!(s.plan.converged && s.grid.converged))
      continue;
    const auto it = by_time.find(std::lround(d.log->scans[s.scan].timestamp * 1000));
    if (it == by_time.end())
      continue;
    const auto& t = it->second;
    const auto add = [&](const Pose2& p, const Pose2& g, Stats& pp, Stats& ph, Stats& gp,
                         Stats& gh) {
      pp.v.push_back(std::hypot(p.x - t[1] * plan_per_world, p.y - t[2] * plan_per_world));
      ph.v.push_back(std::abs(wrap(p.theta - t[3])));
      gp.v.push_back(std::hypot(g.x - t[4], g.y - t[5]));
      gh.v.push_back(std::abs(wrap(g.theta - t[6])));
    };
    add(s.plan.pose, s.grid.pose, plan_pos, plan_head, grid_pos, grid_head);
    if (s.plan.match.ok() && s.grid.match.ok())
      add(s.plan.match.pose, s.grid.match.pose, mplan_pos, mplan_head, mgrid_pos, mgrid_head);
  }
  const auto error_char = [](double e) {
    return e < 0.05 ? '0' : e < 0.1 ? '1' : e < 0.25 ? '2' : e < 0.5 ? '3' : e < 1.0 ? '4' : '9';
  };
  for (const bool plan : {true, false})
    print_line(std::string(plan ? "plan" : "grid") +
                   " filter error vs truth (0 <5 cm, 1 <10, 2 <25, 3 <50, 4 <100, 9 more)",
               timeline(r, [&](std::size_t a, std::size_t b) {
                 double e = 0;
                 int n = 0;
                 for (std::size_t k = a; k < b; ++k) {
                   const FilterRecord& f = plan ? r.scans[k].plan : r.scans[k].grid;
                   const auto it = by_time.find(std::lround(d.log->scans[k].timestamp * 1000));
                   if (it == by_time.end() || f.state == FilterState::uninitialized)
                     continue;
                   const auto& t = it->second;
                   e += plan ? std::hypot(f.pose.x - t[1] * plan_per_world,
                                          f.pose.y - t[2] * plan_per_world)
                             : std::hypot(f.pose.x - t[4], f.pose.y - t[5]);
                   ++n;
                 }
                 return n ? error_char(e / n) : '-';
               }));
  if (!trace_out.empty()) {
    // One line per scan: each filter's state and its error against the truth.
    std::ofstream out(trace_out);
    out << "scan,step_m,turn_deg,grid_conv,grid_err,grid_fit,grid_match,plan_state,plan_conv,"
           "plan_err,plan_head_deg,plan_fit,pos_std,head_std,plan_match,match_err,reinit,"
           "consistent,pairs,grid_pos_std,grid_head_std,grid_updated,plan_guide\n";
    for (const ScanRecord& s : r.scans) {
      // The truth holds one pose per scan in line order (timestamps may repeat).
      if (s.scan >= truth["trajectory"]["poses"].size())
        continue;
      const std::vector<double> t = truth["trajectory"]["poses"][s.scan].get<std::vector<double>>();
      double step = 0.0, turn = 0.0;
      if (s.scan > 0) {
        const Pose2 a = d.log->scans[s.scan - 1].robot_pose, b = d.log->scans[s.scan].robot_pose;
        step = std::hypot(b.x - a.x, b.y - a.y);
        turn = std::abs(wrap(b.theta - a.theta)) * 180 / M_PI;
      }
      out << fmt::format(
                 "{},{:.3f},{:.1f},{},{:.3f},{:.2f},{},{},{},{:.3f},{:.2f},{:.2f},{:.3f},{:.3f},{},"
                 "{:.3f},"
                 "{},"
                 "{},{}",
                 s.scan, step, turn, s.grid.converged ? 1 : 0,
                 std::hypot(s.grid.pose.x - t[4], s.grid.pose.y - t[5]), s.grid.fit,
                 to_string(s.grid.match.failure), to_string(s.plan.state), s.plan.converged ? 1 : 0,
                 std::hypot(s.plan.pose.x - t[1] * plan_per_world,
                            s.plan.pose.y - t[2] * plan_per_world),
                 wrap(s.plan.pose.theta - t[3]) * 180 / M_PI, s.plan.fit,
                 s.plan.estimate.position_std, s.plan.estimate.heading_std,
                 to_string(s.plan.match.failure),
                 std::hypot(s.plan.match.pose.x - t[1] * plan_per_world,
                            s.plan.match.pose.y - t[2] * plan_per_world),
                 s.plan_reinitialized ? 1 : 0, s.consistent ? 1 : 0, s.pairs)
          << fmt::format(",{:.3f},{:.3f},{},{}\n", s.grid.estimate.position_std,
                         s.grid.estimate.heading_std, s.grid.updated ? 1 : 0, 0);
    }
  }
  for (Eigen::Index i = 0; i < r.pairs.size(); ++i)
    pair.v.push_back(
        (d.truth_warp->plan_to_grid(r.pairs.points_in_plan.col(i)) - r.pairs.points_in_grid.col(i))
            .norm());
  if (bad_pairs) {
    Eigen::Index k = 0;
    for (const ScanRecord& s : r.scans) {
      double worst = 0.0, sum = 0.0;
      for (std::size_t j = 0; j < s.pairs; ++j, ++k) {
        worst = std::max(worst, pair.v[static_cast<std::size_t>(k)]);
        sum += pair.v[static_cast<std::size_t>(k)];
      }
      if (s.pairs && sum / s.pairs > 0.15) {
        const auto it = by_time.find(std::lround(d.log->scans[s.scan].timestamp * 1000));
        const auto& t = it->second;
        fmt::print(
            "scan {} pairs {} mean {:.3f} worst {:.3f}; plan match err {:.3f} m {:.2f} deg in "
            "{}/{} c {:.2f}; grid match err {:.3f} m {:.2f} deg\n",
            s.scan, s.pairs, sum / s.pairs, worst,
            std::hypot(s.plan.match.pose.x - t[1] * plan_per_world,
                       s.plan.match.pose.y - t[2] * plan_per_world),
            wrap(s.plan.match.pose.theta - t[3]) * 180 / M_PI, s.plan.match.inliers,
            s.plan.match.endpoints, s.plan.match.constraint,
            std::hypot(s.grid.match.pose.x - t[4], s.grid.match.pose.y - t[5]),
            wrap(s.grid.match.pose.theta - t[6]) * 180 / M_PI);
      }
    }
  }
  fmt::print("true scale {:.5f}\n", 1.0 / plan_per_world);
  fmt::print("plan pose         {}; heading {} deg\n", plan_pos.text(), plan_head.text(180 / M_PI));
  fmt::print("grid pose         {}; heading {} deg\n", grid_pos.text(), grid_head.text(180 / M_PI));
  fmt::print("matched plan pose {}; heading {} deg\n", mplan_pos.text(),
             mplan_head.text(180 / M_PI));
  fmt::print("matched grid pose {}; heading {} deg\n", mgrid_pos.text(),
             mgrid_head.text(180 / M_PI));
  fmt::print("pairs     {}: error {}\n", r.pairs.size(), pair.text());
  return 0;
}
