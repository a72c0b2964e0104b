#include "floorgrid/simulation/log_dataset.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/random.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"
#include "floorgrid/maps/plan_units.hpp"
#include "floorgrid/simulation/arc_bend.hpp"
#include "floorgrid/simulation/drawing_raster.hpp"
#include "floorgrid/simulation/manual_pairs.hpp"
#include "floorgrid/simulation/raster_outline.hpp"
#include "floorgrid/simulation/slam_map.hpp"

namespace floorgrid {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kMaxPlanPixels = 2e8;     // a plan raster larger than this is refused
constexpr int kVectorOversampling = 4;     // vector walls are traced on a raster this much finer
constexpr double kVectorTolerance = 0.02;  // metres: vector walls simplified to this

// The log's scans as the occupancy mapper takes them: the corrected laser pose, and readings
// beyond `mapping_range` (or no return) as no return, mapped as free space up to that range.
std::vector<SlamMapInput> mapping_inputs(const RobotLog& log, double mapping_range) {
  std::vector<SlamMapInput> inputs;
  inputs.reserve(log.scans.size());
  for (const LaserScan& scan : log.scans) {
    SlamMapInput in;
    in.laser_pose_in_world = scan.laser_pose;
    in.start_angle = scan.start_angle;
    in.angle_increment = scan.angle_increment;
    in.max_range = std::min(scan.max_range, mapping_range);
    in.ranges.reserve(scan.ranges.size());
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      switch (scan.range_kind(i)) {
        case RangeKind::hit:
          in.ranges.push_back(scan.ranges[i]);
          break;
        case RangeKind::no_return:
          in.ranges.push_back(in.max_range);
          break;
        case RangeKind::too_close:
        case RangeKind::invalid:
          in.ranges.push_back(std::numeric_limits<double>::quiet_NaN());
          break;
      }
    }
    inputs.push_back(std::move(in));
  }
  return inputs;
}

// A grid's cells of one class as an 8-bit mask (255 where true), row iy = cell row iy.
cv::Mat mask_of(const OccupancyGrid& grid, CellState state) {
  cv::Mat mask(grid.height(), grid.width(), CV_8UC1, cv::Scalar(0));
  for (int iy = 0; iy < grid.height(); ++iy) {
    auto* row = mask.ptr<std::uint8_t>(iy);
    for (int ix = 0; ix < grid.width(); ++ix)
      row[ix] = grid.state(ix, iy) == state ? 255 : 0;
  }
  return mask;
}

// The walls a drafter would draw from the gridmap: occupied blobs, counting cells up to 0.2 m
// apart as one, at least `min_extent` metres across (smaller ones are clutter), their gaps of up
// to 0.2 m closed where a closing closes them, thickened by `thickness - 1` cells into space the
// laser never saw free (so the wall's surface stays where the laser found it: see
// drawn_as_wall).
cv::Mat drawn_walls(const OccupancyGrid& gridmap, double min_extent, int thickness,
                    LogDatasetStatistics& s) {
  const cv::Mat cells = mask_of(gridmap, CellState::occupied);
  const int gap = std::max(1, static_cast<int>(std::lround(0.1 / gridmap.resolution())));
  const cv::Mat disk = cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * gap + 1, 2 * gap + 1});
  // A wall seen as dots (sparse scans, beams grazing it) is one wall. Blobs are found on the
  // cells dilated by half the gap: a closing alone does not join the dots of a one-cell line
  // (no disk fits between two dots), which left ACES's corridor walls out of its plan.
  cv::Mat joined, occupied;
  cv::dilate(cells, joined, disk);
  cv::morphologyEx(cells, occupied, cv::MORPH_CLOSE, disk);
  cv::Mat labels;
  const int count = cv::connectedComponents(joined, labels, 8, CV_32S);
  // Each blob's extent over its occupied cells.
  std::vector<cv::Rect> extent(static_cast<std::size_t>(count));
  for (int y = 0; y < cells.rows; ++y) {
    const auto* row = cells.ptr<std::uint8_t>(y);
    const int* label = labels.ptr<int>(y);
    for (int x = 0; x < cells.cols; ++x) {
      if (row[x] == 0)
        continue;
      cv::Rect& r = extent[static_cast<std::size_t>(label[x])];
      r = r.area() == 0 ? cv::Rect(x, y, 1, 1) : (r | cv::Rect(x, y, 1, 1));
    }
  }
  std::vector<std::uint8_t> keep(static_cast<std::size_t>(count), 0);
  for (int label = 1; label < count; ++label) {
    const cv::Rect& r = extent[static_cast<std::size_t>(label)];
    keep[static_cast<std::size_t>(label)] =
        std::hypot(r.width, r.height) * gridmap.resolution() >= min_extent ? 255 : 0;
  }
  cv::Mat walls(occupied.size(), CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < walls.rows; ++y) {
    const auto* closed = occupied.ptr<std::uint8_t>(y);
    const int* label = labels.ptr<int>(y);
    auto* row = walls.ptr<std::uint8_t>(y);
    for (int x = 0; x < walls.cols; ++x) {
      if (closed[x] == 0)
        continue;
      row[x] = keep[static_cast<std::size_t>(label[x])];
      (row[x] != 0 ? s.wall_cells : s.clutter_cells) += 1;
    }
  }
  if (thickness > 1) {
    const int size = 2 * (thickness - 1) + 1;
    cv::Mat thick;
    cv::dilate(walls, thick, cv::getStructuringElement(cv::MORPH_ELLIPSE, {size, size}));
    cv::Mat not_free;
    cv::bitwise_not(mask_of(gridmap, CellState::free), not_free);
    cv::bitwise_and(thick, not_free, thick);
    cv::bitwise_or(thick, walls, walls);
  }
  return walls;
}

