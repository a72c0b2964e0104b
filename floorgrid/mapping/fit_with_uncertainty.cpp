#include "floorgrid/mapping/fit_with_uncertainty.hpp"

namespace floorgrid {

FitSummary fit_with_uncertainty(PointMapping& model, const MappingOptions& options,
                                const ReferencePairs& pairs, const CrossValidationOptions& cv) {
  FitSummary summary = model.fit(pairs);
  if (cv.folds < 2)
    return summary;
  const CrossValidationResult r = cross_validate(options, pairs, cv);
  model.set_cv_error(r.mean_error_m, r.method);
  // auto has its chosen model's already; the others' from their held-out errors.
  if (model.name() != "auto") {
    model.set_error_model(fit_model_error(options, pairs, cv, pair_noise(pairs),
                                          cv.kind == CrossValidationKind::blocked ? &r : nullptr,
                                          cv.kind == CrossValidationKind::runs ? &r : nullptr));
  }
  return summary;
}

}  // namespace floorgrid
