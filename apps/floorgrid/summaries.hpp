#pragma once

#include <optional>

#include "floorgrid/pipeline/align.hpp"

namespace floorgrid::app {

/// Prints what the dual localization did: pairs kept and rejected by reason, convergence,
/// the plan's scale, the starts found, divergences and timings (and the pair error against a
/// truth when known), and where the pairs came from: the run, the maps standing in for it, or
/// both.
void print_localization(const DualLocalization& localization,
                        const std::optional<ErrorStatistics>& pair_errors,
                        PairSource from = PairSource::run);

/// Prints what the wall slide did (and the filters' pairs' median error before it, when known).
void print_wall_slide(const WallSlide& slide, std::size_t pairs,
                      const std::optional<ErrorStatistics>& errors_before);

/// Prints one row per model: errors against the truth, cross-validated error, wall distance,
/// back-and-forth drift, fit time; and the model `auto` chose.
void print_models(const Alignment& alignment);

}  // namespace floorgrid::app
