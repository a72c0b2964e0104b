#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/maps/plan_unit_features.hpp"
#include "floorgrid/maps/plan_units.hpp"

namespace floorgrid {

/// What a drawing tells about its units. Lengths in drawing units.
struct PlanUnitEvidence {
  Eigen::AlignedBox2d extent;            ///< bounds of the geometry
  Eigen::AlignedBox2d core_extent;       ///< bounds without far-off strays; empty: `extent`
  std::vector<PlanArc> arcs;             ///< every circular arc of the geometry
  std::vector<StatedLength> dimensions;  ///< dimensions whose text states a length and unit
  WallBandSummary walls;                 ///< wall thickness and spacing
  std::optional<PlanUnit> header_unit;   ///< the header's unit when it is a PlanUnit
  std::string header_name = "none";      ///< what the header says, for messages
};

/// What a building drawing looks like in metres, and how much each kind of evidence weighs.
/// Weights are points (natural log-odds): a unit's score is the sum of the points of the
/// evidence that fits it, and its probability the softmax of the scores. Defaults in one place.
struct PlanUnitOptions {
  double min_span = 5.0;    ///< metres: smallest typical larger side of a storey
  double max_span = 500.0;  ///< metres: largest typical one (a site or storeys side by side may be
                            ///< larger: the extent is weak evidence)
  double min_drawing_span = 2.5;      ///< metres: a building drawing smaller than this is absurd
  double max_drawing_span = 20000.0;  ///< metres: one larger than this is absurd
  double min_door_radius = 0.6;       ///< metres: smallest door swing radius
  double max_door_radius = 1.2;       ///< metres: largest door swing radius
  double min_door_sweep = 80.0 * std::numbers::pi / 180.0;   ///< radians: door swing arcs sweep
  double max_door_sweep = 100.0 * std::numbers::pi / 180.0;  ///< radians: about a quarter turn
  double min_wall_thickness = 0.07;                          ///< metres: thinnest typical wall
  double max_wall_thickness = 0.6;                           ///< metres: thickest typical wall
  std::size_t min_wall_faces = 8;  ///< wall faces needed before their thickness counts
  double min_wall_share = 0.1;     ///< share of their length needed at the common thickness
  double min_room_spacing = 1.5;   ///< metres: narrowest typical room or corridor beyond a wall
  double max_room_spacing = 15.0;  ///< metres: widest typical one
  double header_weight = 6.0;  ///< points for the header's unit: what the drawing must outweigh to
                               ///< overrule `$INSUNITS` (more than 4 doors, fewer than 10)
  double door_weight = 1.0;    ///< points per door swing (an arc with a leaf) of a door's radius
  double bare_door_weight = 0.75;  ///< per quarter arc of a door's radius without a leaf (counted
                                   ///< only when fewer than 3 arcs have a leaf)
  double max_door_points = 24.0;   ///< cap on the door points: more arcs only shift the shares
  double dimension_weight = 1.5;   ///< points per dimension text whose length fits the unit
  double max_dimension_points = 24.0;  ///< cap on the dimension points, likewise
  double wall_weight = 3.0;     ///< points when the common wall thickness is typical in the unit
  double room_weight = 1.5;     ///< points when the spacing beyond walls is typical in the unit
  double extent_weight = 1.0;   ///< points when the extent is a storey's: a tie-break, no more
  double absurd_weight = 20.0;  ///< points against a unit that makes the drawing absurd in size
};

/// The quarter-turn arcs counted as door swings: only those with a leaf when at least three
/// have one (the others are then fillets or fixtures), else all of them.
struct DoorSwings {
  std::vector<PlanArc> arcs;    ///< the arcs counted
  std::vector<double> weights;  ///< points of each when its radius is a door's
  bool with_leaves = false;     ///< only arcs with a leaf are counted
  double total = 0.0;           ///< sum of the weights
};

/// How the drawing looks in one unit, and the points each kind of evidence gives it.
struct PlanUnitScore {
  PlanUnit unit = PlanUnit::m;         ///< the unit
  double metres_per_unit = 1.0;        ///< of `unit`
  double span = 0.0;                   ///< metres: larger side of the (core) extent in this unit
  bool absurd = false;                 ///< the span is absurd for a building drawing
  double extent = 0.0;                 ///< points: a storey's size (weak), absurd sizes (strong)
  double doors = 0.0;                  ///< points: door swings of a door's radius
  double dimensions = 0.0;             ///< points: dimension texts whose length fits
  double walls = 0.0;                  ///< points: a typical wall thickness
  double rooms = 0.0;                  ///< points: a typical spacing beyond the walls
  double header = 0.0;                 ///< points: `$INSUNITS` says this unit
  std::size_t door_count = 0;          ///< door swings of a door's radius in this unit
  double door_min = 0.0;               ///< their smallest radius, drawing units
  double door_max = 0.0;               ///< their largest radius, drawing units
  std::size_t dimensions_fitting = 0;  ///< dimension texts whose length fits
  std::size_t example = 0;             ///< index of the first of them in the evidence

  /// Points of the drawing's features, extent and header left out.
  double features() const { return doors + dimensions + walls + rooms; }
  /// All points.
  double total() const { return features() + extent + header; }
};

/// Every unit scored on one drawing's evidence.
struct PlanUnitScores {
  DoorSwings doors;                                ///< the door swings counted
  Eigen::Vector2d size = Eigen::Vector2d::Zero();  ///< the (core) extent's sides, drawing units
  bool walls_count = false;                        ///< the wall thickness is clear enough to count
  std::vector<PlanUnitScore> units;                ///< in the order of kPlanUnits

  /// The score of `unit`.
  const PlanUnitScore& of(PlanUnit unit) const;
  /// The unit the features alone fit best (ties: the more typical extent, then kPlanUnits order).
  const PlanUnitScore& best_by_features() const;
};

/// Scores every PlanUnit on `evidence`: a door swing (weighted, capped at max_door_points) for
/// each unit in which its radius is a door's, a dimension text for each unit in which its stated
/// length matches its measurement within 5%, the wall thickness and the spacing beyond walls
/// when typical in the unit (a third when within a factor 2 of typical), the extent weakly
/// towards a storey's size and strongly against absurd sizes, and the header.
PlanUnitScores score_plan_units(const PlanUnitEvidence& evidence, const PlanUnitOptions& options);

}  // namespace floorgrid