// The warp: the plan's world turned by `theta` about the walls' centre into the grid, its long
// axis (the walls' principal axis) bent by `bend` metres at the far end.
WarpParams choose_warp(const Eigen::Matrix2Xd& walls_in_grid, double theta, double bend,
                       LogDatasetStatistics& s) {
  const Eigen::Vector2d centre = walls_in_grid.rowwise().mean();
  WarpParams warp;
  warp.T_grid_world = {centre.x(), centre.y(), theta};
  // The rigid inverse is enough to find the axis: the bend is defined on the world it gives.
  const Eigen::Matrix2Xd world =
      rotation_2d(-theta) * (walls_in_grid.colwise() - centre);  // centred on the origin
  const Eigen::Matrix2d covariance = world * world.transpose() / double(world.cols());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance);
  const Eigen::Vector2d axis = solver.eigenvectors().col(1);  // the larger eigenvalue's
  const Eigen::Vector2d normal(-axis.y(), axis.x());
  const Eigen::RowVectorXd u = axis.transpose() * world;
  const Eigen::RowVectorXd v = normal.transpose() * world;
  const double length = u.maxCoeff() - u.minCoeff();
  warp.bend.axis_origin = axis * u.minCoeff();
  warp.bend.axis_angle = std::atan2(axis.y(), axis.x());
  try {
    warp.bend.curvature = bend == 0.0 ? 0.0 : curvature_for_deviation(bend, length);
  } catch (const InputError& e) {
    std::ostringstream message;
    message << "the walls mapped from the log span " << length
            << " m along their axis: too short to bend by " << bend
            << " m (give a smaller bend, or a log that covers more of the building; " << e.message()
            << ")";
    throw InputError(message.str(), "", 0, "bend");
  }
  s.bend_deviation = bend_deviation(warp.bend.curvature, length);
  s.max_bend_strain = max_strain(warp.bend.curvature, v.cwiseAbs().maxCoeff());
  return warp;
}

// Whether the point at continuous cell coordinates `c` of wall cell (ix, iy) is drawn as wall.
// A laser's wall surface lies, on average, on the centre of the cell its beams ended in, so a
// wall cell's half toward a cell that is no wall is room, not wall, unless the cell is the whole
// wall there (one cell thick along that axis).
bool drawn_as_wall(const cv::Mat& walls, const Eigen::Vector2d& c, int ix, int iy) {
  const auto wall = [&](int jx, int jy) {
    return jx >= 0 && jy >= 0 && jx < walls.cols && jy < walls.rows &&
           walls.at<std::uint8_t>(jy, jx) != 0;
  };
  if (!wall(ix, iy))
    return false;
  const bool low_x = c.x() - ix < 0.5, low_y = c.y() - iy < 0.5;
  const int near_x = low_x ? ix - 1 : ix + 1, far_x = low_x ? ix + 1 : ix - 1;
  const int near_y = low_y ? iy - 1 : iy + 1, far_y = low_y ? iy + 1 : iy - 1;
  if (!wall(near_x, iy) && wall(far_x, iy))
    return false;
  return wall(ix, near_y) || !wall(ix, far_y);
}

// Renders the drawn walls through the warp onto a raster of the world: pixel `pixel` metres,
// lower-left corner at `corner`, set where the point under the pixel's centre is drawn as wall.
cv::Mat render_walls(const cv::Mat& walls, const GridGeometry& geometry, const SimulatedWarp& warp,
                     const Eigen::Vector2d& corner, double pixel, int width, int height) {
  cv::Mat raster(height, width, CV_8UC1, cv::Scalar(0));
  Eigen::Matrix2Xd row_points(2, width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x)
      row_points.col(x) = corner + pixel * Eigen::Vector2d(x + 0.5, y + 0.5);
    const Eigen::Matrix2Xd in_grid = warp.world_to_grid_batch(row_points);
    auto* row = raster.ptr<std::uint8_t>(y);
    for (int x = 0; x < width; ++x) {
      int ix = 0, iy = 0;
      if (geometry.cell_of(in_grid.col(x), ix, iy) &&
          drawn_as_wall(walls, geometry.to_cell_coordinates(in_grid.col(x)), ix, iy)) {
        row[x] = 255;
      }
    }
  }
  return raster;
}

