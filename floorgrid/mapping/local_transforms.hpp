#pragma once

#include <vector>

#include "floorgrid/geometry/transform_estimation.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

/// Options of the `ct` model.
struct LocalTransformsOptions {
  TransformKind kind = TransformKind::similarity;  ///< the family of each local transform
  double cell_size = 0.0;     ///< metres of the finest clustering cells; 0: extent / 12
  int levels = 4;             ///< coarser levels (cells doubled each) over which clusters merge
  double agreement = 0.05;    ///< metres: a pair agrees with a transform within this distance
  int min_cluster_pairs = 6;  ///< smaller clusters are dropped
  int hypotheses = 20;        ///< seeded minimal samples tried per cluster in a cell
  double weight_power = 2.0;  ///< w_k = 1 / d^power, d = distance to cluster k's centroid
  /// Pairs kept (spatial binning, the pairs of a cell averaged) before clustering: bounds the
  /// cost (10^6 laser pairs took 17 s unreduced) while leaving cells of a few centimetres.
  std::size_t budget = 20000;
};

/// `ct` (thesis 4.3, 5.1, Algorithms 1 and 2): the plan is cut into square cells; in each cell
/// clusters grow around seeded minimal samples (the best of `hypotheses` tries) with every pair
/// that agrees with the cluster's transform; clusters of neighbouring cells whose transforms
/// agree on each other's pairs merge, level by level with cells doubling in size. A point maps
/// by the normalized inverse-distance-weighted sum of the clusters' transforms (eq. 4.10-4.12
/// with the weights normalized as Algorithm 2 does; eq. 4.11 leaves them unnormalized).
class LocalTransformsMapping : public PointMapping {
 public:
  /// A ct model.
  LocalTransformsMapping(MappingCommonOptions common, LocalTransformsOptions options);

  std::string name() const override { return "ct"; }
  std::size_t min_pairs() const override { return 3; }
  bool needs_non_collinear() const override { return false; }
  bool reduces_pairs() const override { return true; }
  std::size_t reduction_budget() const override { return options_.budget; }

  Eigen::Vector2d forward(const Eigen::Vector2d& point_in_plan) const override;
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const override;

  /// One cluster: its transform and where it lies.
  struct Cluster {
    Eigen::Matrix3d T_grid_plan = Eigen::Matrix3d::Identity();  ///< its transform
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();         ///< mean plan point, metres
    std::size_t pairs = 0;                                      ///< members
    double rms = 0.0;                                           ///< metres over its members
  };
  /// The clusters found.
  const std::vector<Cluster>& clusters() const { return clusters_; }

 protected:
  void fit_model(const ReferencePairs& pairs, FitSummary& summary) override;
  Value parameters() const override;
  void load_parameters(const Value& parameters, const std::string& where) override;

 private:
  LocalTransformsOptions options_;
  std::vector<Cluster> clusters_;
};

}  // namespace floorgrid
