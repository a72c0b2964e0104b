#include "floorgrid/mapping/thin_plate_spline_lattice.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/parallel.hpp"

namespace floorgrid {
namespace {

constexpr double kMaxNodes = 1e8;
constexpr int kPerNode = 8;
// The measurement's regular sample of cells, per axis.
constexpr Eigen::Index kSampleCells = 32;
// Test cells per task of the measurement (fixed: the result does not depend on the threads).
constexpr std::size_t kCellsPerTask = 64;

// Cubic Hermite basis on [0, 1] at s: values at 0 and 1 (v0, v1), unit slopes at 0 and 1
// (d0, d1), and, when kWithDerivative, their derivatives.
template <bool kWithDerivative>
struct Hermite {
  double v[2], d[2];    // basis functions
  double dv[2], dd[2];  // their derivatives

  explicit Hermite(double s) {
    const double s2 = s * s, s3 = s2 * s;
    v[0] = 2 * s3 - 3 * s2 + 1, v[1] = -2 * s3 + 3 * s2;
    d[0] = s3 - 2 * s2 + s, d[1] = s3 - s2;
    if constexpr (kWithDerivative) {
      dv[0] = 6 * s2 - 6 * s, dv[1] = -6 * s2 + 6 * s;
      dd[0] = 3 * s2 - 4 * s + 1, dd[1] = 3 * s2 - 2 * s;
    }
  }
};

// The four nodes of a cell, corner (a, b) at [2 b + a] (a, b in {0, 1}: left/right, bottom/top).
using Corners = std::array<const double*, 4>;

// The bicubic Hermite patch through `corners` at cell coordinates (s, t) in [0, 1]^2 (and,
// when kWithJacobian, its derivative in metres, for nodes `spacing` apart, in *jacobian).
// Inlined into the loops over many points, where it is most of the work.
template <bool kWithJacobian>
inline Eigen::Vector2d patch(const Corners& corners, double s, double t, double spacing,
                             Eigen::Matrix2d* jacobian) {
  const Hermite<kWithJacobian> hx(s), hy(t);
  Eigen::Vector2d value = Eigen::Vector2d::Zero();
  Eigen::Vector2d along_x = Eigen::Vector2d::Zero(), along_y = Eigen::Vector2d::Zero();
  for (int b = 0; b < 2; ++b) {
    for (int a = 0; a < 2; ++a) {
      const double* n = corners[static_cast<std::size_t>(2 * b + a)];
      const Eigen::Vector2d f(n[0], n[1]), fx(n[2], n[3]), fy(n[4], n[5]), fxy(n[6], n[7]);
      value += f * (hx.v[a] * hy.v[b]) + fx * (hx.d[a] * hy.v[b]) + fy * (hx.v[a] * hy.d[b]) +
               fxy * (hx.d[a] * hy.d[b]);
      if constexpr (kWithJacobian) {
        along_x += f * (hx.dv[a] * hy.v[b]) + fx * (hx.dd[a] * hy.v[b]) +
                   fy * (hx.dv[a] * hy.d[b]) + fxy * (hx.dd[a] * hy.d[b]);
        along_y += f * (hx.v[a] * hy.dv[b]) + fx * (hx.d[a] * hy.dv[b]) +
                   fy * (hx.v[a] * hy.dd[b]) + fxy * (hx.d[a] * hy.dd[b]);
      }
    }
  }
  if constexpr (kWithJacobian) {
    jacobian->col(0) = along_x / spacing;
    jacobian->col(1) = along_y / spacing;
  }
  return value;
}

// What a lattice stores at a node at `point_in_plan`, for nodes `spacing` apart.
void sample_node(const ThinPlateSpline& spline, const Eigen::Vector2d& point_in_plan,
                 double spacing, double* node) {
  const ThinPlateSplineDerivatives e = spline.derivatives(point_in_plan);
  const Eigen::Matrix2d& J = e.J_grid_plan;
  node[0] = e.value.x(), node[1] = e.value.y();
  node[2] = spacing * J(0, 0), node[3] = spacing * J(1, 0);
  node[4] = spacing * J(0, 1), node[5] = spacing * J(1, 1);
  node[6] = spacing * spacing * e.mixed.x(), node[7] = spacing * spacing * e.mixed.y();
}

// Where the nodes of a lattice lie: lo + spacing (i, j), i < columns, j < rows.
struct Layout {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero();
  double spacing = 0.0;
  Eigen::Index columns = 0, rows = 0;

