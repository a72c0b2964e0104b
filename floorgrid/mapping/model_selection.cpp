#include "floorgrid/mapping/model_selection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/geometry/point_index.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid {

const char* to_string(CrossValidationKind kind) {
  switch (kind) {
    case CrossValidationKind::blocked:
      return "blocked";
    case CrossValidationKind::random:
      return "random";
    case CrossValidationKind::runs:
      return "runs";
  }
  return "blocked";
}

CrossValidationKind parse_cv_kind(const std::string& name, const std::string& field) {
  for (const auto kind :
       {CrossValidationKind::blocked, CrossValidationKind::random, CrossValidationKind::runs}) {
    if (name == to_string(kind))
      return kind;
  }
  throw InputError("must be blocked, random or runs (got " + name + ")", {}, 0, field);
}

void validate(const CrossValidationOptions& cv, const std::string& prefix) {
  require_option(cv.folds >= 2, prefix + "folds", cv.folds, ">= 2");
  require_option(cv.block_size >= 0.0 && cv.block_size <= kMaxCoordinate, prefix + "block_size",
                 cv.block_size, "0 (chosen from the pairs) or a size in metres");
}

namespace {

/// Each model's mean squared error over the `kept` pairs (infinite for a model whose errors are
/// not one per pair, or with an infinite error on a kept pair).
std::vector<double> mean_squares_over(const std::vector<std::vector<double>>& errors,
                                      const std::vector<char>& kept) {
  std::vector<double> scores(errors.size(), std::numeric_limits<double>::infinity());
  for (std::size_t m = 0; m < errors.size(); ++m) {
    if (errors[m].size() != kept.size())
      continue;
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < kept.size(); ++i) {
      if (kept[i] != 0) {
        sum += errors[m][i] * errors[m][i];
        ++count;
      }
    }
    if (count > 0 && std::isfinite(sum))
      scores[m] = sum / static_cast<double>(count);
  }
  return scores;
}

/// The folds `cv` asks for over `pairs`, blocked in the grid frame (metres whatever the plan's
/// units), with what was used.
Folds deal_folds(const ReferencePairs& pairs, const CrossValidationOptions& cv,
                 std::uint64_t seed) {
  const auto folds = static_cast<std::size_t>(cv.folds);
  if (cv.kind == CrossValidationKind::random)
    return random_folds(static_cast<std::size_t>(pairs.size()), folds, seed);
  if (cv.kind == CrossValidationKind::runs)
    return run_folds(static_cast<std::size_t>(pairs.size()), folds, kRunsPerFold);
  const double size =
      cv.block_size > 0.0 ? cv.block_size : choose_block_size(pairs.points_in_grid, folds);
  return blocked_folds(pairs.points_in_grid, folds, size, seed);
}

}  // namespace

CrossValidationResult cross_validate(const MappingOptions& options, const ReferencePairs& given,
                                     const CrossValidationOptions& cv) {
  validate(cv);
  validate_pairs(given);
  ReductionOptions budget;
  budget.budget = std::max<std::size_t>(cv.max_pairs, 3);
  // Runs keep the pairs' order: thinned evenly along it, not binned in space.
  const ReferencePairs pairs = cv.kind == CrossValidationKind::runs
                                   ? thin_in_order(given, budget.budget)
                                   : reduce_pairs(merge_duplicates(given), budget);
  const auto n = static_cast<std::size_t>(pairs.size());
  CrossValidationResult result;
  result.pairs = n;
  const Folds folds = deal_folds(pairs, cv, options.common.seed);
  result.method = {
      .kind = to_string(cv.kind), .folds = folds.count, .block_size = folds.block_size, .pairs = n};
  std::vector<double> errors;
  result.pair_errors.assign(n, std::numeric_limits<double>::infinity());
  for (std::size_t f = 0; f < folds.count; ++f) {
    std::vector<Eigen::Index> train, test;
    folds.split(f, train, test);
    auto model = make_mapping(options);
    try {
      model->fit(select_pairs(pairs, train));
    } catch (const InputError&) {
      ++result.failed_folds;
      continue;
    }
    const PointIndex2D training(select_pairs(pairs, train).points_in_plan);
    double sum = 0.0;
    for (const Eigen::Index i : test) {
      const double e =
          (model->forward(pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i)).norm();
      errors.push_back(std::isfinite(e) ? e : std::numeric_limits<double>::infinity());
      result.pair_errors[static_cast<std::size_t>(i)] = errors.back();
      sum += errors.back();
      if (std::isfinite(e) && cv.kind != CrossValidationKind::random)
        result.held_out.push_back({e, training.nearest(pairs.points_in_plan.col(i)).distance,
                                   pairs.points_in_plan.col(i)});
    }
    result.fold_errors.push_back(sum / static_cast<double>(test.size()));
  }
  if (errors.empty()) {
    result.mean_error_m = result.median_error_m = std::numeric_limits<double>::infinity();
    return result;
  }
  double sum = 0.0;
  for (const double e : errors)
    sum += e;
  result.mean_error_m = sum / static_cast<double>(errors.size());
  result.median_error_m = upper_median(errors);
  return result;
}

