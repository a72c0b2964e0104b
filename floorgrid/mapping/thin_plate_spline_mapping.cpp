#include "floorgrid/mapping/thin_plate_spline_mapping.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "floorgrid/core/random.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/mapping/cross_validation_folds.hpp"
#include "floorgrid/mapping/pair_preparation.hpp"

#include "floorgrid/core/error.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid {

namespace {
/// Folds of the blocked cross-validation that chooses lambda.
constexpr std::size_t kTuningFolds = 5;

std::string fmt_lambda(double lambda) {
  std::ostringstream out;
  out << lambda;
  return out.str();
}
}  // namespace

ThinPlateSplineMapping::ThinPlateSplineMapping(MappingCommonOptions common,
                                               ThinPlateSplineModelOptions options)
    : PointMapping(std::move(common)), options_(options) {
  if (options_.regularization && !(*options_.regularization >= 0.0)) {
    throw InputError("must be >= 0 (m^2)", {}, 0, "tps.regularization");
  }
  if (options_.tuning_pairs < 20)
    throw InputError("must be >= 20", {}, 0, "tps.tuning_pairs");
  validate(options_.lattice);
}

namespace {

/// Robust weights of the pairs for a spline of `lambda` (see
/// ThinPlateSplineModelOptions::robust_max_pairs); all 1 when no pair stands out.
Eigen::VectorXd robust_weights(const ReferencePairs& pairs, double lambda,
                               const ThinPlateSplineModelOptions& o) {
  const Eigen::Index n = pairs.size();
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(n);
  for (int iteration = 0; iteration < o.robust_iterations; ++iteration) {
    std::vector<double> errors(static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) {
      std::vector<Eigen::Index> others;
      for (Eigen::Index k = 0; k < n; ++k) {
        if (k != i)
          others.push_back(k);
      }
      const ReferencePairs training = select_pairs(pairs, others);
      Eigen::VectorXd training_weights(n - 1);
      for (Eigen::Index k = 0; k < n - 1; ++k)
        training_weights[k] = weights[others[static_cast<std::size_t>(k)]];
      try {
        const ThinPlateSpline spline = ThinPlateSpline::fit(
            training.points_in_plan, training.points_in_grid, {lambda}, training_weights);
        errors[static_cast<std::size_t>(i)] =
            (spline.evaluate(pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i)).norm();
      } catch (const InputError&) {
        return Eigen::VectorXd::Ones(n);  // a training set the spline refuses: no reweighting
      }
    }
    const double limit = o.robust_cutoff * upper_median(errors);
    if (!(limit > 0.0))
      break;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double e = errors[static_cast<std::size_t>(i)];
      weights[i] = e > limit ? (limit / e) * (limit / e) : 1.0;
    }
  }
  return weights;
}

/// The robust weights of `pairs` for a spline of `lambda` when they apply (lambda > 0, 5 to
/// robust_max_pairs pairs), else none.
Eigen::VectorXd weights_for(const ReferencePairs& pairs, double lambda,
                            const ThinPlateSplineModelOptions& o) {
  const auto n = static_cast<std::size_t>(pairs.size());
  if (!(lambda > 0.0) || o.robust_iterations <= 0 || n > o.robust_max_pairs || n < 5)
    return {};
  return robust_weights(pairs, lambda, o);
}

/// Mean held-out error of a spline with `lambda` over `folds` of `pairs`.
double cross_validated_error(const ReferencePairs& pairs, const Folds& folds, double lambda) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t fold = 0; fold < folds.count; ++fold) {
    std::vector<Eigen::Index> train, test;
    folds.split(fold, train, test);
    const ReferencePairs t = select_pairs(pairs, train);
    try {
      const ThinPlateSpline spline =
          ThinPlateSpline::fit(t.points_in_plan, t.points_in_grid, {lambda});
      for (const Eigen::Index i : test) {
        sum += (spline.evaluate(pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i)).norm();
        ++count;
      }
    } catch (const InputError&) {
      return std::numeric_limits<double>::infinity();
    }
  }
  return count > 0 ? sum / static_cast<double>(count) : std::numeric_limits<double>::infinity();
}

}  // namespace

double ThinPlateSplineMapping::choose_regularization(const ReferencePairs& pairs,
                                                     Value& table) const {
  // A seeded random subsample, dealt into folds by position.
  std::vector<Eigen::Index> order(static_cast<std::size_t>(pairs.size()));
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    order[static_cast<std::size_t>(i)] = i;
  Random random(common().seed);
  for (std::size_t i = order.size(); i > 1; --i) {
    std::swap(order[i - 1],
              order[static_cast<std::size_t>(random.integer(0, static_cast<std::int64_t>(i) - 1))]);
  }
  order.resize(std::min(order.size(), options_.tuning_pairs));
  const ReferencePairs sample = select_pairs(pairs, order);
  // Whole spatial blocks held out (grid frame, metres): random folds of dense laser pairs keep
  // a held-out pair's near-copies in training and so favour interpolating their noise. Sparse
  // hand-picked pairs have no near-copies: there the subsample's own random order deals them.
  Folds folds;
  if (static_cast<std::size_t>(sample.size()) >= kBlockedTuningMinPairs) {
    folds = blocked_folds(sample.points_in_grid, kTuningFolds,
                          choose_block_size(sample.points_in_grid, kTuningFolds), common().seed);
  }
  if (folds.count < 2) {
    folds.count = kTuningFolds;
    folds.fold_of.resize(static_cast<std::size_t>(sample.size()));
    for (std::size_t i = 0; i < folds.fold_of.size(); ++i)
      folds.fold_of[i] = i % kTuningFolds;
  }
  double best = 0.0, best_error = std::numeric_limits<double>::infinity();
  for (const double lambda : {0.0, 1e-3, 1e-2, 0.1, 1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0}) {
    const double error = cross_validated_error(sample, folds, lambda);
    table[fmt_lambda(lambda)] = std::isfinite(error) ? Value(error) : Value(nullptr);
    if (error < best_error) {
      best_error = error;
      best = lambda;
    }
  }
  return best * static_cast<double>(pairs.size()) / static_cast<double>(sample.size());
}

