#include "floorgrid/io/export/export_nav2_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/formats/map_io.hpp"

namespace floorgrid::io {

namespace {

void check(const Nav2MapOptions& options) {
  if (!(options.samples_per_cell >= 1.0 && options.samples_per_cell <= 100.0)) {
    throw InputError(fmt::format("must be in [1, 100] (got {})", options.samples_per_cell), {}, 0,
                     "samples_per_cell");
  }
}

/// Plan metres per gridmap cell at the model's overall scale (its support similarity's): the
/// sample spacing in the plan is this over samples_per_cell.
double plan_metres_per_cell(const PointMapping& model, const GridGeometry& gridmap) {
  const double det = model.support_similarity().topLeftCorner<2, 2>().determinant();
  const double scale = std::sqrt(std::abs(det));
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw InputError("the model's scale is degenerate", {}, 0, "model");
  return gridmap.resolution / scale;
}

/// Marks the cells the mapped points land in.
void mark(OccupancyGrid& grid, const Eigen::Matrix2Xd& points_in_grid) {
  for (Eigen::Index i = 0; i < points_in_grid.cols(); ++i) {
    int ix = 0, iy = 0;
    if (points_in_grid.col(i).allFinite() &&
        grid.geometry().cell_of(points_in_grid.col(i), ix, iy)) {
      grid.set_state(ix, iy, CellState::occupied);
    }
  }
}

/// Maps `points_in_plan` in chunks (a bounded batch for models with costly batches). A model
/// that puts no wall on the gridmap gives no map: an empty one would pass for a drawing.
void draw(OccupancyGrid& grid, const PointMapping& model, const Eigen::Matrix2Xd& points_in_plan) {
  constexpr Eigen::Index kChunk = 65536;
  for (Eigen::Index begin = 0; begin < points_in_plan.cols(); begin += kChunk) {
    const Eigen::Index n = std::min(kChunk, points_in_plan.cols() - begin);
    mark(grid, model.forward_batch(points_in_plan.middleCols(begin, n)));
  }
  if (grid.counts().occupied == 0) {
    throw InputError(fmt::format("the {} model maps none of the plan's {} wall points onto the "
                                 "gridmap: no map is written",
                                 model.name(), points_in_plan.cols()),
                     {}, 0, "model");
  }
}

}  // namespace

OccupancyGrid plan_walls_in_grid(const PointMapping& model, const VectorFloorplan& plan,
                                 const GridGeometry& gridmap, const Nav2MapOptions& options) {
  check(options);
  OccupancyGrid grid(gridmap, options.background);
  const double spacing = plan_metres_per_cell(model, gridmap) / options.samples_per_cell;
  draw(grid, model, plan.sample_points(spacing));
  return grid;
}

OccupancyGrid plan_walls_in_grid(const PointMapping& model, const OccupancyGrid& plan,
                                 const GridGeometry& gridmap, const Nav2MapOptions& options) {
  check(options);
  OccupancyGrid grid(gridmap, options.background);
  const double spacing = plan_metres_per_cell(model, gridmap) / options.samples_per_cell;
  const GridGeometry& g = plan.geometry();
  // Samples per plan cell side, at most `spacing` apart, spread evenly inside the cell.
  const int k = std::max(1, static_cast<int>(std::ceil(g.resolution / spacing)));
  std::vector<Eigen::Vector2d> samples;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if (plan.state(ix, iy) != CellState::occupied)
        continue;
      for (int j = 0; j < k; ++j) {
        for (int i = 0; i < k; ++i) {
          samples.push_back(g.from_cell_coordinates({ix + (i + 0.5) / k, iy + (j + 0.5) / k}));
        }
      }
    }
  }
  Eigen::Matrix2Xd points(2, static_cast<Eigen::Index>(samples.size()));
  for (std::size_t i = 0; i < samples.size(); ++i)
    points.col(static_cast<Eigen::Index>(i)) = samples[i];
  draw(grid, model, points);
  return grid;
}

std::filesystem::path write_nav2_map(const OccupancyGrid& grid,
                                     const std::filesystem::path& yaml_path) {
  MapWriteOptions options;
  options.mode = MapMode::trinary;
  options.image_format = "pgm";
  options.occupied_thresh = 0.65;
  options.free_thresh = 0.25;
  return write_map(grid, yaml_path, options);
}

}  // namespace floorgrid::io
