// lc's triangle as its rule says (thesis 4.1, SPEC's lc): among the nearest plan points, widened
// while none makes a well-shaped triangle (every angle at least 10 degrees), the first triangle
// by farthest vertex that holds the point, else the first well-shaped one. Checked against the
// rule tried triangle by triangle, on pairs in straight rows as the maps alone give them (many
// neighbours in a row exactly collinear), where lc passes over vertices that cannot serve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>
#include <optional>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid {
namespace {

/// The smallest angle of triangle abc, degrees.
double smallest_angle_deg(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                          const Eigen::Vector2d& c) {
  const auto angle = [](const Eigen::Vector2d& at, const Eigen::Vector2d& u,
                        const Eigen::Vector2d& v) {
    const Eigen::Vector2d x = u - at, y = v - at;
    return std::acos(std::clamp(x.dot(y) / (x.norm() * y.norm()), -1.0, 1.0));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)}) * 180.0 / std::numbers::pi;
}

/// Where the rule maps p: the affine map of the triangle it chooses (none: no well-shaped one).
std::optional<Eigen::Vector2d> by_the_rule(const Eigen::Matrix2Xd& P, const Eigen::Matrix2Xd& G,
                                           const Eigen::Vector2d& p) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(P.cols()));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](Eigen::Index x, Eigen::Index y) {
    return (P.col(x) - p).squaredNorm() < (P.col(y) - p).squaredNorm();
  });
  const auto map_by = [&](Eigen::Index a, Eigen::Index b, Eigen::Index c) {
    Eigen::Matrix2d R, S;
    R << P.col(b) - P.col(a), P.col(c) - P.col(a);
    S << G.col(b) - G.col(a), G.col(c) - G.col(a);
    return Eigen::Vector2d(G.col(a) + S * R.inverse() * (p - P.col(a)));
  };
  for (std::size_t k = 12;; k *= 2) {
    const std::size_t n = std::min(k, order.size());
    std::optional<Eigen::Vector2d> first;
    for (std::size_t l = 2; l < n; ++l) {
      for (std::size_t i = 0; i < l; ++i) {
        for (std::size_t j = i + 1; j < l; ++j) {
          const Eigen::Index a = order[i], b = order[j], c = order[l];
          if (smallest_angle_deg(P.col(a), P.col(b), P.col(c)) < 10.0)
            continue;
          Eigen::Matrix2d R;
          R << P.col(b) - P.col(a), P.col(c) - P.col(a);
          const Eigen::Vector2d w = R.inverse() * (p - P.col(a));
          if (w.minCoeff() >= 0.0 && w.sum() <= 1.0)
            return map_by(a, b, c);
          if (!first)
            first = map_by(a, b, c);
        }
      }
    }
    if (first || n < k || k >= 256)
      return first;
  }
}

/// Whether p's 12 nearest plan points lie on one of the walls y = 0, y = 6 or x = 0.
bool twelve_nearest_on_one_line(const Eigen::Matrix2Xd& P, const Eigen::Vector2d& p) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(P.cols()));
  std::iota(order.begin(), order.end(), 0);
  std::partial_sort(order.begin(), order.begin() + 12, order.end(),
                    [&](Eigen::Index x, Eigen::Index y) {
                      return (P.col(x) - p).squaredNorm() < (P.col(y) - p).squaredNorm();
                    });
  const auto all = [&](int axis, double value) {
    return std::all_of(order.begin(), order.begin() + 12,
                       [&](Eigen::Index i) { return P(axis, i) == value; });
  };
  return all(1, 0.0) || all(1, 6.0) || all(0, 0.0);
}

/// An lc model fitted to pairs at these plan points (the grid side bent and noisy, so that every
/// triangle maps differently), as a file of an earlier build loads it: without cells, every
/// point chooses its own triangle. With the plan and grid points it kept.
struct PointwiseLc {
  std::unique_ptr<PointMapping> model;
  Eigen::Matrix2Xd plan, grid;
};

