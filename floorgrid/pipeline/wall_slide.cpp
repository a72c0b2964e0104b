#include "floorgrid/pipeline/wall_slide.hpp"

#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/statistics.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/localization/wall_field.hpp"
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
  const Eigen::Vector2d normal =
      occupied_line_normal(gridmap, g.to_cell_coordinates(point_in_grid),
                           std::max(2.0, radius / g.resolution), max_flatness, 4);
  return {-normal.y(), normal.x()};
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
