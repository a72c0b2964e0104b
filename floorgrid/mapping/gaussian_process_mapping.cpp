#include "floorgrid/mapping/gaussian_process_mapping.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"
#include "floorgrid/mapping/cross_validation_folds.hpp"
#include "floorgrid/mapping/gp_blocked_tuning.hpp"
#include "floorgrid/mapping/model_file.hpp"
#include "floorgrid/mapping/pair_preparation.hpp"

namespace floorgrid {

namespace {

/// The zero map as a mean: the GP's constant mean alone (all outputs are residuals of nothing).
Eigen::Matrix3d no_mean() {
  Eigen::Matrix3d zero = Eigen::Matrix3d::Identity();
  zero.topRows<2>().setZero();
  return zero;
}

}  // namespace

GaussianProcessMapping::GaussianProcessMapping(MappingCommonOptions common,
                                               GaussianProcessOptions gp, bool on_global_transform,
                                               RansacOptions ransac)
    : PointMapping(std::move(common)),
      gp_options_(std::move(gp)),
      global_(on_global_transform),
      ransac_(ransac) {
  validate_gaussian_process_options(gp_options_);
  if (!global_)
    T_grid_plan_ = no_mean();  // until fitted
  ransac_.kind = TransformKind::similarity;
  ransac_.seed = this->common().seed;
}

GaussianProcessMapping::~GaussianProcessMapping() = default;

namespace {

/// Folds of the blocked cross-validation that re-chooses the hyperparameters' scale.
constexpr std::size_t kTuningFolds = 5;

/// gp's smallest length scale, in extents of the pairs.
constexpr double kGpMinLengthExtent = 0.25;

/// gp's mean: the least-squares similarity of every pair, or a zero one (the GP's constant
/// mean alone) where the pairs determine none.
Eigen::Matrix3d least_squares_mean(const ReferencePairs& pairs) {
  try {
    return estimate_transform(pairs.points_in_plan, pairs.points_in_grid).T_grid_plan;
  } catch (const InputError&) {
    return no_mean();
  }
}

}  // namespace

void GaussianProcessMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  Value global;
  if (global_) {
    // eq. 4.17-4.18: the residuals of the global transform are what the GP learns.
    const RansacResult gt = ransac_transform(pairs, ransac_);
    if (!gt.ok)
      throw InputError("no global transform fits the pairs: " + gt.message, {}, 0, "pairs");
    T_grid_plan_ = gt.estimate.T_grid_plan;
    global = {{"T_grid_plan", model_fields::matrix(T_grid_plan_)},
              {"inliers", gt.inlier_count},
              {"rms_m", gt.estimate.rms},
              {"inlier_threshold_m", gt.inlier_threshold},
              {"inlier_threshold_source", gt.threshold_adaptive ? "adaptive" : "given"}};
  } else {
    // A constant mean (thesis 4.4.1) sends every point far from the pairs to the pairs'
    // centroid: metres off wherever the plan reaches beyond them. The least-squares similarity
    // of all pairs is the mean instead, so the map reverts to it, as gpgt's to its RANSAC one.
    T_grid_plan_ = least_squares_mean(pairs);
    global = {{"T_grid_plan", model_fields::matrix(T_grid_plan_)},
              {"fit", T_grid_plan_ == no_mean() ? "none (degenerate pairs): the outputs' mean"
                                                : "least-squares similarity of all pairs"}};
  }
  Eigen::Matrix2Xd outputs =
      pairs.points_in_grid -
      ((T_grid_plan_.topLeftCorner<2, 2>() * pairs.points_in_plan).colwise() +
       T_grid_plan_.topRightCorner<2, 1>());
  GaussianProcessOptions options = gp_options_;
  if (!global_) {
    // gp models the building's smooth global warp about its similarity (a bend, a drift): a
    // kernel at least a quarter of the pairs' extent long. gpgt's short kernel follows local
    // residuals; with gp's, what both miss far from the pairs stays the similarity's.
    options.tuning.min_length_scale_extent =
        std::max(options.tuning.min_length_scale_extent, kGpMinLengthExtent);
  }
  Value blocked;
  std::optional<GpTuningResult> likelihood;
  if (!options.hyperparameters &&
      static_cast<std::size_t>(pairs.size()) >= kBlockedTuningMinPairs) {
    // The likelihood's hyperparameters, then their scale re-chosen by blocked CV on the same
    // spread subsample (see refine_by_blocked_cv).
    const Eigen::Matrix2Xd centred = outputs.colwise() - outputs.rowwise().mean();
    likelihood = tune_gp_hyperparameters(pairs.points_in_plan, centred, options.tuning);
    const std::vector<Eigen::Index> sample =
        gp_spread_subsample(pairs.points_in_plan, options.tuning.max_points);
    const ReferencePairs subsample = select_pairs(pairs, sample);
    Eigen::Matrix2Xd sample_outputs(2, static_cast<Eigen::Index>(sample.size()));
    for (std::size_t k = 0; k < sample.size(); ++k)
      sample_outputs.col(static_cast<Eigen::Index>(k)) = outputs.col(sample[k]);
    const GpBlockedTuning refined =
        refine_by_blocked_cv(subsample.points_in_plan, sample_outputs, subsample.points_in_grid,
                             likelihood->hyperparameters, kTuningFolds, common().seed);
    options.hyperparameters = refined.hyperparameters;
    Value table = Value::array();
    for (const GpBlockedCandidate& c : refined.table) {
      table.push_back({{"length_factor", c.length_factor},
                       {"noise_factor", c.noise_factor},
                       {"error_m", std::isfinite(c.error_m) ? Value(c.error_m) : Value()}});
    }
    blocked = {{"folds", refined.folds}, {"block_size_m", refined.block_size}, {"table", table}};
  }
  GaussianProcessFit fit = fit_gaussian_process(pairs.points_in_plan, outputs, options);
  if (likelihood) {
    GaussianProcessSummary& s = fit.summary;
    s.tuned = true;
    s.tuning_points = likelihood->tuning_points;
    s.iterations = likelihood->rprop.iterations;
    s.converged = likelihood->rprop.converged;
    s.at_bounds = likelihood->at_bounds;
  }
  process_.emplace(std::move(fit.model));
  const Eigen::Matrix2Xd residual = forward_batch(pairs.points_in_plan) - pairs.points_in_grid;
  summary.rms_m = std::sqrt(residual.colwise().squaredNorm().mean());
  const GaussianProcessSummary& s = fit.summary;
  const GpHyperparameters& h = s.hyperparameters;
  summary.details = {
      {"kernel",
       "squared exponential, a length scale per plan axis, shared by both grid coordinates"},
      {"mean", global_ ? "global similarity (gt) plus the GP of its residuals"
                       : "least-squares similarity plus the GP of its residuals"},
      {"length_scale_m", Value::array({h.length_scale.x(), h.length_scale.y()})},
      {"signal_std_m", h.signal_std},
      {"noise_std_m", h.noise_std},
      {"tuned", s.tuned},
      {"tuning",
       !s.tuned ? "hyperparameters given"
       : likelihood
           ? "RPROP (iRprop+) on log-parameters, log marginal likelihood, analytic gradients; "
             "then length scales and noise std scaled by spatially blocked cross-validation on "
             "the same subsample"
           : "RPROP (iRprop+) on log-parameters, log marginal likelihood, analytic gradients "
             "(too few pairs for blocked cross-validation)"},
      {"likelihood_hyperparameters",
       likelihood
           ? Value{{"length_scale_m", Value::array({likelihood->hyperparameters.length_scale.x(),
                                                    likelihood->hyperparameters.length_scale.y()})},
                   {"signal_std_m", likelihood->hyperparameters.signal_std},
                   {"noise_std_m", likelihood->hyperparameters.noise_std}}
           : Value()},
      {"blocked_cv", blocked},
      {"tuning_points", s.tuning_points},
      {"training_points", s.training_points},
      {"iterations", s.iterations},
      {"converged", s.converged},
      {"log_marginal_likelihood", s.log_marginal_likelihood},
      {"at_bounds", Value(s.at_bounds)},
      {"jitter", s.jitter},
      {"lattice_spacing_m", Value::array({s.lattice_spacing.x(), s.lattice_spacing.y()})},
      {"lattice_error_m", s.lattice_error},
      {"global_transform", global}};
  if (!s.at_bounds.empty()) {
    std::string list;
    for (const auto& b : s.at_bounds)
      list += (list.empty() ? "" : ", ") + b;
    summary.warnings.push_back("GP hyperparameters at their bounds: " + list);
  }
}

