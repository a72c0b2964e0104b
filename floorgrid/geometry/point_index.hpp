#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace floorgrid {

/// Nearest-neighbour queries over a fixed set of 2D points (a k-d tree, nanoflann).
class PointIndex2D {
 public:
  /// An empty index.
  PointIndex2D();
  /// Indexes the columns of `points` (copied).
  explicit PointIndex2D(const Eigen::Matrix2Xd& points);
  ~PointIndex2D();
  PointIndex2D(PointIndex2D&&) noexcept;
  PointIndex2D& operator=(PointIndex2D&&) noexcept;
  PointIndex2D(const PointIndex2D& other);
  PointIndex2D& operator=(const PointIndex2D& other);

  /// The points indexed.
  const Eigen::Matrix2Xd& points() const { return points_; }
  /// Number of points.
  Eigen::Index size() const { return points_.cols(); }

  /// One neighbour: its column and distance (metres).
  struct Neighbour {
    Eigen::Index index = -1;  ///< column of the point, -1 when the index is empty
    double distance = 0.0;    ///< metres
  };
  /// The nearest point to `query`.
  Neighbour nearest(const Eigen::Vector2d& query) const;
  /// The `k` nearest points, nearest first (fewer when the index holds fewer).
  std::vector<Neighbour> nearest_k(const Eigen::Vector2d& query, std::size_t k) const;
  /// All points within `radius` metres, nearest first.
  std::vector<Neighbour> within(const Eigen::Vector2d& query, double radius) const;

 private:
  struct Tree;
  Eigen::Matrix2Xd points_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace floorgrid
