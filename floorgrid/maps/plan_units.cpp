#include "floorgrid/maps/plan_units.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "floorgrid/core/error.hpp"

namespace floorgrid {

namespace {

/// A length in metres for messages: three significant digits are enough to judge a unit.
std::string metres(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g m", value);
  return buffer;
}

/// How a drawing looks under one candidate unit.
struct Candidate {
  PlanUnit unit = PlanUnit::m;
  double width = 0.0;      ///< metres
  double height = 0.0;     ///< metres
  bool span_ok = false;    ///< the larger side lies in the plausible range
  std::size_t doors = 0;   ///< door-like arcs with a door radius under this unit
  double tie_break = 0.0;  ///< |log(span / typical span)|: smaller is more typical
};

std::string describe(const Candidate& c, std::size_t door_arcs) {
  std::ostringstream out;
  out << "in " << unit_name(c.unit) << " it spans " << metres(c.width) << " x " << metres(c.height);
  if (door_arcs > 0) {
    out << " and " << c.doors << " of " << door_arcs
        << " door-swing-like arcs have a door's radius";
  }
  return out.str();
}

std::vector<Candidate> evaluate_candidates(const PlanUnitEvidence& evidence,
                                           const std::vector<double>& door_radii,
                                           const PlanUnitOptions& options) {
  const double typical = std::sqrt(options.min_span * options.max_span);
  const Eigen::Vector2d size = evidence.extent.isEmpty() ? Eigen::Vector2d::Zero()
                                                         : Eigen::Vector2d(evidence.extent.sizes());
  std::vector<Candidate> candidates;
  for (const PlanUnit unit : kPlanUnits) {
    const double k = metres_per_unit(unit);
    Candidate c;
    c.unit = unit;
    c.width = size.x() * k;
    c.height = size.y() * k;
    const double span = std::max(c.width, c.height);
    c.span_ok = span >= options.min_span && span <= options.max_span;
    c.doors =
        static_cast<std::size_t>(std::count_if(door_radii.begin(), door_radii.end(), [&](double r) {
          return r * k >= options.min_door_radius && r * k <= options.max_door_radius;
        }));
    c.tie_break = span > 0.0 ? std::abs(std::log(span / typical)) : HUGE_VAL;
    candidates.push_back(c);
  }
  return candidates;
}

/// The candidate ranked first: plausible span, then most door radii, then most typical span.
const Candidate& best_candidate(const std::vector<Candidate>& candidates,
                                const PlanUnitOptions& options) {
  const auto distance_to_range = [&](const Candidate& c) {
    const double span = std::max(c.width, c.height);
    if (span <= 0.0) {
      return HUGE_VAL;
    }
    return std::max({0.0, std::log(options.min_span / span), std::log(span / options.max_span)});
  };
  return *std::min_element(candidates.begin(), candidates.end(),
                           [&](const Candidate& a, const Candidate& b) {
                             if (a.span_ok != b.span_ok) {
                               return a.span_ok;
                             }
                             if (!a.span_ok) {
                               return distance_to_range(a) < distance_to_range(b);
                             }
                             if (a.doors != b.doors) {
                               return a.doors > b.doors;
                             }
                             return a.tie_break < b.tie_break;
                           });
}

PlanUnitChoice make_choice(PlanUnit unit, std::string reason) {
  PlanUnitChoice choice;
  choice.unit = unit;
  choice.metres_per_unit = metres_per_unit(unit);
  choice.reason = std::move(reason);
  return choice;
}

}  // namespace

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

PlanUnitChoice choose_plan_unit(const PlanUnitEvidence& evidence, std::optional<PlanUnit> requested,
                                const PlanUnitOptions& options) {
  std::vector<double> door_radii;
  for (const PlanArc& arc : evidence.arcs) {
    if (arc.sweep >= options.min_door_sweep && arc.sweep <= options.max_door_sweep) {
      door_radii.push_back(arc.radius);
    }
  }
  const std::vector<Candidate> candidates = evaluate_candidates(evidence, door_radii, options);
  const auto candidate_of = [&](PlanUnit unit) -> const Candidate& {
    return *std::find_if(candidates.begin(), candidates.end(),
                         [&](const Candidate& c) { return c.unit == unit; });
  };
  const std::string says = "$INSUNITS says " + evidence.header_name;
  const std::string range =
      "the plausible " + metres(options.min_span) + " to " + metres(options.max_span);

  if (requested) {
    const Candidate& c = candidate_of(*requested);
    PlanUnitChoice choice =
        make_choice(*requested, "requested explicitly; " + describe(c, door_radii.size()));
    if (evidence.header_unit && *evidence.header_unit != *requested) {
      choice.warnings.push_back(says + ", overridden by the requested " +
                                std::string(unit_name(*requested)));
    }
    if (!c.span_ok && !evidence.extent.isEmpty()) {
      choice.warnings.push_back("in the requested " + std::string(unit_name(*requested)) +
                                " the drawing's larger side is outside " + range);
    }
    return choice;
  }

  if (evidence.extent.isEmpty()) {
    const PlanUnit unit = evidence.header_unit.value_or(PlanUnit::m);
    return make_choice(unit,
                       "the drawing holds no geometry to check the units against; using " +
                           std::string(evidence.header_unit ? "the header's " : "the default ") +
                           std::string(unit_name(unit)));
  }

  const Candidate& best = best_candidate(candidates, options);
  if (evidence.header_unit) {
    const Candidate& header = candidate_of(*evidence.header_unit);
    if (header.span_ok && 2 * header.doors >= best.doors) {
      return make_choice(header.unit,
                         says + ", which is plausible: " + describe(header, door_radii.size()));
    }
  }

  std::string evidence_text = describe(best, door_radii.size());
  std::string reason;
  if (evidence.header_unit) {
    evidence_text =
        describe(candidate_of(*evidence.header_unit), door_radii.size()) + "; " + evidence_text;
    reason = says + " but " + evidence_text;
  } else if (evidence.header_name != "none") {
    reason = says + ", which is not one of m, cm, mm, in, ft; " + evidence_text;
  } else {
    reason = "no $INSUNITS; " + evidence_text;
  }
  PlanUnitChoice choice = make_choice(best.unit, reason);
  if (evidence.header_name != "none") {
    choice.warnings.push_back(says + " but the drawing reads as " +
                              std::string(unit_name(best.unit)) + ": " + evidence_text);
  }
  if (!best.span_ok) {
    choice.warnings.push_back(
        "the drawing is implausible in every unit (its larger side is "
        "never within " +
        range + "); chose the closest, " + std::string(unit_name(best.unit)));
  } else {
    std::vector<std::string> rivals;
    for (const Candidate& c : candidates) {
      if (c.unit != best.unit && c.span_ok && c.doors == best.doors) {
        rivals.emplace_back(unit_name(c.unit));
      }
    }
    if (!rivals.empty()) {
      std::string list;
      for (const std::string& r : rivals) {
        list += (list.empty() ? "" : ", ") + r;
      }
      choice.warnings.push_back("the units are ambiguous: " + list +
                                " would also be plausible; "
                                "chose " +
                                std::string(unit_name(best.unit)) +
                                ", whose size is closest to a typical storey; set the units "
                                "explicitly if this is wrong");
    }
  }
  return choice;
}

}  // namespace floorgrid