PointwiseLc pointwise_lc(const std::vector<Eigen::Vector2d>& plan, Random& r) {
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, static_cast<Eigen::Index>(plan.size()));
  pairs.points_in_grid.resize(2, pairs.points_in_plan.cols());
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const Eigen::Vector2d& q = plan[i];
    pairs.points_in_plan.col(static_cast<Eigen::Index>(i)) = q;
    pairs.points_in_grid.col(static_cast<Eigen::Index>(i)) =
        Eigen::Vector2d(1.02 * q.x() + 0.3 * std::sin(q.y()), 0.98 * q.y() + 0.01 * q.x() * q.x()) +
        Eigen::Vector2d(r.normal(0.05), r.normal(0.05));
  }
  MappingOptions options;
  options.model = "lc";
  const auto fitted = make_mapping(options);
  fitted->fit(pairs);
  Value file = fitted->to_model_file();
  Value without_cells = Value::object();
  for (const auto& [key, value] : file["parameters"].members()) {
    if (key != "cell_m")
      without_cells[key] = value;
  }
  file["parameters"] = without_cells;
  PointwiseLc lc{load_mapping(file, "test"),
                 model_fields::points(without_cells["plan"], "test", "plan"),
                 model_fields::points(without_cells["grid"], "test", "grid")};
  EXPECT_EQ(lc.plan.cols(), static_cast<Eigen::Index>(plan.size()));  // none merged or binned
  return lc;
}

TEST(LinearCombination, ChoosesTheRulesTriangleAmongPairsInStraightRows) {
  // Two long walls 6 m apart and one across their end, points at random along them but exactly
  // on them, and a few points elsewhere.
  Random r(7);
  std::vector<Eigen::Vector2d> plan;
  for (int i = 0; i < 150; ++i)
    plan.emplace_back(r.uniform(0.0, 20.0), 0.0);
  for (int i = 0; i < 100; ++i)
    plan.emplace_back(r.uniform(0.0, 20.0), 6.0);
  for (int i = 0; i < 30; ++i)
    plan.emplace_back(0.0, r.uniform(0.5, 5.5));
  for (const Eigen::Vector2d& q :
       {Eigen::Vector2d(10.3, 2.9), Eigen::Vector2d(26.0, 11.0), Eigen::Vector2d(-4.0, 12.5)})
    plan.push_back(q);
  const PointwiseLc lc = pointwise_lc(plan, r);

  int compared = 0, widened = 0;
  for (int i = 0; i < 600; ++i) {
    // Inside the walls, beside them and beyond every pair.
    const Eigen::Vector2d p(r.uniform(-6.0, 30.0), r.uniform(-5.0, 15.0));
    const std::optional<Eigen::Vector2d> expected = by_the_rule(lc.plan, lc.grid, p);
    if (!expected)
      continue;
    EXPECT_LT((lc.model->forward(p) - *expected).norm(), 1e-9) << p.transpose();
    ++compared;
    // Points whose nearest 12 pairs lie on one wall: the search had to widen.
    widened += twelve_nearest_on_one_line(lc.plan, p);
  }
  EXPECT_GT(compared, 550);
  EXPECT_GT(widened, 20);
}

TEST(LinearCombination, FindsAThinTriangleJustAboveTheSmallestAngle) {
  // A row of 11 points 1 m long and one apex 3 m off its middle: the only well-shaped
  // triangles have an angle of 18.9 degrees at the apex, and the points of the row, seen from
  // it, lie within that angle.
  Random r(8);
  std::vector<Eigen::Vector2d> plan;
  for (int i = 0; i <= 10; ++i)
    plan.emplace_back(0.1 * i, 0.0);
  plan.emplace_back(0.5, 3.0);
  const PointwiseLc lc = pointwise_lc(plan, r);
  for (const Eigen::Vector2d& p :
       {Eigen::Vector2d(0.5, 0.3), Eigen::Vector2d(0.3, 0.5), Eigen::Vector2d(0.6, 2.0),
        Eigen::Vector2d(0.5, -0.5), Eigen::Vector2d(3.0, 1.0)}) {
    const std::optional<Eigen::Vector2d> expected = by_the_rule(lc.plan, lc.grid, p);
    ASSERT_TRUE(expected.has_value()) << p.transpose();
    EXPECT_LT((lc.model->forward(p) - *expected).norm(), 1e-9) << p.transpose();
  }
}

}  // namespace
}  // namespace floorgrid
