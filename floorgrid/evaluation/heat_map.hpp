#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/evaluation/model_evaluation.hpp"
#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid {

/// Plan points (2 x N, plan metres) to grid points (2 x N): a model's or a truth's batch.
using PlanToGridBatch = std::function<Eigen::Matrix2Xd(const Eigen::Ref<const Eigen::Matrix2Xd>&)>;

/// A truth given point by point as a batch (each column mapped in turn).
PlanToGridBatch batch_of(const GroundTruth& truth);

/// How heat maps are computed.
struct HeatMapOptions {
  /// Cells of the mask mapped per batch at least (under twice as many; all of them when the
  /// mask has fewer): the unit of work shared between threads. A model may map a large batch
  /// otherwise than a small one, within its stated accuracy (tps through its lattice from
  /// ThinPlateSplineModelOptions::lattice_from, 30,000 points): with batches this large, every
  /// cell of a large map takes the same path. Larger batches outgrow the caches (gt's map of
  /// 4,000 x 4,000 cells takes half as long again with 2^16).
  std::size_t chunk = 1 << 15;
  int threads = kDefaultThreads;  ///< threads; the result does not depend on it
  /// Cells between the nodes at which the uncertainty map evaluates std_m (bilinear between
  /// them; 1: every cell). std_m's local part costs microseconds a point; the map is a guide
  /// to where the mapping is guessed, not a measurement. The error map is always exact.
  int uncertainty_step = 4;
};

/// Which cells of a raster are in a heat map's domain: 1 in, 0 out, one byte per cell, indexed
/// iy * width + ix (cell rows from the bottom, as OccupancyGrid).
using CellMask = std::vector<std::uint8_t>;

/// One value per cell of a raster in the plan frame (thesis Fig. 6.18-6.25): NaN where the value
/// is unknown (outside the domain, or where the model does not say).
struct HeatMap {
  GridGeometry raster;        ///< the cells, in the plan frame (the plan grid's)
  std::vector<float> values;  ///< raster.size() values, metres, NaN unknown
  /// What the values are: "error_m" (|model - truth|), "std_m" (the model's own predicted
  /// error, PointMapping::error_std) or "nearest_pair_m" (distance to the nearest pair: the
  /// model states no std_m).
  std::string quantity;
  double seconds = 0.0;  ///< wall-clock time of the computation

  /// Cells with a finite value.
  std::size_t known() const;
  /// The q-quantile (0..1) of the finite values, metres (0 when none is finite).
  double quantile(double q) const;
};

/// The cells of `raster` whose centre, mapped to the grid by `plan_to_grid`, falls on an
/// observed (free or occupied) cell of `gridmap`: the cells where a warp truth is known to hold,
/// or where a model puts the plan on what the robot saw.
CellMask observed_cells(const GridGeometry& raster, const OccupancyGrid& gridmap,
                        const PlanToGridBatch& plan_to_grid, const HeatMapOptions& options = {});

/// The cells of `raster` whose centre lies inside the convex hull of `points_in_plan` (the
/// manual pairs' domain).
CellMask hull_cells(const GridGeometry& raster, const Eigen::Matrix2Xd& points_in_plan);

/// The error |model(p) - truth(p)| at the centre p of every cell in `mask`, metres.
HeatMap error_heat_map(const PointMapping& model, const PlanToGridBatch& truth,
                       const GridGeometry& raster, const CellMask& mask,
                       const HeatMapOptions& options = {});

/// The model's own uncertainty at the centre of every cell in `mask`: its std_m
/// (PointMapping::error_std) when it has an error model, else the distance to the nearest pair.
/// Where no truth exists this shows the operator where the mapping is guessed.
HeatMap uncertainty_map(const PointMapping& model, const GridGeometry& raster, const CellMask& mask,
                        const HeatMapOptions& options = {});

}  // namespace floorgrid
