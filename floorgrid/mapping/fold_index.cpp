#include "floorgrid/mapping/fold_index.hpp"

#include <algorithm>
#include <cmath>

#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid {

PlanLattice PlanLattice::over(const Eigen::AlignedBox2d& box, double margin, double min_spacing,
                              std::size_t max_nodes) {
  PlanLattice lattice;
  const Eigen::Vector2d lo = box.min() - Eigen::Vector2d::Constant(margin);
  const Eigen::Vector2d size = box.sizes() + Eigen::Vector2d::Constant(2.0 * margin);
  lattice.spacing = std::max(
      {min_spacing, std::sqrt(size.x() * size.y() / static_cast<double>(max_nodes)), 1e-9});
  lattice.origin = lo;
  lattice.columns = static_cast<int>(std::ceil(size.x() / lattice.spacing)) + 1;
  lattice.rows = static_cast<int>(std::ceil(size.y() / lattice.spacing)) + 1;
  return lattice;
}

Eigen::Matrix2Xd PlanLattice::nodes() const {
  Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(columns) * rows);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c)
      out.col(static_cast<Eigen::Index>(r) * columns + c) = node(c, r);
  }
  return out;
}

std::vector<Eigen::Vector2d> distinct_points(const std::vector<Eigen::Vector2d>& points,
                                             double tolerance) {
  std::vector<Eigen::Vector2d> out;
  for (const Eigen::Vector2d& p : points) {
    if (std::none_of(out.begin(), out.end(),
                     [&](const Eigen::Vector2d& q) { return (p - q).norm() <= tolerance; }))
      out.push_back(p);
  }
  return out;
}

GridBoxIndex::GridBoxIndex(std::vector<Eigen::AlignedBox2d> boxes) {
  for (auto& b : boxes) {
    if (!b.isEmpty() && b.min().allFinite() && b.max().allFinite())
      boxes_.push_back(b);
  }
  if (boxes_.empty())
    return;
  Eigen::AlignedBox2d all;
  double size_sum = 0.0;
  for (const auto& b : boxes_) {
    all.extend(b);
    size_sum += b.sizes().maxCoeff();
  }
  // Buckets about as wide as the average box, at most a million of them.
  cell_ = std::max(size_sum / static_cast<double>(boxes_.size()), 1e-9);
  const double area_cells = (all.sizes().x() / cell_ + 1.0) * (all.sizes().y() / cell_ + 1.0);
  if (area_cells > 1e6)
    cell_ *= std::sqrt(area_cells / 1e6);
  origin_ = all.min();
  columns_ = static_cast<int>(all.sizes().x() / cell_) + 1;
  rows_ = static_cast<int>(all.sizes().y() / cell_) + 1;
  buckets_.assign(static_cast<std::size_t>(columns_) * rows_, {});
  for (std::size_t i = 0; i < boxes_.size(); ++i) {
    const Eigen::Vector2d lo = (boxes_[i].min() - origin_) / cell_;
    const Eigen::Vector2d hi = (boxes_[i].max() - origin_) / cell_;
    for (int y = std::max(0, static_cast<int>(lo.y()));
         y <= std::min(rows_ - 1, static_cast<int>(hi.y())); ++y) {
      for (int x = std::max(0, static_cast<int>(lo.x()));
           x <= std::min(columns_ - 1, static_cast<int>(hi.x())); ++x)
        buckets_[static_cast<std::size_t>(y) * columns_ + x].push_back(static_cast<int>(i));
    }
  }
}

const std::vector<int>* GridBoxIndex::bucket_of(const Eigen::Vector2d& point) const {
  if (buckets_.empty() || !point.allFinite())
    return nullptr;
  const Eigen::Vector2d c = (point - origin_) / cell_;
  if (!(c.x() >= 0.0 && c.y() >= 0.0 && c.x() < columns_ && c.y() < rows_))
    return nullptr;
  return &buckets_[static_cast<std::size_t>(c.y()) * columns_ + static_cast<std::size_t>(c.x())];
}

void GridBoxIndex::holding(const Eigen::Vector2d& point, std::vector<int>& out) const {
  if (const std::vector<int>* bucket = bucket_of(point)) {
    for (const int i : *bucket) {
      if (boxes_[static_cast<std::size_t>(i)].contains(point))
        out.push_back(i);
    }
  }
}

bool GridBoxIndex::any_holds(const Eigen::Vector2d& point) const {
  const std::vector<int>* bucket = bucket_of(point);
  return bucket && std::any_of(bucket->begin(), bucket->end(), [&](int i) {
           return boxes_[static_cast<std::size_t>(i)].contains(point);
         });
}

FoldIndex::FoldIndex(const PointMapping& mapping, const PlanLattice& lattice, double orientation) {
  const Eigen::Matrix2Xd grid = mapping.forward_batch(lattice.nodes());
  const auto at = [&](int c, int r) -> Eigen::Vector2d {
    return grid.col(static_cast<Eigen::Index>(r) * lattice.columns + c);
  };
  const auto turns = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                         const Eigen::Vector2d& c) {
    const Eigen::Vector2d ab = b - a, ac = c - a;
    return !(orientation * (ab.x() * ac.y() - ab.y() * ac.x()) > 0.0);
  };
  const int columns = lattice.columns - 1, rows = lattice.rows - 1;
  if (columns <= 0 || rows <= 0)
    return;
  std::vector<bool> folded(static_cast<std::size_t>(columns) * rows, false);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      const Eigen::Vector2d p00 = at(c, r), p10 = at(c + 1, r), p01 = at(c, r + 1),
                            p11 = at(c + 1, r + 1);
      if (turns(p00, p10, p11) || turns(p00, p11, p01)) {
        folded[static_cast<std::size_t>(r) * columns + c] = true;
        ++folded_cells_;
      }
    }
  }
  if (folded_cells_ == 0)
    return;
  std::vector<Eigen::AlignedBox2d> boxes;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      bool near_fold = false;
      for (int dr = -1; dr <= 1 && !near_fold; ++dr) {
        for (int dc = -1; dc <= 1 && !near_fold; ++dc) {
          const int cc = c + dc, rr = r + dr;
          near_fold = cc >= 0 && rr >= 0 && cc < columns && rr < rows &&
                      folded[static_cast<std::size_t>(rr) * columns + cc];
        }
      }
      if (!near_fold)
        continue;
      Eigen::AlignedBox2d box;
      for (const Eigen::Vector2d& p : {at(c, r), at(c + 1, r), at(c, r + 1), at(c + 1, r + 1)})
        box.extend(p);
      // Inside a fold the cell's image may bulge past its corners: grow by a cell's image.
      const Eigen::Vector2d grow = Eigen::Vector2d::Constant(box.sizes().maxCoeff());
      boxes.emplace_back(box.min() - grow, box.max() + grow);
    }
  }
  boxes_ = GridBoxIndex(std::move(boxes));
}

}  // namespace floorgrid
