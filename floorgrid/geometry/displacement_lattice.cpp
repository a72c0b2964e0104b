#include "floorgrid/geometry/displacement_lattice.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cassert>
#include <cmath>

namespace floorgrid {

DisplacementLattice::DisplacementLattice(const Eigen::AlignedBox2d& box, double spacing)
    : origin_(box.min()), spacing_(spacing) {
  assert(spacing > 0.0 && !box.isEmpty());
  columns_ = std::max(2, static_cast<int>(std::ceil(box.sizes().x() / spacing)) + 1);
  rows_ = std::max(2, static_cast<int>(std::ceil(box.sizes().y() / spacing)) + 1);
  nodes_.assign(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_),
                Eigen::Vector2d::Zero());
}

void DisplacementLattice::corners(const Eigen::Vector2d& point, int index[4],
                                  double weight[4]) const {
  const double fx = std::clamp((point.x() - origin_.x()) / spacing_, 0.0, columns_ - 1.0);
  const double fy = std::clamp((point.y() - origin_.y()) / spacing_, 0.0, rows_ - 1.0);
  const int ix = std::min(static_cast<int>(fx), columns_ - 2);
  const int iy = std::min(static_cast<int>(fy), rows_ - 2);
  const double tx = fx - ix, ty = fy - iy;
  index[0] = iy * columns_ + ix;
  index[1] = index[0] + 1;
  index[2] = index[0] + columns_;
  index[3] = index[2] + 1;
  weight[0] = (1 - tx) * (1 - ty);
  weight[1] = tx * (1 - ty);
  weight[2] = (1 - tx) * ty;
  weight[3] = tx * ty;
}

Eigen::Vector2d DisplacementLattice::at(const Eigen::Vector2d& point) const {
  int index[4];
  double weight[4];
  corners(point, index, weight);
  Eigen::Vector2d d = Eigen::Vector2d::Zero();
  for (int k = 0; k < 4; ++k)
    d += weight[k] * nodes_[static_cast<std::size_t>(index[k])];
  return d;
}

bool DisplacementLattice::fit(const std::vector<LatticeConstraint>& constraints, double stiffness) {
  const auto n = static_cast<Eigen::Index>(nodes_.size());
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(constraints.size() * 64 + static_cast<std::size_t>(n) * 12);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * n);
  double total_weight = 0.0;
  for (const LatticeConstraint& c : constraints) {
    if (!(c.weight > 0.0))
      continue;
    total_weight += c.weight;
    int index[4];
    double weight[4];
    corners(c.point, index, weight);
    // The row's coefficients: unknown 2 i + a carries weight[k] * normal[a].
    Eigen::Index columns[8];
    double values[8];
    for (int k = 0; k < 4; ++k) {
      for (int a = 0; a < 2; ++a) {
        columns[2 * k + a] = 2 * index[k] + a;
        values[2 * k + a] = weight[k] * c.normal[a];
      }
    }
    for (int r = 0; r < 8; ++r) {
      rhs[columns[r]] += c.weight * values[r] * c.offset;
      for (int s = 0; s < 8; ++s)
        triplets.emplace_back(columns[r], columns[s], c.weight * values[r] * values[s]);
    }
  }
  if (total_weight <= 0.0)
    return false;
  const double lambda = stiffness * total_weight / double(n);
  const auto edge = [&](Eigen::Index a, Eigen::Index b) {
    for (int d = 0; d < 2; ++d) {
      triplets.emplace_back(2 * a + d, 2 * a + d, lambda);
      triplets.emplace_back(2 * b + d, 2 * b + d, lambda);
      triplets.emplace_back(2 * a + d, 2 * b + d, -lambda);
      triplets.emplace_back(2 * b + d, 2 * a + d, -lambda);
    }
  };
  for (int iy = 0; iy < rows_; ++iy) {
    for (int ix = 0; ix < columns_; ++ix) {
      const Eigen::Index i = iy * columns_ + ix;
      if (ix + 1 < columns_)
        edge(i, i + 1);
      if (iy + 1 < rows_)
        edge(i, i + columns_);
    }
  }
  const double ridge = 1e-6 * std::max(lambda, total_weight / double(n));
  for (Eigen::Index i = 0; i < 2 * n; ++i)
    triplets.emplace_back(i, i, ridge);
  Eigen::SparseMatrix<double> normal(2 * n, 2 * n);
  normal.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success)
    return false;
  const Eigen::VectorXd u = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !u.allFinite())
    return false;
  for (Eigen::Index i = 0; i < n; ++i)
    nodes_[static_cast<std::size_t>(i)] = u.segment<2>(2 * i);
  return true;
}

}  // namespace floorgrid
