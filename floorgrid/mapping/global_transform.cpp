#include "floorgrid/mapping/global_transform.hpp"

#include "floorgrid/core/error.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid {

std::string global_transform_model_name(TransformKind kind) {
  switch (kind) {
    case TransformKind::rigid:
      return "gt-rigid";
    case TransformKind::affine:
      return "gt-affine";
    case TransformKind::similarity:
      break;
  }
  return "gt";
}

namespace {

// The model file's record of where the threshold came from.
constexpr const char* kThresholdGiven = "given";
constexpr const char* kThresholdAdaptive = "adaptive";

}  // namespace

GlobalTransformMapping::GlobalTransformMapping(MappingCommonOptions common, RansacOptions ransac)
    : PointMapping(std::move(common)), ransac_(ransac) {
  ransac_.seed = this->common().seed;
  threshold_used_ = ransac_.inlier_threshold;
  threshold_source_ = ransac_.inlier_threshold ? kThresholdGiven : kThresholdAdaptive;
}

std::string GlobalTransformMapping::name() const {
  return global_transform_model_name(ransac_.kind);
}

std::size_t GlobalTransformMapping::min_pairs() const {
  return static_cast<std::size_t>(minimal_sample_size(ransac_.kind));
}

void GlobalTransformMapping::set_transform(const Eigen::Matrix3d& T) {
  T_grid_plan_ = T;
  T_plan_grid_ = T.inverse();
}

void GlobalTransformMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  const RansacResult result = ransac_transform(pairs, ransac_);
  if (!result.ok)
    throw InputError("no transform fits the pairs: " + result.message, {}, 0, "pairs");
  set_transform(result.estimate.T_grid_plan);
  threshold_used_ = result.inlier_threshold;
  threshold_source_ = result.threshold_adaptive ? kThresholdAdaptive : kThresholdGiven;
  summary.inliers = result.inlier_count;
  summary.rms_m = result.estimate.rms;
  summary.details = {{"kind", transform_kind_name(ransac_.kind)},
                     {"scale", result.estimate.scale},
                     {"reflected", result.estimate.reflected},
                     {"iterations", result.iterations},
                     {"refit_passes", result.refit_passes},
                     {"inlier_threshold_m", result.inlier_threshold},
                     {"inlier_threshold_source", threshold_source_},
                     {"inlier_fraction", double(result.inlier_count) / double(pairs.size())}};
  if (result.threshold_adaptive) {
    summary.details["noise_sigma_m"] = result.noise_sigma;
    summary.details["threshold_sigmas"] = ransac_.threshold_sigmas;
    summary.details["scale_passes"] = result.scale_passes;
  }
  if (!result.message.empty())
    summary.warnings.push_back(result.message);
}

Eigen::Vector2d GlobalTransformMapping::forward(const Eigen::Vector2d& p) const {
  return T_grid_plan_.topLeftCorner<2, 2>() * p + T_grid_plan_.topRightCorner<2, 1>();
}

Eigen::Matrix2Xd GlobalTransformMapping::forward_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& p) const {
  return (T_grid_plan_.topLeftCorner<2, 2>() * p).colwise() + T_grid_plan_.topRightCorner<2, 1>();
}

Eigen::Matrix2d GlobalTransformMapping::jacobian(const Eigen::Vector2d&) const {
  return T_grid_plan_.topLeftCorner<2, 2>();
}

InverseMapping GlobalTransformMapping::inverse(const Eigen::Vector2d& g) const {
  InverseMapping m;
  m.point = T_plan_grid_.topLeftCorner<2, 2>() * g + T_plan_grid_.topRightCorner<2, 1>();
  m.invertible = m.point.allFinite();
  m.residual = (forward(m.point) - g).norm();
  return m;
}

Value GlobalTransformMapping::parameters() const {
  // The threshold the fit used (null: a file that did not say, loaded and written again).
  return {{"kind", transform_kind_name(ransac_.kind)},
          {"T_grid_plan", model_fields::matrix(T_grid_plan_)},
          {"ransac",
           {{"inlier_threshold_m", threshold_used_ ? Value(*threshold_used_) : Value(nullptr)},
            {"inlier_threshold_source", threshold_source_},
            {"confidence", ransac_.confidence},
            {"max_iterations", ransac_.max_iterations}}}};
}

void GlobalTransformMapping::load_parameters(const Value& j, const std::string& where) {
  const Eigen::Matrix3d T =
      model_fields::matrix(model_fields::member(j, "T_grid_plan", where, "parameters."), where,
                           "parameters.T_grid_plan", 3, 3);
  // A physical transform: a linear part of sane size and conditioning (scales within 1e-6 to
  // 1e6, so that its inverse is finite too), a translation within kMaxCoordinate.
  const Eigen::Matrix2d A = T.topLeftCorner<2, 2>();
  const double det = std::abs(A.determinant());
  const double norm = A.norm();
  if (!(det > 1e-12 && norm < 1e6 && norm * norm / det < 1e12) ||
      !(T.topRightCorner<2, 1>().cwiseAbs().maxCoeff() <= kMaxCoordinate) ||
      T.row(2) != Eigen::RowVector3d(0.0, 0.0, 1.0)) {
    throw InputError("not a usable transform (singular, of absurd scale, or not [A t; 0 0 1])",
                     where, 0, "parameters.T_grid_plan");
  }
  set_transform(T);
  // A record only (mapping does not need it), kept so that the file is written back as read.
  // Files before the adaptive threshold hold the fixed one they used and no source.
  threshold_used_.reset();
  threshold_source_ = kThresholdGiven;
  if (const Value* ransac = model_fields::optional_member(j, "ransac")) {
    if (const Value* t = model_fields::optional_member(*ransac, "inlier_threshold_m")) {
      threshold_used_ = model_fields::number(*t, where, "parameters.ransac.inlier_threshold_m", 0.0,
                                             kMaxCoordinate);
    }
    if (const Value* source = model_fields::optional_member(*ransac, "inlier_threshold_source")) {
      threshold_source_ =
          model_fields::text(*source, where, "parameters.ransac.inlier_threshold_source");
      if (threshold_source_ != kThresholdGiven && threshold_source_ != kThresholdAdaptive) {
        throw InputError("must be 'given' or 'adaptive' (got '" + threshold_source_ + "')", where,
                         0, "parameters.ransac.inlier_threshold_source");
      }
    }
  }
}

}  // namespace floorgrid
