#include "floorgrid/pipeline/map_alignment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <set>

#include "floorgrid/core/statistics.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/geometry/displacement_lattice.hpp"
#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"
#include "floorgrid/maps/wall_surface_field.hpp"
#include "floorgrid/pipeline/wall_faces.hpp"
#include "floorgrid/pipeline/wall_slide.hpp"

namespace floorgrid {

namespace {

// A gridmap wall point and its wall's normal in the grid (zero at a corner or a blob), and
// the side the robot saw it from: the normal towards the free side (zero when not one side).
struct WallPoint {
  Eigen::Vector2d point;
  Eigen::Vector2d normal;
  Eigen::Vector2d facing = Eigen::Vector2d::Zero();
};

// The unit normal towards the side of the wall at `point` that the gridmap holds free: the next
// cell along the normal free on one side, and not on the other (a wall's inside, occupied or
// unknown); zero otherwise (a one-cell wall seen from both sides, a wall's middle).
Eigen::Vector2d free_side(const OccupancyGrid& grid, const Eigen::Vector2d& point,
                          const Eigen::Vector2d& normal) {
  const double step = grid.geometry().resolution;
  const auto free_at = [&](const Eigen::Vector2d& p) {
    int ix = 0, iy = 0;
    return grid.geometry().cell_of(p, ix, iy) && grid.state(ix, iy) == CellState::free;
  };
  const bool plus = free_at(point + step * normal), minus = free_at(point - step * normal);
  if (plus == minus)
    return Eigen::Vector2d::Zero();
  return plus ? normal : Eigen::Vector2d(-normal);
}

// The gridmap's wall cells (`cells`, their centres), one per `spacing`-metre square (the
// first met), with their walls' normals.
std::vector<WallPoint> spaced_wall_points(const OccupancyGrid& grid,
                                          const std::vector<Eigen::Vector2d>& cells,
                                          double spacing) {
  std::set<std::pair<long, long>> taken;
  std::vector<WallPoint> points;
  for (const Eigen::Vector2d& c : cells) {
    if (!taken
             .emplace(std::lround(std::floor(c.x() / spacing)),
                      std::lround(std::floor(c.y() / spacing)))
             .second)
      continue;
    const Eigen::Vector2d along = wall_direction(grid, c, 0.25, 0.25);
    const Eigen::Vector2d normal(-along.y(), along.x());
    points.push_back({c, normal, free_side(grid, c, normal)});
  }
  return points;
}

using PlanWarp = MapWarp;

// A gridmap wall point matched to the plan's nearest wall surface: where it lies on the plan
// now, the unit normal of that surface, its distance to it (plan metres), and how far off the
// surface its wall's face lies (plan metres into the room: WallFaceFit).
struct Match {
  bool found = false;
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
  double distance = 0.0;
  double offset = 0.0;
  bool facing = false;  // the surface faces the side the robot saw the wall from
  bool exterior = false;
  /// The plan point the gridmap point belongs at: its surface point moved to the face.
  Eigen::Vector2d target() const { return at - (distance - offset) * normal; }
};

// Where the laser's faces lie off the drawn walls (wall_faces.hpp), once fitted.
struct Faces {
  const ExteriorWalls* walls = nullptr;
  WallFaceFit fit;
  double max_depth = 0.0;  // plan metres
  double reach = 0.0;      // plan metres: the larger offset of a fitted fit, else 0
};

Match match_to_plan(const WallSurfaceField& field, const PlanWarp& warp, const WallPoint& w,
                    double radius_plan, double step, double min_cosine, const Faces& faces) {
  Match m;
  m.at = warp.apply(w.point);
  m.distance = field.distance(m.at);
  // The radius is about the face: a point may lie as far off the drawn surface as the faces do.
  if (!(m.distance <= radius_plan + faces.reach))
    return m;
  const Eigen::Vector2d gradient(field.distance(m.at + Eigen::Vector2d(step, 0)) -
                                     field.distance(m.at - Eigen::Vector2d(step, 0)),
                                 field.distance(m.at + Eigen::Vector2d(0, step)) -
                                     field.distance(m.at - Eigen::Vector2d(0, step)));
  const double norm = gradient.norm() / (2.0 * step);
  if (norm < 0.5)  // a ridge between two walls, or a wall's inside: no clear nearest surface
    return m;
  m.normal = gradient.normalized();
  if (w.normal.squaredNorm() > 0.0) {
    const Eigen::Vector2d normal_in_plan = rotation_2d(warp.similarity.theta) * w.normal;
    if (std::abs(normal_in_plan.dot(m.normal)) < min_cosine)
      return m;
  }
  m.found = true;
  // The face the laser saw lies off the surface that faces the same way (a point matched to a
  // stroke's far surface keeps the surface).
  if (faces.walls && (rotation_2d(warp.similarity.theta) * w.facing).dot(m.normal) > 0.0) {
    m.facing = true;
    m.exterior = faces.walls->exterior(m.at - m.distance * m.normal, m.normal, faces.max_depth);
    m.offset = face_offset(faces.fit, m.exterior);
  }
  m.found = m.distance - m.offset <= radius_plan;
  return m;
}

// The gridmap bent onto the plan's walls from `similarity`, coarse to fine: at each stage a
// lattice is refitted `rounds` times to move the wall points matched within the stage's radius
// across their walls onto them.
PlanWarp bend_onto_plan(const WallSurfaceField& field, const std::vector<WallPoint>& points,
                        const MapSimilarity& similarity, double step, double min_cosine,
                        const Faces& faces, const MapAlignmentOptions& o) {
  const double scale = similarity.scale;
  Eigen::AlignedBox2d box;
  for (const WallPoint& w : points)
    box.extend(similarity.apply(w.point));
  PlanWarp warp{similarity, DisplacementLattice(box, o.first_spacing * scale)};
  const int stages = 1 + static_cast<int>(std::round(std::log2(o.first_spacing / o.last_spacing)));
  for (int stage = 0; stage < stages; ++stage) {
    const double t = stages > 1 ? double(stage) / (stages - 1) : 1.0;
    const double spacing = o.first_spacing * std::pow(o.last_spacing / o.first_spacing, t);
    const double radius = o.first_radius * std::pow(o.last_radius / o.first_radius, t) * scale;
    DisplacementLattice lattice(box, spacing * scale);
    for (int round = 0; round < o.rounds; ++round) {
      std::vector<LatticeConstraint> constraints;
      for (const WallPoint& w : points) {
        const Match m = match_to_plan(field, warp, w, radius, step, min_cosine, faces);
        if (!m.found)
          continue;
        const Eigen::Vector2d p0 = warp.similarity.apply(w.point);
        // Move across the wall onto its face: n . D(p0) = n . (p - p0) - (d - offset)
        // (Huber-weighted).
        const double off = m.distance - m.offset;
        const double huber = std::min(1.0, radius / 3.0 / std::max(off, 1e-9));
        constraints.push_back({p0, m.normal, m.normal.dot(m.at - p0) - off, huber});
      }
      if (!lattice.fit(constraints, o.stiffness))
        break;
      warp.lattice = lattice;
    }
    ++warp.stages;
  }
  return warp;
}

}  // namespace

Eigen::Vector2d MapWarp::apply(const Eigen::Vector2d& g) const {
  const Eigen::Vector2d p0 = similarity.apply(g);
  return stages > 0 ? Eigen::Vector2d(p0 + lattice.at(p0)) : p0;
}

Eigen::Matrix2d MapWarp::jacobian(const Eigen::Vector2d& g) const {
  const double h = 0.05;
  Eigen::Matrix2d J;
  J.col(0) = (apply(Eigen::Vector2d(g + h * Eigen::Vector2d::UnitX())) -
              apply(Eigen::Vector2d(g - h * Eigen::Vector2d::UnitX()))) /
             (2.0 * h);
  J.col(1) = (apply(Eigen::Vector2d(g + h * Eigen::Vector2d::UnitY())) -
              apply(Eigen::Vector2d(g - h * Eigen::Vector2d::UnitY()))) /
             (2.0 * h);
  return J;
}

Eigen::Vector2d MapWarp::inverse(const Eigen::Vector2d& p) const {
  Eigen::Vector2d g = similarity.inverse(stages > 0 ? Eigen::Vector2d(p - lattice.at(p)) : p);
  if (stages == 0)
    return g;
  // The lattice is smooth and its displacement small against its spacing: a few Newton steps
  // from the first-order inverse reach the exact one.
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector2d r = apply(g) - p;
    if (r.norm() < 1e-9 * std::max(1.0, p.norm()))
      break;
    const Eigen::Matrix2d J = jacobian(g);
    if (!(std::abs(J.determinant()) > 1e-12))
      break;
    g -= J.inverse() * r;
  }
  return g;
}

