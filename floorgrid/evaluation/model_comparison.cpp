#include "floorgrid/evaluation/model_comparison.hpp"

#include <algorithm>
#include <chrono>

#include "floorgrid/core/error.hpp"
#include "floorgrid/mapping/model_selection.hpp"

#include <map>

namespace floorgrid {

MappingOptions run_mapping_defaults() {
  MappingOptions options;
  options.auto_select.cv.kind = CrossValidationKind::runs;
  return options;
}

namespace {

// The pairs' plan points with the grid points the truth gives them.
ReferencePairs ideal_pairs(const ReferencePairs& pairs, const GroundTruth& truth) {
  ReferencePairs ideal = pairs;
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    ideal.points_in_grid.col(i) = truth(pairs.points_in_plan.col(i));
  return ideal;
}

// The model fitted on ideal pairs, judged over the domain (nothing when it cannot be fitted).
std::optional<ErrorStatistics> ideal_errors(const MappingOptions& mapping,
                                            const ReferencePairs& ideal,
                                            const EvaluationDomain& domain,
                                            const GroundTruth& truth) {
  try {
    auto model = make_mapping(mapping);
    model->fit(ideal);
    return error_statistics(model_errors(*model, domain.points_in_plan, truth));
  } catch (const InputError&) {
    return std::nullopt;
  }
}

}  // namespace

void judge_model(ModelReport& report, const EvaluationDomain& domain,
                 const std::optional<GroundTruth>& truth, const Eigen::Matrix2Xd& drift_points,
                 const ModelComparisonOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (truth && domain.points_in_plan.cols() > 0) {
    const std::vector<double> errors = model_errors(*report.model, domain.points_in_plan, *truth);
    report.errors = error_statistics(errors);
    report.histogram = error_histogram(errors);
    report.calibration = calibration(*report.model, domain.points_in_plan, errors);
  }
  report.back_and_forth = back_and_forth(*report.model, drift_points, options.back_and_forth_rounds,
                                         options.back_and_forth_points);
  report.evaluate_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<ModelReport> compare_models(const ReferencePairs& pairs, const EvaluationDomain& domain,
                                        const std::optional<GroundTruth>& truth,
                                        const std::optional<PairNoise>& noise,
                                        const ModelComparisonOptions& options,
                                        const ModelProgress& progress,
                                        const ReferencePairs* error_pairs) {
  std::vector<ModelReport> reports(options.models.size());
  // auto last: it reuses the other models' cross-validation when the folds agree.
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < options.models.size(); ++k)
    if (options.models[k] != "auto")
      order.push_back(k);
  for (std::size_t k = 0; k < options.models.size(); ++k)
    if (options.models[k] == "auto")
      order.push_back(k);
  // Each model's own cross-validation (its cv_error_m and std_m: blocked, or random when auto
  // compares so) and, when auto compares by runs, its candidates' runs.
  const CrossValidationKind auto_kind = options.mapping.auto_select.cv.kind;
  const std::vector<std::string> candidates = options.mapping.auto_select.candidates;
  std::map<std::string, CrossValidationResult> cross_validated, by_runs;
  const std::optional<ReferencePairs> ideal =
      options.ideal_pairs && truth && domain.points_in_plan.cols() > 0
          ? std::optional<ReferencePairs>(ideal_pairs(pairs, *truth))
          : std::nullopt;
  for (std::size_t done = 0; done < order.size(); ++done) {
    const std::size_t k = order[done];
    const std::string& name = options.models[k];
    if (progress)
      progress(name, done, options.models.size());
    ModelReport report;
    report.name = name;
    MappingOptions mapping = options.mapping;
    mapping.model = name;
    try {
      auto model = make_mapping(mapping);
      if (auto* chooser = dynamic_cast<AutoMapping*>(model.get());
          chooser && options.cv_folds == mapping.auto_select.cv.folds) {
        chooser->reuse_cross_validation(auto_kind == CrossValidationKind::runs ? by_runs
                                                                               : cross_validated);
        chooser->reuse_blocked_cross_validation(cross_validated);
        chooser->reuse_pair_noise(noise);
      }
      report.summary = model->fit(pairs);
      if (options.cv_folds >= 2 && name == "auto") {
        report.summary.cv_error_m = model->summary().cv_error_m;
        report.summary.cv = model->summary().cv;
        if (const auto* chooser = dynamic_cast<const AutoMapping*>(model.get());
            chooser && error_pairs) {
          MappingOptions chosen = mapping;
          chosen.model = chooser->chosen().name();
          CrossValidationOptions cv = mapping.auto_select.cv;
          cv.folds = options.cv_folds;
          cv.kind = CrossValidationKind::blocked;
          // The chosen model's blocked folds on those pairs are known (fitted before auto).
          const auto known = cross_validated.find(chosen.model);
          model->set_error_model(
              fit_model_error(chosen, *error_pairs, cv, noise,
                              known != cross_validated.end() ? &known->second : nullptr, nullptr));
        }
      } else if (options.cv_folds >= 2) {
        // The same blocks and pair budget as auto's, so that auto can reuse the result.
        CrossValidationOptions cv = mapping.auto_select.cv;
        cv.folds = options.cv_folds;
        if (auto_kind == CrossValidationKind::runs) {
          if (std::find(candidates.begin(), candidates.end(), name) != candidates.end())
            by_runs[name] = cross_validate(mapping, pairs, cv);
          cv.kind = CrossValidationKind::blocked;
        }
        // cv_error_m and std_m from the filters' own pairs when the fitted ones were slid
        // (error_pairs); auto still compares its candidates on the fitted pairs.
        const ReferencePairs& held = error_pairs ? *error_pairs : pairs;
        const CrossValidationResult r = cross_validate(mapping, held, cv);
        model->set_cv_error(r.mean_error_m, r.method);
        const auto runs = error_pairs ? by_runs.end() : by_runs.find(name);
        model->set_error_model(fit_model_error(
            mapping, held, cv, noise, cv.kind == CrossValidationKind::blocked ? &r : nullptr,
            runs != by_runs.end() ? &runs->second : nullptr));
        report.summary.cv_error_m = r.mean_error_m;
        report.summary.cv = r.method;
        cross_validated[name] = r;
      }
      report.model = std::move(model);
    } catch (const InputError& e) {
      report.failure = e.what();
      reports[k] = std::move(report);
      continue;
    }
    judge_model(report, domain, truth, domain.points_in_plan, options);
    if (ideal && name != "auto")
      report.ideal_errors = ideal_errors(mapping, *ideal, domain, *truth);
    reports[k] = std::move(report);
  }
  if (progress)
    progress("", options.models.size(), options.models.size());
  return reports;
}

}  // namespace floorgrid
