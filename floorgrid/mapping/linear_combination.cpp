#include "floorgrid/mapping/linear_combination.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/parallel.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid {

LinearCombinationMapping::LinearCombinationMapping(MappingCommonOptions common,
                                                   LinearCombinationOptions options)
    : PointMapping(std::move(common)), options_(options) {
  if (options_.neighbours < 3 || options_.neighbours > kMaxNeighbours)
    throw InputError("must be in [3, " + std::to_string(kMaxNeighbours) + "]", {}, 0,
                     "lc.neighbours");
  if (!(options_.min_angle_deg > 0.0 && options_.min_angle_deg < 60.0)) {
    throw InputError("must be in (0, 60) degrees", {}, 0, "lc.min_angle_deg");
  }
  min_sin_angle_ = std::sin(options_.min_angle_deg * std::numbers::pi / 180.0);
}

void LinearCombinationMapping::prepare(const ReferencePairs& pairs) {
  pairs_ = pairs;
  plan_index_ = PointIndex2D(pairs_.points_in_plan);
}

void LinearCombinationMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  prepare(pairs);
  summary.rms_m = 0.0;  // an interpolating model: every used pair maps exactly
  summary.details = {{"neighbours", options_.neighbours},
                     {"min_angle_deg", options_.min_angle_deg}};
}

namespace {

// Points per task of a batch: large enough that a task costs far more than handing it out.
constexpr std::size_t kBatchChunk = 4096;

/// Whether triangle abc has every angle's sine above `min_sin` (and is not degenerate).
bool well_shaped(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                 double min_sin) {
  const Eigen::Vector2d ab = b - a, ac = c - a, bc = c - b;
  const double twice_area = std::abs(ab.x() * ac.y() - ab.y() * ac.x());
  const double lab = ab.norm(), lac = ac.norm(), lbc = bc.norm();
  if (!(twice_area > 0.0))
    return false;
  // sin(angle at a) = 2 area / (|ab| |ac|), likewise at b and c.
  return twice_area >= min_sin * lab * lac && twice_area >= min_sin * lab * lbc &&
         twice_area >= min_sin * lac * lbc;
}
}  // namespace

LinearCombinationMapping::Triangle LinearCombinationMapping::choose(
    const Eigen::Vector2d& p) const {
  const auto& P = pairs_.points_in_plan;
  for (std::size_t k = static_cast<std::size_t>(options_.neighbours);; k *= 2) {
    const auto near = plan_index_.nearest_k(p, k);
    // A triangle scores by its farthest vertex (the neighbours come nearest first): grow the
    // farthest vertex l and try every pair of nearer ones, so the first triangle that holds p
    // is the best one, usually among the first few neighbours.
    Triangle nearest_not_holding;
    for (std::size_t l = 2; l < near.size(); ++l) {
      const Eigen::Vector2d c = P.col(near[l].index);
      for (std::size_t i = 0; i + 1 < l; ++i) {
        const Eigen::Vector2d a = P.col(near[i].index);
        for (std::size_t j = i + 1; j < l; ++j) {
          const Eigen::Vector2d b = P.col(near[j].index);
          if (!well_shaped(a, b, c, min_sin_angle_))
            continue;
          const Triangle t{near[i].index, near[j].index, near[l].index};
          Eigen::Matrix2d R;
          R << b - a, c - a;
          const Eigen::Vector2d w = R.inverse() * (p - a);
          if (w.minCoeff() >= 0.0 && w.sum() <= 1.0)
            return t;
          if (!nearest_not_holding.valid())
            nearest_not_holding = t;
        }
      }
    }
    // No triangle holds p (it lies outside the pairs): the nearest well-shaped one extrapolates.
    if (nearest_not_holding.valid() || near.size() < k || k >= 256)
      return nearest_not_holding;
  }
}

Eigen::Matrix2Xd LinearCombinationMapping::forward_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan) const {
  Eigen::Matrix2Xd out(2, points_in_plan.cols());
  parallel_chunks(static_cast<std::size_t>(points_in_plan.cols()), kBatchChunk, kDefaultThreads,
                  [&](std::size_t begin, std::size_t end) {
                    for (std::size_t i = begin; i < end; ++i) {
                      const auto c = static_cast<Eigen::Index>(i);
                      out.col(c) = forward(points_in_plan.col(c));
                    }
                  });
  return out;
}

