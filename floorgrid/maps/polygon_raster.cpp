#include "floorgrid/maps/polygon_raster.hpp"

#include <algorithm>
#include <cmath>

namespace floorgrid {

CellMask::CellMask(const GridGeometry& g) : geometry(g), cells(g.size(), 0) {}

std::size_t CellMask::count() const {
  return static_cast<std::size_t>(std::count(cells.begin(), cells.end(), std::uint8_t{1}));
}

CellMask rasterize_rings(const std::vector<Eigen::Matrix2Xd>& rings, const GridGeometry& geometry) {
  CellMask mask(geometry);
  // Edges in continuous cell coordinates: cell (ix, iy) has its centre at (ix + 0.5, iy + 0.5).
  struct Edge {
    double x0, y0, x1, y1;
  };
  std::vector<Edge> edges;
  double ymin = INFINITY, ymax = -INFINITY;
  for (const Eigen::Matrix2Xd& ring : rings) {
    const Eigen::Index n = ring.cols();
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector2d a = geometry.to_cell_coordinates(ring.col(i));
      const Eigen::Vector2d b = geometry.to_cell_coordinates(ring.col((i + 1) % n));
      if (!a.allFinite() || !b.allFinite() || a.y() == b.y())
        continue;  // horizontal edges never cross a scanline's half-open rule
      edges.push_back({a.x(), a.y(), b.x(), b.y()});
      ymin = std::min({ymin, a.y(), b.y()});
      ymax = std::max({ymax, a.y(), b.y()});
    }
  }
  if (edges.empty())
    return mask;
  const int row_begin = std::max(0, static_cast<int>(std::floor(ymin - 0.5)));
  const int row_end = std::min(geometry.height - 1, static_cast<int>(std::ceil(ymax - 0.5)));
  std::vector<double> xs;
  for (int iy = row_begin; iy <= row_end; ++iy) {
    const double y = iy + 0.5;
    xs.clear();
    for (const Edge& e : edges) {
      // Half-open in y: an edge counts for y in [min, max), so a vertex on the scanline is
      // counted once by the two edges meeting there (even-odd stays right).
      const bool crosses = (e.y0 <= y && y < e.y1) || (e.y1 <= y && y < e.y0);
      if (crosses)
        xs.push_back(e.x0 + (y - e.y0) / (e.y1 - e.y0) * (e.x1 - e.x0));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      // Cells whose centre ix + 0.5 lies in [xs[k], xs[k+1]).
      const int first = std::max(0, static_cast<int>(std::ceil(xs[k] - 0.5)));
      const int last =
          std::min(geometry.width - 1, static_cast<int>(std::ceil(xs[k + 1] - 0.5)) - 1);
      std::uint8_t* row = mask.cells.data() + static_cast<std::size_t>(iy) * geometry.width;
      for (int ix = first; ix <= last; ++ix)
        row[ix] ^= 1;  // even-odd: overlapping spans of separate rings cancel
    }
  }
  return mask;
}

std::size_t stamp_disks(CellMask& mask, const Eigen::Matrix2Xd& points,
                        const Eigen::VectorXd& radii) {
  const GridGeometry& g = mask.geometry;
  std::size_t added = 0;
  for (Eigen::Index i = 0; i < points.cols(); ++i) {
    const double r = radii(i);
    if (!(r > 0.0) || !std::isfinite(r) || !points.col(i).allFinite())
      continue;
    const Eigen::Vector2d c = g.to_cell_coordinates(points.col(i));
    const double rc = r / g.resolution;  // radius in cells
    const double rc2 = rc * rc;
    const int y0 = std::max(0, static_cast<int>(std::floor(c.y() - rc - 0.5)));
    const int y1 = std::min(g.height - 1, static_cast<int>(std::ceil(c.y() + rc - 0.5)));
    for (int iy = y0; iy <= y1; ++iy) {
      const double dy = iy + 0.5 - c.y();
      const double h2 = rc2 - dy * dy;
      if (h2 < 0.0)
        continue;
      const double h = std::sqrt(h2);
      const int x0 = std::max(0, static_cast<int>(std::ceil(c.x() - h - 0.5)));
      const int x1 = std::min(g.width - 1, static_cast<int>(std::floor(c.x() + h - 0.5)));
      std::uint8_t* row = mask.cells.data() + static_cast<std::size_t>(iy) * g.width;
      for (int ix = x0; ix <= x1; ++ix) {
        added += row[ix] == 0;
        row[ix] = 1;
      }
    }
  }
  return added;
}

double intersection_over_union(const CellMask& a, const CellMask& b) {
  std::size_t both = 0, either = 0;
  const std::size_t n = std::min(a.cells.size(), b.cells.size());
  for (std::size_t i = 0; i < n; ++i) {
    both += a.cells[i] && b.cells[i];
    either += a.cells[i] || b.cells[i];
  }
  return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
}

}  // namespace floorgrid
