#include "floorgrid/simulation/plan_dataset.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"
#include "floorgrid/simulation/arc_bend.hpp"
#include "floorgrid/simulation/manual_pairs.hpp"
#include "floorgrid/simulation/segment_ray_caster.hpp"
#include "floorgrid/simulation/simulated_run.hpp"
#include "floorgrid/simulation/slam_map.hpp"

namespace floorgrid {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kMaxFitPoints = 200'000;  // drawn ink points the warp's similarity is fitted on
constexpr double kMinRoomJacobian = 0.3;   // a turned room whose blend folds less is refused

// A number that tells drawings apart, so that one seed gives each drawing its own choices.
std::uint64_t drawing_fingerprint(const PlanDrawing& drawing) {
  std::vector<double> values;
  if (drawing.raster) {
    const GridGeometry& g = drawing.raster->geometry();
    const CellCounts c = drawing.raster->counts();
    values = {double(g.width), double(g.height),   g.resolution,  g.origin.x,
              g.origin.y,      double(c.occupied), double(c.free)};
  } else {
    const Eigen::AlignedBox2d box = drawing.vector.bounds();
    values = {double(drawing.vector.segments().size()),
              double(drawing.vector.arcs().size()),
              box.min().x(),
              box.min().y(),
              box.max().x(),
              box.max().y()};
  }
  std::uint64_t h = 1469598103934665603ull;
  for (const double v : values) {
    h ^= static_cast<std::uint64_t>(std::llround(v * 1000.0));
    h *= 1099511628211ull;
  }
  return h;
}

// The turned room: a visited room (not a corridor) of at least 9 square metres, turned as a
// whole with its walls' inner faces, blended out over the band beyond them.
std::optional<RoomRotation> choose_room(const PlanDataset& d, Random& random) {
  const SimulationPreset& p = d.options.run;
  std::vector<std::size_t> rooms;
  for (std::size_t r = 0; r < d.world.regions.size(); ++r) {
    const WorldRegion& region = d.world.regions[r];
    if (region.visited && region.kind == "room" && region.area >= 9.0 &&
        region.box.sizes().minCoeff() >= 2.5)
      rooms.push_back(r);
  }
  for (std::size_t i = rooms.size(); i > 1; --i)
    std::swap(rooms[i - 1],
              rooms[static_cast<std::size_t>(random.integer(0, static_cast<std::int64_t>(i) - 1))]);
  const double sign = random.bernoulli(0.5) ? 1.0 : -1.0;
  const double angle =
      sign * random.uniform(p.room_rotation_min_deg, p.room_rotation_max_deg) * kDegree;
  for (const std::size_t r : rooms) {
    RoomRotation room;
    room.core = d.world.regions[r].box;
    room.band = p.room_rotation_band;
    room.center = room.core.center();
    room.angle = angle;
    if (min_jacobian_determinant(room, 0.05) >= kMinRoomJacobian)
      return room;
  }
  return std::nullopt;
}

// The gridmap's distortion: turned by the rotation about the drawing's centre and moved a few
// metres, its long axis (the drawn walls' principal axis) bent, one room turned.
WarpParams choose_warp(const PlanDataset& d, double bend_sign, Random& random,
                       PlanDatasetStatistics& s) {
  const Eigen::Matrix2Xd& ink = d.world.drawn_ink;
  const Eigen::Vector2d centre = ink.rowwise().mean();
  const Eigen::Matrix2Xd centred = ink.colwise() - centre;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(centred * centred.transpose());
  const Eigen::Vector2d axis = solver.eigenvectors().col(1);
  const Eigen::Vector2d normal(-axis.y(), axis.x());
  const Eigen::RowVectorXd u = axis.transpose() * centred;
  const Eigen::RowVectorXd v = normal.transpose() * centred;
  const double length = std::max(u.maxCoeff() - u.minCoeff(), 1.0);
  WarpParams warp;
  const double theta = *d.options.rotation_deg * kDegree;
  const Eigen::Vector2d offset(random.uniform(-5.0, 5.0), random.uniform(-5.0, 5.0));
  const Eigen::Vector2d t = offset - rotation_2d(theta) * centre;
  warp.T_grid_world = {t.x(), t.y(), theta};
  warp.bend.axis_origin = centre + axis * u.minCoeff();
  warp.bend.axis_angle = std::atan2(axis.y(), axis.x());
  warp.bend.curvature =
      *d.options.bend == 0.0 ? 0.0 : curvature_for_deviation(bend_sign * *d.options.bend, length);
  s.bend_deviation = bend_deviation(warp.bend.curvature, length);
  s.max_bend_strain = max_strain(warp.bend.curvature, v.cwiseAbs().maxCoeff());
  warp.room = choose_room(d, random);
  if (warp.room) {
    s.room_rotation_deg = warp.room->angle / kDegree;
    s.min_room_jacobian = min_jacobian_determinant(*warp.room, 0.05);
  }
  return warp;
}

// The scale of the least-squares similarity world -> grid over the drawn walls.
double warp_fit_scale(const Eigen::Matrix2Xd& ink, const SimulatedWarp& warp) {
  const Eigen::Index step =
      std::max<Eigen::Index>(1, static_cast<Eigen::Index>(std::ceil(ink.cols() / kMaxFitPoints)));
  Eigen::Matrix2Xd world(2, (ink.cols() + step - 1) / step);
  for (Eigen::Index i = 0; i < world.cols(); ++i)
    world.col(i) = ink.col(i * step);
  return estimate_transform(world, warp.world_to_grid_batch(world)).scale;
}

void count_statistics(const PlanDataset& d, const SimulatedRun& run, PlanDatasetStatistics& s) {
  s.path_length = path_length(d.true_trajectory);
  s.duration = d.true_trajectory.back().time - d.true_trajectory.front().time;
  s.scans = d.log.scans.size();
  s.beams = run.counts.beams;
  s.returns = run.counts.returns;
  const auto hits = [&](SurfaceKind kind) {
    const auto it = run.counts.true_hits_per_layer.find(static_cast<int>(kind));
    return it == run.counts.true_hits_per_layer.end() ? std::size_t{0} : it->second;
  };
  s.wall_beams = hits(SurfaceKind::wall);
  s.furniture_beams = hits(SurfaceKind::furniture);
  s.door_beams = hits(SurfaceKind::door_leaf);
  s.column_beams = hits(SurfaceKind::column) + hits(SurfaceKind::mullion);
  s.clutter_fraction = s.beams ? double(s.furniture_beams + s.door_beams) / double(s.beams) : 0.0;
  const Pose2 start = d.true_trajectory.front().pose;
  const Pose2 true_end = start.between(d.true_trajectory.back().pose);
  s.final_odometry_error = (true_end.translation() - run.final_odometry.translation()).norm();
  const CellCounts cells = d.gridmap.counts();
  s.occupied_cells = cells.occupied;
  s.free_cells = cells.free;
  s.unknown_cells = cells.unknown;
}

}  // namespace