Pose2 MapWarp::apply(const Pose2& pose) const {
  const Eigen::Vector2d g = pose.translation();
  const Eigen::Vector2d heading =
      jacobian(g) * Eigen::Vector2d(std::cos(pose.theta), std::sin(pose.theta));
  const Eigen::Vector2d p = apply(g);
  return {p.x(), p.y(), std::atan2(heading.y(), heading.x())};
}

Pose2 MapWarp::inverse(const Pose2& pose) const {
  const Eigen::Vector2d g = inverse(pose.translation());
  const Eigen::Matrix2d J = jacobian(g);
  Eigen::Vector2d heading(std::cos(pose.theta), std::sin(pose.theta));
  if (std::abs(J.determinant()) > 1e-12)
    heading = J.inverse() * heading;
  return {g.x(), g.y(), std::atan2(heading.y(), heading.x())};
}

WarpScale warp_scale(const MapWarp& warp, const std::vector<Eigen::Vector2d>& points) {
  std::vector<double> scales;
  scales.reserve(points.size());
  for (const Eigen::Vector2d& g : points) {
    const double det = std::abs(warp.jacobian(g).determinant());
    if (det > 0.0 && std::isfinite(det))
      scales.push_back(1.0 / std::sqrt(det));
  }
  WarpScale s{1.0 / warp.similarity.scale, 0.0, 1.0 / warp.similarity.scale};
  if (scales.empty())
    return s;
  // The least-squares similarity of the warp's images onto the gridmap points (plan -> world):
  // its scale is world metres per plan metre.
  PairMoments moments;
  moments.origin_in_grid = points.front();
  moments.origin_in_plan = warp.apply(points.front());
  for (const Eigen::Vector2d& g : points)
    moments.add(warp.apply(g), g);
  const std::optional<TransformEstimate> fit =
      fit_transform(moments, {.kind = TransformKind::similarity, .reflection = Reflection::forbid});
  if (fit && fit->scale > 0.0 && std::isfinite(fit->scale))
    s.similarity_scale = fit->scale;
  s.scale = median(scales);
  std::vector<double> deviations;
  deviations.reserve(scales.size());
  for (const double v : scales)
    deviations.push_back(std::abs(v - s.scale));
  s.relative_std = 1.4826 * median(deviations) / s.scale;
  return s;
}

