#include "floorgrid/pipeline/wall_slide.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/mapping/model_registry.hpp"
#include "floorgrid/mapping/pair_preparation.hpp"

namespace floorgrid {

void validate(const WallSlideOptions& o) {
  const std::string p = "align.wall_slide.";
  require_option(o.iterations <= 100, p + "iterations", o.iterations, "<= 100");
  require_option(o.radius > 0.0 && std::isfinite(o.radius), p + "radius", o.radius, "> 0 metres");
  require_option(o.max_flatness > 0.0 && o.max_flatness < 1.0, p + "max_flatness", o.max_flatness,
                 "in (0, 1)");
  require_option(o.min_along_ratio >= 1.0 && std::isfinite(o.min_along_ratio),
                 p + "min_along_ratio", o.min_along_ratio, ">= 1");
  const std::vector<std::string> names = mapping_model_names();
  require_option(std::find(names.begin(), names.end(), o.smoother) != names.end(), p + "smoother",
                 o.smoother, "a model name");
}

Eigen::Vector2d wall_direction(const OccupancyGrid& gridmap, const Eigen::Vector2d& point_in_grid,
                               double radius, double max_flatness) {
  const GridGeometry& g = gridmap.geometry();
  const Eigen::Vector2d c = g.to_cell_coordinates(point_in_grid);
  const double r_cells = std::max(2.0, radius / g.resolution);
  const int r = static_cast<int>(std::ceil(r_cells));
  const int cx = static_cast<int>(std::floor(c.x())), cy = static_cast<int>(std::floor(c.y()));
  // The scatter of the occupied cell centres near the point, in cell units.
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d outer = Eigen::Matrix2d::Zero();
  int n = 0;
  for (int iy = cy - r; iy <= cy + r; ++iy) {
    for (int ix = cx - r; ix <= cx + r; ++ix) {
      if (!g.contains(ix, iy) || !gridmap.is_occupied(ix, iy))
        continue;
      const Eigen::Vector2d d = Eigen::Vector2d(ix + 0.5, iy + 0.5) - c;
      if (d.squaredNorm() > r_cells * r_cells)
        continue;
      sum += d;
      outer += d * d.transpose();
      ++n;
    }
  }
  if (n < 4)
    return Eigen::Vector2d::Zero();
  const Eigen::Vector2d mean = sum / n;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(outer / n - mean * mean.transpose());
  const double across = eigen.eigenvalues()(0), along = eigen.eigenvalues()(1);
  if (!(along > 0.0) || across > max_flatness * along)
    return Eigen::Vector2d::Zero();
  // Cell axes are the grid's axes; the grid's yaw turns them into the map frame.
  return (g.origin.rotation() * eigen.eigenvectors().col(1)).normalized();
}

WallSlide slide_pairs_along_walls(const ReferencePairs& pairs, const OccupancyGrid& gridmap,
                                  const WallSlideOptions& options, const MappingOptions& mapping) {
  validate(options);
  WallSlide out;
  out.pairs = pairs;
  const Eigen::Index n = pairs.size();
  std::vector<Eigen::Vector2d> along(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    along[static_cast<std::size_t>(i)] =
        wall_direction(gridmap, pairs.points_in_grid.col(i), options.radius, options.max_flatness);
    out.pairs_on_walls += along[static_cast<std::size_t>(i)].squaredNorm() > 0.0 ? 1 : 0;
  }
  MappingOptions smoother_options = mapping;
  smoother_options.model = options.smoother;
  if (out.pairs_on_walls == 0 || options.iterations == 0)
    return out;
  out.noise = pair_noise_along(pairs, along);
  const double ratio = options.min_along_ratio;
  if (!out.noise || !(out.noise->along_m2 >= ratio * ratio * out.noise->across_m2))
    return out;
  for (std::size_t round = 0; round < options.iterations; ++round) {
    std::unique_ptr<PointMapping> smoother = make_mapping(smoother_options);
    if (distinct_plan_points(out.pairs) < smoother->min_pairs())
      break;
    try {
      smoother->fit(out.pairs);
    } catch (const InputError&) {
      break;  // pairs the smoother cannot fit (collinear, say): they stay as they are
    }
    const Eigen::Matrix2Xd predicted = smoother->forward_batch(pairs.points_in_plan);
    // Slide from where the filters put each pair (not from the last round's place): the
    // across-wall part stays the measured one exactly.
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector2d& t = along[static_cast<std::size_t>(i)];
      const Eigen::Vector2d measured = pairs.points_in_grid.col(i);
      const double slide = t.dot(predicted.col(i) - measured);
      if (std::isfinite(slide))
        out.pairs.points_in_grid.col(i) = measured + slide * t;
    }
    ++out.iterations;
  }
  out.applied = out.iterations > 0;
  std::vector<double> slides;
  slides.reserve(out.pairs_on_walls);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (along[static_cast<std::size_t>(i)].squaredNorm() > 0.0)
      slides.push_back((out.pairs.points_in_grid.col(i) - pairs.points_in_grid.col(i)).norm());
  }
  out.median_slide_m = median(slides);
  out.p95_slide_m = quantile(slides, 0.95);
  return out;
}

}  // namespace floorgrid
