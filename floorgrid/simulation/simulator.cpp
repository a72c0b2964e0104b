#include "floorgrid/simulation/simulator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/maps/plan_units.hpp"
#include "floorgrid/simulation/arc_bend.hpp"
#include "floorgrid/simulation/laser_simulator.hpp"
#include "floorgrid/simulation/manual_pairs.hpp"
#include "floorgrid/simulation/segment_ray_caster.hpp"
#include "floorgrid/simulation/simulated_run.hpp"
#include "floorgrid/simulation/slam_map.hpp"

namespace floorgrid {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

/// The gridmap's distortion: a random rigid frame with the start near its origin, the bend of
/// the building's long axis and the chosen room turned about its centre.
WarpParams choose_warp(const SimulatedDataset& d, const Pose2& start, Random& random) {
  const SimulationPreset& p = d.preset;
  const Building& b = d.building;
  WarpParams w;
  const double theta = random.uniform(-std::numbers::pi, std::numbers::pi);
  const Eigen::Vector2d offset(random.uniform(-5.0, 5.0), random.uniform(-5.0, 5.0));
  const Eigen::Vector2d t = offset - rotation_2d(theta) * start.translation();
  w.T_grid_world = {t.x(), t.y(), theta};
  const double sign = random.bernoulli(0.5) ? 1.0 : -1.0;
  w.bend = {b.axis_origin, b.axis_angle,
            sign * curvature_for_deviation(p.bend_deviation, b.length)};
  if (b.rotated_room >= 0) {
    const Room& room = b.rooms[static_cast<std::size_t>(b.rotated_room)];
    RoomRotation r;
    // The whole room turns, both faces of its walls included; the blend lies outside them.
    const double grow = room.doors.front().wall_thickness + 0.02;
    r.core =
        Eigen::AlignedBox2d(room.interior.min().array() - grow, room.interior.max().array() + grow);
    r.band = p.room_rotation_band;
    r.center = room.interior.center();
    r.angle = (random.bernoulli(0.5) ? 1.0 : -1.0) *
              random.uniform(p.room_rotation_min_deg, p.room_rotation_max_deg) * kDegree;
    w.room = r;
  }
  return w;
}

}  // namespace

void validate(const SimulationOptions& o) {
  require_option(std::isfinite(o.scan_rate) && o.scan_rate > 0.0, "scan_rate", o.scan_rate,
                 "a positive number of scans a second");
  require_option(std::isfinite(o.max_duration) && o.max_duration > 0.0, "max_duration",
                 o.max_duration, "a positive number of seconds");
  if (o.duration) {
    const double d = *o.duration;
    require_option(std::isfinite(d) && d > 0.0, "duration", d, "a positive number of seconds");
    require_option(d <= o.max_duration, "duration", d,
                   fmt::format("at most {:g} seconds", o.max_duration));
    require_option(d * o.scan_rate >= 2.0, "duration", d,
                   fmt::format("at least {:g} seconds (two scans)", 2.0 / o.scan_rate));
  }
}