  Layout(const Eigen::Vector2d& corner, const Eigen::Vector2d& extent, double h)
      : lo(corner), spacing(h) {
    columns = static_cast<Eigen::Index>(std::max(2.0, std::ceil(extent.x() / h) + 1.0));
    rows = static_cast<Eigen::Index>(std::max(2.0, std::ceil(extent.y() / h) + 1.0));
  }
  double nodes() const { return static_cast<double>(columns) * static_cast<double>(rows); }
  Eigen::Vector2d node(Eigen::Index i, Eigen::Index j) const {
    return lo + spacing * Eigen::Vector2d(static_cast<double>(i), static_cast<double>(j));
  }
  // The cell (clamped to the lattice) holding a point, as a linear index j (columns - 1) + i.
  Eigen::Index cell_of(const Eigen::Vector2d& point) const {
    const Eigen::Vector2d cell = (point - lo) / spacing;
    const auto i =
        std::clamp(static_cast<Eigen::Index>(std::floor(cell.x())), Eigen::Index{0}, columns - 2);
    const auto j =
        std::clamp(static_cast<Eigen::Index>(std::floor(cell.y())), Eigen::Index{0}, rows - 2);
    return j * (columns - 1) + i;
  }
};

// The largest |patch - spline| over the test points of a lattice laid out as `layout`, from
// nodes sampled for the test cells alone: the centre and edge midpoints of every cell holding
// a centre inside the lattice and of kSampleCells^2 cells spread over it, and every such
// centre.
double measure_error(const ThinPlateSpline& spline, const Layout& layout, int threads) {
  const Eigen::Matrix2Xd& centres = spline.data().centres_in_plan;
  const Eigen::AlignedBox2d box(layout.lo, layout.node(layout.columns - 1, layout.rows - 1));
  // (cell, centre) for the centres inside, then the sample cells (centre -1), by cell.
  std::vector<std::pair<Eigen::Index, Eigen::Index>> tests;
  for (Eigen::Index c = 0; c < centres.cols(); ++c) {
    if (box.contains(centres.col(c)))
      tests.emplace_back(layout.cell_of(centres.col(c)), c);
  }
  const Eigen::Index cell_columns = layout.columns - 1, cell_rows = layout.rows - 1;
  for (Eigen::Index b = 0; b < kSampleCells; ++b) {
    for (Eigen::Index a = 0; a < kSampleCells; ++a) {
      const Eigen::Index i = a * (cell_columns - 1) / (kSampleCells - 1);
      const Eigen::Index j = b * (cell_rows - 1) / (kSampleCells - 1);
      tests.emplace_back(j * cell_columns + i, -1);
    }
  }
  std::sort(tests.begin(), tests.end());
  tests.erase(std::unique(tests.begin(), tests.end()), tests.end());
  std::vector<std::size_t> starts;  // where each cell's tests begin in `tests`
  for (std::size_t k = 0; k < tests.size(); ++k) {
    if (k == 0 || tests[k].first != tests[k - 1].first)
      starts.push_back(k);
  }
  starts.push_back(tests.size());

  const std::size_t cells = starts.size() - 1;
  const std::size_t tasks = (cells + kCellsPerTask - 1) / kCellsPerTask;
  std::vector<double> worst(tasks, 0.0);
  parallel_tasks(tasks, threads, [&](std::size_t task) {
    std::array<std::array<double, kPerNode>, 4> nodes;
    const Corners corners = {nodes[0].data(), nodes[1].data(), nodes[2].data(), nodes[3].data()};
    for (std::size_t k = task * kCellsPerTask; k < std::min(cells, (task + 1) * kCellsPerTask);
         ++k) {
      const Eigen::Index cell = tests[starts[k]].first;
      const Eigen::Index i = cell % cell_columns, j = cell / cell_columns;
      for (int b = 0; b < 2; ++b) {
        for (int a = 0; a < 2; ++a) {
          sample_node(spline, layout.node(i + a, j + b), layout.spacing,
                      nodes[static_cast<std::size_t>(2 * b + a)].data());
        }
      }
      const auto measure_at = [&](double s, double t) {
        const Eigen::Vector2d p = layout.node(i, j) + layout.spacing * Eigen::Vector2d(s, t);
        const double error =
            (patch<false>(corners, s, t, layout.spacing, nullptr) - spline.evaluate(p)).norm();
        worst[task] = std::max(worst[task], error);
      };
      for (const auto& [s, t] :
           {std::pair{0.5, 0.5}, {0.5, 0.0}, {0.5, 1.0}, {0.0, 0.5}, {1.0, 0.5}}) {
        measure_at(s, t);
      }
      for (std::size_t m = starts[k]; m < starts[k + 1]; ++m) {
        if (tests[m].second < 0)
          continue;
        const Eigen::Vector2d st =
            (Eigen::Vector2d(centres.col(tests[m].second)) - layout.node(i, j)) / layout.spacing;
        measure_at(st.x(), st.y());
      }
    }
  });
  return worst.empty() ? 0.0 : *std::max_element(worst.begin(), worst.end());
}

[[noreturn]] void fail(const char* field, const std::string& what, double value) {
  std::ostringstream message;
  message << what << " (got " << value << ")";
  throw InputError(message.str(), {}, 0, std::string("tps_lattice.") + field);
}

}  // namespace

void validate(const ThinPlateSplineLatticeOptions& options) {
  if (!(options.spacing > 0.0) || !std::isfinite(options.spacing))
    fail("spacing", "must be finite and > 0 metres", options.spacing);
  if (!(options.margin >= 0.0) || !std::isfinite(options.margin))
    fail("margin", "must be finite and >= 0 metres", options.margin);
  if (options.threads < 1 || options.threads > 2)
    fail("threads", "must be 1 or 2", options.threads);
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    fail("tolerance", "must be finite and > 0 metres", options.tolerance);
  if (options.max_nodes < 4)
    fail("max_nodes", "must be >= 4", static_cast<double>(options.max_nodes));
}

ThinPlateSplineLattice::ThinPlateSplineLattice(ThinPlateSpline spline,
                                               const Eigen::AlignedBox2d& box_in_plan,
                                               const ThinPlateSplineLatticeOptions& options)
    : spline_(std::move(spline)) {
  validate(options);
  if (box_in_plan.isEmpty() || !box_in_plan.min().allFinite() || !box_in_plan.max().allFinite()) {
    throw InputError("must be a finite, non-empty box", {}, 0, "tps_lattice.box");
  }
  const Eigen::Vector2d lo = box_in_plan.min().array() - options.margin;
  const Eigen::Vector2d extent = box_in_plan.sizes().array() + 2.0 * options.margin;
  if (!(Layout(lo, extent, options.spacing).nodes() <= kMaxNodes)) {
    fail("spacing", "must give at most 1e8 nodes over the box", options.spacing);
  }

  // Halving the spacing divides the error near a centre by 4 (it grows as h^2 there) and by
  // 16 elsewhere: refine by the power of 2 the h^2 law asks for, at most 8.
  const double target = 0.5 * options.tolerance;
  double h = options.spacing;
  for (int attempt = 1;; ++attempt) {
    const Layout layout(lo, extent, h);
    if (layout.nodes() > static_cast<double>(options.max_nodes)) {
      std::ostringstream message;
      message << "no lattice: ";
      if (attempt == 1) {
        message << "the first spacing, " << h << " m, needs more than max_nodes ("
                << options.max_nodes << ") nodes";
      } else {
        message << "still " << measured_error_ << " m off at " << spacing_ << " m, and the next "
                << "spacing needs more than max_nodes (" << options.max_nodes << ") nodes";
      }
      message << "; the exact spline everywhere";
      message_ = message.str();
      measured_error_ = std::numeric_limits<double>::infinity();
      spacing_ = 0.0;
      attempts_ = attempt - 1;
      return;
    }
    spacing_ = h;
    attempts_ = attempt;
    measured_error_ = measure_error(spline_, layout, options.threads);
    if (measured_error_ <= target) {
      columns_ = layout.columns;
      rows_ = layout.rows;
      break;
    }
    const double steps = std::ceil(std::log2(std::sqrt(measured_error_ / target)));
    h /= std::exp2(std::clamp(steps, 1.0, 3.0));
  }
  const Layout layout(lo, extent, spacing_);
  box_ = Eigen::AlignedBox2d(lo, layout.node(columns_ - 1, rows_ - 1));
  nodes_.resize(static_cast<std::size_t>(kPerNode * columns_ * rows_));
  parallel_blocks(
      static_cast<std::size_t>(rows_), rows_ >= 4 ? options.threads : 1,
      [&](std::size_t first, std::size_t last) {
        for (auto j = static_cast<Eigen::Index>(first); j < static_cast<Eigen::Index>(last); ++j) {
          for (Eigen::Index i = 0; i < columns_; ++i) {
            sample_node(spline_, layout.node(i, j), spacing_,
                        &nodes_[static_cast<std::size_t>(kPerNode * (j * columns_ + i))]);
          }
        }
      });
  std::ostringstream message;
  message << columns_ << " x " << rows_ << " nodes, spacing " << spacing_ << " m, measured error "
          << measured_error_ << " m";
  message_ = message.str();
}

bool ThinPlateSplineLattice::contains(const Eigen::Vector2d& point_in_plan) const {
  return !empty() && box_.contains(point_in_plan);
}

template <bool kWithJacobian>
Eigen::Vector2d ThinPlateSplineLattice::interpolate(const Eigen::Vector2d& point_in_plan,
                                                    Eigen::Matrix2d* jacobian) const {
  const Eigen::Vector2d cell = (point_in_plan - box_.min()) / spacing_;
  const Eigen::Index i =
      std::clamp(static_cast<Eigen::Index>(cell.x()), Eigen::Index{0}, columns_ - 2);
  const Eigen::Index j =
      std::clamp(static_cast<Eigen::Index>(cell.y()), Eigen::Index{0}, rows_ - 2);
  const double* node = &nodes_[static_cast<std::size_t>(kPerNode * (j * columns_ + i))];
  const double* above = node + kPerNode * columns_;
  return patch<kWithJacobian>({node, node + kPerNode, above, above + kPerNode},
                              cell.x() - static_cast<double>(i), cell.y() - static_cast<double>(j),
                              spacing_, jacobian);
}

Eigen::Vector2d ThinPlateSplineLattice::evaluate(const Eigen::Vector2d& point_in_plan) const {
  if (!contains(point_in_plan))
    return spline_.evaluate(point_in_plan);
  return interpolate<false>(point_in_plan, nullptr);
}

Eigen::Matrix2Xd ThinPlateSplineLattice::evaluate_batch(
    const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan, int threads) const {
  const Eigen::Index m = points_in_plan.cols();
  Eigen::Matrix2Xd out(2, m);
  const auto run = [&](Eigen::Index first, Eigen::Index last) {
    for (Eigen::Index k = first; k < last; ++k)
      out.col(k) = evaluate(points_in_plan.col(k));
  };
  parallel_blocks(static_cast<std::size_t>(m), m >= 100000 ? threads : 1,
                  [&](std::size_t first, std::size_t last) {
                    run(static_cast<Eigen::Index>(first), static_cast<Eigen::Index>(last));
                  });
  return out;
}

Eigen::Matrix2d ThinPlateSplineLattice::jacobian(const Eigen::Vector2d& point_in_plan) const {
  if (!contains(point_in_plan))
    return spline_.jacobian(point_in_plan);
  Eigen::Matrix2d J;
  interpolate<true>(point_in_plan, &J);
  return J;
}

}  // namespace floorgrid
