// Thin-plate spline: the fit on up to 2,000 centres (target 0.5 s), exact evaluation of 10^6
// points, and the bicubic lattice (build, 10^6 evaluations, added error against the exact spline,
// at a given spacing and refined to the 1 mm tolerance).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/thin_plate_spline.hpp"
#include "floorgrid/mapping/thin_plate_spline_lattice.hpp"

namespace {

using floorgrid::ThinPlateSpline;
using floorgrid::ThinPlateSplineLattice;

constexpr double kWidth = 100.0;  // metres: a 100 x 60 m building
constexpr double kHeight = 60.0;

// A SLAM-like distortion: rotation, shift, a bend of 0.5 m.
Eigen::Vector2d warp(const Eigen::Vector2d& p) {
  const double c = std::cos(0.3), s = std::sin(0.3);
  const Eigen::Vector2d bent(p.x(), p.y() + 0.5 * std::sin(p.x() / 30.0));
  return Eigen::Vector2d(c * bent.x() - s * bent.y() + 12.0, s * bent.x() + c * bent.y() - 7.0);
}

Eigen::Matrix2Xd random_points(floorgrid::Random& random, Eigen::Index count) {
  Eigen::Matrix2Xd points(2, count);
  for (Eigen::Index i = 0; i < count; ++i) {
    points.col(i) = Eigen::Vector2d(random.uniform(0, kWidth), random.uniform(0, kHeight));
  }
  return points;
}

// `count` pairs of one of two kinds. Raw (kind 0): plan points uniform over the building, grid
// points through the warp with 2 cm of noise per axis, as single laser pairs (a worst case
// for an interpolant: neighbours a few mm apart disagree by centimetres). Binned (kind 1): one
// pair per cell of a jittered grid with 5 mm of noise, as the models' pair reduction (spatial
// binning, averaging the pairs per cell) hands them over.
struct Pairs {
  Eigen::Matrix2Xd plan, grid;
};
const Pairs& pairs(Eigen::Index count, int kind = 0) {
  static std::map<std::pair<Eigen::Index, int>, std::unique_ptr<Pairs>> cache;
  std::unique_ptr<Pairs>& slot = cache[{count, kind}];
  if (!slot) {
    floorgrid::Random random(static_cast<std::uint64_t>(count + kind));
    slot = std::make_unique<Pairs>();
    double noise = 0.02;
    if (kind == 0) {
      slot->plan = random_points(random, count);
    } else {
      noise = 0.005;
      const double cell = std::sqrt(kWidth * kHeight / static_cast<double>(count));
      const auto columns = static_cast<Eigen::Index>(std::ceil(kWidth / cell));
      slot->plan.resize(2, count);
      for (Eigen::Index i = 0; i < count; ++i) {
        slot->plan.col(i) =
            cell * Eigen::Vector2d(static_cast<double>(i % columns) + random.uniform(0.1, 0.9),
                                   static_cast<double>(i / columns) + random.uniform(0.1, 0.9));
      }
    }
    slot->grid.resize(2, count);
    for (Eigen::Index i = 0; i < count; ++i) {
      slot->grid.col(i) =
          warp(slot->plan.col(i)) + Eigen::Vector2d(random.normal(noise), random.normal(noise));
    }
  }
  return *slot;
}

const Eigen::Matrix2Xd& queries(Eigen::Index count) {
  static std::map<Eigen::Index, std::unique_ptr<Eigen::Matrix2Xd>> cache;
  std::unique_ptr<Eigen::Matrix2Xd>& slot = cache[count];
  if (!slot) {
    floorgrid::Random random(99);
    slot = std::make_unique<Eigen::Matrix2Xd>(random_points(random, count));
  }
  return *slot;
}

// Args: centres, regularization in 1e-3 m^2.
void BM_TpsFit(benchmark::State& state) {
  const Pairs& p = pairs(state.range(0));
  const double lambda = 1e-3 * static_cast<double>(state.range(1));
  for (auto _ : state) {
    const ThinPlateSpline spline = ThinPlateSpline::fit(p.plan, p.grid, {lambda});
    benchmark::DoNotOptimize(spline.data().affine.data());
  }
}
BENCHMARK(BM_TpsFit)
    ->Args({500, 0})
    ->Args({1000, 0})
    ->Args({2000, 0})
    ->Args({2000, 100})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Args: query points, threads. 2,000 centres.
void BM_TpsEvaluateExact(benchmark::State& state) {
  const Pairs& p = pairs(2000);
  const ThinPlateSpline spline = ThinPlateSpline::fit(p.plan, p.grid);
  const Eigen::Matrix2Xd& q = queries(state.range(0));
  for (auto _ : state) {
    const Eigen::Matrix2Xd out = spline.evaluate_batch(q, static_cast<int>(state.range(1)));
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["ns_per_point"] = benchmark::Counter(
      static_cast<double>(state.range(0)),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_TpsEvaluateExact)
    ->Args({100000, 1})
    ->Args({1000000, 2})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Args: lattice spacing in mm (tried first), regularization in 1e-3 m^2, pairs kind (0 raw,
// 1 binned), refine (0: keep the first spacing whatever its error, 1: refine it until the
// measured error is within half the default 1 mm tolerance). 2,000 centres; times the build
// (with the measurement that chooses the spacing) and then 10^6 evaluations; the counters give
// the spacing kept (0: no lattice, the exact spline everywhere), the lattice's own measured
// error, and the added error against the exact spline on 10^5 points (max, 99.9th percentile,
// mean), in metres.
void BM_TpsLattice(benchmark::State& state) {
  const Pairs& p = pairs(2000, static_cast<int>(state.range(2)));
  floorgrid::ThinPlateSplineLatticeOptions options;
  options.spacing = 1e-3 * static_cast<double>(state.range(0));
  if (state.range(3) == 0)
    options.tolerance = 1e9;
  const double lambda = 1e-3 * static_cast<double>(state.range(1));
  const ThinPlateSpline spline = ThinPlateSpline::fit(p.plan, p.grid, {lambda});
  const Eigen::AlignedBox2d box(Eigen::Vector2d(0, 0), Eigen::Vector2d(kWidth, kHeight));
  const Eigen::Matrix2Xd& q = queries(1000000);
  double build_s = 0.0, evaluate_s = 0.0;
  std::unique_ptr<ThinPlateSplineLattice> lattice;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    lattice = std::make_unique<ThinPlateSplineLattice>(spline, box, options);
    const auto built = std::chrono::steady_clock::now();
    const Eigen::Matrix2Xd out = lattice->evaluate_batch(q);
    benchmark::DoNotOptimize(out.data());
    build_s += std::chrono::duration<double>(built - start).count();
    evaluate_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count();
  }
  const auto runs = static_cast<double>(state.iterations());
  const Eigen::Matrix2Xd sample = q.leftCols(100000);
  const Eigen::VectorXd error =
      (lattice->evaluate_batch(sample) - spline.evaluate_batch(sample)).colwise().norm();
  std::vector<double> sorted(error.data(), error.data() + error.size());
  std::sort(sorted.begin(), sorted.end());
  state.counters["spacing_m"] = lattice->spacing();
  state.counters["measured_m"] = lattice->empty() ? -1.0 : lattice->measured_error();
  state.counters["build_ms"] = 1e3 * build_s / runs;
  state.counters["eval_1e6_ms"] = 1e3 * evaluate_s / runs;
  state.counters["max_error_m"] = sorted.back();
  state.counters["p999_error_m"] = sorted[sorted.size() * 999 / 1000];
  state.counters["mean_error_m"] = error.mean();
}
BENCHMARK(BM_TpsLattice)
    ->Args({500, 0, 1, 0})
    ->Args({250, 0, 1, 0})
    ->Args({250, 10, 1, 0})
    ->Args({500, 0, 0, 0})
    ->Args({250, 0, 0, 0})
    ->Args({125, 0, 0, 0})
    ->Args({250, 100, 0, 0})
    ->Args({125, 100, 0, 0})
    ->Args({1000, 0, 1, 1})
    ->Args({1000, 10, 1, 1})
    ->Args({1000, 100, 0, 1})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
