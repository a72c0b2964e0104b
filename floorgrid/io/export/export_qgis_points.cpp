#include "floorgrid/io/export/export_qgis_points.hpp"

#include <fmt/format.h>

#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/export/export_raster.hpp"
#include "floorgrid/mapping/pair_preparation.hpp"

namespace floorgrid::io {

QgisPoints qgis_points(const PointMapping& model, const ReferencePairs& pairs,
                       const std::optional<GridGeometry>& plan_raster,
                       const QgisPointsOptions& options) {
  if (pairs.empty())
    throw InputError("no pairs to write as control points", {}, 0, "pairs");
  if (options.max_points < 3) {
    throw InputError(fmt::format("must be at least 3 (got {})", options.max_points), {}, 0,
                     "max_points");
  }
  validate_pairs(pairs);
  ReductionOptions reduction;
  reduction.budget = options.max_points;
  const ReferencePairs kept = reduce_pairs(pairs, reduction);
  const Eigen::Matrix2Xd mapped = model.forward_batch(kept.points_in_plan);
  QgisPoints out;
  out.pairs = static_cast<std::size_t>(pairs.size());
  out.points = static_cast<std::size_t>(kept.size());
  out.source_in_pixels = plan_raster.has_value();
  // QGIS writes `#CRS: ` and the CRS's WKT; an invalid (no) CRS has an empty WKT.
  std::string text = "#CRS: \nmapX,mapY,sourceX,sourceY,enable,dX,dY,residual\n";
  double sum_squares = 0.0;
  for (Eigen::Index i = 0; i < kept.size(); ++i) {
    const Eigen::Vector2d plan = kept.points_in_plan.col(i);
    const Eigen::Vector2d grid = kept.points_in_grid.col(i);
    Eigen::Vector2d source = plan;
    if (plan_raster) {
      const Eigen::Vector2d pixel_line = frame_to_image(*plan_raster, plan);
      source = {pixel_line.x(), -pixel_line.y()};
    }
    const Eigen::Vector2d d = mapped.col(i) - grid;
    if (!d.allFinite() || !source.allFinite()) {
      throw InputError(fmt::format("the {} model maps pair {} (plan [{}, {}]) to a non-finite "
                                   "point: no control points are written",
                                   model.name(), i + 1, plan.x(), plan.y()),
                       {}, 0, "model");
    }
    sum_squares += d.squaredNorm();
    text += fmt::format("{},{},{},{},1,{},{},{}\n", grid.x(), grid.y(), source.x(), source.y(),
                        d.x(), d.y(), d.norm());
  }
  out.rms_m = std::sqrt(sum_squares / static_cast<double>(kept.size()));
  out.text = std::move(text);
  return out;
}

}  // namespace floorgrid::io
