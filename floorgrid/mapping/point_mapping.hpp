#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "floorgrid/core/value.hpp"
#include "floorgrid/geometry/convex_hull.hpp"
#include "floorgrid/geometry/point_index.hpp"
#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/error_model.hpp"
#include "floorgrid/mapping/fold_index.hpp"
#include "floorgrid/mapping/pair_preparation.hpp"

namespace floorgrid {

/// How far a mapped point may be trusted (SPEC `map` CSV `flag`): the first that applies of
/// not_invertible, outside_hull, extrapolated, uncertain, ok.
enum class MapFlag {
  ok,              ///< within the pairs' hull, near a pair, 2 std_m within the maximal error
  uncertain,       ///< 2 std_m (the 95% bound) above MappingCommonOptions::max_error
  extrapolated,    ///< farther than the extrapolation distance from any pair
  outside_hull,    ///< outside the convex hull of the pairs
  not_invertible,  ///< the inverse does not exist here (the mapping folds) or did not converge,
                   ///< or the model maps the point beyond kMaxCoordinate (no number is given)
};

/// The flag's name as written in the `map` CSV.
std::string to_string(MapFlag flag);

/// One point mapped, with its confidence.
struct MappedPoint {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< metres, in the target frame (NaN if
                                                    ///< not_invertible)
  /// Predictive standard deviation of the error (root mean square length of the 2D error
  /// vector, see ErrorModel: |error| <= std_m about 63%, <= 2 std_m about 95% of the time);
  /// empty where the model has no error model (too few pairs, or a file without one).
  std::optional<double> std_m;
  double nearest_pair_m = 0.0;  ///< metres from the input point to the nearest reference pair
  MapFlag flag = MapFlag::ok;   ///< how far to trust it
};

/// The result of inverting one point.
struct InverseMapping {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  ///< the plan point found, metres
  bool invertible = false;                          ///< found, and the mapping does not fold there
  int iterations = 0;     ///< Newton steps taken (0 for an analytic inverse)
  double residual = 0.0;  ///< |forward(point) - target|, metres
};

/// Settings every mapping model shares.
struct MappingCommonOptions {
  double extrapolation_distance = 2.0;  ///< metres: farther from every pair is "extrapolated"
  /// Metres: a point whose 95% bound (2 std_m) exceeds this is flagged "uncertain" (0.25 m:
  /// nav2's default goal tolerance, what a navigation goal may be off).
  double max_error = 0.25;
  ReductionOptions reduction;         ///< pair budget of models that reduce their pairs
  std::size_t support_budget = 2000;  ///< pairs kept for confidence, hull and inverse start
  double inverse_tolerance = 1e-11;   ///< Newton inverse: residual relative to the extent
  int inverse_max_iterations = 50;    ///< Newton inverse: steps at most
  std::uint64_t seed = 1;             ///< randomness of the fit (RANSAC, subsampling)
};

/// Checks `options`; throws InputError naming `mapping.<field>` when one is out of range.
void validate(const MappingCommonOptions& options);

/// How a cross-validated error was measured (recorded with it in the model file).
struct CrossValidationRecord {
  std::string kind;         ///< "blocked" (whole spatial blocks held out) or "random"
  std::size_t folds = 0;    ///< folds used
  double block_size = 0.0;  ///< metres, side of the blocks (0 for random folds)
  std::size_t pairs = 0;    ///< pairs cross-validated (after binning)
};

/// What a fit did (printed by `fit`, stored in the model file).
struct FitSummary {
  std::string model;                   ///< model name
  std::size_t pairs_given = 0;         ///< pairs passed to fit
  std::size_t pairs_merged = 0;        ///< duplicates merged away
  std::size_t pairs_conflicting = 0;   ///< duplicate plan points with grid points > 1 cm apart
  std::size_t pairs_used = 0;          ///< pairs the model was fitted on
  ReductionSummary reduction;          ///< spatial binning applied before fitting
  std::optional<std::size_t> inliers;  ///< RANSAC inliers (global-transform models)
  double rms_m = 0.0;                 ///< residual rms over the pairs used (inliers if any), metres
  double seconds = 0.0;               ///< wall-clock time of the fit
  std::optional<double> cv_error_m;   ///< k-fold cross-validated mean error, metres
  std::vector<std::string> warnings;  ///< duplicates merged, weak conditioning, ...
  Value details = Value::object();    ///< model-specific figures
  /// How cv_error_m was measured (none in files of earlier builds, which dealt pairs at random).
  std::optional<CrossValidationRecord> cv;
};

/// A mapping from the plan frame to the grid frame learnt from reference pairs (SPEC "Mapping
/// models"): forward and a consistent inverse, poses through the local Jacobian, confidence,
/// and a model file. Subclasses implement fit_model(), forward() and their parameters; the base
/// validates and prepares the pairs, keeps a support set of pairs for confidence, and inverts by
/// Newton iterations on forward() from a similarity unless a model overrides inverse().
class PointMapping {
 public:
  /// A model with the shared settings.
  explicit PointMapping(MappingCommonOptions common);
  virtual ~PointMapping();
  PointMapping(const PointMapping&) = delete;
  PointMapping& operator=(const PointMapping&) = delete;

