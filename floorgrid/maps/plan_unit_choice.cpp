#include "floorgrid/maps/plan_unit_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace floorgrid {

namespace {

/// A length in metres for messages: three significant digits are enough to judge a unit.
std::string metres(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, std::abs(value) >= 1e3 ? "%.0f m" : "%.3g m", value);
  return buffer;
}

/// A length in drawing units for messages: 4 significant digits, whole numbers from 10^4.
std::string drawing_units(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, std::abs(value) >= 1e4 ? "%.0f" : "%.4g", value);
  return buffer;
}

/// "a" or "a-b" for a range of drawing lengths.
std::string drawing_range(double lo, double hi) {
  return hi <= lo * 1.0005 ? drawing_units(lo) : drawing_units(lo) + "-" + drawing_units(hi);
}

std::string percent(double p) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, p >= 0.1 ? "%.0f%%" : "%.1f%%", 100.0 * p);
  return buffer;
}

std::string name(PlanUnit unit) {
  return std::string(unit_name(unit));
}

/// "in inches", "in millimetres", ...: for prose.
std::string in_words(PlanUnit unit) {
  switch (unit) {
    case PlanUnit::m:
      return "in metres";
    case PlanUnit::cm:
      return "in centimetres";
    case PlanUnit::mm:
      return "in millimetres";
    case PlanUnit::in:
      return "in inches";
    case PlanUnit::ft:
      return "in feet";
  }
  return "in " + name(unit);
}

/// "a" or "a-b" for a range of lengths in metres.
std::string metre_range(double lo, double hi) {
  if (hi <= lo * 1.005) {
    return metres(lo);
  }
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.3g-%.3g m", lo, hi);
  return buffer;
}

/// Words what the evidence shows in each unit.
class Wording {
 public:
  Wording(const PlanUnitEvidence& evidence, const PlanUnitOptions& options,
          const PlanUnitScores& scores)
      : e_(evidence), o_(options), scores_(scores) {}

  /// What the features that fit `unit` look like in it: "10 door swings 0.61-0.91 m wide, ...".
  std::string support(PlanUnit unit) const {
    const PlanUnitScore& v = of(unit);
    std::vector<std::string> parts;
    if (v.dimensions_fitting > 0) {
      parts.push_back(std::to_string(v.dimensions_fitting) + " of " +
                      std::to_string(e_.dimensions.size()) + " dimension texts fit (" +
                      e_.dimensions[v.example].text + " for " +
                      drawing_units(e_.dimensions[v.example].measured) + " units)");
    }
    if (v.door_count > 0) {
      parts.push_back(door_phrase(v));
    }
    if (scores_.walls_count && v.walls >= o_.wall_weight) {
      parts.push_back("walls " + metres(e_.walls.thickness * v.metres_per_unit) + " thick");
    }
    if (e_.walls.spacing > 0.0 && scores_.walls_count && v.rooms >= o_.room_weight) {
      parts.push_back("rooms and corridors about " + metres(e_.walls.spacing * v.metres_per_unit) +
                      " wide");
    }
    parts.push_back(size_phrase(v));
    return join(parts);
  }

  /// What the features that fit `better` rather than `unit` would be in `unit`: "no dimension
  /// text fits, the 10 door swings would be 24-36 mm wide, ...".
  std::string misfit(PlanUnit unit, PlanUnit better) const {
    const PlanUnitScore& v = of(unit);
    const PlanUnitScore& b = of(better);
    std::vector<std::string> parts;
    if (b.dimensions_fitting > v.dimensions_fitting) {
      parts.push_back(v.dimensions_fitting == 0
                          ? std::string("no dimension text fits")
                          : std::to_string(v.dimensions_fitting) + " of " +
                                std::to_string(e_.dimensions.size()) + " dimension texts fit");
    }
    if (b.door_count > v.door_count) {
      parts.push_back("the " + std::to_string(b.door_count) + " door " +
                      (scores_.doors.with_leaves ? "swings" : "swing-like arcs") + " would be " +
                      metre_range(b.door_min * v.metres_per_unit, b.door_max * v.metres_per_unit) +
                      " wide");
    }
    if (scores_.walls_count && b.walls > v.walls) {
      parts.push_back("walls " + metres(e_.walls.thickness * v.metres_per_unit) + " thick");
    }
    if (scores_.walls_count && b.rooms > v.rooms) {
      parts.push_back("rooms " + metres(e_.walls.spacing * v.metres_per_unit) + " wide");
    }
    if (b.extent > v.extent + 1.0) {
      parts.push_back(size_phrase(v));
    }
    return join(parts);
  }