// A number that tells logs apart: their scan count and first pose.
std::uint64_t log_fingerprint(const RobotLog& log) {
  const Pose2& p = log.scans.front().robot_pose;
  std::uint64_t h = 1469598103934665603ull;
  for (const double v : {double(log.scans.size()), p.x, p.y, p.theta}) {
    h ^= static_cast<std::uint64_t>(std::llround(v * 1000.0));
    h *= 1099511628211ull;
  }
  return h;
}

void trace_statistics(const RobotLog& log, LogDatasetStatistics& s) {
  s.scans = log.scans.size();
  std::vector<double> steps, turns;
  for (std::size_t i = 1; i < log.scans.size(); ++i) {
    const Pose2 step = log.scans[i - 1].robot_pose.between(log.scans[i].robot_pose);
    steps.push_back(step.translation().norm());
    turns.push_back(std::abs(step.theta) / kDegree);
    s.path_length += steps.back();
  }
  if (!steps.empty()) {
    s.median_step = median(steps);
    s.median_turn_deg = median(turns);
  }
}

}  // namespace

void validate_log_dataset_options(const LogDatasetOptions& o) {
  const auto positive = [](double value, const char* field) {
    if (!std::isfinite(value) || value <= 0.0)
      throw InputError("must be a finite number > 0", "", 0, field);
  };
  validate_warp_choice(o.plan_scale, o.bend, o.rotation_deg);
  if (o.wall_thickness_px && (*o.wall_thickness_px < 1 || *o.wall_thickness_px > 20))
    throw InputError("must be 1..20 pixels", "", 0, "wall_thickness_px");
  positive(o.resolution, "resolution");
  positive(o.mapping_range, "mapping_range");
  positive(o.min_wall_extent, "min_wall_extent");
  if (!std::isfinite(o.margin) || o.margin < 0.0)
    throw InputError("must be a finite number >= 0", "", 0, "margin");
  if (!plan_unit_from_name(o.drawing_units))
    throw InputError("must be m, cm, mm, in or ft", "", 0, "drawing_units");
  if (!insunits_code(o.header_units))
    throw InputError("must be none, m, cm, mm, in or ft", "", 0, "header_units");
}

