#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "floorgrid/mapping/cross_validation_folds.hpp"
#include "floorgrid/mapping/model_registry.hpp"
#include "floorgrid/mapping/pair_noise.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

struct MappingOptions;

/// How the pairs are dealt into folds.
enum class CrossValidationKind {
  blocked,  ///< whole spatial blocks held out: the error away from the pairs
  random,   ///< pairs dealt at random: near-copies of a held-out pair stay in training
  /// stretches of the pairs in their own order held out (a run's pairs, in scan order: the
  /// pairs of one stretch of the run share their errors, so the held-out pairs are predicted
  /// from other passes and other stretches, not from their own scans' siblings)
  runs,
};

/// The name of a kind as options and outputs spell it: "blocked", "random" or "runs".
const char* to_string(CrossValidationKind kind);
/// The kind `name` spells; throws InputError naming `field` for another name.
CrossValidationKind parse_cv_kind(const std::string& name, const std::string& field = "--cv-kind");

/// How models are cross-validated.
struct CrossValidationOptions {
  int folds = 5;                 ///< k of k-fold, >= 2
  std::size_t max_pairs = 3000;  ///< pairs binned down to this before the folds (cost bound)
  CrossValidationKind kind = CrossValidationKind::blocked;  ///< how pairs are dealt into folds
  /// Side of the square blocks of blocked folds in the grid frame, metres (0: chosen from the
  /// pairs' extent and density, at most kLargestAutoBlock).
  double block_size = 0.0;
};

/// Checks `cv`; throws InputError naming `<prefix>folds` or `<prefix>block_size`.
void validate(const CrossValidationOptions& cv, const std::string& prefix = "cv.");

/// The outcome of a k-fold cross-validation.
struct CrossValidationResult {
  double mean_error_m = 0.0;        ///< mean |model(plan) - grid| over all held-out pairs
  double median_error_m = 0.0;      ///< median of the same
  std::vector<double> fold_errors;  ///< mean error per fold, metres
  std::size_t pairs = 0;            ///< pairs cross-validated (after binning)
  std::size_t failed_folds = 0;     ///< folds whose training set the model refused
  CrossValidationRecord method;     ///< kind, folds and block size used
  /// Blocked and runs folds: every held-out pair's error and distance to its fold's training
  /// pairs (finite errors), for the model's error model (fit_model_error); empty for random
  /// folds, whose held-out pairs have near-copies in training.
  std::vector<HeldOutResidual> held_out;
  /// Every pair's held-out error, by pair (infinite where its fold failed): the same pairs and
  /// folds for every model cross-validated with the same options, so models compare pair by
  /// pair (see paired_scores).
  std::vector<double> pair_errors;
};

/// Scores models pair by pair on their held-out errors (`errors[m][i]`: model m's at pair i,
/// the same pairs for all): each model's mean squared error over the pairs whose median error
/// over the models is at most `trim` times the median of those (a stretch the filters got
/// wrong, pairs far off, would weigh on every model's mean, most on the smooth models that do
/// not follow it). The pairs' own noise adds the same to every model's mean squared error, so
/// the differences are the models' own (a median of the errors hides them under that noise).
/// Infinite for a model with an infinite error on a kept pair.
std::vector<double> paired_scores(const std::vector<std::vector<double>>& errors,
                                  double trim = 3.0);

/// Which pairs paired_scores keeps (1) for `errors` and `trim`.
std::vector<char> paired_pairs_kept(const std::vector<std::vector<double>>& errors,
                                    double trim = 3.0);

/// The standard error of the difference of two models' paired scores (mean squared held-out
/// errors `a` and `b` over the `kept` pairs): the pairs, in run order, cut into `stretches`
/// consecutive stretches whose errors may be correlated within but not between them, the
/// spread of the stretches' summed differences (a ratio estimator). Infinite with fewer than
/// two stretches holding kept pairs, sizes that differ, or an infinite error on a kept pair.
double paired_score_difference_se(const std::vector<double>& a, const std::vector<double>& b,
                                  const std::vector<char>& kept, std::size_t stretches);

/// k-fold cross-validation of the model `options` names: pairs are merged, binned to
/// max_pairs, and dealt into k folds (seeded by options.common.seed): by default whole square
/// blocks of the grid frame per fold (blocked_folds), or at random; each fold is predicted by
/// the model fitted on the others. A fold the model cannot be fitted on (too few pairs) counts
/// as failed; when every fold fails the error is infinite.
CrossValidationResult cross_validate(const MappingOptions& options, const ReferencePairs& pairs,
                                     const CrossValidationOptions& cv = {});