  /// One line per kind of evidence, with what it means in `units` (the ones worth comparing).
  std::vector<std::string> evidence_lines(const std::vector<PlanUnit>& units) const {
    std::vector<std::string> lines;
    const auto in_units = [&](const auto& describe) {
      std::string out;
      for (const PlanUnit unit : units) {
        out += (out.empty() ? "" : "; ") + describe(of(unit)) + " " + in_words(unit);
      }
      return out;
    };
    lines.push_back("extent " + drawing_units(scores_.size.x()) + " x " +
                    drawing_units(scores_.size.y()) + " units" +
                    (e_.core_extent.isEmpty() ? "" : " (far-off strays left out)") + ": " +
                    in_units([&](const PlanUnitScore& v) {
                      return metres(scores_.size.x() * v.metres_per_unit) + " x " +
                             metres(scores_.size.y() * v.metres_per_unit);
                    }));
    if (!scores_.doors.arcs.empty()) {
      double lo = HUGE_VAL, hi = 0.0;
      for (const PlanArc& arc : scores_.doors.arcs) {
        lo = std::min(lo, arc.radius);
        hi = std::max(hi, arc.radius);
      }
      lines.push_back(std::to_string(scores_.doors.arcs.size()) +
                      (scores_.doors.with_leaves ? " door swings (quarter arcs with a leaf)"
                                                 : " quarter arcs without door leaves") +
                      ", radius " + drawing_range(lo, hi) +
                      " units: " + in_units([&](const PlanUnitScore& v) {
                        return std::to_string(v.door_count) + " door-sized";
                      }));
    } else {
      lines.push_back("no door swings (quarter arcs)");
    }
    if (!e_.dimensions.empty()) {
      lines.push_back(
          std::to_string(e_.dimensions.size()) +
          " dimension texts state a length with its unit: " + in_units([&](const PlanUnitScore& v) {
            return std::to_string(v.dimensions_fitting) + " fit";
          }));
    }
    if (scores_.walls_count) {
      char share[32];
      std::snprintf(share, sizeof share, "%.0f%%", 100.0 * e_.walls.thickness_share);
      lines.push_back(std::to_string(e_.walls.faces) + " wall faces, most (" + share + ") " +
                      drawing_units(e_.walls.thickness) +
                      " units thick: " + in_units([&](const PlanUnitScore& v) {
                        return metres(e_.walls.thickness * v.metres_per_unit);
                      }));
      if (e_.walls.spacing > 0.0) {
        lines.push_back("beyond the walls, rooms and corridors about " +
                        drawing_units(e_.walls.spacing) +
                        " units wide: " + in_units([&](const PlanUnitScore& v) {
                          return metres(e_.walls.spacing * v.metres_per_unit);
                        }));
      }
    } else {
      lines.push_back(std::to_string(e_.walls.faces) +
                      " wall faces (parallel lines far closer on one side than the other): too "
                      "few, or of no common thickness, to tell the units");
    }
    return lines;
  }

 private:
  static std::string join(const std::vector<std::string>& parts) {
    std::string out;
    for (const std::string& p : parts) {
      out += (out.empty() ? "" : ", ") + p;
    }
    return out;
  }

  std::string door_phrase(const PlanUnitScore& v) const {
    return std::to_string(v.door_count) + " door " +
           (scores_.doors.with_leaves ? "swings" : "swing-like arcs") + " " +
           metre_range(v.door_min * v.metres_per_unit, v.door_max * v.metres_per_unit) + " wide";
  }

