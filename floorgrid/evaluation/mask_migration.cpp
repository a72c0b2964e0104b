#include "floorgrid/evaluation/mask_migration.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"
#include "floorgrid/maps/polygon_raster.hpp"

namespace floorgrid {

namespace {

/// Lattice nodes every this many cells: the model's inverse (Newton iterations) is taken there
/// and interpolated bilinearly between, as a cell-by-cell inverse of a large map is too slow
/// (smooth models: well under a millimetre off at 4 cells of 5 cm).
constexpr int kLatticeStep = 4;

/// The old-frame point of each new cell centre (NaN where the model cannot map it back),
/// row-major from the bottom row.
Eigen::Matrix2Xd inverse_on_lattice(const PointMapping& old_to_new, const GridGeometry& g) {
  const int nx = (g.width + kLatticeStep - 1) / kLatticeStep + 1;
  const int ny = (g.height + kLatticeStep - 1) / kLatticeStep + 1;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::Matrix2Xd nodes(2, static_cast<Eigen::Index>(nx) * ny);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d centre =
          g.from_cell_coordinates({i * kLatticeStep + 0.5, j * kLatticeStep + 0.5});
      const InverseMapping back = old_to_new.inverse(centre);
      nodes.col(static_cast<Eigen::Index>(j) * nx + i) =
          back.invertible && back.point.allFinite() ? back.point : Eigen::Vector2d(nan, nan);
    }
  }
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(g.size()));
  for (int iy = 0; iy < g.height; ++iy) {
    const int j = iy / kLatticeStep;
    const double v = static_cast<double>(iy % kLatticeStep) / kLatticeStep;
    for (int ix = 0; ix < g.width; ++ix) {
      const int i = ix / kLatticeStep;
      const double u = static_cast<double>(ix % kLatticeStep) / kLatticeStep;
      const auto node = [&](int a, int b) -> Eigen::Vector2d {
        return nodes.col(static_cast<Eigen::Index>(b) * nx + a);
      };
      const Eigen::Vector2d p = (1 - u) * (1 - v) * node(i, j) + u * (1 - v) * node(i + 1, j) +
                                (1 - u) * v * node(i, j + 1) + u * v * node(i + 1, j + 1);
      const Eigen::Index k = static_cast<Eigen::Index>(iy) * g.width + ix;
      if (p.allFinite()) {
        out.col(k) = p;
        continue;
      }
      // A corner could not be mapped back (a fold, the edge of the model): this cell alone.
      const InverseMapping back = old_to_new.inverse(g.cell_center(ix, iy));
      out.col(k) =
          back.invertible && back.point.allFinite() ? back.point : Eigen::Vector2d(nan, nan);
    }
  }
  return out;
}

}  // namespace

void validate(const MaskMigrationOptions& options) {
  require_option(options.margin_sigma >= 0.0 && options.margin_sigma <= 10.0, "migrate",
                 "margin_sigma", options.margin_sigma, "in [0, 10]");
}

GridGeometry migrated_geometry(const PointMapping& old_to_new, const GridGeometry& old_mask) {
  Eigen::AlignedBox2d box;
  // The outline of the old grid, sampled (a bent model bends the outline too).
  const int n = 64;
  for (int k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) / n;
    for (const Eigen::Vector2d& c : {Eigen::Vector2d(t * old_mask.width, 0.0),
                                     Eigen::Vector2d(t * old_mask.width, old_mask.height),
                                     Eigen::Vector2d(0.0, t * old_mask.height),
                                     Eigen::Vector2d(old_mask.width, t * old_mask.height)}) {
      const Eigen::Vector2d p = old_to_new.forward(old_mask.from_cell_coordinates(c));
      if (p.allFinite())
        box.extend(p);
    }
  }
  if (box.isEmpty())
    throw InputError("the model maps no part of the old mask to finite coordinates", {}, 0,
                     "model");
  GridGeometry g;
  g.resolution = old_mask.resolution;
  g.origin = {std::floor(box.min().x() / g.resolution) * g.resolution,
              std::floor(box.min().y() / g.resolution) * g.resolution, 0.0};
  g.width = static_cast<int>(std::ceil((box.max().x() - g.origin.x) / g.resolution));
  g.height = static_cast<int>(std::ceil((box.max().y() - g.origin.y) / g.resolution));
  constexpr int kMaxSide = 20000;
  if (g.width <= 0 || g.height <= 0 || g.width > kMaxSide || g.height > kMaxSide) {
    throw InputError(fmt::format("the old mask mapped forward spans {} x {} cells (at most {} a "
                                 "side): give the new map's geometry (--gridmap)",
                                 g.width, g.height, kMaxSide),
                     {}, 0, "model");
  }
  return g;
}

