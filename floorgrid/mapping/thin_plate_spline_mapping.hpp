#pragma once

#include <memory>
#include <mutex>
#include <optional>

#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/mapping/thin_plate_spline.hpp"
#include "floorgrid/mapping/thin_plate_spline_lattice.hpp"

namespace floorgrid {

/// Options of the `tps` model.
struct ThinPlateSplineModelOptions {
  /// Regularization weight lambda, m^2 (0 interpolates); nullopt chooses it by 5-fold
  /// spatially blocked cross-validation on a subsample (see ThinPlateSplineMapping).
  std::optional<double> regularization;
  std::size_t tuning_pairs = 400;  ///< subsample size of the lambda choice
  /// A few pairs (hand-picked: at most this many, 0: never) are refitted robustly when lambda
  /// > 0: a pair whose leave-one-out error exceeds `robust_cutoff` times the pairs' median
  /// leave-one-out error gets the weight (that limit / its error)^2, `robust_iterations` times,
  /// so that a mis-clicked pair bends the spline less around it.
  std::size_t robust_max_pairs = 200;
  int robust_iterations = 2;
  double robust_cutoff = 2.2;
  ThinPlateSplineLatticeOptions lattice;  ///< for mapping many points at once
  /// Batches at least this large use the lattice (a heat map's batches, HeatMapOptions::chunk,
  /// are larger: all its cells take one path).
  Eigen::Index lattice_from = 30'000;
};

/// `tps`: a thin-plate spline from plan to grid with a regularization weight, as in the QGIS
/// and GDAL georeferencers (there unregularized). Pairs are reduced by spatial binning first.
/// Unless given, lambda is chosen among 0 and 10^-3 .. 10^3 m^2 by 5-fold spatially blocked
/// cross-validation (blocks of the grid frame, see blocked_folds) on a random subsample of at most
/// `tuning_pairs` pairs, then scaled by (pairs / subsample) so the penalty keeps its weight against
/// the larger sum of squared residuals. Large batches are mapped through a bicubic lattice of the
/// spline over the support's box (built on first use, its spacing refined until the added error
/// measured is within half of lattice.tolerance, 1 mm); single points and small batches exactly.
class ThinPlateSplineMapping : public PointMapping {
 public:
  /// A tps model.
  ThinPlateSplineMapping(MappingCommonOptions common, ThinPlateSplineModelOptions options);
  ~ThinPlateSplineMapping() override;

  std::string name() const override { return "tps"; }
  std::size_t min_pairs() const override { return 3; }
  bool needs_non_collinear() const override { return true; }
  bool reduces_pairs() const override { return true; }

  Eigen::Vector2d forward(const Eigen::Vector2d& point_in_plan) const override;
  Eigen::Matrix2Xd forward_batch(
      const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const override;
  Eigen::Matrix2d jacobian(const Eigen::Vector2d& point_in_plan) const override;

 protected:
  void fit_model(const ReferencePairs& pairs, FitSummary& summary) override;
  Value parameters() const override;
  void load_parameters(const Value& parameters, const std::string& where) override;

 private:
  /// lambda by cross-validation on a subsample; `table` gets the error of every candidate.
  double choose_regularization(const ReferencePairs& pairs, Value& table) const;

  ThinPlateSplineModelOptions options_;
  std::optional<ThinPlateSpline> spline_;
  mutable std::once_flag lattice_once_;
  mutable std::unique_ptr<ThinPlateSplineLattice> lattice_;
};

}  // namespace floorgrid