  std::string size_phrase(const PlanUnitScore& v) const {
    const std::string x = metres(scores_.size.x() * v.metres_per_unit);
    return x.substr(0, x.size() - 2) + " x " + metres(scores_.size.y() * v.metres_per_unit) +
           " in all";
  }

  const PlanUnitScore& of(PlanUnit unit) const { return scores_.of(unit); }

  const PlanUnitEvidence& e_;
  const PlanUnitOptions& o_;
  const PlanUnitScores& scores_;
};

/// Softmax of the scores; candidates of at least 1% (and `chosen`), most probable first.
std::vector<PlanUnitCandidate> candidates_of(const std::vector<PlanUnitScore>& scores,
                                             PlanUnit chosen) {
  double top = -HUGE_VAL;
  for (const PlanUnitScore& v : scores) {
    top = std::max(top, v.total());
  }
  double sum = 0.0;
  for (const PlanUnitScore& v : scores) {
    sum += std::exp(v.total() - top);
  }
  std::vector<PlanUnitCandidate> out;
  for (const PlanUnitScore& v : scores) {
    const double p = std::exp(v.total() - top) / sum;
    if (p >= 0.01 || v.unit == chosen) {
      out.push_back({v.unit, v.total(), p});
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.probability > b.probability; });
  return out;
}

std::string candidates_text(const std::vector<PlanUnitCandidate>& candidates) {
  std::string out;
  for (const PlanUnitCandidate& c : candidates) {
    out += (out.empty() ? "" : ", ") + name(c.unit) + " " + percent(c.probability);
  }
  return out;
}

}  // namespace

std::string_view to_string(UnitConfidence confidence) {
  switch (confidence) {
    case UnitConfidence::low:
      return "low";
    case UnitConfidence::medium:
      return "medium";
    case UnitConfidence::high:
      return "high";
  }
  return "low";
}

std::string_view to_string(UnitSource source) {
  switch (source) {
    case UnitSource::requested:
      return "requested";
    case UnitSource::header:
      return "header";
    case UnitSource::header_overruled:
      return "header_overruled";
    case UnitSource::guessed:
      return "guessed";
  }
  return "guessed";
}