std::optional<ErrorModel> fit_model_error(const MappingOptions& options,
                                          const ReferencePairs& pairs,
                                          const CrossValidationOptions& cv,
                                          const std::optional<PairNoise>& noise,
                                          const CrossValidationResult* blocked,
                                          const CrossValidationResult* runs) {
  CrossValidationOptions folds = cv;
  std::optional<CrossValidationResult> done_blocked, done_runs;
  if (!blocked) {
    folds.kind = CrossValidationKind::blocked;
    blocked = &done_blocked.emplace(cross_validate(options, pairs, folds));
  }
  std::optional<ErrorLevel> level;
  if (noise) {
    if (!runs) {
      folds.kind = CrossValidationKind::runs;
      runs = &done_runs.emplace(cross_validate(options, pairs, folds));
    }
    level = ErrorLevel{runs->held_out, noise->mean_square_m2};
  }
  return fit_error_model(blocked->held_out, options.uncertainty, level);
}

std::vector<char> paired_pairs_kept(const std::vector<std::vector<double>>& errors, double trim) {
  if (errors.empty())
    return {};
  const std::size_t n = errors.front().size();
  std::vector<double> typical(n, std::numeric_limits<double>::infinity()), finite;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<double> at;
    for (const std::vector<double>& model : errors) {
      if (i < model.size() && std::isfinite(model[i]))
        at.push_back(model[i]);
    }
    if (!at.empty()) {
      typical[i] = upper_median(at);
      finite.push_back(typical[i]);
    }
  }
  std::vector<char> kept(n, 0);
  if (finite.empty())
    return kept;
  const double limit = trim * upper_median(finite);
  for (std::size_t i = 0; i < n; ++i)
    kept[i] = typical[i] <= limit ? 1 : 0;
  return kept;
}

std::vector<double> paired_scores(const std::vector<std::vector<double>>& errors, double trim) {
  return mean_squares_over(errors, paired_pairs_kept(errors, trim));
}

double paired_score_difference_se(const std::vector<double>& a, const std::vector<double>& b,
                                  const std::vector<char>& kept, std::size_t stretches) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const std::size_t n = kept.size();
  if (a.size() != n || b.size() != n || stretches < 2)
    return kInfinity;
  // Per stretch: its kept pairs and the sum of their differences of squared errors.
  std::vector<double> sums(stretches, 0.0), counts(stretches, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (kept[i] == 0)
      continue;
    const double d = a[i] * a[i] - b[i] * b[i];
    if (!std::isfinite(d))
      return kInfinity;
    const std::size_t s = run_stretch(i, n, stretches);
    sums[s] += d;
    counts[s] += 1.0;
  }
  double total = 0.0, count = 0.0, used = 0.0;
  for (std::size_t s = 0; s < stretches; ++s) {
    total += sums[s];
    count += counts[s];
    used += counts[s] > 0.0 ? 1.0 : 0.0;
  }
  if (used < 2.0)
    return kInfinity;
  // The variance of a ratio of sums over independent stretches (the mean difference is
  // total / count): sum over stretches of (sum_s - mean count_s)^2, times used / (used - 1).
  const double mean = total / count;
  double spread = 0.0;
  for (std::size_t s = 0; s < stretches; ++s)
    spread += (sums[s] - mean * counts[s]) * (sums[s] - mean * counts[s]);
  return std::sqrt(spread * used / (used - 1.0)) / count;
}