void LinearCombinationMapping::affine(const Triangle& t, Eigen::Matrix2d& A,
                                      Eigen::Vector2d& offset) const {
  const auto& P = pairs_.points_in_plan;
  const auto& G = pairs_.points_in_grid;
  Eigen::Matrix2d R, S;
  R << P.col(t.b) - P.col(t.a), P.col(t.c) - P.col(t.a);
  S << G.col(t.b) - G.col(t.a), G.col(t.c) - G.col(t.a);
  // p = a + R w  and  q = s_a + S w, so q = S R^-1 (p - a) + s_a (eq. 4.2-4.9 in one basis).
  A = S * R.inverse();
  offset = G.col(t.a) - A * P.col(t.a);
}

Eigen::Vector2d LinearCombinationMapping::forward(const Eigen::Vector2d& p) const {
  const Triangle t = choose(p);
  if (!t.valid()) {
    const Eigen::Matrix3d& T = support_similarity();
    return T.topLeftCorner<2, 2>() * p + T.topRightCorner<2, 1>();
  }
  Eigen::Matrix2d A;
  Eigen::Vector2d offset;
  affine(t, A, offset);
  return A * p + offset;
}

Eigen::Matrix2d LinearCombinationMapping::jacobian(const Eigen::Vector2d& p) const {
  const Triangle t = choose(p);
  if (!t.valid())
    return support_similarity().topLeftCorner<2, 2>();
  Eigen::Matrix2d A;
  Eigen::Vector2d offset;
  affine(t, A, offset);
  return A;
}

InverseMapping LinearCombinationMapping::inverse(const Eigen::Vector2d& g) const {
  // A fixed point of "the triangle chosen at x, inverted at g": then forward(x) = g exactly.
  InverseMapping m;
  const Eigen::Matrix3d T = support_similarity().inverse();
  Eigen::Vector2d x = T.topLeftCorner<2, 2>() * g + T.topRightCorner<2, 1>();
  const auto solve_in = [&](const Triangle& t, Eigen::Vector2d& out) {
    Eigen::Matrix2d A;
    Eigen::Vector2d offset;
    affine(t, A, offset);
    if (!(std::abs(A.determinant()) > 0.0))
      return false;
    out = A.inverse() * (g - offset);
    return choose(out) == t;
  };
  for (int k = 0; k < common().inverse_max_iterations; ++k) {
    m.iterations = k + 1;
    const Triangle t = choose(x);
    if (!t.valid())
      break;
    Eigen::Vector2d y;
    if (solve_in(t, y)) {
      m.point = y;
      m.invertible = true;
      m.residual = (forward(y) - g).norm();
      return m;
    }
    if ((y - x).norm() < 1e-12 * extent())
      break;
    x = y;
  }
  // The iteration cycled between triangles: try those chosen near the start.
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Vector2d start = T.topLeftCorner<2, 2>() * g + T.topRightCorner<2, 1>();
  for (const auto& n : plan_index_.nearest_k(start, 16)) {
    const Triangle t = choose(pairs_.points_in_plan.col(n.index));
    Eigen::Vector2d y;
    if (t.valid() && solve_in(t, y) && (y - start).norm() < best) {
      best = (y - start).norm();
      m.point = y;
      m.invertible = true;
    }
  }
  m.residual =
      m.invertible ? (forward(m.point) - g).norm() : std::numeric_limits<double>::infinity();
  if (!m.invertible)
    m.point = x;
  return m;
}

Value LinearCombinationMapping::parameters() const {
  return {{"neighbours", options_.neighbours},
          {"min_angle_deg", options_.min_angle_deg},
          {"plan", model_fields::points(pairs_.points_in_plan)},
          {"grid", model_fields::points(pairs_.points_in_grid)}};
}

void LinearCombinationMapping::load_parameters(const Value& j, const std::string& where) {
  using namespace model_fields;
  const std::string p = "parameters.";
  // The neighbour search grows from this count: too few never finds a triangle, too many
  // costs its cube per mapped point.
  options_.neighbours = static_cast<int>(
      integer(member(j, "neighbours", where, p), where, p + "neighbours", 3, kMaxNeighbours));
  options_.min_angle_deg =
      number(member(j, "min_angle_deg", where, p), where, p + "min_angle_deg", 1e-3, 60.0);
  min_sin_angle_ = std::sin(options_.min_angle_deg * std::numbers::pi / 180.0);
  ReferencePairs pairs;
  pairs.points_in_plan = points(member(j, "plan", where, p), where, p + "plan");
  pairs.points_in_grid = points(member(j, "grid", where, p), where, p + "grid");
  if (pairs.points_in_plan.cols() != pairs.points_in_grid.cols() || pairs.size() < 3) {
    throw InputError("plan and grid points differ in number or are fewer than 3", where, 0,
                     "parameters");
  }
  prepare(pairs);
}

}  // namespace floorgrid