MigratedMask migrate_mask(const PointMapping& old_to_new, const OccupancyGrid& old_mask,
                          const GridGeometry& g, const MaskMigrationOptions& options) {
  validate(options);
  MigratedMask result;
  result.mask = OccupancyGrid(g, CellState::unknown);
  const GridGeometry& old = old_mask.geometry();
  bool binary = true;
  for (const std::int8_t v : old_mask.values())
    binary = binary && (v == 0 || v == 100 || v < 0);
  const Eigen::Matrix2Xd old_points = inverse_on_lattice(old_to_new, g);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const Eigen::Vector2d back =
          old_points.col(static_cast<Eigen::Index>(result.mask.index(ix, iy)));
      if (!back.allFinite()) {
        ++result.cells_not_invertible;
        continue;
      }
      int ox = 0, oy = 0;
      if (!old.cell_of(back, ox, oy)) {
        ++result.cells_off_old_mask;
        continue;
      }
      result.mask.set_cell(ix, iy, old_mask.state(ox, oy), old_mask.value(ox, oy));
    }
  }
  if (options.margin_sigma <= 0.0)
    return result;
  if (!binary) {
    result.warnings.push_back(
        "the mask holds values other than 0 and 100 (a speed mask): not "
        "widened, its values have no order a margin could respect");
    return result;
  }
  // Widen the keep-out: a disk of K std_m at each zone cell on the zone's boundary.
  CellMask zone(g);
  for (std::size_t i = 0; i < g.size(); ++i)
    zone.cells[i] = result.mask.values()[i] == kOccupancyOccupied;
  std::vector<Eigen::Vector2d> centres;
  std::vector<double> radii;
  bool any_std = false;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if (!zone.at(ix, iy))
        continue;
      bool boundary = false;
      for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int nx = ix + dx, ny = iy + dy;
        boundary = boundary || !g.contains(nx, ny) || !zone.at(nx, ny);
      }
      if (!boundary)
        continue;
      const std::size_t i = result.mask.index(ix, iy);
      const auto s = old_to_new.error_std(old_points.col(static_cast<Eigen::Index>(i)));
      if (!s)
        continue;
      any_std = true;
      centres.push_back(g.cell_center(ix, iy));
      radii.push_back(options.margin_sigma * *s);
    }
  }
  if (!any_std) {
    result.warnings.push_back(
        "the model states no std_m (no error model): the mask is not "
        "widened");
    return result;
  }
  Eigen::Matrix2Xd points(2, static_cast<Eigen::Index>(centres.size()));
  Eigen::VectorXd r(static_cast<Eigen::Index>(radii.size()));
  for (std::size_t k = 0; k < centres.size(); ++k) {
    points.col(static_cast<Eigen::Index>(k)) = centres[k];
    r(static_cast<Eigen::Index>(k)) = radii[k];
  }
  CellMask widened = zone;
  stamp_disks(widened, points, r);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if (widened.at(ix, iy) && !zone.at(ix, iy)) {
        result.mask.set_state(ix, iy, CellState::occupied);
        ++result.cells_widened;
      }
    }
  }
  result.widened = true;
  return result;
}

}  // namespace floorgrid
