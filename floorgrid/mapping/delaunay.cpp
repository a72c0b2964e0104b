#include "floorgrid/mapping/delaunay.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/hilbert_curve.hpp"
#include "floorgrid/geometry/predicates.hpp"
#include "floorgrid/mapping/bowyer_watson.hpp"

namespace floorgrid {
namespace {

// Rounds of the insertion order smaller than this are merged into the first round.
constexpr int kSmallestRound = 64;

// Biased randomized insertion order (Amenta, Choi and Rote 2003): shuffle, then rounds of
// doubling size (the last round holds half the points), each sorted along a Hilbert curve.
// Randomness between rounds bounds the expected work; the Hilbert order within a round keeps
// each walk short.
std::vector<int> brio_order(const std::vector<std::uint64_t>& keys, std::uint64_t seed) {
  const int n = static_cast<int>(keys.size());
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  Random random(seed);
  for (int i = n - 1; i > 0; --i)
    std::swap(order[static_cast<std::size_t>(i)],
              order[static_cast<std::size_t>(random.integer(0, i))]);
  int end = n;
  while (end > kSmallestRound) {
    const int begin = end / 2;
    sort_by_hilbert_key(order.begin() + begin, order.begin() + end, keys);
    end = begin;
  }
  sort_by_hilbert_key(order.begin(), order.begin() + end, keys);
  return order;
}

bool same_point(const Eigen::Matrix2Xd& points, int i, int j) {
  return points(0, i) == points(0, j) && points(1, i) == points(1, j);
}

}  // namespace

DelaunayTriangulation::DelaunayTriangulation(const Eigen::Matrix2Xd& points,
                                             const DelaunayOptions& options)
    : points_(points) {
  for (Eigen::Index i = 0; i < points_.cols(); ++i) {
    if (!std::isfinite(points_(0, i)) || !std::isfinite(points_(1, i))) {
      std::ostringstream message;
      message << "point " << i << " is not finite (" << points_(0, i) << ", " << points_(1, i)
              << ")";
      throw InputError(message.str(), {}, 0, "points");
    }
  }
  build(options);
}

void DelaunayTriangulation::mark_degenerate() {
  // Duplicates by sorting: each group of equal points maps to its lowest index.
  const int n = static_cast<int>(points_.cols());
  std::vector<int> sorted(static_cast<std::size_t>(n));
  std::iota(sorted.begin(), sorted.end(), 0);
  std::sort(sorted.begin(), sorted.end(), [this](int i, int j) {
    if (points_(0, i) != points_(0, j))
      return points_(0, i) < points_(0, j);
    if (points_(1, i) != points_(1, j))
      return points_(1, i) < points_(1, j);
    return i < j;
  });
  duplicate_of_.resize(static_cast<std::size_t>(n));
  duplicate_count_ = 0;
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    const int i = sorted[k];
    if (k > 0 && same_point(points_, i, sorted[k - 1])) {
      duplicate_of_[static_cast<std::size_t>(i)] =
          duplicate_of_[static_cast<std::size_t>(sorted[k - 1])];
      ++duplicate_count_;
    } else {
      duplicate_of_[static_cast<std::size_t>(i)] = i;
    }
  }
  const int distinct = vertex_count();
  std::ostringstream message;
  if (distinct < 3) {
    status_ = DelaunayStatus::too_few_points;
    message << "needs at least 3 distinct points, got " << distinct;
    if (duplicate_count_ > 0)
      message << " (" << n << " points with " << duplicate_count_ << " duplicates)";
  } else {
    status_ = DelaunayStatus::collinear;
    message << "all " << distinct << " distinct points lie on one line";
  }
  message_ = message.str();
  triangles_.clear();
  neighbors_.clear();
  hull_.clear();
}

void DelaunayTriangulation::build(const DelaunayOptions& options) {
  const int n = static_cast<int>(points_.cols());
  const std::vector<std::uint64_t> keys = hilbert_keys(points_);
  const std::vector<int> order = brio_order(keys, options.seed);

  // The first triangle: the first point in the order, the next distinct one, and the next one
  // off their line. Points skipped on the way are inserted later like any other.
  int b_pos = -1, c_pos = -1;
  if (n > 0) {
    const int a = order[0];
    for (int k = 1; k < n && b_pos < 0; ++k) {
      if (!same_point(points_, a, order[static_cast<std::size_t>(k)]))
        b_pos = k;
    }
    for (int k = b_pos + 1; b_pos >= 0 && k < n && c_pos < 0; ++k) {
      if (orient2d(points_.col(a).data(),
                   points_.col(order[static_cast<std::size_t>(b_pos)]).data(),
                   points_.col(order[static_cast<std::size_t>(k)]).data()) != 0.0)
        c_pos = k;
    }
  }
  if (c_pos < 0) {
    mark_degenerate();
    return;
  }

  detail::BowyerWatson kernel(points_.data(), n);
  kernel.start(order[0], order[static_cast<std::size_t>(b_pos)],
               order[static_cast<std::size_t>(c_pos)]);
  std::vector<int> inserted_twin(static_cast<std::size_t>(n), -1);
  for (int k = 1; k < n; ++k) {
    if (k == b_pos || k == c_pos)
      continue;
    const int p = order[static_cast<std::size_t>(k)];
    inserted_twin[static_cast<std::size_t>(p)] = kernel.insert(p);
  }
  const std::vector<int> representative = record_duplicates(inserted_twin);
  adopt_triangles(kernel, keys, representative);
  build_walk_index();
  build_start_grid();
}

