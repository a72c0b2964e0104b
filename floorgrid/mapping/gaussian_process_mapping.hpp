#pragma once

#include <optional>

#include "floorgrid/geometry/ransac.hpp"
#include "floorgrid/mapping/gaussian_process.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// `gp` (thesis 4.4.1) and `gpgt` (4.4.2): a global similarity plus a Gaussian process on its
/// residuals, so that far from the pairs the map falls back to the similarity: gp's is the
/// least-squares similarity of all pairs (the thesis' constant mean sent every point far from
/// the pairs to their centroid), gpgt's the RANSAC one of `gt`. One squared-exponential kernel
/// with a length scale per plan axis is shared by both output coordinates (one Cholesky serves
/// both); its hyperparameters maximize the log marginal likelihood by RPROP on log-parameters
/// with analytic gradients, tuned on a spread subsample of at most 400 reduced pairs; then
/// their scale (length scales, noise std) is re-chosen by spatially blocked cross-validation on
/// that subsample (refine_by_blocked_cv), and the GP is conditioned on all pairs. The mean is
/// evaluated on a lattice with bicubic interpolation (measured added error <= 1 mm); the
/// predictive standard deviation is exact. An exact GP over every laser pair is infeasible: the
/// pairs are first reduced by spatial binning (MappingCommonOptions::reduction), and the model
/// file says so.
class GaussianProcessMapping : public PointMapping {
 public:
  /// A gp model (`on_global_transform` false) or a gpgt model (true, with `ransac` for its
  /// global similarity).
  GaussianProcessMapping(MappingCommonOptions common, GaussianProcessOptions gp,
                         bool on_global_transform, RansacOptions ransac);
  ~GaussianProcessMapping() override;

  std::string name() const override { return global_ ? "gpgt" : "gp"; }
  /// gp: 5 (fewer cannot tell a trend from noise); gpgt: 3 (the similarity takes 2, the
  /// residual GP one more).
  std::size_t min_pairs() const override { return global_ ? 3 : 5; }
  bool needs_non_collinear() const override { return false; }
  bool reduces_pairs() const override { return true; }

  Eigen::Vector2d forward(const Eigen::Vector2d& point_in_plan) const override;
  Eigen::Matrix2Xd forward_batch(
      const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const override;
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const override;
  std::optional<double> predictive_std(const Eigen::Vector2d& point_in_plan) const override;

  /// The fitted process.
  const GaussianProcess& process() const { return *process_; }

 protected:
  void fit_model(const ReferencePairs& pairs, FitSummary& summary) override;
  Value parameters() const override;
  void load_parameters(const Value& parameters, const std::string& where) override;

 private:
  GaussianProcessOptions gp_options_;
  bool global_;
  RansacOptions ransac_;
  Eigen::Matrix3d T_grid_plan_ = Eigen::Matrix3d::Identity();  ///< the mean similarity
  std::optional<GaussianProcess> process_;
};

}  // namespace floorgrid
