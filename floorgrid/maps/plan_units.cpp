#include "floorgrid/maps/plan_units.hpp"

#include <iterator>

#include "floorgrid/core/error.hpp"

namespace floorgrid {

double metres_per_unit(PlanUnit unit) {
  switch (unit) {
    case PlanUnit::m:
      return 1.0;
    case PlanUnit::cm:
      return 0.01;
    case PlanUnit::mm:
      return 0.001;
    case PlanUnit::in:
      return 0.0254;
    case PlanUnit::ft:
      return 0.3048;
  }
  return 1.0;
}

std::string_view unit_name(PlanUnit unit) {
  switch (unit) {
    case PlanUnit::m:
      return "m";
    case PlanUnit::cm:
      return "cm";
    case PlanUnit::mm:
      return "mm";
    case PlanUnit::in:
      return "in";
    case PlanUnit::ft:
      return "ft";
  }
  return "m";
}

std::optional<PlanUnit> plan_unit_from_name(std::string_view name) {
  std::string lower(name);
  for (char& c : lower) {
    if (c >= 'A' && c <= 'Z') {
      c = static_cast<char>(c - 'A' + 'a');
    }
  }
  for (const PlanUnit unit : kPlanUnits) {
    if (lower == unit_name(unit)) {
      return unit;
    }
  }
  return std::nullopt;
}

std::optional<PlanUnit> parse_units_option(std::string_view value, const std::string& field) {
  if (value == "auto") {
    return std::nullopt;
  }
  if (const auto unit = plan_unit_from_name(value)) {
    return unit;
  }
  throw InputError(
      "unknown unit \"" + std::string(value) + "\" (expected auto, m, cm, mm, in or ft)", {}, 0,
      field);
}

std::optional<PlanUnit> plan_unit_from_insunits(int code) {
  switch (code) {
    case 1:
      return PlanUnit::in;
    case 2:
      return PlanUnit::ft;
    case 4:
      return PlanUnit::mm;
    case 5:
      return PlanUnit::cm;
    case 6:
      return PlanUnit::m;
    case 21:
      return PlanUnit::ft;  // US survey foot: 2 ppm off the international foot
    default:
      return std::nullopt;
  }
}

std::string insunits_name(int code) {
  static const char* const kNames[] = {"none",  "in",    "ft",    "mi",   "mm",       "cm", "m",
                                       "km",    "uin",   "mil",   "yd",   "angstrom", "nm", "um",
                                       "dm",    "dam",   "hm",    "Gm",   "au",       "ly", "pc",
                                       "us-ft", "us-in", "us-yd", "us-mi"};
  if (code >= 0 && code < static_cast<int>(std::size(kNames))) {
    return kNames[code];
  }
  return "code " + std::to_string(code);
}

std::optional<int> insunits_code(std::string_view name) {
  if (name == "none") {
    return 0;
  }
  const auto unit = plan_unit_from_name(name);
  if (!unit) {
    return std::nullopt;
  }
  switch (*unit) {
    case PlanUnit::in:
      return 1;
    case PlanUnit::ft:
      return 2;
    case PlanUnit::mm:
      return 4;
    case PlanUnit::cm:
      return 5;
    case PlanUnit::m:
      return 6;
  }
  return std::nullopt;
}

}  // namespace floorgrid