std::vector<double> leave_one_out_errors(const MappingOptions& options,
                                         const ReferencePairs& pairs) {
  std::vector<double> errors;
  for (Eigen::Index left_out = 0; left_out < pairs.size(); ++left_out) {
    std::vector<Eigen::Index> train;
    for (Eigen::Index i = 0; i < pairs.size(); ++i) {
      if (i != left_out)
        train.push_back(i);
    }
    auto model = make_mapping(options);
    try {
      model->fit(select_pairs(pairs, train));
      errors.push_back(
          (model->forward(pairs.points_in_plan.col(left_out)) - pairs.points_in_grid.col(left_out))
              .norm());
    } catch (const InputError&) {
      errors.push_back(std::numeric_limits<double>::infinity());
    }
  }
  return errors;
}

AutoMapping::AutoMapping(const MappingOptions& options)
    : PointMapping(options.common), options_(std::make_unique<MappingOptions>(options)) {
  for (const auto& name : options_->auto_select.candidates) {
    if (name == "auto")
      throw InputError("auto cannot choose itself", {}, 0, "auto.candidates");
    MappingOptions probe = *options_;
    probe.model = name;
    make_mapping(probe);  // throws for an unknown name
  }
  if (options_->auto_select.candidates.empty()) {
    throw InputError("needs at least one candidate", {}, 0, "auto.candidates");
  }
  validate(options_->auto_select.cv, "auto_select.cv.");
  require_option(options_->auto_select.tie_standard_errors >= 0.0 &&
                     options_->auto_select.tie_standard_errors <= 100.0,
                 "auto_select.tie_standard_errors", options_->auto_select.tie_standard_errors,
                 "in [0, 100]");
}

AutoMapping::~AutoMapping() = default;

void AutoMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  table_.clear();
  // Runs are compared pair by pair (paired_scores): trimmed of the stretches the filters got
  // wrong, which would weigh on every model's mean alike, and most on the smooth models that
  // do not follow it (Orebro: the mean picks gpgt, 2.8x the best); by mean squared error, whose
  // differences are the models' own, where a median hides them under the pairs' noise (FR079:
  // the median picks tps, 1.45x gp's error).
  const bool paired = options_->auto_select.cv.kind == CrossValidationKind::runs;
  std::vector<CrossValidationResult> results;
  for (const auto& name : options_->auto_select.candidates) {
    MappingOptions candidate = *options_;
    candidate.model = name;
    const auto known = known_.find(name);
    results.push_back(known != known_.end()
                          ? known->second
                          : cross_validate(candidate, pairs, options_->auto_select.cv));
  }
  std::vector<double> scores;
  std::vector<std::vector<double>> errors;
  for (const CrossValidationResult& cv : results) {
    scores.push_back(cv.mean_error_m);
    errors.push_back(cv.pair_errors);
  }
  const std::vector<char> kept = paired ? paired_pairs_kept(errors) : std::vector<char>{};
  if (paired)
    scores = mean_squares_over(errors, kept);
  // The lowest score (the earlier on ties); by runs then the earliest candidate within
  // tie_standard_errors of it: a difference the pairs' noise could make is no reason to leave
  // the cheaper model.
  std::size_t pick = results.size();
  for (std::size_t k = 0; k < results.size(); ++k) {
    if (std::isfinite(scores[k]) && (pick == results.size() || scores[k] < scores[pick]))
      pick = k;
  }
  if (pick == results.size())
    throw InputError("no candidate model could be fitted to the pairs", {}, 0, "pairs");
  const std::size_t lowest = pick;
  std::vector<double> standard_errors(results.size(), 0.0);
  if (paired && options_->auto_select.tie_standard_errors > 0.0) {
    for (std::size_t k = 0; k < results.size(); ++k) {
      if (k != lowest) {
        standard_errors[k] =
            paired_score_difference_se(errors[k], errors[lowest], kept, kRunStretches);
      }
    }
    for (std::size_t k = 0; k < lowest; ++k) {
      if (scores[k] <=
          scores[lowest] + options_->auto_select.tie_standard_errors * standard_errors[k]) {
        pick = k;
        break;
      }
    }
  }
  Value table = Value::object();
  for (std::size_t k = 0; k < results.size(); ++k) {
    const std::string& name = options_->auto_select.candidates[k];
    const CrossValidationResult& cv = results[k];
    table_[name] = cv.mean_error_m;
    table[name] = {
        {"mean_error_m", std::isfinite(cv.mean_error_m) ? Value(cv.mean_error_m) : Value()},
        {"median_error_m", std::isfinite(cv.median_error_m) ? Value(cv.median_error_m) : Value()},
        {"failed_folds", cv.failed_folds}};
    if (paired) {
      table[name]["paired_rms_m"] =
          std::isfinite(scores[k]) ? Value(std::sqrt(scores[k])) : Value();
      // The standard error of its mean squared error's difference from the lowest's, m^2.
      table[name]["paired_difference_se_m2"] =
          std::isfinite(standard_errors[k]) ? Value(standard_errors[k]) : Value();
    }
  }
  const std::string& best = options_->auto_select.candidates[pick];
  const double best_error = results[pick].mean_error_m;
  const CrossValidationRecord& best_method = results[pick].method;
  MappingOptions chosen = *options_;
  chosen.model = best;
  chosen_ = make_mapping(chosen);
  const FitSummary inner = chosen_->fit(pairs);
  chosen_->set_cv_error(best_error, best_method);
  // The chosen model's std_m, from its own held-out errors: the candidates' cross-validation
  // is one of the two it needs (blocked or runs), when it compared so.
  const auto known = known_blocked_.find(best);
  const CrossValidationResult* blocked =
      known != known_blocked_.end()                                   ? &known->second
      : options_->auto_select.cv.kind == CrossValidationKind::blocked ? &results[pick]
                                                                      : nullptr;
  chosen_->set_error_model(fit_model_error(chosen, pairs, options_->auto_select.cv,
                                           known_noise_ ? *known_noise_ : pair_noise(pairs),
                                           blocked, paired ? &results[pick] : nullptr));
  set_error_model(chosen_->error_model());
  summary.rms_m = inner.rms_m;
  summary.inliers = inner.inliers;
  summary.pairs_used = inner.pairs_used;
  summary.reduction = inner.reduction;
  summary.cv_error_m = best_error;
  summary.cv = best_method;
  summary.details = {{"chosen", best},
                     {"folds", options_->auto_select.cv.folds},
                     {"cv_kind", best_method.kind},
                     {"cv_block_size_m", best_method.block_size},
                     {"cv_table", table},
                     {"chosen_details", inner.details}};
  summary.warnings.insert(summary.warnings.end(), inner.warnings.begin(), inner.warnings.end());
}

