#pragma once

#include <optional>
#include <string>
#include <string_view>

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

}  // namespace floorgrid