/// A model's std_m (fit_error_model) from cross-validations of `options` over `pairs` with
/// `cv`'s folds, block size and pair budget: the shape from the held-out errors of blocked folds,
/// the level from those of runs folds and the pairs' `noise` (ErrorLevel; variance_scale without
/// a noise estimate). `blocked` and `runs`, when given, are those already done; the others are done
/// here.
std::optional<ErrorModel> fit_model_error(const MappingOptions& options,
                                          const ReferencePairs& pairs,
                                          const CrossValidationOptions& cv,
                                          const std::optional<PairNoise>& noise,
                                          const CrossValidationResult* blocked = nullptr,
                                          const CrossValidationResult* runs = nullptr);

/// Leave-one-out errors: for each pair, the model fitted on all others predicts it (metres;
/// infinite where the model cannot be fitted). For small hand-picked sets.
std::vector<double> leave_one_out_errors(const MappingOptions& options,
                                         const ReferencePairs& pairs);

/// Options of the `auto` model.
struct AutoOptions {
  /// The models compared, cheapest first (ties go to the earlier one): the registry's
  /// candidates by default.
  std::vector<std::string> candidates = auto_candidates();
  CrossValidationOptions cv;  ///< how they are compared
  /// Compared by runs, an earlier candidate whose paired score exceeds the lowest by at most
  /// this many standard errors of the difference (paired_score_difference_se) is chosen
  /// instead (the one-standard-error rule; 0: the lowest score always).
  double tie_standard_errors = 1.0;
};

/// `auto`: the candidate with the lowest cross-validated mean error (spatially blocked folds
/// by default, see cross_validate; for runs, the lowest paired_scores, or an earlier candidate
/// within tie_standard_errors of it), refitted on all pairs; the
/// table of every candidate's error is kept in the fit's details and the model file, with how it
/// was cross-validated.
class AutoMapping : public PointMapping {
 public:
  /// An auto model choosing among `options.auto_select.candidates`, each built from `options`.
  explicit AutoMapping(const MappingOptions& options);
  ~AutoMapping() override;

  std::string name() const override { return "auto"; }
  std::size_t min_pairs() const override { return 2; }
  bool needs_non_collinear() const override { return false; }
  bool reduces_pairs() const override { return false; }

  Eigen::Vector2d forward(const Eigen::Vector2d& point_in_plan) const override;
  Eigen::Matrix2Xd forward_batch(
      const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const override;
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const override;
  InverseMapping inverse(const Eigen::Vector2d& point_in_grid) const override;
  std::optional<double> predictive_std(const Eigen::Vector2d& point_in_plan) const override;

  /// Cross-validation results already computed (same folds, pair budget and seed as this
  /// model's) for some candidates: fit() uses them instead of cross-validating again.
  void reuse_cross_validation(std::map<std::string, CrossValidationResult> results) {
    known_ = std::move(results);
  }
  /// Blocked cross-validations already computed (same folds, budget and seed) for some
  /// candidates: when auto compares by runs, the chosen model's std_m is fitted on its blocked
  /// held-out errors, from these instead of cross-validating again.
  void reuse_blocked_cross_validation(std::map<std::string, CrossValidationResult> results) {
    known_blocked_ = std::move(results);
  }
  /// The pairs' own noise (pair_noise) already estimated on the pairs fit() will be given:
  /// used for the chosen model's std_m instead of estimating it again.
  void reuse_pair_noise(std::optional<PairNoise> noise) { known_noise_ = std::move(noise); }
  /// The model chosen (after fit or load).
  const PointMapping& chosen() const { return *chosen_; }
  /// Cross-validated mean error per candidate, metres (infinite: could not be fitted).
  const std::map<std::string, double>& table() const { return table_; }

 protected:
  void fit_model(const ReferencePairs& pairs, FitSummary& summary) override;
  Value parameters() const override;
  void load_parameters(const Value& parameters, const std::string& where) override;

 private:
  std::unique_ptr<MappingOptions> options_;
  std::unique_ptr<PointMapping> chosen_;
  std::map<std::string, CrossValidationResult> known_;
  std::map<std::string, CrossValidationResult> known_blocked_;
  /// Set by reuse_pair_noise: the estimate (itself empty where the pairs gave none).
  std::optional<std::optional<PairNoise>> known_noise_;
  std::map<std::string, double> table_;
};

}  // namespace floorgrid
