#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace floorgrid {

/// The length units a floorplan drawing can be in.
enum class PlanUnit { m, cm, mm, in, ft };

/// Every PlanUnit, in the order used to break exact ties.
inline constexpr PlanUnit kPlanUnits[] = {PlanUnit::m, PlanUnit::cm, PlanUnit::mm, PlanUnit::in,
                                          PlanUnit::ft};

/// Metres per drawing unit: 1, 0.01, 0.001, 0.0254, 0.3048.
double metres_per_unit(PlanUnit unit);
/// The short name: "m", "cm", "mm", "in", "ft".
std::string_view unit_name(PlanUnit unit);
/// The unit of a short name (ASCII case ignored), or nullopt.
std::optional<PlanUnit> plan_unit_from_name(std::string_view name);
/// Parses a units option: "auto" gives nullopt (infer), a short name gives that unit; anything
/// else throws InputError naming `field`.
std::optional<PlanUnit> parse_units_option(std::string_view value, const std::string& field);

/// The unit of a DXF `$INSUNITS` code when it is one of ours (1 in, 2 ft, 4 mm, 5 cm, 6 m,
/// 21 US survey feet as ft), else nullopt.
std::optional<PlanUnit> plan_unit_from_insunits(int code);
/// A readable name of any `$INSUNITS` code: "none" for 0, "mm" for 4, "km" for 7, "code 99"...
std::string insunits_name(int code);
/// The `$INSUNITS` code of a unit name accepted by DXF writers: "none" (0) or a PlanUnit name;
/// nullopt otherwise.
std::optional<int> insunits_code(std::string_view name);

/// A circular arc of the drawing, as unit evidence.
struct PlanArc {
  double radius = 0.0;  ///< drawing units
  double sweep = 0.0;   ///< radians, (0, 2 pi]
};

/// What a drawing tells about its units.
struct PlanUnitEvidence {
  Eigen::AlignedBox2d extent;           ///< bounds of the geometry, drawing units
  std::vector<PlanArc> arcs;            ///< every circular arc of the geometry
  std::optional<PlanUnit> header_unit;  ///< the header's unit when it is a PlanUnit
  std::string header_name = "none";     ///< what the header says, for messages ("none" if nothing)
};

/// What makes a drawing plausible as a building storey. Defaults from the product spec.
struct PlanUnitOptions {
  double min_span = 5.0;         ///< metres: smallest plausible larger side of the extent
  double max_span = 500.0;       ///< metres: largest plausible larger side of the extent
  double min_door_radius = 0.6;  ///< metres: smallest door swing radius
  double max_door_radius = 1.2;  ///< metres: largest door swing radius
  double min_door_sweep = 80.0 * std::numbers::pi / 180.0;   ///< radians: door swing arcs sweep
  double max_door_sweep = 100.0 * std::numbers::pi / 180.0;  ///< radians: about a quarter turn
};

/// The unit chosen for a drawing and why.
struct PlanUnitChoice {
  PlanUnit unit = PlanUnit::m;        ///< the unit used
  double metres_per_unit = 1.0;       ///< of `unit`
  std::string reason;                 ///< one sentence: why this unit
  std::vector<std::string> warnings;  ///< disagreements with the header, ambiguity, implausibility
};

/// Chooses the drawing's unit. An explicit `requested` unit is obeyed (with warnings when it
/// disagrees with the header or makes the drawing implausible). Otherwise the header's unit is
/// kept when the drawing is plausible in it: the extent's larger side within [min_span,
/// max_span] and, when the drawing has door-swing-like arcs (sweep within [min_door_sweep,
/// max_door_sweep]), at least half as many of them with a door radius as under the best unit.
/// Failing that, the unit with a plausible span and the most door-radius arcs wins, ties going
/// to the span closest to sqrt(min_span * max_span); a warning says when the header disagrees
/// or when nothing but that tie-break decided.
PlanUnitChoice choose_plan_unit(const PlanUnitEvidence& evidence, std::optional<PlanUnit> requested,
                                const PlanUnitOptions& options = {});

}  // namespace floorgrid
