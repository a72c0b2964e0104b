#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/evaluation/calibration.hpp"
#include "floorgrid/evaluation/domain.hpp"
#include "floorgrid/evaluation/model_evaluation.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/pair_noise.hpp"

namespace floorgrid {

/// One model fitted to a dataset's pairs and judged.
struct ModelReport {
  std::string name;                       ///< model name
  std::shared_ptr<PointMapping> model;    ///< the fitted model (null when the fit failed)
  std::string failure;                    ///< why the fit failed (empty when it did not)
  FitSummary summary;                     ///< the fit
  std::optional<ErrorStatistics> errors;  ///< against the ground truth over the domain
  std::vector<std::size_t> histogram;     ///< 0.05 m bins up to "1.0 m and more"
  /// Its std_m against the true errors over the domain (with a truth and an error model).
  std::optional<Calibration> calibration;
  /// With a truth and ModelComparisonOptions::ideal_pairs: the errors over the domain of the
  /// same model fitted on ideal pairs (the pairs' plan points with their true grid points):
  /// what the model could reach from pairs at those places, so errors / ideal_errors is the
  /// pairs' own loss.
  std::optional<ErrorStatistics> ideal_errors;
  BackAndForth back_and_forth;    ///< drift of points mapped there and back
  double evaluate_seconds = 0.0;  ///< time of the judging
};

/// The models' options in `align`: MappingOptions' defaults, except that auto compares its
/// candidates by runs (align's pairs are in scan order; CrossValidationKind::runs).
MappingOptions run_mapping_defaults();

/// Which models are fitted and how they are judged.
struct ModelComparisonOptions {
  /// The models fitted (SPEC: at least gt, gp, gpgt, ct, dt, tps, lc, auto).
  std::vector<std::string> models = {"lc", "gt",   "gt-rigid", "gt-affine", "ct",
                                     "gp", "gpgt", "dt",       "tps",       "auto"};
  MappingOptions mapping = run_mapping_defaults();  ///< every model's (`model` set per model)
  /// k-fold cross-validation of each model (0: none); its blocks and pair budget are
  /// mapping.auto_select.cv's, so that auto reuses the results when the folds agree, and its
  /// kind too, except that auto's runs are cross-validated besides blocked folds (the models'
  /// cv_error_m and std_m stay those of blocked folds).
  int cv_folds = 5;
  /// With a truth: also fit each model (but auto) on ideal pairs and judge it (ideal_errors).
  bool ideal_pairs = false;
  int back_and_forth_rounds = 100;          ///< thesis 6.5
  std::size_t back_and_forth_points = 300;  ///< domain points followed
};

/// Judges a fitted model (report.model set): with a truth and domain points, its errors over the
/// domain, their histogram and its std_m's calibration; its back-and-forth drift over
/// `drift_points_in_plan` (align passes the domain's points); report.evaluate_seconds. The one
/// judge of `align` and `evaluate`.
void judge_model(ModelReport& report, const EvaluationDomain& domain,
                 const std::optional<GroundTruth>& truth,
                 const Eigen::Matrix2Xd& drift_points_in_plan,
                 const ModelComparisonOptions& options);

/// Progress: the model being worked on, and how many are done.
using ModelProgress =
    std::function<void(const std::string& model, std::size_t done, std::size_t total)>;

/// Fits every model to `pairs`, cross-validates it, and (with a domain and a truth) measures its
/// errors and its back-and-forth drift over the domain. A model that cannot be fitted is
/// reported with its failure instead of stopping the others.
/// With `error_pairs`, every model's cv_error_m and std_m (auto's: its chosen model's std_m)
/// come from cross-validation on those pairs instead of `pairs`, and auto still compares its
/// candidates on `pairs`: align passes the filters' own pairs when the fitted ones were slid
/// along their walls (a slid pair's along-wall place comes from a fit of every pair, its
/// held-out neighbours included, so held-out errors on slid pairs understate the error).
/// `noise` is the own noise (pair_noise) of the pairs std_m is learnt from, taken out of every
/// model's std_m.
std::vector<ModelReport> compare_models(const ReferencePairs& pairs, const EvaluationDomain& domain,
                                        const std::optional<GroundTruth>& truth,
                                        const std::optional<PairNoise>& noise,
                                        const ModelComparisonOptions& options,
                                        const ModelProgress& progress = {},
                                        const ReferencePairs* error_pairs = nullptr);

}  // namespace floorgrid
