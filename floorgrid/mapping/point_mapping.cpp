#include "floorgrid/mapping/point_mapping.hpp"

#include <chrono>
#include <cmath>
#include <limits>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/geometry/transform_estimation.hpp"

namespace floorgrid {

namespace {

/// A mapped point a model may answer: finite, within kMaxCoordinate of the origin.
bool plausible(const Eigen::Vector2d& point) {
  return point.allFinite() && point.cwiseAbs().maxCoeff() <= kMaxCoordinate;
}

}  // namespace

std::string to_string(MapFlag flag) {
  switch (flag) {
    case MapFlag::uncertain:
      return "uncertain";
    case MapFlag::extrapolated:
      return "extrapolated";
    case MapFlag::outside_hull:
      return "outside_hull";
    case MapFlag::not_invertible:
      return "not_invertible";
    case MapFlag::ok:
      break;
  }
  return "ok";
}

void validate(const MappingCommonOptions& options) {
  require_option(
      options.extrapolation_distance >= 0.0 && options.extrapolation_distance <= kMaxCoordinate,
      "mapping.extrapolation_distance", options.extrapolation_distance,
      "a distance in [0, 1e7] metres");
  require_option(options.max_error > 0.0 && options.max_error <= kMaxCoordinate,
                 "mapping.max_error", options.max_error, "a distance in (0, 1e7] metres");
  require_option(options.reduction.budget >= 3, "mapping.reduction.budget",
                 options.reduction.budget, ">= 3");
  require_option(options.support_budget >= 3, "mapping.support_budget", options.support_budget,
                 ">= 3");
  require_option(options.inverse_tolerance > 0.0 && options.inverse_tolerance < 1.0,
                 "mapping.inverse_tolerance", options.inverse_tolerance, "in (0, 1)");
  require_option(options.inverse_max_iterations >= 1, "mapping.inverse_max_iterations",
                 options.inverse_max_iterations, ">= 1");
}

PointMapping::PointMapping(MappingCommonOptions common) : common_(std::move(common)) {
  validate(common_);
}
PointMapping::~PointMapping() = default;

FitSummary PointMapping::fit(const ReferencePairs& given) {
  const auto start = std::chrono::steady_clock::now();
  validate_pairs(given);
  FitSummary summary;
  summary.model = name();
  summary.pairs_given = static_cast<std::size_t>(given.size());
  DuplicateMerge merge;
  ReferencePairs pairs = merge_duplicates(given, &merge);
  summary.pairs_merged = merge.merged;
  summary.pairs_conflicting = merge.conflicting;
  if (merge.merged > 0) {
    summary.warnings.push_back(std::to_string(merge.merged) +
                               " duplicate plan points merged (grid points averaged)");
  }
  if (merge.conflicting > 0) {
    summary.warnings.push_back(std::to_string(merge.conflicting) +
                               " duplicate plan points had grid points up to " +
                               std::to_string(merge.largest_conflict) + " m apart");
  }
  const std::size_t distinct = static_cast<std::size_t>(pairs.size());
  if (distinct < min_pairs()) {
    throw InputError("model " + name() + " needs at least " + std::to_string(min_pairs()) +
                         " distinct pairs (got " + std::to_string(distinct) + ")",
                     {}, 0, "pairs");
  }
  if (needs_non_collinear() && plan_points_collinear(pairs)) {
    throw InputError("model " + name() + " needs plan points that are not all on one line", {}, 0,
                     "pairs");
  }
  if (reduces_pairs()) {
    ReductionOptions reduction = common_.reduction;
    reduction.budget = reduction_budget();
    pairs = reduce_pairs(pairs, reduction, &summary.reduction);
  }
  summary.pairs_used = static_cast<std::size_t>(pairs.size());
  error_model_.reset();  // a new fit: the error model of the last one no longer holds
  {
    const std::lock_guard lock(fold_index_mutex_);
    fold_index_.reset();  // nor its folds
  }
  build_support(pairs);
  fit_model(pairs, summary);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary_ = summary;
  fitted_ = true;
  return summary_;
}

void PointMapping::build_support(const ReferencePairs& pairs) {
  ReductionOptions budget;
  budget.budget = common_.support_budget;
  support_ = reduce_pairs(pairs, budget);
  support_plan_index_ = PointIndex2D(support_.points_in_plan);
  support_grid_index_ = PointIndex2D(support_.points_in_grid);
  plan_hull_ = convex_hull(support_.points_in_plan);
  grid_hull_ = convex_hull(support_.points_in_grid);
  extent_ = std::max(plan_extent(support_), 1e-9);
  try {
    TransformEstimationOptions similarity;
    similarity.kind = TransformKind::similarity;
    T_support_ = estimate_transform(support_.points_in_plan, support_.points_in_grid,
                                    support_.weights, similarity)
                     .T_grid_plan;
  } catch (const InputError&) {
    T_support_ = Eigen::Matrix3d::Identity();  // a single distinct point: no similarity
  }
}

Eigen::Matrix2Xd PointMapping::forward_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& points) const {
  Eigen::Matrix2Xd out(2, points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    out.col(i) = forward(points.col(i));
  return out;
}

Eigen::Matrix2d PointMapping::jacobian(const Eigen::Vector2d& p) const {
  const double h = 1e-6 * extent_;
  Eigen::Matrix2d j;
  for (int d = 0; d < 2; ++d) {
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    step[d] = h;
    j.col(d) = (forward(p + step) - forward(p - step)) / (2.0 * h);
  }
  return j;
}

InverseMapping PointMapping::inverse(const Eigen::Vector2d& target) const {
  const Eigen::Matrix3d T_plan_grid = T_support_.inverse();
  const Eigen::Matrix2d A_plan_grid = T_plan_grid.topLeftCorner<2, 2>();
  const double tolerance = common_.inverse_tolerance * extent_;
  const double orientation = T_support_.topLeftCorner<2, 2>().determinant();
  // Damped Newton iterations from `x`: halve the step until the residual falls.
  const auto newton = [&](Eigen::Vector2d x) {
    InverseMapping result;
    Eigen::Vector2d residual = forward(x) - target;
    for (int k = 0; k < common_.inverse_max_iterations; ++k) {
      result.iterations = k;
      if (residual.norm() <= tolerance)
        break;
      const Eigen::Matrix2d j = jacobian(x);
      const double det = j.determinant();
      if (!(std::abs(det) > 1e-12) || !std::isfinite(det))
        break;
      const Eigen::Vector2d step = j.inverse() * residual;
      double scale = 1.0;
      Eigen::Vector2d next = x - step, next_residual = forward(next) - target;
      while (next_residual.norm() >= residual.norm() && scale > 1e-6) {
        scale *= 0.5;
        next = x - scale * step;
        next_residual = forward(next) - target;
      }
      if (scale <= 1e-6)
        break;
      x = next;
      residual = next_residual;
      result.iterations = k + 1;
    }
    result.point = x;
    result.residual = residual.norm();
    return result;
  };
  // From the similarity's guess; where that stalls (in a fold, say), again from the nearest
  // support pair's plan point, carried by the similarity to the target.
  InverseMapping result = newton(A_plan_grid * target + T_plan_grid.topRightCorner<2, 1>());
  if (!(result.residual <= tolerance) && support_.size() > 0) {
    const Eigen::Index k = support_grid_index_.nearest(target).index;
    const InverseMapping again = newton(Eigen::Vector2d(support_.points_in_plan.col(k)) +
                                        A_plan_grid * (target - support_.points_in_grid.col(k)));
    if (again.residual < result.residual)
      result = again;
  }
  // Invertible: converged where the mapping keeps the similarity's orientation (no fold), at a
  // grid point no fold covers (else the point found may not be the one meant).
  result.invertible = result.residual <= tolerance &&
                      jacobian(result.point).determinant() * orientation > 0.0 &&
                      !fold_index().covers(target);
  return result;
}

const FoldIndex& PointMapping::fold_index() const {
  const std::lock_guard lock(fold_index_mutex_);
  if (!fold_index_) {
    Eigen::AlignedBox2d box;
    for (Eigen::Index i = 0; i < support_.points_in_plan.cols(); ++i)
      box.extend(Eigen::Vector2d(support_.points_in_plan.col(i)));
    const PlanLattice lattice =
        PlanLattice::over(box, common_.extrapolation_distance, 0.05, 250'000);
    const double orientation = T_support_.topLeftCorner<2, 2>().determinant() >= 0.0 ? 1.0 : -1.0;
    fold_index_ = std::make_shared<const FoldIndex>(*this, lattice, orientation);
  }
  return *fold_index_;
}

std::optional<double> PointMapping::predictive_std(const Eigen::Vector2d&) const {
  return std::nullopt;
}

std::optional<double> PointMapping::error_std(const Eigen::Vector2d& point_in_plan) const {
  if (!error_model_)
    return std::nullopt;
  return error_model_->std_at(point_in_plan, nearest_pair_in_plan(point_in_plan));
}

void PointMapping::set_max_error(double metres) {
  MappingCommonOptions common = common_;
  common.max_error = metres;
  validate(common);
  common_.max_error = metres;
}

MapFlag PointMapping::flag_of(bool inside_hull, double nearest_pair_m,
                              const std::optional<double>& std_m) const {
  if (!inside_hull)
    return MapFlag::outside_hull;
  if (nearest_pair_m > common_.extrapolation_distance)
    return MapFlag::extrapolated;
  // 2 std_m: the 95% bound of the error's length (ErrorModel).
  if (std_m && 2.0 * *std_m > common_.max_error)
    return MapFlag::uncertain;
  return MapFlag::ok;
}

double PointMapping::heading_in_grid(const Eigen::Vector2d& point_in_plan,
                                     double theta_in_plan) const {
  const Eigen::Vector2d heading =
      jacobian(point_in_plan) * Eigen::Vector2d(std::cos(theta_in_plan), std::sin(theta_in_plan));
  return std::atan2(heading.y(), heading.x());
}

double PointMapping::heading_in_plan(const Eigen::Vector2d& point_in_plan,
                                     double theta_in_grid) const {
  const Eigen::Vector2d heading = jacobian(point_in_plan).inverse() *
                                  Eigen::Vector2d(std::cos(theta_in_grid), std::sin(theta_in_grid));
  return std::atan2(heading.y(), heading.x());
}

Pose2 PointMapping::forward_pose(const Pose2& pose) const {
  const Eigen::Vector2d p = forward(pose.translation());
  return {p.x(), p.y(), heading_in_grid(pose.translation(), pose.theta)};
}

std::optional<Pose2> PointMapping::inverse_pose(const Pose2& pose) const {
  const InverseMapping inv = inverse(pose.translation());
  if (!inv.invertible)
    return std::nullopt;
  return Pose2{inv.point.x(), inv.point.y(), heading_in_plan(inv.point, pose.theta)};
}

double PointMapping::nearest_pair_in_plan(const Eigen::Vector2d& p) const {
  return support_plan_index_.nearest(p).distance;
}

double PointMapping::nearest_pair_in_grid(const Eigen::Vector2d& p) const {
  return support_grid_index_.nearest(p).distance;
}

bool PointMapping::inside_plan_hull(const Eigen::Vector2d& p) const {
  return inside_convex_polygon(plan_hull_, p, 1e-9 * extent_);
}

bool PointMapping::inside_grid_hull(const Eigen::Vector2d& p) const {
  return inside_convex_polygon(grid_hull_, p, 1e-9 * extent_);
}

MappedPoint PointMapping::map_forward(const Eigen::Vector2d& p) const {
  MappedPoint m;
  m.point = forward(p);
  m.nearest_pair_m = nearest_pair_in_plan(p);
  if (error_model_)
    m.std_m = error_model_->std_at(p, m.nearest_pair_m);
  m.flag = flag_of(inside_plan_hull(p), m.nearest_pair_m, m.std_m);
  if (!plausible(m.point)) {
    // No number rather than an absurd one (a damaged model's 1e303 m).
    m.point = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    m.flag = MapFlag::not_invertible;
  }
  return m;
}

MappedPoint PointMapping::map_inverse(const Eigen::Vector2d& g) const {
  MappedPoint m;
  const InverseMapping inv = inverse(g);
  m.nearest_pair_m = nearest_pair_in_grid(g);
  if (!inv.invertible) {
    m.point = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    m.flag = MapFlag::not_invertible;
    return m;
  }
  if (!plausible(inv.point)) {
    m.point = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    m.flag = MapFlag::not_invertible;
    return m;
  }
  m.point = inv.point;
  // The error model's distances are the plan's: the plan point found is where it is judged.
  m.std_m = error_std(inv.point);
  m.flag = flag_of(inside_grid_hull(g), m.nearest_pair_m, m.std_m);
  return m;
}

}  // namespace floorgrid
