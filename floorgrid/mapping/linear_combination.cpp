#include "floorgrid/mapping/linear_combination.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
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
  set_min_angle(options_.min_angle_deg);
}

void LinearCombinationMapping::set_min_angle(double degrees) {
  options_.min_angle_deg = degrees;
  min_sin_angle_ = std::sin(degrees * std::numbers::pi / 180.0);
  // 0.999: rounding never skips a farthest vertex that has a well-shaped triangle.
  half_sin2_ = 0.999 * std::pow(std::sin(degrees * std::numbers::pi / 360.0), 2);
}

void LinearCombinationMapping::prepare(const ReferencePairs& pairs, double cell_m) {
  pairs_ = pairs;
  plan_index_ = PointIndex2D(pairs_.points_in_plan);
  build_cells(cell_m);
}

void LinearCombinationMapping::fit_model(const ReferencePairs& pairs, FitSummary& summary) {
  prepare(pairs, 0.0);
  summary.rms_m = 0.0;  // an interpolating model: every used pair maps exactly
  summary.details = {{"neighbours", options_.neighbours},
                     {"min_angle_deg", options_.min_angle_deg},
                     {"cell_m", cells_.spacing},
                     {"cells", cell_piece_.size()},
                     {"triangles", pieces_.size()}};
}

namespace {

/// The index of the first column of `points` equal to an earlier one, or -1.
Eigen::Index first_repeated_point(const Eigen::Matrix2Xd& points) {
  std::vector<std::pair<std::pair<double, double>, Eigen::Index>> sorted;
  sorted.reserve(static_cast<std::size_t>(points.cols()));
  for (Eigen::Index i = 0; i < points.cols(); ++i)
    sorted.push_back({{points(0, i), points(1, i)}, i});
  std::sort(sorted.begin(), sorted.end());
  Eigen::Index first = -1;
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i].first == sorted[i - 1].first &&
        (first < 0 || std::max(sorted[i].second, sorted[i - 1].second) < first))
      first = std::max(sorted[i].second, sorted[i - 1].second);
  }
  return first;
}

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

/// Whether some of the first `count` neighbours, seen from c, lie off the line from c to the
/// first by at least the angle whose squared sine is `half_sin2` (half the smallest angle a
/// triangle may have). If none does, no two of them make that smallest angle at c, and no
/// triangle with c as its farthest vertex is well-shaped.
bool seen_apart(const Eigen::Matrix2Xd& P, const std::vector<PointIndex2D::Neighbour>& near,
                std::size_t count, const Eigen::Vector2d& c, double half_sin2) {
  const Eigen::Vector2d u = Eigen::Vector2d(P.col(near[0].index)) - c;
  const double uu = u.squaredNorm();
  for (std::size_t i = 1; i < count; ++i) {
    const Eigen::Vector2d v = Eigen::Vector2d(P.col(near[i].index)) - c;
    const double cross = u.x() * v.y() - u.y() * v.x();
    if (cross * cross >= half_sin2 * uu * v.squaredNorm())
      return true;
  }
  return false;
}

/// The directions from a point to others, as the narrowest arc holding them all. Until it spans
/// half a turn, the others lie on one side of a line through the point, and no triangle of them
/// holds it.
class DirectionArc {
 public:
  explicit DirectionArc(const Eigen::Vector2d& centre) : centre_(centre) {}

  void add(const Eigen::Vector2d& q) {
    if (surrounded_)
      return;
    const Eigen::Vector2d d = q - centre_;
    if (d.x() == 0.0 && d.y() == 0.0) {
      surrounded_ = true;  // a vertex at the point: a triangle of it holds the point
      return;
    }
    constexpr double kTurn = 2.0 * std::numbers::pi;
    const double theta = std::atan2(d.y(), d.x());
    if (empty_) {
      start_ = theta;
      empty_ = false;
      return;
    }
    const double ahead = theta - start_ - kTurn * std::floor((theta - start_) / kTurn);
    if (ahead <= width_)
      return;
    const double widened_ahead = ahead, widened_behind = width_ + kTurn - ahead;
    // Half a turn less a hair: a point on a triangle's edge counts as held, whatever rounding.
    if (std::min(widened_ahead, widened_behind) >= std::numbers::pi - 1e-9) {
      surrounded_ = true;
    } else if (widened_ahead <= widened_behind) {
      width_ = widened_ahead;
    } else {
      start_ = theta;
      width_ = widened_behind;
    }
  }