  /// The model's name (SPEC: lc, gt, gt-rigid, gt-affine, ct, gp, gpgt, dt, tps, auto).
  virtual std::string name() const = 0;
  /// Distinct plan points the model needs at least.
  virtual std::size_t min_pairs() const = 0;
  /// Whether the model needs its plan points not all on one line.
  virtual bool needs_non_collinear() const = 0;
  /// Whether the model reduces its pairs to reduction_budget() first.
  virtual bool reduces_pairs() const = 0;
  /// The pairs a reducing model keeps at most (default MappingCommonOptions::reduction).
  virtual std::size_t reduction_budget() const { return common_.reduction.budget; }

  /// Fits the model to pairs in metres. Validates (non-finite values: InputError naming
  /// "pairs"), merges duplicate plan points (with a warning), refuses too few or collinear
  /// pairs (InputError), reduces the pairs when the model does, fits, and keeps a support set.
  FitSummary fit(const ReferencePairs& pairs);
  /// Whether fit() or a model file has given the model its parameters.
  bool fitted() const { return fitted_; }
  /// The last fit's summary.
  const FitSummary& summary() const { return summary_; }
  /// Sets the cross-validated error reported with the model, and how it was measured.
  void set_cv_error(double error_m, CrossValidationRecord how) {
    summary_.cv_error_m = error_m;
    summary_.cv = std::move(how);
  }