ThinPlateSplineMapping::~ThinPlateSplineMapping() = default;

void ThinPlateSplineMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  Value table = Value::object();
  const double lambda =
      options_.regularization ? *options_.regularization : choose_regularization(pairs, table);
  const Eigen::VectorXd weights = weights_for(pairs, lambda, options_);
  const bool robust = weights.size() > 0;
  spline_.emplace(
      ThinPlateSpline::fit(pairs.points_in_plan, pairs.points_in_grid, {lambda}, weights));
  const Eigen::Matrix2Xd residual =
      spline_->evaluate_batch(pairs.points_in_plan, 2) - pairs.points_in_grid;
  summary.rms_m = std::sqrt(residual.colwise().squaredNorm().mean());
  summary.details = {
      {"centres", spline_->size()},
      {"regularization_m2", lambda},
      {"regularization_chosen",
       options_.regularization
           ? "given"
           : "5-fold cross-validation on a subsample (spatially blocked from 100 pairs, "
             "round robin below), scaled by pairs / subsample"},
      {"regularization_cv_error_m", table},
      {"bending_energy", spline_->bending_energy()},
      {"robust_downweighted",
       robust ? Value(static_cast<std::int64_t>((weights.array() < 1.0).count())) : Value()}};
}

Eigen::Vector2d ThinPlateSplineMapping::forward(const Eigen::Vector2d& p) const {
  return spline_->evaluate(p);
}

Eigen::Matrix2Xd ThinPlateSplineMapping::forward_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& p) const {
  if (p.cols() < options_.lattice_from)
    return spline_->evaluate_batch(p, 2);
  std::call_once(lattice_once_, [&] {
    Eigen::AlignedBox2d box(support().points_in_plan.rowwise().minCoeff(),
                            support().points_in_plan.rowwise().maxCoeff());
    lattice_ = std::make_unique<ThinPlateSplineLattice>(*spline_, box, options_.lattice);
  });
  return lattice_->evaluate_batch(p);
}

Eigen::Matrix2d ThinPlateSplineMapping::jacobian(const Eigen::Vector2d& p) const {
  return spline_->jacobian(p);
}

Value ThinPlateSplineMapping::parameters() const {
  const ThinPlateSplineData& d = spline_->data();
  return {{"centres", model_fields::points(d.centres_in_plan)},
          {"kernel_weights", model_fields::points(d.kernel_weights)},
          {"affine", model_fields::matrix(d.affine)},
          {"regularization_m2", d.regularization},
          {"input_offset", Value::array({d.input_offset.x(), d.input_offset.y()})},
          {"input_scale", d.input_scale},
          {"output_offset", Value::array({d.output_offset.x(), d.output_offset.y()})},
          {"lattice_spacing_m", options_.lattice.spacing}};
}

void ThinPlateSplineMapping::load_parameters(const Value& j, const std::string& where) {
  using namespace model_fields;
  const std::string p = "parameters.";
  ThinPlateSplineData d;
  d.centres_in_plan = points(member(j, "centres", where, p), where, p + "centres");
  d.kernel_weights =
      number_pairs(member(j, "kernel_weights", where, p), where, p + "kernel_weights");
  if (d.kernel_weights.cols() != d.centres_in_plan.cols() || d.centres_in_plan.cols() == 0)
    throw InputError("centres and kernel weights differ in number or are empty", where, 0,
                     p + "kernel_weights");
  d.affine = matrix(member(j, "affine", where, p), where, p + "affine", 2, 3);
  d.regularization =
      number(member(j, "regularization_m2", where, p), where, p + "regularization_m2", 0.0, 1e300);
  d.input_offset = vector(member(j, "input_offset", where, p), where, p + "input_offset", 2);
  d.output_offset = vector(member(j, "output_offset", where, p), where, p + "output_offset", 2);
  d.input_scale =
      number(member(j, "input_scale", where, p), where, p + "input_scale", 1e-12, kMaxCoordinate);
  if (const Value* spacing = optional_member(j, "lattice_spacing_m")) {
    // The lattice covers the centres' box: a spacing below a millimetre would make it huge.
    options_.lattice.spacing =
        number(*spacing, where, p + "lattice_spacing_m", 1e-3, kMaxCoordinate);
  }
  try {
    spline_.emplace(std::move(d));
  } catch (const InputError& e) {
    throw InputError(e.message(), where, 0, p + e.field());
  }
}

}  // namespace floorgrid