Eigen::Vector2d AutoMapping::forward(const Eigen::Vector2d& p) const {
  return chosen_->forward(p);
}

Eigen::Matrix2Xd AutoMapping::forward_batch(const Eigen::Ref<const Eigen::Matrix2Xd>& p) const {
  return chosen_->forward_batch(p);
}

Eigen::Matrix2d AutoMapping::jacobian(const Eigen::Vector2d& p) const {
  return chosen_->jacobian(p);
}

InverseMapping AutoMapping::inverse(const Eigen::Vector2d& g) const {
  return chosen_->inverse(g);
}

std::optional<double> AutoMapping::predictive_std(const Eigen::Vector2d& p) const {
  return chosen_->predictive_std(p);
}

Value AutoMapping::parameters() const {
  Value table = Value::object();
  for (const auto& [name, error] : table_)
    table[name] = std::isfinite(error) ? Value(error) : Value(nullptr);
  return {
      {"chosen", chosen_->name()}, {"cv_mean_error_m", table}, {"model", chosen_->to_model_file()}};
}

void AutoMapping::load_parameters(const Value& j, const std::string& where) {
  using namespace model_fields;
  const Value& model = member(j, "model", where, "parameters.");
  const Value* name = model.find("model");
  if (name != nullptr && name->is_string() && name->as_string() == "auto")
    throw InputError("auto cannot choose auto", where, 0, "parameters.model.model");
  chosen_ = load_mapping(model, where, *options_);
  table_.clear();
  if (const Value* table = optional_member(j, "cv_mean_error_m"); table && table->is_object()) {
    for (const auto& [candidate, error] : table->members()) {
      table_[candidate] = error.is_number() && std::isfinite(error.as_number())
                              ? error.as_number()
                              : std::numeric_limits<double>::infinity();
    }
  }
}

}  // namespace floorgrid
