#include "floorgrid/mapping/piecewise_affine.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/predicates.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid {

PiecewiseAffineMapping::PiecewiseAffineMapping(MappingCommonOptions common)
    : PointMapping(std::move(common)) {}

PiecewiseAffineMapping::~PiecewiseAffineMapping() = default;

void PiecewiseAffineMapping::build(const ReferencePairs& pairs) {
  pairs_ = pairs;
  DelaunayOptions options;
  options.seed = common().seed;
  triangulation_ = std::make_unique<DelaunayTriangulation>(pairs_.points_in_plan, options);
  if (triangulation_->degenerate()) {
    throw InputError(triangulation_->message(), {}, 0, "pairs");
  }
  const auto& triangles = triangulation_->triangles();
  const auto& G = pairs_.points_in_grid;
  // A grid triangle is folded when its orientation disagrees with the map's overall one.
  const double orientation =
      support_similarity().topLeftCorner<2, 2>().determinant() >= 0 ? 1.0 : -1.0;
  folded_.assign(triangles.size(), false);
  Eigen::AlignedBox2d box;
  double size_sum = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& v = triangles[t];
    folded_[t] = orientation * orient2d(G.col(v[0]), G.col(v[1]), G.col(v[2])) <= 0.0;
    for (const int i : v)
      box.extend(G.col(i));
    size_sum += (G.col(v[1]) - G.col(v[0])).norm();
  }
  // Buckets about two triangles wide over the grid side.
  bucket_size_ = std::max(2.0 * size_sum / static_cast<double>(triangles.size()),
                          1e-9 * box.diagonal().norm() + 1e-12);
  bucket_origin_ = box.min();
  bucket_width_ = std::max(1, static_cast<int>(std::ceil(box.sizes().x() / bucket_size_)) + 1);
  bucket_height_ = std::max(1, static_cast<int>(std::ceil(box.sizes().y() / bucket_size_)) + 1);
  const long cells = static_cast<long>(bucket_width_) * bucket_height_;
  if (cells > 4'000'000) {  // spread-out folds: coarser buckets
    const double factor = std::sqrt(static_cast<double>(cells) / 4e6);
    bucket_size_ *= factor;
    bucket_width_ = std::max(1, static_cast<int>(std::ceil(box.sizes().x() / bucket_size_)) + 1);
    bucket_height_ = std::max(1, static_cast<int>(std::ceil(box.sizes().y() / bucket_size_)) + 1);
  }
  buckets_.assign(static_cast<std::size_t>(bucket_width_) * bucket_height_, {});
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    Eigen::AlignedBox2d tb;
    for (const int i : triangles[t])
      tb.extend(G.col(i));
    const Eigen::Vector2d lo = (tb.min() - bucket_origin_) / bucket_size_;
    const Eigen::Vector2d hi = (tb.max() - bucket_origin_) / bucket_size_;
    for (int y = std::max(0, static_cast<int>(lo.y()));
         y <= std::min(bucket_height_ - 1, static_cast<int>(hi.y())); ++y) {
      for (int x = std::max(0, static_cast<int>(lo.x()));
           x <= std::min(bucket_width_ - 1, static_cast<int>(hi.x())); ++x) {
        buckets_[static_cast<std::size_t>(y) * bucket_width_ + x].push_back(static_cast<int>(t));
      }
    }
  }
}

void PiecewiseAffineMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  build(pairs);
  summary.rms_m = 0.0;  // the map passes through every pair it was built on
  summary.details = {{"triangles", triangulation_->triangles().size()},
                     {"hull_vertices", triangulation_->hull().size()},
                     {"folded_triangles", folded_triangles()},
                     {"predicates", "exact (adaptive floating point, expansion arithmetic)"}};
  if (folded_triangles() > 0) {
    summary.warnings.push_back(std::to_string(folded_triangles()) +
                               " triangles fold over on the grid: points there are not invertible");
  }
}

std::size_t PiecewiseAffineMapping::folded_triangles() const {
  return static_cast<std::size_t>(std::count(folded_.begin(), folded_.end(), true));
}

Eigen::Vector2d PiecewiseAffineMapping::map_in(int t, const Eigen::Vector3d& b) const {
  const auto& v = triangulation_->triangles()[static_cast<std::size_t>(t)];
  const auto& G = pairs_.points_in_grid;
  return b[0] * G.col(v[0]) + b[1] * G.col(v[1]) + b[2] * G.col(v[2]);  // eq. 4.23
}