std::vector<int> DelaunayTriangulation::record_duplicates(const std::vector<int>& inserted_twin) {
  // Each group of equal points is represented by its lowest index, whichever came first.
  const int n = static_cast<int>(inserted_twin.size());
  std::vector<int> representative(static_cast<std::size_t>(n));
  std::iota(representative.begin(), representative.end(), 0);
  for (int p = 0; p < n; ++p) {
    const int twin = inserted_twin[static_cast<std::size_t>(p)];
    if (twin >= 0) {
      int& r = representative[static_cast<std::size_t>(twin)];
      r = std::min(r, p);
    }
  }
  duplicate_of_.assign(static_cast<std::size_t>(n), 0);
  duplicate_count_ = 0;
  for (int p = 0; p < n; ++p) {
    const int twin = inserted_twin[static_cast<std::size_t>(p)];
    const int vertex = twin >= 0 ? twin : p;
    duplicate_of_[static_cast<std::size_t>(p)] = representative[static_cast<std::size_t>(vertex)];
    if (duplicate_of_[static_cast<std::size_t>(p)] != p)
      ++duplicate_count_;
  }
  return representative;
}

void DelaunayTriangulation::adopt_triangles(const detail::BowyerWatson& kernel,
                                            const std::vector<std::uint64_t>& keys,
                                            const std::vector<int>& representative) {
  // Real triangles are numbered along the Hilbert curve (by their first vertex), so that walks
  // between nearby points touch nearby memory; ghosts become the hull.
  const int slots = kernel.slot_count();
  std::vector<int> real_slots;
  std::vector<std::uint64_t> slot_keys(static_cast<std::size_t>(slots), 0);
  for (int s = 0; s < slots; ++s) {
    if (!kernel.is_ghost(s)) {
      real_slots.push_back(s);
      slot_keys[static_cast<std::size_t>(s)] = keys[static_cast<std::size_t>(kernel.vertex(s, 0))];
    }
  }
  sort_by_hilbert_key(real_slots.begin(), real_slots.end(), slot_keys);
  std::vector<int> index_of_slot(static_cast<std::size_t>(slots), -1);
  const int real_count = static_cast<int>(real_slots.size());
  for (int t = 0; t < real_count; ++t)
    index_of_slot[static_cast<std::size_t>(real_slots[static_cast<std::size_t>(t)])] = t;
  triangles_.resize(static_cast<std::size_t>(real_count));
  neighbors_.resize(static_cast<std::size_t>(real_count));
  auto rep = [&](int v) { return representative[static_cast<std::size_t>(v)]; };
  const int n = static_cast<int>(points_.cols());
  std::vector<int> hull_next(static_cast<std::size_t>(n), -1);
  std::vector<int> edge_triangle(static_cast<std::size_t>(n), -1);
  std::vector<int> edge_local(static_cast<std::size_t>(n), -1);
  for (int s = 0; s < slots; ++s) {
    if (kernel.is_ghost(s)) {
      // Ghost (p, q, ghost) lies beyond the hull edge q -> p (counter-clockwise).
      const int p = rep(kernel.vertex(s, 0));
      const int q = rep(kernel.vertex(s, 1));
      const int inner = kernel.neighbor(s, 2);
      int k = 0;
      while (rep(kernel.vertex(inner, k)) == p || rep(kernel.vertex(inner, k)) == q)
        ++k;
      hull_next[static_cast<std::size_t>(q)] = p;
      edge_triangle[static_cast<std::size_t>(q)] = index_of_slot[static_cast<std::size_t>(inner)];
      edge_local[static_cast<std::size_t>(q)] = k;
      continue;
    }
    const int t = index_of_slot[static_cast<std::size_t>(s)];
    for (int k = 0; k < 3; ++k) {
      triangles_[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)] =
          rep(kernel.vertex(s, k));
      const int across = kernel.neighbor(s, k);
      neighbors_[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)] =
          index_of_slot[static_cast<std::size_t>(across)];
    }
  }

  int first = -1;
  for (int v = 0; v < n && first < 0; ++v) {
    if (hull_next[static_cast<std::size_t>(v)] >= 0)
      first = v;
  }
  hull_position_.assign(static_cast<std::size_t>(n), -1);
  hull_.clear();
  hull_triangle_.clear();
  hull_local_edge_.clear();
  int v = first;
  do {
    hull_position_[static_cast<std::size_t>(v)] = static_cast<int>(hull_.size());
    hull_.push_back(v);
    hull_triangle_.push_back(edge_triangle[static_cast<std::size_t>(v)]);
    hull_local_edge_.push_back(edge_local[static_cast<std::size_t>(v)]);
    v = hull_next[static_cast<std::size_t>(v)];
  } while (v != first);
}

