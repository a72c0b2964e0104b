#pragma once

#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/model_selection.hpp"

namespace floorgrid {

/// Fits `model` (made by make_mapping(options)) to `pairs` with its accuracy, as `floorgrid fit
/// --cv` does: its error cross-validated by `cv` (none when cv.folds < 2), and its error model
/// (std_m) fitted on those folds' held-out residuals (auto keeps its chosen model's). Returns
/// the fit's summary; InputError from the fit (too few pairs, for one).
FitSummary fit_with_uncertainty(PointMapping& model, const MappingOptions& options,
                                const ReferencePairs& pairs, const CrossValidationOptions& cv);

}  // namespace floorgrid
