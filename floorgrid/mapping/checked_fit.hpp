#pragma once

#include <memory>
#include <string>
#include <vector>

#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// How one model is fitted to pairs (`floorgrid fit`, the Python module's Model.fit).
struct ModelFitRequest {
  MappingOptions mapping;        ///< the model (`mapping.model`) and its settings
  int cv_folds = 5;              ///< k of the cross-validation (0: none, and no std_m)
  double unit = 1.0;             ///< metres per unit of the pairs, recorded in the model
  double memory_limit_gb = 0.0;  ///< GiB a fit may use at most (0: no limit)
};

/// A model fitted by fit_checked.
struct CheckedFit {
  std::unique_ptr<PointMapping> model;  ///< fitted, with its cv error and std_m when asked
  FitSummary summary;                   ///< what fit_with_uncertainty returned (its warnings)
};

/// Fits one model with its accuracy (fit_with_uncertainty) as `floorgrid fit` does, and refuses
/// what it would not write, each an InputError naming `source` (the pairs' file):
/// - a pair far outside the box of the others (a typo or a unit slip: see far_pairs), naming
///   its line (`lines[i]`, 1-based, when given; else its 1-based row) and column;
/// - a fit whose dense matrices would need more than the memory limit (field `--budget`);
/// - a fit whose rms or cross-validated error is not finite (field `pairs`).
/// `pairs` in metres.
CheckedFit fit_checked(const ReferencePairs& pairs, const ModelFitRequest& request,
                       const std::string& source, const std::vector<long>& lines = {});

}  // namespace floorgrid