PlanUnitChoice choose_plan_unit(const PlanUnitEvidence& evidence, std::optional<PlanUnit> requested,
                                const PlanUnitOptions& options) {
  const PlanUnitScores scores = score_plan_units(evidence, options);
  const Wording words(evidence, options, scores);
  const std::string says = "$INSUNITS says " + evidence.header_name;
  PlanUnitChoice choice;

  const auto finish = [&](PlanUnit unit) {
    choice.unit = unit;
    choice.metres_per_unit = metres_per_unit(unit);
    choice.candidates = candidates_of(scores.units, unit);
    // Compare the chosen unit with the header's and the features' favourite, where they differ.
    std::vector<PlanUnit> shown{unit};
    for (const PlanUnit other :
         {evidence.header_unit.value_or(unit), scores.best_by_features().unit}) {
      if (std::find(shown.begin(), shown.end(), other) == shown.end()) {
        shown.push_back(other);
      }
    }
    for (const PlanUnitCandidate& c : choice.candidates) {
      if (shown.size() < 3 && std::find(shown.begin(), shown.end(), c.unit) == shown.end()) {
        shown.push_back(c.unit);
      }
    }
    choice.evidence = words.evidence_lines(shown);
  };

  if (requested) {
    finish(*requested);
    choice.source = UnitSource::requested;
    choice.confidence = UnitConfidence::high;
    choice.reason =
        "requested explicitly; " + in_words(*requested) + ": " + words.support(*requested);
    if (evidence.header_unit && *evidence.header_unit != *requested) {
      choice.warnings.push_back(says + ", overridden by the requested " + name(*requested));
    }
    const PlanUnitScore& v = scores.of(*requested);
    if (v.span > 0.0 && (v.span < options.min_span || v.span > options.max_span)) {
      choice.warnings.push_back("in the requested " + name(*requested) +
                                " the drawing's larger side is " + metres(v.span) +
                                ", outside the plausible " + metres(options.min_span) + " to " +
                                metres(options.max_span) + " of a storey");
    }
    return choice;
  }

  if (evidence.extent.isEmpty()) {
    const PlanUnit unit = evidence.header_unit.value_or(PlanUnit::m);
    finish(unit);
    choice.source = evidence.header_unit ? UnitSource::header : UnitSource::guessed;
    choice.reason = "the drawing holds no geometry to check the units against; using " +
                    std::string(evidence.header_unit ? "the header's " : "the default ") +
                    name(unit);
    if (!evidence.header_unit) {
      choice.warnings.push_back("no usable $INSUNITS and no geometry: the units were guessed as " +
                                name(unit) + "; set floorplan_units if this is wrong");
    }
    return choice;
  }

  // The best total score; exact ties go to the earlier unit of kPlanUnits.
  const PlanUnitScore* best = &scores.units.front();
  for (const PlanUnitScore& v : scores.units) {
    best = v.total() > best->total() ? &v : best;
  }
  finish(best->unit);
  const double p =
      choice.candidates.front().unit == best->unit ? choice.candidates.front().probability : 0.0;
  const PlanUnitScore& favourite = scores.best_by_features();
  // The features favour another unit by more than a point: worth a warning, not a verdict.
  const bool contradicted = favourite.features() > best->features() + 1.0;
  const bool supported = !contradicted && best->features() >= options.wall_weight;
  choice.confidence = p >= 0.99 && supported ? UnitConfidence::high
                      : p >= 0.8             ? UnitConfidence::medium
                                             : UnitConfidence::low;
  const std::string how_sure =
      std::string(choice.confidence == UnitConfidence::low ? "ambiguous: " : "") + "confidence " +
      std::string(to_string(choice.confidence)) + "; candidates " +
      candidates_text(choice.candidates);
  const std::string unit = name(best->unit);

  if (evidence.header_unit && *evidence.header_unit == best->unit) {
    choice.source = UnitSource::header;
    choice.reason = says + ", which " +
                    (contradicted ? std::string("the drawing does not contradict strongly enough")
                                  : "is plausible") +
                    ": " + in_words(best->unit) + " " + words.support(best->unit);
    if (contradicted) {
      choice.warnings.push_back(
          "the drawing partly disagrees with the header (" + says + "): " + in_words(best->unit) +
          " " + words.misfit(best->unit, favourite.unit) + ", as if it were drawn " +
          in_words(favourite.unit) + "; too little to overrule the header, kept " + unit + " (" +
          how_sure + ")");
    }
  } else if (evidence.header_unit) {
    choice.source = UnitSource::header_overruled;
    const PlanUnit header = *evidence.header_unit;
    choice.reason = says + " but the drawing reads as " + unit + ": " + in_words(best->unit) + " " +
                    words.support(best->unit) + "; " + in_words(header) + " " +
                    words.misfit(header, best->unit);
    choice.warnings.push_back(choice.reason + " (" + how_sure + ")");
  } else {
    choice.source = UnitSource::guessed;
    const std::string header_text = evidence.header_name == "none"
                                        ? "no $INSUNITS"
                                        : says + ", which is not one of m, cm, mm, in, ft";
    choice.reason = header_text + "; guessed " + unit +
                    " from the drawing: " + in_words(best->unit) + " " + words.support(best->unit);
    choice.warnings.push_back(header_text + ": the units were guessed as " + unit + " (" +
                              how_sure + "); set floorplan_units if this is wrong");
  }
  if (best->absurd) {
    choice.warnings.push_back("the drawing is implausible in every unit (its larger side is " +
                              metres(best->span) + " in " + unit + ", the closest of all units)");
  }
  return choice;
}

}  // namespace floorgrid