void validate(const MapAlignmentOptions& o, const std::string& prefix) {
  const auto positive = [&](double value, const char* field) {
    require_option(value > 0.0 && std::isfinite(value), prefix + field, value, "> 0");
  };
  positive(o.first_spacing, "first_spacing");
  positive(o.last_spacing, "last_spacing");
  require_option(o.last_spacing <= o.first_spacing, prefix + "last_spacing", o.last_spacing,
                 "<= first_spacing");
  positive(o.first_radius, "first_radius");
  positive(o.last_radius, "last_radius");
  require_option(o.rounds >= 1 && o.rounds <= 100, prefix + "rounds", o.rounds, "in 1..100");
  require_option(o.stiffness >= 0.0 && std::isfinite(o.stiffness), prefix + "stiffness",
                 o.stiffness, ">= 0");
  positive(o.point_spacing, "point_spacing");
  require_option(o.max_normal_angle > 0.0 && o.max_normal_angle <= 90.0,
                 prefix + "max_normal_angle", o.max_normal_angle, "in (0, 90] degrees");
  positive(o.pair_radius, "pair_radius");
  require_option(std::isfinite(o.min_fitness), prefix + "min_fitness", o.min_fitness, "a number");
  require_option(o.min_on_walls >= 0.0 && o.min_on_walls <= 1.0, prefix + "min_on_walls",
                 o.min_on_walls, "in 0..1");
  require_option(o.max_ambiguity > 0.0 && std::isfinite(o.max_ambiguity), prefix + "max_ambiguity",
                 o.max_ambiguity, "> 0");
  require_option(std::isfinite(o.correlation_below), prefix + "correlation_below",
                 o.correlation_below, "a number");
}