Eigen::Vector2d GaussianProcessMapping::forward(const Eigen::Vector2d& p) const {
  return process_->mean(p) + T_grid_plan_.topLeftCorner<2, 2>() * p +
         T_grid_plan_.topRightCorner<2, 1>();
}

Eigen::Matrix2Xd GaussianProcessMapping::forward_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& p) const {
  Eigen::Matrix2Xd q = process_->mean_batch(p);
  q += (T_grid_plan_.topLeftCorner<2, 2>() * p).colwise() + T_grid_plan_.topRightCorner<2, 1>();
  return q;
}

Eigen::Matrix2d GaussianProcessMapping::jacobian(const Eigen::Vector2d& p) const {
  return process_->mean_jacobian(p) + T_grid_plan_.topLeftCorner<2, 2>();
}

std::optional<double> GaussianProcessMapping::predictive_std(const Eigen::Vector2d& p) const {
  return process_->standard_deviation(p);
}

Value GaussianProcessMapping::parameters() const {
  const GaussianProcessState& s = process_->state();
  const GpHyperparameters& h = s.hyperparameters;
  const GpLatticeOptions& lattice = process_->prediction_options().lattice;
  Value j = {
      {"approximation", "pairs reduced by spatial binning to at most " +
                            std::to_string(reduction_budget()) + ", then an exact GP on them"},
      {"inputs", model_fields::points(s.inputs)},
      {"alpha", model_fields::points(s.alpha)},
      {"output_mean", Value::array({s.output_mean.x(), s.output_mean.y()})},
      {"length_scale_m", Value::array({h.length_scale.x(), h.length_scale.y()})},
      {"signal_std_m", h.signal_std},
      {"noise_std_m", h.noise_std},
      {"jitter", s.jitter},
      {"lattice",
       {{"enabled", lattice.enabled},
        {"tolerance_m", lattice.tolerance},
        {"initial_spacing", lattice.initial_spacing},
        {"margin", lattice.margin},
        {"max_nodes", lattice.max_nodes},
        {"max_attempts", lattice.max_attempts}}}};
  j["T_grid_plan"] = model_fields::matrix(T_grid_plan_);
  return j;
}

