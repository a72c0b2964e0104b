#include "floorgrid/maps/plan_unit_scores.hpp"

#include <algorithm>
#include <cmath>

namespace floorgrid {

namespace {

enum class Fit { none, partial, full };

/// Whether `value` lies in [lo, hi] (full) or within a factor `slack` outside (partial).
Fit fit(double value, double lo, double hi, double slack = 2.0) {
  if (value >= lo && value <= hi) {
    return Fit::full;
  }
  return value >= lo / slack && value <= hi * slack ? Fit::partial : Fit::none;
}

double points(Fit f, double weight) {
  return f == Fit::full ? weight : f == Fit::partial ? weight / 3.0 : 0.0;
}

/// log10 of how far `value` lies outside [lo, hi]; 0 inside.
double decades_outside(double value, double lo, double hi) {
  return std::max({0.0, std::log10(lo / value), std::log10(value / hi)});
}

DoorSwings door_swings(const PlanUnitEvidence& evidence, const PlanUnitOptions& options) {
  DoorSwings doors;
  std::vector<PlanArc> quarter;
  std::size_t leaves = 0;
  for (const PlanArc& arc : evidence.arcs) {
    if (arc.sweep >= options.min_door_sweep && arc.sweep <= options.max_door_sweep) {
      quarter.push_back(arc);
      leaves += arc.leaf ? 1 : 0;
    }
  }
  doors.with_leaves = leaves >= 3;
  for (const PlanArc& arc : quarter) {
    if (doors.with_leaves && !arc.leaf) {
      continue;
    }
    doors.arcs.push_back(arc);
    doors.weights.push_back(arc.leaf ? options.door_weight : options.bare_door_weight);
    doors.total += doors.weights.back();
  }
  return doors;
}

PlanUnitScore score_unit(PlanUnit unit, const PlanUnitScores& scores,
                         const PlanUnitEvidence& evidence, const PlanUnitOptions& o) {
  PlanUnitScore s;
  s.unit = unit;
  const double k = s.metres_per_unit = metres_per_unit(unit);
  s.span = scores.size.maxCoeff() * k;
  // Extent: absurd sizes weigh heavily, the rest only as a tie-break towards a storey's size.
  if (s.span <= 0.0) {
    s.extent = 0.0;
  } else if (s.span < o.min_drawing_span || s.span > o.max_drawing_span) {
    s.absurd = true;
    s.extent =
        -o.absurd_weight - 5.0 * decades_outside(s.span, o.min_drawing_span, o.max_drawing_span);
  } else {
    const double typical = std::sqrt(o.min_span * o.max_span);
    s.extent = o.extent_weight * (1.0 - 0.05 * std::abs(std::log10(s.span / typical)) -
                                  2.0 * decades_outside(s.span, o.min_span, o.max_span));
  }

  double door_points = 0.0;
  s.door_min = HUGE_VAL;
  for (std::size_t i = 0; i < scores.doors.arcs.size(); ++i) {
    const double r = scores.doors.arcs[i].radius;
    if (fit(r * k, o.min_door_radius, o.max_door_radius) == Fit::full) {
      ++s.door_count;
      door_points += scores.doors.weights[i];
      s.door_min = std::min(s.door_min, r);
      s.door_max = std::max(s.door_max, r);
    }
  }
  s.door_min = s.door_count > 0 ? s.door_min : 0.0;
  // Past the cap more arcs only shift the shares: a drawing full of fillets stays weak evidence.
  s.doors = door_points * std::min(1.0, o.max_door_points / std::max(scores.doors.total, 1e-12));

  // A text fits when it and the measurement agree within 5%: texts are rounded (to an inch, a
  // centimetre), and a mismatch of units is a factor of 2.5 at least.
  for (std::size_t i = 0; i < evidence.dimensions.size(); ++i) {
    const StatedLength& d = evidence.dimensions[i];
    if (d.measured > 0.0 && std::abs(std::log(d.stated_m / (d.measured * k))) < 0.05) {
      s.example = s.dimensions_fitting == 0 ? i : s.example;
      ++s.dimensions_fitting;
    }
  }
  const double all_dimensions =
      o.dimension_weight * static_cast<double>(evidence.dimensions.size());
  s.dimensions = o.dimension_weight * static_cast<double>(s.dimensions_fitting) *
                 std::min(1.0, o.max_dimension_points / std::max(all_dimensions, 1e-12));

  if (scores.walls_count) {
    s.walls = points(fit(evidence.walls.thickness * k, o.min_wall_thickness, o.max_wall_thickness),
                     o.wall_weight);
    if (evidence.walls.spacing > 0.0) {
      s.rooms = points(fit(evidence.walls.spacing * k, o.min_room_spacing, o.max_room_spacing),
                       o.room_weight);
    }
  }
  s.header = evidence.header_unit == unit ? o.header_weight : 0.0;
  return s;
}

}  // namespace

const PlanUnitScore& PlanUnitScores::of(PlanUnit unit) const {
  return *std::find_if(units.begin(), units.end(),
                       [&](const PlanUnitScore& s) { return s.unit == unit; });
}

const PlanUnitScore& PlanUnitScores::best_by_features() const {
  const PlanUnitScore* best = &units.front();
  for (const PlanUnitScore& s : units) {
    if (s.features() > best->features() ||
        (s.features() == best->features() && s.extent > best->extent)) {
      best = &s;
    }
  }
  return *best;
}

PlanUnitScores score_plan_units(const PlanUnitEvidence& evidence, const PlanUnitOptions& options) {
  PlanUnitScores scores;
  scores.doors = door_swings(evidence, options);
  const Eigen::AlignedBox2d& box =
      evidence.core_extent.isEmpty() ? evidence.extent : evidence.core_extent;
  scores.size = box.isEmpty() ? Eigen::Vector2d::Zero() : Eigen::Vector2d(box.sizes());
  scores.walls_count = evidence.walls.faces >= options.min_wall_faces &&
                       evidence.walls.thickness > 0.0 &&
                       evidence.walls.thickness_share >= options.min_wall_share;
  for (const PlanUnit unit : kPlanUnits) {
    scores.units.push_back(score_unit(unit, scores, evidence, options));
  }
  return scores;
}

}  // namespace floorgrid