MapAlignment align_maps(const OccupancyGrid& gridmap, const OccupancyGrid& plan,
                        PlanWalls plan_walls, const MapRegistrationOptions& registration,
                        const MapAlignmentOptions& o) {
  validate(o);
  const auto clock = std::chrono::steady_clock::now();
  MapAlignment a;
  a.options = o;
  MapRegistrationOptions search = registration;
  search.correlation_below = o.correlation_below;
  // One scorer for the registration and the bent map: the fitness is the registration's
  // score, on the same wall points (its final ones), of the bent map.
  MapFitScorer scorer(gridmap, plan, plan_walls, registration.max_points,
                      registration.free_violation_distance);
  a.registration = register_maps(scorer, search);
  if (!a.registration.found) {
    a.diagnosis = "a map has no walls: no registration was scored";
    return a;
  }
  const WallSurfaceField& field = scorer.plan_field();
  const std::vector<WallPoint> points =
      spaced_wall_points(gridmap, scorer.grid_cells(), o.point_spacing);
  a.points = points.size();
  const double step = plan.geometry().resolution;
  const double min_cosine = std::cos(o.max_normal_angle * std::numbers::pi / 180.0);
  // The registration refined with where the laser meets the drawn walls (their faces), and
  // the bend aimed at the faces too.
  Faces faces;
  std::optional<ExteriorWalls> exterior;
  // A raster drawing's strokes only: a vector drawing's lines are rasterized along their axis,
  // and its walls are usually drawn as their two faces.
  if (o.faces.enabled && plan_walls == PlanWalls::raster_strokes) {
    const double plan_per_world = a.registration.best.transform.scale;
    exterior.emplace(plan, o.faces.seal_radius * plan_per_world);
    faces.walls = &*exterior;
    faces.max_depth = o.faces.max_depth * plan_per_world;
    const auto observe = [&](const MapSimilarity& similarity, double radius) {
      const PlanWarp rigid{similarity};
      std::vector<FaceObservation> observed;
      for (const WallPoint& w : points) {
        if (w.normal.squaredNorm() == 0.0)
          continue;
        const Match m = match_to_plan(field, rigid, w, radius, step, min_cosine, faces);
        if (m.found && m.facing)
          observed.push_back({w.point, m.at - m.distance * m.normal, m.normal, m.exterior});
      }
      return observed;
    };
    faces.fit = fit_wall_faces(observe, a.registration.best.transform, o.faces);
    faces.reach = std::max({0.0, face_offset(faces.fit, true), face_offset(faces.fit, false)});
    a.faces = faces.fit;
    if (faces.fit.fitted) {
      a.registration.best.transform = faces.fit.similarity;
      if (o.faces.localize_on_faces)
        a.plan_at_faces = plan_at_faces(plan, *exterior, faces.fit, faces.max_depth);
    }
  }
  const auto bend = [&](const MapSimilarity& similarity) {
    return bend_onto_plan(field, points, similarity, step, min_cosine, faces, o);
  };
  const auto fit_of = [&](const PlanWarp& warp) {
    return scorer.score([&](const Eigen::Vector2d& g) { return warp.apply(g); },
                        [&](const Eigen::Vector2d& p) { return warp.inverse(p); },
                        warp.similarity.scale, registration.sigma);
  };
  const PlanWarp warp = bend(a.registration.best.transform);
  a.stages = warp.stages;
  a.warp = warp;
  {
    std::vector<Eigen::Vector2d> at;
    at.reserve(points.size());
    for (const auto& p : points)
      at.push_back(p.point);
    a.scale = warp_scale(warp, at);
  }
  a.fit = fit_of(warp);
  // The other places the registration found, bent too: how near the best of them comes.
  for (const ScoredSimilarity& other : a.registration.alternatives) {
    const MapFit fit = fit_of(bend(other.transform));
    if (!a.runner_up || fit.score > a.runner_up->fit.score)
      a.runner_up = MapAlignment::Other{other.transform, fit};
  }
  const double scale = warp.similarity.scale;

  // The final matches of the points on a straight wall are the pairs: the plan wall surface
  // point, the gridmap wall point (the bending used every point).
  std::vector<Eigen::Vector2d> plan_side, grid_side;
  std::vector<double> distances;
  for (const WallPoint& w : points) {
    if (w.normal.squaredNorm() == 0.0)
      continue;  // a corner or a blob (clutter) tells no wall it lies on
    const Match m = match_to_plan(field, warp, w, o.pair_radius * scale, step, min_cosine, faces);
    if (!m.found)
      continue;
    plan_side.push_back(m.target());
    grid_side.push_back(w.point);
    distances.push_back((m.distance - m.offset) / scale);
  }
  a.pairs.points_in_plan.resize(2, static_cast<Eigen::Index>(plan_side.size()));
  a.pairs.points_in_grid.resize(2, static_cast<Eigen::Index>(plan_side.size()));
  for (std::size_t i = 0; i < plan_side.size(); ++i) {
    a.pairs.points_in_plan.col(static_cast<Eigen::Index>(i)) = plan_side[i];
    a.pairs.points_in_grid.col(static_cast<Eigen::Index>(i)) = grid_side[i];
  }
  a.median_distance_m = distances.empty() ? 0.0 : upper_median(distances);
  if (a.runner_up)
    a.ambiguity = a.fit.score > 0.0 ? std::max(0.0, a.runner_up->fit.score / a.fit.score) : 1.0;
  if (a.pairs.size() < 3)
    a.diagnosis = "fewer than 3 gridmap wall points lie on the plan's walls";
  else if (a.fit.score < o.min_fitness)
    a.diagnosis = fmt::format(
        "the maps do not fit each other well enough (a fitness of {:.2f} "
        "needed)",
        o.min_fitness);
  else if (a.fit.on_walls < o.min_on_walls)
    a.diagnosis = fmt::format(
        "only {:.0f}% of the gridmap's walls lie on the plan's (at least {:.0f}% needed)",
        100.0 * a.fit.on_walls, 100.0 * o.min_on_walls);
  else if (a.ambiguity >= o.max_ambiguity)
    a.diagnosis = fmt::format(
        "another place fits about as well ({:.0f}% as well, at most {:.0f}% allowed): the maps "
        "do not tell where the gridmap is",
        100.0 * a.ambiguity, 100.0 * o.max_ambiguity);
  a.accepted = a.diagnosis.empty();
  a.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
  return a;
}

}  // namespace floorgrid