void validate_plan_dataset_options(const PlanDatasetOptions& o) {
  validate_warp_choice(o.plan_scale, o.bend, o.rotation_deg);
  if (!(o.min_plan_scale > 0.0 && o.max_plan_scale >= o.min_plan_scale &&
        std::isfinite(o.max_plan_scale)))
    throw InputError("must be 0 < min <= max", "", 0, "plan_scale_range");
  if (!(o.bend_range.min >= 0.0 && o.bend_range.max >= o.bend_range.min &&
        o.bend_range.max <= 20.0))
    throw InputError("must be 0 <= min <= max <= 20 metres", "", 0, "bend_range");
  if (!(o.min_doorway > 0.0 && std::isfinite(o.min_doorway)))
    throw InputError("must be a finite number > 0", "", 0, "min_doorway");
  if (!(o.tour.clearance > 0.0 && o.tour.resolution > 0.0 && o.tour.goal_spacing > 0.0 &&
        o.tour.max_length > 0.0 && o.tour.wall_distance > 0.0 && o.tour.wall_penalty >= 0.0))
    throw InputError("must be finite numbers > 0", "", 0, "tour");
}

PlanDataset simulate_from_plan(const PlanDrawing& drawing, const PlanDatasetOptions& options) {
  validate_plan_dataset_options(options);
  PlanDataset d;
  d.options = options;
  PlanDatasetOptions& o = d.options;
  PlanDatasetStatistics& s = d.statistics;
  Random random(o.seed ^ drawing_fingerprint(drawing));
  Random choices(random.fork()), world_random(random.fork()), tour_random(random.fork()),
      odometry_random(random.fork()), laser_random(random.fork()), warp_random(random.fork()),
      pairs_random(random.fork());
  // The plan's scale; a vector drawing's world is its plan scaled, so it must stay walkable.
  s.plan_scale_low = o.min_plan_scale;
  if (!o.plan_scale) {
    if (!drawing.raster) {
      const double width = median_doorway_width(drawing, 1.0, o.world);
      if (width > 0.0)
        s.plan_scale_low = std::clamp(o.min_doorway / width, o.min_plan_scale, o.max_plan_scale);
    }
    o.plan_scale =
        std::exp(choices.uniform(std::log(s.plan_scale_low), std::log(o.max_plan_scale)));
  }
  s.plan_scale = *o.plan_scale;
  if (!o.bend)
    o.bend = choices.uniform(o.bend_range.min, o.bend_range.max);
  const double bend_sign = choices.bernoulli(0.5) ? 1.0 : -1.0;
  if (!o.rotation_deg)
    o.rotation_deg = choices.uniform(-180.0, 180.0);
  s.rotation_deg = *o.rotation_deg;

  // A raster drawing is the world at its stated resolution (its plan carries the scale); a
  // vector drawing is the plan, the world its scaled copy.
  const double drawing_to_world = drawing.raster ? 1.0 : s.plan_scale;
  d.world = build_plan_world(drawing, drawing_to_world, o.world, o.drawing_errors, o.tour.clearance,
                             world_random);
  s.raster_resolution = d.world.raster.resolution;
  d.tour = plan_tour(d.world, o.tour, tour_random);
  for (const int r : d.tour.visited)
    d.world.regions[static_cast<std::size_t>(r)].visited = true;
  d.true_trajectory = drive_tour(d.tour.waypoints, o.run.tour);
  if (d.true_trajectory.size() < 2)
    throw InputError("the robot's tour has no leg to drive", "", 0, "plan");

  const SegmentRayCaster caster(d.world.world_segments());
  SimulatedRun run = simulate_run(d.true_trajectory, caster, o.run, odometry_random, laser_random);
  d.log = std::move(run.log);

  d.warp = choose_warp(d, bend_sign, warp_random, s);
  const SimulatedWarp warp(d.warp);
  SlamMapOptions map_options;
  map_options.resolution = o.run.gridmap_resolution;
  d.gridmap = build_slam_map(
      run.slam_inputs, [&](const Eigen::Vector2d& q) { return warp.world_to_grid(q); },
      map_options);
  s.warp_fit_scale = warp_fit_scale(d.world.drawn_ink, warp);

  const PlanTruth truth = d.truth();
  ManualPairsOptions pair_options;
  pair_options.min_pairs = o.run.min_manual_pairs;
  pair_options.max_pairs = o.run.max_manual_pairs;
  pair_options.noise = o.run.manual_pair_noise;
  // A drawn corner lies inside its wall, up to half the thickest wall from the face seen.
  pair_options.visible_within =
      1 + static_cast<int>(std::ceil(d.world.exterior_thickness / 2 / o.run.gridmap_resolution));
  d.manual_pairs = emulate_manual_pairs(d.world.drawn_corners, truth, 1.0 / s.plan_scale, d.gridmap,
                                        pair_options, pairs_random);
  const Pose2 start = d.true_trajectory.front().pose;
  d.start_in_plan = {start.x / s.plan_scale, start.y / s.plan_scale, start.theta};
  d.start_in_grid = warp.pose_world_to_grid(start);
  count_statistics(d, run, s);
  return d;
}

}  // namespace floorgrid