void GaussianProcessMapping::load_parameters(const Value& j, const std::string& where) {
  using namespace model_fields;
  const std::string p = "parameters.";
  GaussianProcessState s;
  s.inputs = points(member(j, "inputs", where, p), where, p + "inputs");
  // The weights of the GP's kernel sums: finite numbers of any size, one per input.
  s.alpha = number_pairs(member(j, "alpha", where, p), where, p + "alpha");
  if (s.alpha.cols() != s.inputs.cols() || s.inputs.cols() == 0)
    throw InputError("inputs and alpha differ in number or are empty", where, 0, p + "alpha");
  s.output_mean = vector(member(j, "output_mean", where, p), where, p + "output_mean", 2);
  s.hyperparameters.length_scale =
      vector(member(j, "length_scale_m", where, p), where, p + "length_scale_m", 2);
  if (!(s.hyperparameters.length_scale.array() > 0.0).all())
    throw InputError("must be > 0", where, 0, p + "length_scale_m");
  s.hyperparameters.signal_std =
      number(member(j, "signal_std_m", where, p), where, p + "signal_std_m", 0.0, kMaxCoordinate);
  s.hyperparameters.noise_std =
      number(member(j, "noise_std_m", where, p), where, p + "noise_std_m", 0.0, kMaxCoordinate);
  s.jitter = number(member(j, "jitter", where, p), where, p + "jitter", 0.0, kMaxCoordinate);
  GpPredictionOptions prediction = gp_options_.prediction;
  const Value& lattice = member(j, "lattice", where, p);
  const std::string l = p + "lattice.";
  if (const Value* enabled = optional_member(lattice, "enabled"))
    prediction.lattice.enabled = flag(*enabled, where, l + "enabled");
  prediction.lattice.tolerance =
      number(member(lattice, "tolerance_m", where, l), where, l + "tolerance_m");
  prediction.lattice.initial_spacing =
      number(member(lattice, "initial_spacing", where, l), where, l + "initial_spacing");
  prediction.lattice.margin = number(member(lattice, "margin", where, l), where, l + "margin");
  // The lattice's size is bounded by this build's own limit, whatever the file says: a file
  // must not make `map` allocate without bound. The loader's options may bound it further.
  const Eigen::Index max_nodes =
      std::min(GpLatticeOptions{}.max_nodes, gp_options_.prediction.lattice.max_nodes);
  if (const Value* nodes = optional_member(lattice, "max_nodes"))
    prediction.lattice.max_nodes = std::min<Eigen::Index>(
        integer(*nodes, where, l + "max_nodes", 4, GpLatticeOptions{}.max_nodes), max_nodes);
  if (const Value* attempts = optional_member(lattice, "max_attempts"))
    prediction.lattice.max_attempts =
        static_cast<int>(integer(*attempts, where, l + "max_attempts", 1, 16));
  if (global_) {
    T_grid_plan_ = matrix(member(j, "T_grid_plan", where, p), where, p + "T_grid_plan", 3, 3);
  } else if (const Value* mean = optional_member(j, "T_grid_plan")) {
    T_grid_plan_ = matrix(*mean, where, p + "T_grid_plan", 3, 3);
  } else {
    T_grid_plan_ = no_mean();  // a gp file from before the similarity mean: constant mean
  }
  try {
    validate_gp_lattice_options(prediction.lattice, p + "lattice");
    process_.emplace(std::move(s), prediction);
  } catch (const InputError& e) {
    throw InputError(e.message(), where, 0, e.field().starts_with(p) ? e.field() : p + e.field());
  }
}

}  // namespace floorgrid
