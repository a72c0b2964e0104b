#include "floorgrid/mapping/checked_fit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/mapping/fit_with_uncertainty.hpp"
#include "floorgrid/mapping/model_registry.hpp"
#include "floorgrid/mapping/pair_extent.hpp"

namespace floorgrid {

namespace {

/// Refuses a fit whose dense matrices would not fit the memory limit, before it starts.
void check_fit_memory(const MappingOptions& options, std::size_t pairs, double limit_gb) {
  const double needed_gb = static_cast<double>(fit_memory_bytes(options, pairs)) / (1u << 30);
  if (limit_gb > 0.0 && needed_gb > limit_gb) {
    throw InputError(
        fmt::format("model {} with {} of the pairs would need about {:.1f} GiB, "
                    "more than the limit of {:.1f} GiB: lower --budget or raise "
                    "--memory-limit",
                    options.model, std::min<std::size_t>(pairs, options.common.reduction.budget),
                    needed_gb, limit_gb),
        {}, 0, "--budget");
  }
}

/// Refuses a pair far outside the box of the others (a typo, a unit slip), naming its line: one
/// such pair made every extent-based choice of a fit about it ("cv error inf", then a model
/// `map` refuses). Dropping it quietly would fit what the user did not mean either.
void refuse_far_pairs(const ReferencePairs& pairs, const std::vector<long>& lines,
                      const std::string& source) {
  const std::vector<FarPair> far = far_pairs(pairs);
  if (far.empty())
    return;
  const FarPair& f = far.front();
  const std::string others =
      far.size() > 1 ? fmt::format(" ({} such pairs; the first named)", far.size()) : "";
  const auto i = static_cast<std::size_t>(f.index);
  throw InputError(
      fmt::format("this pair's {} point lies {:.4g} m outside the box of the pairs' {} points "
                  "({:.4g} m across, their 1st to 99th percentiles): farther than {:g} times "
                  "that, a typo or a unit slip?{}; correct or delete it",
                  f.side, f.distance, f.side, f.extent, FarPairOptions{}.factor, others),
      source, i < lines.size() ? lines[i] : static_cast<long>(i) + 1,
      f.side + (f.axis == 0 ? "_x" : "_y"));
}

/// Runs `work`; an InputError about the pairs that names no file gets `source`'s name.
template <typename Work>
auto with_source(const std::string& source, const Work& work) {
  try {
    return work();
  } catch (const InputError& e) {
    if (!e.file().empty())
      throw;
    throw InputError(e.message(), source, e.line(), e.field());
  }
}

}  // namespace

CheckedFit fit_checked(const ReferencePairs& pairs, const ModelFitRequest& request,
                       const std::string& source, const std::vector<long>& lines) {
  refuse_far_pairs(pairs, lines, source);
  check_fit_memory(request.mapping, static_cast<std::size_t>(pairs.size()),
                   request.memory_limit_gb);
  auto model = make_mapping(request.mapping);
  model->set_unit(request.unit);
  CrossValidationOptions folds = request.mapping.auto_select.cv;
  folds.folds = request.cv_folds >= 2 ? request.cv_folds : 0;
  FitSummary s = with_source(
      source, [&] { return fit_with_uncertainty(*model, request.mapping, pairs, folds); });
  // Numerical trouble is reported, not written: `map` refuses such a model.
  const FitSummary& fitted = model->summary();
  if (!std::isfinite(fitted.rms_m) || (fitted.cv_error_m && !std::isfinite(*fitted.cv_error_m))) {
    throw InputError(
        fmt::format("the fit's rms ({}) or cross-validated error ({}) is not finite: these "
                    "pairs do not support model {}; no model written",
                    fitted.rms_m, fitted.cv_error_m ? *fitted.cv_error_m : 0.0, fitted.model),
        source, 0, "pairs");
  }
  return {std::move(model), std::move(s)};
}

}  // namespace floorgrid