Eigen::Vector2d PiecewiseAffineMapping::map_located(
    const Eigen::Vector2d& p, const DelaunayTriangulation::Located& located) const {
  if (located.inside || located.hull_edge < 0 || located.triangle < 0)
    return map_in(located.triangle, located.barycentric);
  const std::vector<int>& hull = triangulation_->hull();
  const auto e = static_cast<std::size_t>(located.hull_edge);
  const int a = hull[e], b = hull[(e + 1) % hull.size()];
  const auto& P = pairs_.points_in_plan;
  const auto& G = pairs_.points_in_grid;
  const Eigen::Vector2d ab = P.col(b) - P.col(a);
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - P.col(a)).dot(ab) / length2, 0.0, 1.0) : 0.0;
  const Eigen::Vector2d nearest = P.col(a) + t * ab;
  const Eigen::Vector2d nearest_in_grid = (1.0 - t) * G.col(a) + t * G.col(b);
  return nearest_in_grid + support_similarity().topLeftCorner<2, 2>() * (p - nearest);
}

Eigen::Vector2d PiecewiseAffineMapping::forward(const Eigen::Vector2d& p) const {
  return map_located(p, triangulation_->locate(p));
}

Eigen::Matrix2Xd PiecewiseAffineMapping::forward_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& points) const {
  const auto located = triangulation_->locate_all(points);
  Eigen::Matrix2Xd out(2, points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    out.col(i) = map_located(points.col(i), located[static_cast<std::size_t>(i)]);
  return out;
}

Eigen::Matrix2d PiecewiseAffineMapping::jacobian(const Eigen::Vector2d& p) const {
  const auto located = triangulation_->locate(p);
  if (!located.inside && located.hull_edge >= 0)
    return support_similarity().topLeftCorner<2, 2>();
  const int t = located.triangle;
  const auto& v = triangulation_->triangles()[static_cast<std::size_t>(t)];
  const auto& P = pairs_.points_in_plan;
  const auto& G = pairs_.points_in_grid;
  Eigen::Matrix2d R, S;
  R << P.col(v[1]) - P.col(v[0]), P.col(v[2]) - P.col(v[0]);
  S << G.col(v[1]) - G.col(v[0]), G.col(v[2]) - G.col(v[0]);
  return S * R.inverse();
}

InverseMapping PiecewiseAffineMapping::inverse(const Eigen::Vector2d& g) const {
  const Eigen::Vector2d c = (g - bucket_origin_) / bucket_size_;
  const int x = static_cast<int>(std::floor(c.x())), y = static_cast<int>(std::floor(c.y()));
  if (x >= 0 && y >= 0 && x < bucket_width_ && y < bucket_height_) {
    const auto& G = pairs_.points_in_grid;
    const auto& P = pairs_.points_in_plan;
    InverseMapping best;
    bool found_folded = false;
    for (const int t : buckets_[static_cast<std::size_t>(y) * bucket_width_ + x]) {
      const auto& v = triangulation_->triangles()[static_cast<std::size_t>(t)];
      Eigen::Matrix2d S;
      S << G.col(v[1]) - G.col(v[0]), G.col(v[2]) - G.col(v[0]);
      if (!(std::abs(S.determinant()) > 0.0))
        continue;
      const Eigen::Vector2d w = S.inverse() * (g - G.col(v[0]));
      const double tolerance = 1e-12;
      if (w.minCoeff() < -tolerance || w.sum() > 1.0 + tolerance)
        continue;
      if (folded_[static_cast<std::size_t>(t)]) {
        found_folded = true;
        continue;
      }
      best.point =
          P.col(v[0]) + w.x() * (P.col(v[1]) - P.col(v[0])) + w.y() * (P.col(v[2]) - P.col(v[0]));
      best.invertible = true;
      best.residual = (forward(best.point) - g).norm();
      if (!found_folded)
        return best;
    }
    // A point covered by a folded triangle has more than one preimage: not invertible.
    if (found_folded)
      return InverseMapping{best.point, false, 0, best.residual};
    if (best.invertible)
      return best;
  }
  // Outside the grid mesh: the extrapolating hull triangles, inverted by Newton iterations.
  return PointMapping::inverse(g);
}

Value PiecewiseAffineMapping::parameters() const {
  return {{"plan", model_fields::points(pairs_.points_in_plan)},
          {"grid", model_fields::points(pairs_.points_in_grid)},
          {"seed", common().seed},
          {"triangulation", "Delaunay of the plan points, rebuilt on load (deterministic)"}};
}

void PiecewiseAffineMapping::load_parameters(const Value& j, const std::string& where) {
  using namespace model_fields;
  ReferencePairs pairs;
  pairs.points_in_plan = points(member(j, "plan", where, "parameters."), where, "parameters.plan");
  pairs.points_in_grid = points(member(j, "grid", where, "parameters."), where, "parameters.grid");
  if (pairs.points_in_plan.cols() != pairs.points_in_grid.cols()) {
    throw InputError("plan and grid points differ in number", where, 0, "parameters");
  }
  try {
    build(pairs);
  } catch (const InputError& e) {
    throw InputError(e.message(), where, 0, "parameters.plan");
  }
}

}  // namespace floorgrid
