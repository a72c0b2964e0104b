#include "floorgrid/evaluation/heat_map.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "floorgrid/core/statistics.hpp"
#include "floorgrid/geometry/convex_hull.hpp"

namespace floorgrid {

namespace {

using Clock = std::chrono::steady_clock;

/// Runs work(points, cells) over the raster's cells in `mask` (all cells when empty), in
/// batches of consecutive cells of the mask: max(1, cells / options.chunk) batches, as equal as
/// can be, so that each holds at least `options.chunk` cells (fewer only when the whole mask
/// does) and under twice as many. `points` holds the centres (plan frame) of the batch's cells,
/// `cells` their indices. Batches do not depend on the threads.
template <typename Work>
void for_cells_in_mask(const GridGeometry& raster, const CellMask& mask,
                       const HeatMapOptions& options, const Work& work) {
  const auto width = static_cast<std::size_t>(raster.width);
  const auto height = static_cast<std::size_t>(raster.height);
  if (width == 0 || height == 0)
    return;
  const auto in_mask = [&](std::size_t c) { return mask.empty() || mask[c] != 0; };
  // before[r]: cells of the mask in the rows below row r.
  std::vector<std::size_t> before(height + 1, 0);
  parallel_blocks(height, options.threads, [&](std::size_t first, std::size_t last) {
    for (std::size_t r = first; r < last; ++r) {
      before[r + 1] = mask.empty()
                          ? width
                          : static_cast<std::size_t>(std::count_if(
                                mask.begin() + static_cast<std::ptrdiff_t>(r * width),
                                mask.begin() + static_cast<std::ptrdiff_t>((r + 1) * width),
                                [](std::uint8_t m) { return m != 0; }));
    }
  });
  for (std::size_t r = 0; r < height; ++r)
    before[r + 1] += before[r];
  const std::size_t total = before[height];
  if (total == 0)
    return;
  const std::size_t batches =
      std::max<std::size_t>(1, total / std::max<std::size_t>(options.chunk, 1));
  parallel_tasks(batches, options.threads, [&](std::size_t b) {
    // The batch's cells of the mask, by rank: [first, last).
    const std::size_t first = total * b / batches, last = total * (b + 1) / batches;
    std::vector<std::size_t> chosen;
    chosen.reserve(last - first);
    const std::size_t row = static_cast<std::size_t>(
        std::upper_bound(before.begin(), before.end(), first) - before.begin() - 1);
    std::size_t rank = before[row];
    for (std::size_t c = row * width; chosen.size() < last - first; ++c) {
      if (in_mask(c)) {
        if (rank >= first)
          chosen.push_back(c);
        ++rank;
      }
    }
    Eigen::Matrix2Xd points(2, static_cast<Eigen::Index>(chosen.size()));
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      points.col(static_cast<Eigen::Index>(k)) = raster.cell_center(
          static_cast<int>(chosen[k] % width), static_cast<int>(chosen[k] / width));
    }
    work(points, chosen);
  });
}

HeatMap empty_map(const GridGeometry& raster, std::string quantity) {
  return {raster, std::vector<float>(raster.size(), std::numeric_limits<float>::quiet_NaN()),
          std::move(quantity), 0.0};
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

PlanToGridBatch batch_of(const GroundTruth& truth) {
  return [truth](const Eigen::Ref<const Eigen::Matrix2Xd>& points) {
    Eigen::Matrix2Xd mapped(2, points.cols());
    for (Eigen::Index i = 0; i < points.cols(); ++i)
      mapped.col(i) = truth(points.col(i));
    return mapped;
  };
}

std::size_t HeatMap::known() const {
  return static_cast<std::size_t>(
      std::count_if(values.begin(), values.end(), [](float v) { return std::isfinite(v); }));
}

double HeatMap::quantile(double q) const {
  std::vector<double> finite;
  finite.reserve(values.size());
  for (const float v : values)
    if (std::isfinite(v))
      finite.push_back(v);
  if (finite.empty())
    return 0.0;
  // nth_element, not a sort: a 4000 x 4000 raster has 16 million values.
  const std::size_t k =
      std::min(finite.size() - 1,
               static_cast<std::size_t>(std::floor(q * static_cast<double>(finite.size()))));
  std::nth_element(finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(k), finite.end());
  return finite[k];
}

CellMask observed_cells(const GridGeometry& raster, const OccupancyGrid& gridmap,
                        const PlanToGridBatch& plan_to_grid, const HeatMapOptions& options) {
  CellMask mask(raster.size(), 0);
  for_cells_in_mask(raster, {}, options,
                    [&](const Eigen::Matrix2Xd& points, const std::vector<std::size_t>& cells) {
                      const Eigen::Matrix2Xd in_grid = plan_to_grid(points);
                      for (std::size_t k = 0; k < cells.size(); ++k) {
                        int ix = 0, iy = 0;
                        const Eigen::Vector2d p = in_grid.col(static_cast<Eigen::Index>(k));
                        if (p.allFinite() && gridmap.geometry().cell_of(p, ix, iy) &&
                            gridmap.state(ix, iy) != CellState::unknown)
                          mask[cells[k]] = 1;
                      }
                    });
  return mask;
}

CellMask hull_cells(const GridGeometry& raster, const Eigen::Matrix2Xd& points_in_plan) {
  CellMask mask(raster.size(), 0);
  const std::vector<Eigen::Vector2d> hull = convex_hull(points_in_plan);
  if (hull.size() < 3)
    return mask;
  for (int iy = 0; iy < raster.height; ++iy) {
    for (int ix = 0; ix < raster.width; ++ix) {
      if (inside_convex_polygon(hull, raster.cell_center(ix, iy)))
        mask[static_cast<std::size_t>(iy) * raster.width + ix] = 1;
    }
  }
  return mask;
}

HeatMap error_heat_map(const PointMapping& model, const PlanToGridBatch& truth,
                       const GridGeometry& raster, const CellMask& mask,
                       const HeatMapOptions& options) {
  const auto start = Clock::now();
  HeatMap map = empty_map(raster, "error_m");
  // Each cell exactly, through the model's own batch: the map shows the model as it maps many
  // points (gp through the lattice its forward() uses too, tps through the lattice of its large
  // batches, within 1 mm of its exact forward()); the map adds no interpolation of its own.
  for_cells_in_mask(raster, mask, options,
                    [&](const Eigen::Matrix2Xd& points, const std::vector<std::size_t>& cells) {
                      const Eigen::Matrix2Xd mapped = model.forward_batch(points);
                      const Eigen::Matrix2Xd truly = truth(points);
                      for (std::size_t k = 0; k < cells.size(); ++k) {
                        const auto i = static_cast<Eigen::Index>(k);
                        map.values[cells[k]] =
                            static_cast<float>((mapped.col(i) - truly.col(i)).norm());
                      }
                    });
  map.seconds = seconds_since(start);
  return map;
}

HeatMap uncertainty_map(const PointMapping& model, const GridGeometry& raster, const CellMask& mask,
                        const HeatMapOptions& options) {
  const auto start = Clock::now();
  const bool has_std = model.error_model().has_value();
  HeatMap map = empty_map(raster, has_std ? "std_m" : "nearest_pair_m");
  const auto value_at = [&](const Eigen::Vector2d& p) {
    return has_std ? model.error_std(p).value_or(NAN) : model.nearest_pair_in_plan(p);
  };
  const int step = std::max(1, options.uncertainty_step);
  if (step == 1 || raster.width < 2 || raster.height < 2) {
    for_cells_in_mask(raster, mask, options,
                      [&](const Eigen::Matrix2Xd& points, const std::vector<std::size_t>& cells) {
                        for (std::size_t k = 0; k < cells.size(); ++k)
                          map.values[cells[k]] = static_cast<float>(
                              value_at(points.col(static_cast<Eigen::Index>(k))));
                      });
    map.seconds = seconds_since(start);
    return map;
  }
  // The lattice: cell centres of every step-th column and row, and the last ones.
  const auto nodes_of = [step](int cells) {
    std::vector<int> nodes;
    for (int i = 0; i < cells; i += step)
      nodes.push_back(i);
    if (nodes.back() != cells - 1)
      nodes.push_back(cells - 1);
    return nodes;
  };
  const std::vector<int> xs = nodes_of(raster.width), ys = nodes_of(raster.height);
  std::vector<double> lattice(xs.size() * ys.size());
  parallel_chunks(ys.size(), 8, options.threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j)
      for (std::size_t i = 0; i < xs.size(); ++i)
        lattice[j * xs.size() + i] = value_at(raster.cell_center(xs[i], ys[j]));
  });
  const auto width = static_cast<std::size_t>(raster.width);
  parallel_chunks(
      raster.size(), options.chunk, options.threads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t c = begin; c < end; ++c) {
          if (!mask.empty() && mask[c] == 0)
            continue;
          const int ix = static_cast<int>(c % width), iy = static_cast<int>(c / width);
          const std::size_t i = std::min<std::size_t>(ix / step, xs.size() - 2);
          const std::size_t j = std::min<std::size_t>(iy / step, ys.size() - 2);
          const double u = static_cast<double>(ix - xs[i]) / static_cast<double>(xs[i + 1] - xs[i]);
          const double v = static_cast<double>(iy - ys[j]) / static_cast<double>(ys[j + 1] - ys[j]);
          const auto at = [&](std::size_t a, std::size_t b) { return lattice[b * xs.size() + a]; };
          map.values[c] =
              static_cast<float>((1 - u) * (1 - v) * at(i, j) + u * (1 - v) * at(i + 1, j) +
                                 (1 - u) * v * at(i, j + 1) + u * v * at(i + 1, j + 1));
        }
      });
  map.seconds = seconds_since(start);
  return map;
}

}  // namespace floorgrid