SimulatedDataset simulate(const std::string& preset_name, std::uint64_t seed,
                          const SimulationOptions& options) {
  validate(options);
  SimulatedDataset d;
  d.preset = simulation_preset(preset_name);
  d.seed = seed;
  if (options.duration) {
    // A scan with every odometry reading, at the rate asked (truth.json says so).
    d.preset.scan_period = 1.0 / options.scan_rate;
    d.preset.tour.tick = d.preset.scan_period;
  }
  const SimulationPreset& p = d.preset;
  // Independent streams, so that a change in one stage does not reshuffle the others.
  Random random(seed);
  Random building_random(random.fork()), warp_random(random.fork()), odometry_random(random.fork()),
      laser_random(random.fork()), pairs_random(random.fork());

  d.building = generate_building({p.building}, building_random);
  const Building& b = d.building;
  const double e = p.max_plan_scale_error;
  d.plan_scale = e > 0.0 ? 1.0 + warp_random.uniform(-e, e) : 1.0;
  d.drawing_units_per_metre = 1.0 / metres_per_unit(*plan_unit_from_name(p.drawing_units));
  d.plan = b.plan_in_world().scaled(d.plan_scale);

  d.true_trajectory = options.duration ? drive_tour_for(b.tour, *options.duration, p.tour)
                                       : drive_tour(b.tour, p.tour);
  const Pose2 start = d.true_trajectory.front().pose;
  d.warp = choose_warp(d, start, warp_random);
  const SimulatedWarp warp(d.warp);
  d.start_in_plan = {start.x * d.plan_scale, start.y * d.plan_scale, start.theta};
  d.start_in_grid = warp.pose_world_to_grid(start);

  // The run: noisy odometry every tick and a scan every scan period, as a robot logs them.
  const SegmentRayCaster caster(b.world_segments());
  SimulatedRun run = simulate_run(d.true_trajectory, caster, p, odometry_random, laser_random);
  d.log = std::move(run.log);
  const std::vector<SlamMapInput>& slam_inputs = run.slam_inputs;
  const LaserScanCounts& counts = run.counts;
  const Pose2& odometry = run.final_odometry;

  SlamMapOptions map_options;
  map_options.resolution = p.gridmap_resolution;
  d.gridmap = build_slam_map(
      slam_inputs, [&](const Eigen::Vector2d& q) { return warp.world_to_grid(q); }, map_options);

  ManualPairsOptions pair_options;
  pair_options.min_pairs = p.min_manual_pairs;
  pair_options.max_pairs = p.max_manual_pairs;
  pair_options.noise = p.manual_pair_noise;
  // An operator clicks corners of walls and of racks, both drawn in the plan.
  std::vector<Eigen::Vector2d> corners = b.wall_corners;
  for (const auto& rack : b.rack_boxes) {
    for (const auto c : {Eigen::AlignedBox2d::BottomLeft, Eigen::AlignedBox2d::BottomRight,
                         Eigen::AlignedBox2d::TopLeft, Eigen::AlignedBox2d::TopRight}) {
      corners.push_back(rack.corner(c));
    }
  }
  d.manual_pairs =
      emulate_manual_pairs(corners, d.truth(), d.plan_scale, d.gridmap, pair_options, pairs_random);

  SimulationStatistics& s = d.statistics;
  s.rooms = b.rooms.size();
  s.rooms_visited = static_cast<std::size_t>(
      std::count_if(b.rooms.begin(), b.rooms.end(), [](const Room& r) { return r.visited; }));
  s.path_length = path_length(d.true_trajectory);
  s.duration = d.true_trajectory.back().time - d.true_trajectory.front().time;
  s.scans = d.log.scans.size();
  s.beams = counts.beams;
  s.returns = counts.returns;
  for (const auto kind : {SurfaceKind::furniture, SurfaceKind::door_leaf}) {
    const auto it = counts.true_hits_per_layer.find(static_cast<int>(kind));
    if (it != counts.true_hits_per_layer.end())
      s.furniture_beams += it->second;
  }
  s.furniture_fraction = counts.beams ? double(s.furniture_beams) / double(counts.beams) : 0.0;
  s.max_bend_strain = max_strain(d.warp.bend.curvature, b.half_width);
  s.bend_deviation = bend_deviation(std::abs(d.warp.bend.curvature), b.length);
  if (d.warp.room) {
    s.room_rotation_deg = d.warp.room->angle / kDegree;
    s.min_room_jacobian = min_jacobian_determinant(*d.warp.room, 0.05);
  }
  const Pose2 true_end_in_odometry = start.between(d.true_trajectory.back().pose);
  s.final_odometry_error = (true_end_in_odometry.translation() - odometry.translation()).norm();
  const CellCounts cells = d.gridmap.counts();
  s.occupied_cells = cells.occupied;
  s.free_cells = cells.free;
  s.unknown_cells = cells.unknown;
  return d;
}

}  // namespace floorgrid
