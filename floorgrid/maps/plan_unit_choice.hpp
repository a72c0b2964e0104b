#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "floorgrid/maps/plan_unit_scores.hpp"
#include "floorgrid/maps/plan_units.hpp"

namespace floorgrid {

/// How sure a unit choice is.
enum class UnitConfidence { low, medium, high };
/// "low", "medium", "high".
std::string_view to_string(UnitConfidence confidence);

/// Where a unit choice came from.
enum class UnitSource { requested, header, header_overruled, guessed };
/// "requested", "header", "header_overruled", "guessed".
std::string_view to_string(UnitSource source);

/// One unit the drawing may be in.
struct PlanUnitCandidate {
  PlanUnit unit = PlanUnit::m;  ///< the unit
  double score = 0.0;           ///< points of the evidence that fits it, the header's included
  double probability = 0.0;     ///< softmax of the scores over every unit
};

/// The unit chosen for a drawing, why, and how sure.
struct PlanUnitChoice {
  PlanUnit unit = PlanUnit::m;              ///< the unit used
  double metres_per_unit = 1.0;             ///< of `unit`
  UnitSource source = UnitSource::guessed;  ///< requested, header (kept or overruled), guess
  UnitConfidence confidence = UnitConfidence::low;  ///< how sure the choice is
  std::string reason;                               ///< one sentence: why this unit
  std::vector<std::string> evidence;  ///< one line per kind of evidence: what it shows, per unit
  /// Units with a probability of at least 1% (the chosen one always), most probable first: what
  /// a robot's run may decide between when the drawing cannot.
  std::vector<PlanUnitCandidate> candidates;
  std::vector<std::string> warnings;  ///< overruled or missing header, ambiguity, implausibility
};

/// Chooses the drawing's unit. An explicit `requested` unit is obeyed (with warnings when it
/// disagrees with the header or makes the drawing implausible). Otherwise every unit is scored by
/// the drawing's features: door swings (arcs of a quarter turn, with a leaf) of a door's radius,
/// dimension texts whose stated length fits the measured one, a typical wall thickness and room
/// spacing, and, weakly, an extent of a storey's size (a site or several storeys side by side
/// is no reason to change units; only an absurd size is). The header's unit gets
/// `header_weight` points, so it is kept unless the drawing contradicts it strongly. Without a
/// usable header the units are guessed, always with a warning.
PlanUnitChoice choose_plan_unit(const PlanUnitEvidence& evidence, std::optional<PlanUnit> requested,
                                const PlanUnitOptions& options = {});

}  // namespace floorgrid
