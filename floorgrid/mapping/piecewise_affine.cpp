#include "floorgrid/mapping/piecewise_affine.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/predicates.hpp"
#include "floorgrid/mapping/fold_index.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid {

PiecewiseAffineMapping::PiecewiseAffineMapping(MappingCommonOptions common, bool untangle)
    : PointMapping(std::move(common)), untangle_(untangle) {}

PiecewiseAffineMapping::~PiecewiseAffineMapping() = default;

namespace {

/// Each vertex's neighbours along the triangles' edges.
std::vector<std::vector<int>> vertex_neighbours(const std::vector<std::array<int, 3>>& triangles,
                                                std::size_t vertices) {
  std::vector<std::vector<int>> out(vertices);
  for (const auto& v : triangles) {
    for (int k = 0; k < 3; ++k) {
      out[static_cast<std::size_t>(v[k])].push_back(v[(k + 1) % 3]);
      out[static_cast<std::size_t>(v[k])].push_back(v[(k + 2) % 3]);
    }
  }
  for (auto& n : out) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return out;
}

/// The outward unit normal of the counter-clockwise hull edge from a to b.
Eigen::Vector2d outward_normal(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  return Eigen::Vector2d(d.y(), -d.x()) / d.norm();
}

}  // namespace

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
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& v = triangles[t];
    folded_[t] = orientation * orient2d(G.col(v[0]), G.col(v[1]), G.col(v[2])) <= 0.0;
  }
}

void PiecewiseAffineMapping::index_grid_triangles() {
  const auto& G = pairs_.points_in_grid;
  std::vector<Eigen::AlignedBox2d> boxes;
  for (const auto& v : triangulation_->triangles()) {
    Eigen::AlignedBox2d box;
    for (const int i : v)
      box.extend(Eigen::Vector2d(G.col(i)));
    boxes.push_back(box);
  }
  grid_triangles_ = GridBoxIndex(std::move(boxes));
}

bool PiecewiseAffineMapping::hull_edge_folds(std::size_t k) const {
  const std::vector<int>& hull = triangulation_->hull();
  const int a = hull[k], b = hull[(k + 1) % hull.size()];
  const auto& P = pairs_.points_in_plan;
  const auto& G = pairs_.points_in_grid;
  const Eigen::Matrix2d A = support_similarity().topLeftCorner<2, 2>();
  const double orientation = A.determinant() >= 0 ? 1.0 : -1.0;
  Eigen::Matrix2d strip;
  strip << G.col(b) - G.col(a), A * outward_normal(P.col(a), P.col(b));
  // In the plan, the edge turns clockwise onto its outward normal (determinant < 0).
  return !(orientation * strip.determinant() < 0.0);
}

ReferencePairs PiecewiseAffineMapping::untangle(const ReferencePairs& given) {
  ReferencePairs kept = given;
  const std::size_t limit = untangle_ ? static_cast<std::size_t>(given.size()) / 4 : 0;
  std::size_t dropped = 0;
  const Eigen::Matrix3d S = support_similarity();
  for (int round = 0; round < 100; ++round) {
    build(kept);
    const auto& P = kept.points_in_plan;
    const auto& G = kept.points_in_grid;
    const auto n = static_cast<std::size_t>(kept.size());
    // Where a pair disagrees with its neighbours: the Laplacian of the displacement from the
    // similarity (a smooth warp has almost none; a noisy pair stands out).
    const Eigen::Matrix2Xd u =
        G - ((S.topLeftCorner<2, 2>() * P).colwise() + Eigen::Vector2d(S.topRightCorner<2, 1>()));
    const auto neighbours = vertex_neighbours(triangulation_->triangles(), n);
    std::vector<double> disagreement(n, 0.0);
    for (std::size_t v = 0; v < n; ++v) {
      if (neighbours[v].empty())
        continue;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const int w : neighbours[v])
        mean += u.col(w);
      disagreement[v] =
          (u.col(static_cast<Eigen::Index>(v)) - mean / static_cast<double>(neighbours[v].size()))
              .norm();
    }
    // The corners of every fold: folded triangles and folded hull strips.
    std::vector<std::vector<int>> folds;
    const auto& triangles = triangulation_->triangles();
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if (folded_[t])
        folds.push_back({triangles[t][0], triangles[t][1], triangles[t][2]});
    }
    const std::vector<int>& hull = triangulation_->hull();
    for (std::size_t k = 0; k < hull.size(); ++k) {
      if (hull_edge_folds(k))
        folds.push_back({hull[k], hull[(k + 1) % hull.size()]});
    }
    if (folds.empty())
      break;
    // Worst first; one corner per fold, none twice, none beside one already dropped this round.
    std::vector<std::pair<double, int>> worst;
    for (const auto& corners : folds) {
      int pick = corners.front();
      for (const int v : corners) {
        if (disagreement[static_cast<std::size_t>(v)] >
            disagreement[static_cast<std::size_t>(pick)])
          pick = v;
      }
      worst.emplace_back(disagreement[static_cast<std::size_t>(pick)], pick);
    }
    std::sort(worst.begin(), worst.end(), std::greater<>());
    std::vector<bool> drop(n, false), touched(n, false);
    std::size_t dropping = 0;
    for (const auto& [score, v] : worst) {
      if (touched[static_cast<std::size_t>(v)] || dropped + dropping >= limit)
        continue;
      drop[static_cast<std::size_t>(v)] = true;
      touched[static_cast<std::size_t>(v)] = true;
      for (const int w : neighbours[static_cast<std::size_t>(v)])
        touched[static_cast<std::size_t>(w)] = true;
      ++dropping;
    }
    if (dropping == 0 || n - dropping < 3)
      break;  // the limit: keep the rest folded (the inverse says where)
    std::vector<Eigen::Index> keep;
    for (std::size_t v = 0; v < n; ++v) {
      if (!drop[v])
        keep.push_back(static_cast<Eigen::Index>(v));
    }
    ReferencePairs next = select_pairs(kept, keep);
    if (DelaunayTriangulation(next.points_in_plan).degenerate())
      break;
    kept = std::move(next);
    dropped += dropping;
  }
  untangled_ = dropped;
  if (pairs_.size() != kept.size())
    build(kept);  // the last round dropped pairs and ran out of rounds
  return kept;
}

void PiecewiseAffineMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  untangle(pairs);
  index_grid_triangles();
  summary.pairs_used = static_cast<std::size_t>(pairs_.size());
  // The map passes through every pair it kept; the dropped ones are off by their disagreement.
  const Eigen::Matrix2Xd residuals = forward_batch(pairs.points_in_plan) - pairs.points_in_grid;
  summary.rms_m = std::sqrt(residuals.colwise().squaredNorm().mean());
  summary.details = {{"triangles", triangulation_->triangles().size()},
                     {"hull_vertices", triangulation_->hull().size()},
                     {"folded_triangles", folded_triangles()},
                     {"untangled_pairs", untangled_},
                     {"predicates", "exact (adaptive floating point, expansion arithmetic)"}};
  if (untangled_ > 0) {
    summary.warnings.push_back(std::to_string(untangled_) +
                               " pairs dropped where the map folded over (each disagreed most "
                               "with its neighbours)");
  }
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

void PiecewiseAffineMapping::outside_preimages(const Eigen::Vector2d& g,
                                               std::vector<Eigen::Vector2d>& out) const {
  const std::vector<int>& hull = triangulation_->hull();
  const auto& P = pairs_.points_in_plan;
  const auto& G = pairs_.points_in_grid;
  const Eigen::Matrix2d A = support_similarity().topLeftCorner<2, 2>();
  const Eigen::Matrix2d A_inverse = A.inverse();
  const double slack = 1e-12, metres_slack = 1e-12 * extent();
  const std::size_t h = hull.size();
  for (std::size_t k = 0; k < h; ++k) {
    const int a = hull[k], b = hull[(k + 1) % h], before = hull[(k + h - 1) % h];
    const Eigen::Vector2d normal = outward_normal(P.col(a), P.col(b));
    // The strip beside edge k: g = G_a + t (G_b - G_a) + s A normal, 0 <= t <= 1, s >= 0.
    Eigen::Matrix2d strip;
    strip << G.col(b) - G.col(a), A * normal;
    if (std::abs(strip.determinant()) > 0.0) {
      const Eigen::Vector2d ts = strip.inverse() * (g - G.col(a));
      if (ts.x() >= -slack && ts.x() <= 1.0 + slack && ts.y() >= -metres_slack)
        out.push_back(P.col(a) + ts.x() * (P.col(b) - P.col(a)) + ts.y() * normal);
    }
    // The wedge at corner a, between the normals of the edges before and after it:
    // g = G_a + A d, d = alpha n_before + beta n_after, alpha, beta >= 0.
    Eigen::Matrix2d wedge;
    wedge << outward_normal(P.col(before), P.col(a)), normal;
    if (std::abs(wedge.determinant()) > 1e-12) {
      const Eigen::Vector2d d = A_inverse * (g - G.col(a));
      const Eigen::Vector2d ab = wedge.inverse() * d;
      if (ab.minCoeff() >= -metres_slack)
        out.push_back(P.col(a) + d);
    }
  }
}

InverseMapping PiecewiseAffineMapping::inverse(const Eigen::Vector2d& g) const {
  // Every plan point that maps to g: inside the hull (the grid triangles holding g), outside it
  // (the strips and wedges holding g). Invertible only when there is exactly one.
  std::vector<Eigen::Vector2d> found;
  bool on_fold = false;
  const auto& G = pairs_.points_in_grid;
  const auto& P = pairs_.points_in_plan;
  std::vector<int> candidates;
  grid_triangles_.holding(g, candidates);
  for (const int t : candidates) {
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
      on_fold = true;  // a flipped triangle covers g: g has more than one plan point
      continue;
    }
    found.push_back(P.col(v[0]) + w.x() * (P.col(v[1]) - P.col(v[0])) +
                    w.y() * (P.col(v[2]) - P.col(v[0])));
  }
  outside_preimages(g, found);
  // Points found twice (on an edge two triangles share, or on the hull) count once.
  const std::vector<Eigen::Vector2d> distinct = distinct_points(found, 1e-9 * extent());
  if (distinct.empty() && !on_fold)
    return PointMapping::inverse(g);  // not reached by exact arithmetic; rounding at a seam
  InverseMapping result;
  result.point = distinct.empty() ? Eigen::Vector2d(g) : distinct.front();
  result.invertible = !on_fold && distinct.size() == 1;
  result.residual = (forward(result.point) - g).norm();
  return result;
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
    index_grid_triangles();
  } catch (const InputError& e) {
    throw InputError(e.message(), where, 0, "parameters.plan");
  }
}

}  // namespace floorgrid