  /// Whether the directions span half a turn (the point may lie in a triangle of the others).
  bool surrounded() const { return surrounded_; }

 private:
  Eigen::Vector2d centre_;
  double start_ = 0.0;  ///< radians, where the arc starts; it runs counterclockwise
  double width_ = 0.0;  ///< radians
  bool empty_ = true;
  bool surrounded_ = false;
};
}  // namespace

LinearCombinationMapping::Triangle LinearCombinationMapping::choose(
    const Eigen::Vector2d& p) const {
  const auto& P = pairs_.points_in_plan;
  for (std::size_t k = static_cast<std::size_t>(options_.neighbours);; k *= 2) {
    const auto near = plan_index_.nearest_k(p, k);
    // A triangle scores by its farthest vertex (the neighbours come nearest first): grow the
    // farthest vertex l and try every pair of nearer ones, so the first triangle that holds p
    // is the best one, usually among the first few neighbours. Pairs along one straight wall
    // widen the search to many neighbours, and trying every triangle of them cost their cube
    // per point: the vertices that cannot make a well-shaped triangle, or one holding p, are
    // passed over whole.
    Triangle nearest_not_holding;
    DirectionArc around(p);
    for (std::size_t l = 0; l < near.size(); ++l) {
      const Eigen::Vector2d c = P.col(near[l].index);
      around.add(c);
      const bool may_hold = around.surrounded();
      if (l < 2 || (nearest_not_holding.valid() && !may_hold) ||
          !seen_apart(P, near, l, c, half_sin2_))
        continue;
      bool next_vertex = false;
      for (std::size_t i = 0; i + 1 < l && !next_vertex; ++i) {
        const Eigen::Vector2d a = P.col(near[i].index);
        for (std::size_t j = i + 1; j < l && !next_vertex; ++j) {
          const Eigen::Vector2d b = P.col(near[j].index);
          if (!well_shaped(a, b, c, min_sin_angle_))
            continue;
          const Triangle t{near[i].index, near[j].index, near[l].index};
          if (may_hold) {
            Eigen::Matrix2d R;
            R << b - a, c - a;
            const Eigen::Vector2d w = R.inverse() * (p - a);
            if (w.minCoeff() >= 0.0 && w.sum() <= 1.0)
              return t;
          }
          if (!nearest_not_holding.valid())
            nearest_not_holding = t;
          next_vertex = !may_hold;  // no other triangle of these vertices holds p either
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
  if (!t.valid()) {
    A = support_similarity().topLeftCorner<2, 2>();
    offset = support_similarity().topRightCorner<2, 1>();
    return;
  }
  const auto& P = pairs_.points_in_plan;
  const auto& G = pairs_.points_in_grid;
  Eigen::Matrix2d R, S;
  R << P.col(t.b) - P.col(t.a), P.col(t.c) - P.col(t.a);
  S << G.col(t.b) - G.col(t.a), G.col(t.c) - G.col(t.a);
  // p = a + R w  and  q = s_a + S w, so q = S R^-1 (p - a) + s_a (eq. 4.2-4.9 in one basis).
  A = S * R.inverse();
  offset = G.col(t.a) - A * P.col(t.a);
}

namespace {

/// Cells by default: 50 per pair (a triangle's region spans about a pair spacing, so its cells
/// are about a seventh of that; each costs a neighbour search at fit time, a dense grid of them
/// tripled align's fit stage on a sparse log), 250,000 at most.
std::size_t default_cells(Eigen::Index pairs) {
  return std::min<std::size_t>(250'000, 50 * static_cast<std::size_t>(pairs));
}

}  // namespace

void LinearCombinationMapping::build_cells(double cell_m) {
  pieces_.clear();
  cell_piece_.clear();
  cells_ = PlanLattice{};
  cell_images_ = GridBoxIndex{};
  if (cell_m < 0.0)
    return;  // no cells: every point chooses its own triangle
  Eigen::AlignedBox2d box;
  for (Eigen::Index i = 0; i < pairs_.points_in_plan.cols(); ++i)
    box.extend(Eigen::Vector2d(pairs_.points_in_plan.col(i)));
  const double margin = common().extrapolation_distance;
  if (cell_m > 0.0 && ((box.sizes().x() + 2.0 * margin) / cell_m + 2.0) *
                              ((box.sizes().y() + 2.0 * margin) / cell_m + 2.0) >
                          4e6) {
    throw InputError("cells of " + std::to_string(cell_m) + " m over this box are more than 4e6",
                     {}, 0, "parameters.cell_m");
  }
  cells_ = cell_m > 0.0 ? PlanLattice::over(box, margin, cell_m, SIZE_MAX)
                        : PlanLattice::over(box, margin, 0.1, default_cells(pairs_.size()));
  const int columns = cells_.columns - 1, rows = cells_.rows - 1;
  const auto cells = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
  std::vector<Triangle> chosen(cells);
  parallel_chunks(cells, kBatchChunk, kDefaultThreads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const auto c = static_cast<int>(i % static_cast<std::size_t>(columns));
      const auto r = static_cast<int>(i / static_cast<std::size_t>(columns));
      chosen[i] = choose(cells_.node(c, r) + Eigen::Vector2d::Constant(cells_.spacing / 2.0));
    }
  });
  pieces_.clear();
  cell_piece_.assign(cells, 0);
  std::map<std::array<Eigen::Index, 3>, std::int32_t> piece_of;
  std::vector<Eigen::AlignedBox2d> images(cells);
  for (std::size_t i = 0; i < cells; ++i) {
    const Triangle& t = chosen[i];
    const auto [it, added] =
        piece_of.try_emplace({t.a, t.b, t.c}, static_cast<std::int32_t>(pieces_.size()));
    if (added) {
      Piece piece;
      affine(t, piece.A, piece.offset);
      pieces_.push_back(piece);
    }
    cell_piece_[i] = it->second;
    const Piece& piece = pieces_[static_cast<std::size_t>(it->second)];
    const auto c = static_cast<int>(i % static_cast<std::size_t>(columns));
    const auto r = static_cast<int>(i / static_cast<std::size_t>(columns));
    for (const auto& corner : {cells_.node(c, r), cells_.node(c + 1, r), cells_.node(c, r + 1),
                               cells_.node(c + 1, r + 1)})
      images[i].extend(Eigen::Vector2d(piece.A * corner + piece.offset));
  }
  cell_images_ = GridBoxIndex(std::move(images));
}

long LinearCombinationMapping::cell_of(const Eigen::Vector2d& p) const {
  if (cell_piece_.empty())
    return -1;
  const Eigen::Vector2d c = (p - cells_.origin) / cells_.spacing;
  const int columns = cells_.columns - 1, rows = cells_.rows - 1;
  if (!(c.x() >= 0.0 && c.y() >= 0.0 && c.x() < columns && c.y() < rows))
    return -1;
  return static_cast<long>(c.y()) * columns + static_cast<long>(c.x());
}

void LinearCombinationMapping::affine_at(const Eigen::Vector2d& p, Eigen::Matrix2d& A,
                                         Eigen::Vector2d& offset) const {
  if (cell_piece_.empty()) {
    affine(choose(p), A, offset);  // a file of an earlier build: the triangle chosen at p
    return;
  }
  const long cell = cell_of(p);
  if (cell < 0) {
    affine(Triangle{}, A, offset);  // beyond the cells: the similarity
    return;
  }
  const Piece& piece =
      pieces_[static_cast<std::size_t>(cell_piece_[static_cast<std::size_t>(cell)])];
  A = piece.A;
  offset = piece.offset;
}

Eigen::Vector2d LinearCombinationMapping::forward(const Eigen::Vector2d& p) const {
  Eigen::Matrix2d A;
  Eigen::Vector2d offset;
  affine_at(p, A, offset);
  return A * p + offset;
}

Eigen::Matrix2d LinearCombinationMapping::jacobian(const Eigen::Vector2d& p) const {
  Eigen::Matrix2d A;
  Eigen::Vector2d offset;
  affine_at(p, A, offset);
  return A;
}

InverseMapping LinearCombinationMapping::inverse(const Eigen::Vector2d& g) const {
  // Every plan point of g, then invertible only when there is one.
  std::vector<Eigen::Vector2d> found;
  // Inside the lattice: each cell whose image's box holds g and whose map takes g back into it.
  std::vector<int> candidates;
  cell_images_.holding(g, candidates);
  for (const int cell : candidates) {
    const Piece& piece =
        pieces_[static_cast<std::size_t>(cell_piece_[static_cast<std::size_t>(cell)])];
    if (!(std::abs(piece.A.determinant()) > 0.0))
      continue;
    const Eigen::Vector2d y = piece.A.inverse() * (g - piece.offset);
    if (cell_of(y) == cell)
      found.push_back(y);
  }
  // Beyond it: the similarity's inverse, if it lies beyond the cells.
  const Eigen::Matrix3d T = support_similarity().inverse();
  const Eigen::Vector2d start = T.topLeftCorner<2, 2>() * g + T.topRightCorner<2, 1>();
  if (!cell_piece_.empty() && cell_of(start) < 0)
    found.push_back(start);
  // A file of an earlier build (no cells): the fixed point of "the triangle chosen at x,
  // inverted at g", from the similarity's inverse.
  Eigen::Vector2d x = start;
  int iterations = 0;
  for (int k = 0; k < common().inverse_max_iterations && cell_piece_.empty(); ++k) {
    iterations = k + 1;
    const Triangle t = choose(x);
    Eigen::Matrix2d A;
    Eigen::Vector2d offset;
    affine(t, A, offset);
    if (!(std::abs(A.determinant()) > 0.0))
      break;
    const Eigen::Vector2d y = A.inverse() * (g - offset);
    if (choose(y) == t) {
      found.push_back(y);
      break;
    }
    if ((y - x).norm() < 1e-12 * extent())
      break;
    x = y;
  }
  const std::vector<Eigen::Vector2d> distinct = distinct_points(found, 1e-9 * extent());
  InverseMapping m;
  m.iterations = iterations;
  m.invertible = distinct.size() == 1;
  if (distinct.empty()) {
    m.point = x;
    m.residual = std::numeric_limits<double>::infinity();
    return m;
  }
  // With several, the one nearest the similarity's guess is reported, flagged not invertible.
  m.point = *std::min_element(distinct.begin(), distinct.end(),
                              [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
                                return (a - start).norm() < (b - start).norm();
                              });
  m.residual = (forward(m.point) - g).norm();
  return m;
}

Value LinearCombinationMapping::parameters() const {
  return {{"neighbours", options_.neighbours},
          {"min_angle_deg", options_.min_angle_deg},
          {"cell_m", cells_.spacing},
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
  set_min_angle(
      number(member(j, "min_angle_deg", where, p), where, p + "min_angle_deg", 1e-3, 60.0));
  ReferencePairs pairs;
  pairs.points_in_plan = points(member(j, "plan", where, p), where, p + "plan");
  pairs.points_in_grid = points(member(j, "grid", where, p), where, p + "grid");
  if (pairs.points_in_plan.cols() != pairs.points_in_grid.cols() || pairs.size() < 3) {
    throw InputError("plan and grid points differ in number or are fewer than 3", where, 0,
                     "parameters");
  }
  // A fitted model's points are distinct and not on one line (fit merges and refuses those);
  // a file's that are not would make every triangle search look through all of them in vain.
  if (const Eigen::Index repeated = first_repeated_point(pairs.points_in_plan); repeated >= 0) {
    throw InputError("point " + std::to_string(repeated + 1) +
                         " repeats an earlier one: a fitted lc model holds distinct points",
                     where, 0, p + "plan");
  }
  if (plan_points_collinear(pairs))
    throw InputError("all points lie on one line: lc needs triangles", where, 0, p + "plan");
  // Files of earlier builds have no cells: their points choose their own triangles, as then.
  const Value* cell = optional_member(j, "cell_m");
  const double cell_m = cell ? number(*cell, where, p + "cell_m", 1e-3, 1e3) : -1.0;
  try {
    prepare(pairs, cell_m);
  } catch (const InputError& e) {
    throw InputError(e.message(), where, 0, p + "cell_m");
  }
}

}  // namespace floorgrid
