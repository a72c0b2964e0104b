#include "floorgrid/geometry/point_index.hpp"

#include <cmath>
#include <nanoflann.hpp>

namespace floorgrid {

namespace {
/// nanoflann's view of the columns of a Matrix2Xd.
struct ColumnsAdaptor {
  const Eigen::Matrix2Xd* points;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(points->cols()); }
  double kdtree_get_pt(std::size_t i, std::size_t d) const {
    return (*points)(static_cast<Eigen::Index>(d), static_cast<Eigen::Index>(i));
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, ColumnsAdaptor>,
                                        ColumnsAdaptor, 2, std::size_t>;
}  // namespace

struct PointIndex2D::Tree {
  explicit Tree(const Eigen::Matrix2Xd* points)
      : adaptor{points}, tree(2, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
  ColumnsAdaptor adaptor;
  KdTree tree;
};

PointIndex2D::PointIndex2D() = default;
PointIndex2D::~PointIndex2D() = default;

PointIndex2D::PointIndex2D(const Eigen::Matrix2Xd& points) : points_(points) {
  if (points_.cols() > 0)
    tree_ = std::make_unique<Tree>(&points_);
}

PointIndex2D::PointIndex2D(const PointIndex2D& other) : PointIndex2D(other.points_) {}

PointIndex2D& PointIndex2D::operator=(const PointIndex2D& other) {
  if (this != &other)
    *this = PointIndex2D(other.points_);
  return *this;
}

// The tree points into points_, whose heap storage survives the move of the matrix.
PointIndex2D::PointIndex2D(PointIndex2D&& other) noexcept
    : points_(std::move(other.points_)), tree_(std::move(other.tree_)) {
  if (tree_)
    tree_->adaptor.points = &points_;
}

PointIndex2D& PointIndex2D::operator=(PointIndex2D&& other) noexcept {
  points_ = std::move(other.points_);
  tree_ = std::move(other.tree_);
  if (tree_)
    tree_->adaptor.points = &points_;
  return *this;
}

PointIndex2D::Neighbour PointIndex2D::nearest(const Eigen::Vector2d& query) const {
  const auto k = nearest_k(query, 1);
  return k.empty() ? Neighbour{} : k.front();
}

std::vector<PointIndex2D::Neighbour> PointIndex2D::nearest_k(const Eigen::Vector2d& query,
                                                             std::size_t k) const {
  std::vector<Neighbour> out;
  if (!tree_ || k == 0)
    return out;
  std::vector<std::size_t> indices(k);
  std::vector<double> squared(k);
  const double q[2] = {query.x(), query.y()};
  const std::size_t found = tree_->tree.knnSearch(q, k, indices.data(), squared.data());
  for (std::size_t i = 0; i < found; ++i) {
    out.push_back({static_cast<Eigen::Index>(indices[i]), std::sqrt(squared[i])});
  }
  return out;
}

std::vector<PointIndex2D::Neighbour> PointIndex2D::within(const Eigen::Vector2d& query,
                                                          double radius) const {
  std::vector<Neighbour> out;
  if (!tree_)
    return out;
  std::vector<std::pair<std::size_t, double>> matches;
  const double q[2] = {query.x(), query.y()};
  nanoflann::SearchParams params;
  params.sorted = true;
  tree_->tree.radiusSearch(q, radius * radius, matches, params);
  for (const auto& [i, d2] : matches)
    out.push_back({static_cast<Eigen::Index>(i), std::sqrt(d2)});
  return out;
}

}  // namespace floorgrid
