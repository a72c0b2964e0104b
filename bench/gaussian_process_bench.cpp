// The Gaussian-process engine behind the gp and gpgt models: fit (tuning + conditioning), mean
// of 10^6 points through the lattice, exact mean, predictive std of 10^4 points, and one
// likelihood gradient. Run: build-*/bench/gaussian_process_bench
// (items_per_second = points/s; the fit's counters say what tuning did).
#include <benchmark/benchmark.h>

#include <cmath>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/gaussian_process.hpp"
#include "floorgrid/mapping/gp_likelihood.hpp"

namespace {

using floorgrid::GaussianProcess;
using floorgrid::GaussianProcessFit;
using floorgrid::GaussianProcessOptions;
using floorgrid::Random;

constexpr double kWidth = 100.0, kHeight = 50.0;  // a warehouse-sized plan, metres

/// `count` plan points over the plan and their grid partners: a rigid transform, a 0.5 m bend
/// at the far end and a 3 x 3 m wobble of 5 cm, plus 2 cm noise (the gp model's raw data).
struct Pairs {
  Eigen::Matrix2Xd plan;
  Eigen::Matrix2Xd grid;
};

Pairs make_pairs(Eigen::Index count, std::uint64_t seed) {
  Random random(seed);
  Pairs pairs{Eigen::Matrix2Xd(2, count), Eigen::Matrix2Xd(2, count)};
  const double c = std::cos(0.4), s = std::sin(0.4);
  for (Eigen::Index i = 0; i < count; ++i) {
    const double x = random.uniform(0.0, kWidth), y = random.uniform(0.0, kHeight);
    const double bent = y + 0.5 * (x / kWidth) * (x / kWidth) + 0.05 * std::sin(x / 3.0);
    pairs.plan.col(i) << x, y;
    pairs.grid.col(i) << c * x - s * bent + 20.0 + random.normal(0.02),
        s * x + c * bent - 5.0 + random.normal(0.02);
  }
  return pairs;
}

/// gpgt's data: the residuals of the global transform (the bend and wobble) only.
Pairs make_residuals(Eigen::Index count, std::uint64_t seed) {
  Pairs pairs = make_pairs(count, seed);
  const double c = std::cos(0.4), s = std::sin(0.4);
  for (Eigen::Index i = 0; i < count; ++i) {
    const Eigen::Vector2d p = pairs.plan.col(i);
    pairs.grid.col(i) -= Eigen::Vector2d(c * p.x() - s * p.y() + 20.0, s * p.x() + c * p.y() - 5.0);
  }
  return pairs;
}

Eigen::Matrix2Xd queries(Eigen::Index count, std::uint64_t seed) {
  Random random(seed);
  Eigen::Matrix2Xd points(2, count);
  for (Eigen::Index i = 0; i < count; ++i) {
    points.col(i) << random.uniform(0.0, kWidth), random.uniform(0.0, kHeight);
  }
  return points;
}

void report_fit(benchmark::State& state, const GaussianProcessFit& fit) {
  state.counters["iterations"] = fit.summary.iterations;
  state.counters["tuning_points"] = static_cast<double>(fit.summary.tuning_points);
  state.counters["lattice_nodes"] = static_cast<double>(fit.summary.lattice_nodes);
  state.counters["lattice_error_mm"] = fit.summary.lattice_error * 1e3;
  state.counters["length_scale_x"] = fit.summary.hyperparameters.length_scale.x();
  state.counters["noise_std_mm"] = fit.summary.hyperparameters.noise_std * 1e3;
  state.SetLabel(fit.summary.converged ? "converged" : "max_iterations");
}

// Args: N, threads, residuals (1: gpgt's residual data, 0: gp's raw grid coordinates).
void BM_GaussianProcessFit(benchmark::State& state) {
  const Pairs pairs =
      state.range(2) ? make_residuals(state.range(0), 1) : make_pairs(state.range(0), 1);
  GaussianProcessOptions options;
  options.prediction.threads = static_cast<int>(state.range(1));
  for (auto _ : state) {
    const GaussianProcessFit fit = floorgrid::fit_gaussian_process(pairs.plan, pairs.grid, options);
    benchmark::DoNotOptimize(fit.model.state().alpha.data());
    report_fit(state, fit);
  }
}
BENCHMARK(BM_GaussianProcessFit)
    ->ArgNames({"N", "threads", "residuals"})
    ->Args({1000, 2, 1})
    ->Args({1000, 2, 0})
    ->Args({1000, 1, 1})
    ->Args({2000, 2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

GaussianProcess fitted_model(Eigen::Index n, int threads) {
  const Pairs pairs = make_residuals(n, 1);
  GaussianProcessOptions options;
  options.prediction.threads = threads;
  return floorgrid::fit_gaussian_process(pairs.plan, pairs.grid, options).model;
}

// Args: M query points, threads.
void BM_GaussianProcessMean(benchmark::State& state) {
  const GaussianProcess gp = fitted_model(1000, static_cast<int>(state.range(1)));
  const Eigen::Matrix2Xd points = queries(state.range(0), 2);
  for (auto _ : state) {
    const Eigen::Matrix2Xd mean = gp.mean_batch(points);
    benchmark::DoNotOptimize(mean.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_GaussianProcessMean)
    ->ArgNames({"M", "threads"})
    ->Args({1'000'000, 2})
    ->Args({1'000'000, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_GaussianProcessExactMean(benchmark::State& state) {
  const GaussianProcess gp = fitted_model(1000, static_cast<int>(state.range(1)));
  const Eigen::Matrix2Xd points = queries(state.range(0), 3);
  for (auto _ : state) {
    const Eigen::Matrix2Xd mean = gp.exact_mean_batch(points);
    benchmark::DoNotOptimize(mean.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_GaussianProcessExactMean)
    ->ArgNames({"M", "threads"})
    ->Args({10'000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_GaussianProcessStd(benchmark::State& state) {
  const GaussianProcess gp = fitted_model(state.range(2), static_cast<int>(state.range(1)));
  const Eigen::Matrix2Xd points = queries(state.range(0), 4);
  for (auto _ : state) {
    const Eigen::VectorXd std = gp.standard_deviation_batch(points);
    benchmark::DoNotOptimize(std.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_GaussianProcessStd)
    ->ArgNames({"M", "threads", "N"})
    ->Args({10'000, 2, 1000})
    ->Args({10'000, 1, 1000})
    ->Args({10'000, 2, 2000})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_GaussianProcessJacobian(benchmark::State& state) {
  const GaussianProcess gp = fitted_model(1000, 1);
  const Eigen::Matrix2Xd points = queries(10'000, 5);
  for (auto _ : state) {
    double sum = 0.0;
    for (Eigen::Index i = 0; i < points.cols(); ++i)
      sum += gp.mean_jacobian(points.col(i)).sum();
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * 10'000);
}
BENCHMARK(BM_GaussianProcessJacobian)->Unit(benchmark::kMillisecond);

// One RPROP iteration's cost: the likelihood and its gradient on N tuning points.
void BM_GaussianProcessLikelihoodGradient(benchmark::State& state) {
  const Pairs pairs = make_residuals(state.range(0), 6);
  const Eigen::Matrix2Xd centred = pairs.grid.colwise() - pairs.grid.rowwise().mean();
  const floorgrid::GpMarginalLikelihood likelihood(pairs.plan, centred);
  const Eigen::Vector4d log_parameters(std::log(5.0), std::log(5.0), std::log(0.2), std::log(0.02));
  for (auto _ : state) {
    benchmark::DoNotOptimize(likelihood.value_and_gradient(log_parameters).value);
  }
}
BENCHMARK(BM_GaussianProcessLikelihoodGradient)
    ->ArgName("N")
    ->Arg(400)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