LogDataset simulate_from_log(const RobotLog& log, const LogDatasetOptions& options) {
  validate_log_dataset_options(options);
  if (log.scans.size() < 2) {
    throw InputError("the log holds " + std::to_string(log.scans.size()) +
                         " laser scan(s) to map: a run needs at least 2",
                     "", 0, "log");
  }
  // Scans without a beam map nothing (an empty map has no walls to draw a plan from).
  std::size_t readings = 0;
  for (const LaserScan& scan : log.scans)
    readings += scan.ranges.size();
  if (readings == 0) {
    throw InputError("none of the log's " + std::to_string(log.scans.size()) +
                         " laser scans holds a beam: nothing to map",
                     "", 0, "log");
  }
  LogDataset d;
  d.log = log;
  // A log read in line order (every stamp 0) gets stamps 1, 2, ... s in that order, so that
  // the dataset's log is a valid CARMEN log.
  if (std::any_of(d.log.scans.begin(), d.log.scans.end(),
                  [](const LaserScan& s) { return !(s.timestamp > 0.0); })) {
    for (std::size_t i = 0; i < d.log.scans.size(); ++i)
      d.log.scans[i].timestamp = double(i + 1);
    for (std::size_t i = 0; i < d.log.odometry.size(); ++i)
      d.log.odometry[i].timestamp = double(i + 1);
  }
  d.options = options;
  LogDatasetOptions& o = d.options;
  LogDatasetStatistics& s = d.statistics;
  // The choices depend on the log too, so one seed gives each building its own scale, bend and
  // turn (a matrix over many logs then covers the ranges).
  Random random(o.seed ^ log_fingerprint(log));
  Random choices(random.fork()), pairs_random(random.fork());
  if (!o.plan_scale)
    o.plan_scale = std::exp(choices.uniform(std::log(0.5), std::log(2.0)));
  if (!o.bend)
    o.bend = choices.uniform(0.2, 1.0);
  const double bend_sign = choices.bernoulli(0.5) ? 1.0 : -1.0;
  if (!o.rotation_deg)
    o.rotation_deg = choices.uniform(-180.0, 180.0);
  if (!o.wall_thickness_px)
    o.wall_thickness_px = static_cast<int>(choices.integer(2, 4));
  d.plan_per_world = 1.0 / *o.plan_scale;
  s.rotation_deg = *o.rotation_deg;
  s.wall_thickness_px = *o.wall_thickness_px;
  trace_statistics(log, s);

  // The gridmap: occupancy mapping along the corrected poses, in the log's frame.
  SlamMapOptions mapping;
  mapping.resolution = o.resolution;
  d.gridmap = build_slam_map(
      mapping_inputs(log, o.mapping_range), [](const Eigen::Vector2d& p) { return p; }, mapping);
  const CellCounts cells = d.gridmap.counts();
  s.occupied_cells = cells.occupied;
  s.free_cells = cells.free;
  if (cells.occupied == 0)
    throw InputError(
        "the log's scans hit no wall (every reading a no-return): no walls to draw "
        "a plan from",
        "", 0, "log");

  const cv::Mat walls = drawn_walls(d.gridmap, o.min_wall_extent, *o.wall_thickness_px, s);
  const Eigen::Matrix2Xd walls_in_grid = plan_world::set_pixels(walls, d.gridmap.geometry());
  if (walls_in_grid.cols() < 10) {
    throw InputError("the log maps no walls to draw a plan from (" +
                         std::to_string(walls_in_grid.cols()) + " wall cells)",
                     "", 0, "log");
  }
  d.warp = choose_warp(walls_in_grid, *o.rotation_deg * kDegree, bend_sign * *o.bend, s);
  const SimulatedWarp warp(d.warp);

  // The drawing's paper: the drawn walls' extent in the world, plus the margin.
  const BatchInverseResult inverse = warp.grid_to_world_batch(walls_in_grid);
  if (!inverse.converged)
    throw InputError("the bend is too strong for this building to invert", "", 0, "bend");
  s.warp_fit_scale = estimate_transform(inverse.points, walls_in_grid).scale;
  Eigen::AlignedBox2d paper;
  for (Eigen::Index i = 0; i < inverse.points.cols(); ++i)
    paper.extend(inverse.points.col(i));
  const Eigen::Vector2d corner = paper.min().array() - o.margin;
  const Eigen::Vector2d size = paper.sizes().array() + 2.0 * o.margin;
  const int width = static_cast<int>(std::ceil(size.x() / o.resolution));
  const int height = static_cast<int>(std::ceil(size.y() / o.resolution));
  if (double(width) * double(height) > kMaxPlanPixels)
    throw InputError("the plan would be too large to draw", "", 0, "resolution");
  const cv::Mat raster =
      render_walls(walls, d.gridmap.geometry(), warp, corner, o.resolution, width, height);

  GridGeometry plan_geometry;
  plan_geometry.width = width;
  plan_geometry.height = height;
  plan_geometry.resolution = o.resolution * d.plan_per_world;
  plan_geometry.origin = {corner.x() * d.plan_per_world, corner.y() * d.plan_per_world, 0.0};
  d.plan_raster = OccupancyGrid(plan_geometry, CellState::free);
  for (int iy = 0; iy < height; ++iy) {
    const auto* row = raster.ptr<std::uint8_t>(iy);
    for (int ix = 0; ix < width; ++ix) {
      if (row[ix] != 0)
        d.plan_raster.set_state(ix, iy, CellState::occupied);
    }
  }

  if (o.vector_plan) {
    const double fine = o.resolution / kVectorOversampling;
    const cv::Mat detailed =
        render_walls(walls, d.gridmap.geometry(), warp, corner, fine, width * kVectorOversampling,
                     height * kVectorOversampling);
    for (const auto& contour : simplified_outlines(detailed, kVectorTolerance / fine)) {
      for (std::size_t i = 0; i < contour.size() && contour.size() > 1; ++i) {
        const cv::Point& a = contour[i];
        const cv::Point& b = contour[(i + 1) % contour.size()];
        const auto plan_point = [&](const cv::Point& p) -> Eigen::Vector2d {
          return (corner + fine * Eigen::Vector2d(p.x + 0.5, p.y + 0.5)) * d.plan_per_world;
        };
        d.plan_vector.add_segment(plan_point(a), plan_point(b), "WALLS");
      }
    }
    s.plan_segments = d.plan_vector.segments().size();
  }

  ManualPairsOptions pair_options;
  d.manual_pairs = emulate_manual_pairs(
      outline_corners(simplified_outlines(raster, 1.0), {corner, o.resolution}), d.truth(),
      d.plan_per_world, d.gridmap, pair_options, pairs_random);

  d.start_in_grid = log.scans.front().robot_pose;
  const PoseInverseResult start = warp.pose_grid_to_world(d.start_in_grid);
  d.start_in_plan = {start.pose.x * d.plan_per_world, start.pose.y * d.plan_per_world,
                     start.pose.theta};
  return d;
}

}  // namespace floorgrid