  /// A plan point (metres) in the grid frame.
  virtual Eigen::Vector2d forward(const Eigen::Vector2d& point_in_plan) const = 0;
  /// Each column mapped forward.
  virtual Eigen::Matrix2Xd forward_batch(
      const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const;
  /// J_grid_plan at a plan point (default: central differences on forward()).
  virtual Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const;
  /// The plan point of a grid point (default: Newton iterations on forward() from the support
  /// similarity's inverse, and, where they stall, from the nearest support pair's plan point, to
  /// inverse_tolerance x extent; not invertible where det J changes
  /// sign against the similarity's, where the iterations fail, or where the grid point may have
  /// another plan point: in the grid image of a fold, see fold_index()).
  virtual InverseMapping inverse(const Eigen::Vector2d& point_in_grid) const;
  /// The model's own posterior standard deviation of the grid point (metres), where the model
  /// has one (the GP's): it sees only uncorrelated pair noise, so map_forward() does not
  /// report it; std_m is error_std().
  virtual std::optional<double> predictive_std(const Eigen::Vector2d& point_in_plan) const;
  /// The calibrated standard deviation of the mapping's error at a plan point (ErrorModel at
  /// its distance from the nearest pair), or nullopt without an error model.
  std::optional<double> error_std(const Eigen::Vector2d& point_in_plan) const;
  /// The error model (from a blocked cross-validation), if any.
  const std::optional<ErrorModel>& error_model() const { return error_model_; }
  /// Sets the error model (nullopt: the model states no std_m).
  void set_error_model(std::optional<ErrorModel> model) { error_model_ = std::move(model); }
  /// Sets the maximal 95% error bound of an `ok` point, metres (> 0; InputError otherwise).
  void set_max_error(double metres);

  /// The grid heading of a plan heading at a plan point (through J_grid_plan there).
  double heading_in_grid(const Eigen::Vector2d& point_in_plan, double theta_in_plan) const;
  /// The plan heading of a grid heading, at the plan point the grid point maps back to (through
  /// J_grid_plan^-1 there): with map_inverse()'s point, a grid pose costs one inverse.
  double heading_in_plan(const Eigen::Vector2d& point_in_plan, double theta_in_grid) const;
  /// A plan pose in the grid frame: position forward, heading through the Jacobian.
  Pose2 forward_pose(const Pose2& pose_in_plan) const;
  /// A grid pose in the plan frame (nullopt where not invertible).
  std::optional<Pose2> inverse_pose(const Pose2& pose_in_grid) const;

  /// forward() with confidence and flag.
  MappedPoint map_forward(const Eigen::Vector2d& point_in_plan) const;
  /// inverse() with confidence and flag (distances on the grid side).
  MappedPoint map_inverse(const Eigen::Vector2d& point_in_grid) const;

  /// Distance to the nearest support pair's plan point, metres.
  double nearest_pair_in_plan(const Eigen::Vector2d& point_in_plan) const;
  /// Distance to the nearest support pair's grid point, metres.
  double nearest_pair_in_grid(const Eigen::Vector2d& point_in_grid) const;
  /// Whether a plan point lies inside the convex hull of the support pairs' plan points.
  bool inside_plan_hull(const Eigen::Vector2d& point_in_plan) const;
  /// Whether a grid point lies inside the convex hull of the support pairs' grid points.
  bool inside_grid_hull(const Eigen::Vector2d& point_in_grid) const;
  /// Where the mapping folds, seen from the grid (built on first use over the support pairs'
  /// box grown by the extrapolation distance: at most 250,000 lattice nodes, 5 cm apart or more).
  const FoldIndex& fold_index() const;
  /// The support pairs: the fitted pairs binned to support_budget.
  const ReferencePairs& support() const { return support_; }
  /// Diagonal of the support plan points' bounds, metres.
  double extent() const { return extent_; }
  /// The least-squares similarity of the support pairs (inverse start, fallback), 3x3.
  const Eigen::Matrix3d& support_similarity() const { return T_support_; }
  /// The shared settings.
  const MappingCommonOptions& common() const { return common_; }
  /// Metres per unit of the pairs the model was fitted from (`fit --unit`); 1 for metres. The
  /// model works in metres; this is recorded so `map` reads and writes in the pairs' units.
  double unit() const { return unit_; }
  /// Records the pairs' unit.
  void set_unit(double metres_per_unit) { unit_ = metres_per_unit; }

  /// The model file's content (format "floorgrid-model", SPEC contract; io/ writes it as JSON):
  /// envelope, support set and the model's parameters.
  Value to_model_file() const;
  /// Restores a model saved by to_model_file() (the envelope was checked by load_mapping());
  /// InputError naming `where` and the field for any field out of type or range.
  void from_model_file(const Value& model_file, const std::string& where);

 protected:
  /// Fits to prepared pairs (validated, merged, reduced when reduces_pairs()). Fills the
  /// summary's rms_m, inliers and details; throws InputError on degenerate pairs.
  virtual void fit_model(const ReferencePairs& pairs, FitSummary& summary) = 0;
  /// The model's own parameters for the model file.
  virtual Value parameters() const = 0;
  /// Restores the model's own parameters, checking each; InputError naming `where` and the
  /// field otherwise.
  virtual void load_parameters(const Value& parameters, const std::string& where) = 0;

 private:
  void build_support(const ReferencePairs& pairs);
  MapFlag flag_of(bool inside_hull, double nearest_pair_m,
                  const std::optional<double>& std_m) const;

  MappingCommonOptions common_;
  FitSummary summary_;
  bool fitted_ = false;
  ReferencePairs support_;
  PointIndex2D support_plan_index_;
  PointIndex2D support_grid_index_;
  std::vector<Eigen::Vector2d> plan_hull_;
  std::vector<Eigen::Vector2d> grid_hull_;
  Eigen::Matrix3d T_support_ = Eigen::Matrix3d::Identity();
  double extent_ = 1.0;
  double unit_ = 1.0;
  std::optional<ErrorModel> error_model_;
  mutable std::mutex fold_index_mutex_;
  mutable std::shared_ptr<const FoldIndex> fold_index_;  ///< built by fold_index() on first use
};

}  // namespace floorgrid
