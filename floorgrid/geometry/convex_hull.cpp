#include "floorgrid/geometry/convex_hull.hpp"

#include <algorithm>

namespace floorgrid {

namespace {
double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}
}  // namespace

std::vector<Eigen::Vector2d> convex_hull(const Eigen::Matrix2Xd& points) {
  std::vector<Eigen::Vector2d> p;
  p.reserve(static_cast<std::size_t>(points.cols()));
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    p.emplace_back(points.col(i));
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3)
    return p;
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (const auto& q : p) {  // lower hull
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], q) <= 0)
      --k;
    hull[k++] = q;
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0)
      --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
}

bool inside_convex_polygon(const std::vector<Eigen::Vector2d>& hull, const Eigen::Vector2d& point,
                           double tolerance) {
  if (hull.size() < 3)
    return false;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
    const double length = (b - a).norm();
    if (cross(a, b, point) < -tolerance * length)
      return false;
  }
  return true;
}

}  // namespace floorgrid