void DelaunayTriangulation::build_walk_index() {
  // Vertices numbered in order of first use by the (curve-ordered) triangles.
  std::vector<int> local(static_cast<std::size_t>(points_.cols()), -1);
  walk_xy_.clear();
  walk_xy_.reserve(2 * static_cast<std::size_t>(vertex_count()));
  walk_triangles_.resize(triangles_.size());
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const int v = triangles_[t][k];
      int& id = local[static_cast<std::size_t>(v)];
      if (id < 0) {
        id = static_cast<int>(walk_xy_.size() / 2);
        walk_xy_.push_back(points_(0, v));
        walk_xy_.push_back(points_(1, v));
      }
      walk_triangles_[t][k] = id;
    }
  }
}

void DelaunayTriangulation::build_start_grid() {
  // A grid of about one cell per two vertices over the bounding box; each cell keeps a triangle
  // at one of its vertices, empty cells borrow from their neighbours along rows, then columns.
  const int n = static_cast<int>(points_.cols());
  std::vector<int> vertex_triangle(static_cast<std::size_t>(n), -1);
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    for (const int v : triangles_[t])
      vertex_triangle[static_cast<std::size_t>(v)] = static_cast<int>(t);
  }
  const Eigen::Vector2d lo = points_.rowwise().minCoeff();
  const Eigen::Vector2d hi = points_.rowwise().maxCoeff();
  const Eigen::Vector2d extent = hi - lo;
  const double target_cells = std::clamp(0.5 * vertex_count(), 1.0, 4194304.0);
  double cell = std::sqrt(extent.x() * extent.y() / target_cells);
  if (!(cell > 0.0))
    cell = std::max(extent.x(), extent.y()) / target_cells;
  grid_origin_ = lo;
  grid_cell_ = cell;
  grid_columns_ = std::clamp(static_cast<int>(extent.x() / cell) + 1, 1, 1 << 22);
  grid_rows_ = std::clamp(static_cast<int>(extent.y() / cell) + 1, 1, (1 << 22) / grid_columns_);
  grid_triangle_.assign(static_cast<std::size_t>(grid_columns_) * grid_rows_, -1);
  for (int v = 0; v < n; ++v) {
    if (vertex_triangle[static_cast<std::size_t>(v)] < 0)
      continue;
    int& slot = grid_triangle_[static_cast<std::size_t>(start_cell(points_.col(v)))];
    if (slot < 0)
      slot = vertex_triangle[static_cast<std::size_t>(v)];
  }
  auto cell_at = [this](int column, int row) -> int& {
    return grid_triangle_[static_cast<std::size_t>(row) * grid_columns_ + column];
  };
  for (int row = 0; row < grid_rows_; ++row) {
    for (int column = 1; column < grid_columns_; ++column) {
      if (cell_at(column, row) < 0)
        cell_at(column, row) = cell_at(column - 1, row);
    }
    for (int column = grid_columns_ - 2; column >= 0; --column) {
      if (cell_at(column, row) < 0)
        cell_at(column, row) = cell_at(column + 1, row);
    }
  }
  for (int column = 0; column < grid_columns_; ++column) {
    for (int row = 1; row < grid_rows_; ++row) {
      if (cell_at(column, row) < 0)
        cell_at(column, row) = cell_at(column, row - 1);
    }
    for (int row = grid_rows_ - 2; row >= 0; --row) {
      if (cell_at(column, row) < 0)
        cell_at(column, row) = cell_at(column, row + 1);
    }
  }
}

int DelaunayTriangulation::start_cell(const Eigen::Vector2d& point) const {
  const double fx = (point.x() - grid_origin_.x()) / grid_cell_;
  const double fy = (point.y() - grid_origin_.y()) / grid_cell_;
  const int column = static_cast<int>(std::clamp(fx, 0.0, grid_columns_ - 1.0));
  const int row = static_cast<int>(std::clamp(fy, 0.0, grid_rows_ - 1.0));
  return row * grid_columns_ + column;
}

}  // namespace floorgrid
