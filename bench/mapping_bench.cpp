// Every mapping model: fitting 10^6 laser-like pairs (along the walls of the simulated office,
// bent warp, 2 cm noise, 10% outliers) and mapping 10^6 points forward; plus the inverse of
// 10^4 points. And the models fitted to pairs as the maps alone give them: plan points exactly on
// the straight walls, with every other 4 m block left out as a blocked fold leaves it. 2 threads
// at most.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace {

using namespace floorgrid;

/// Laser-like pairs: points along the office's walls, through its exact warp.
const ReferencePairs& laser_pairs() {
  static const ReferencePairs pairs = [] {
    const SimulatedDataset d = simulate("bent-office", 1);
    const PlanTruth truth = d.truth();
    const Eigen::Matrix2Xd walls = filter_layers(d.plan, {{"WALLS"}, {}}).sample_points(0.02);
    Random r(3);
    ReferencePairs p;
    const Eigen::Index n = 1'000'000;
    p.points_in_plan.resize(2, n);
    p.points_in_grid.resize(2, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector2d q = walls.col(r.integer(0, walls.cols() - 1)) +
                                Eigen::Vector2d(r.normal(0.01), r.normal(0.01));
      p.points_in_plan.col(i) = q;
      p.points_in_grid.col(i) =
          truth.plan_to_grid(q) + Eigen::Vector2d(r.normal(0.02), r.normal(0.02));
      if (r.bernoulli(0.1))
        p.points_in_grid.col(i) += Eigen::Vector2d(r.uniform(-3, 3), r.uniform(-3, 3));
    }
    return p;
  }();
  return pairs;
}

/// Pairs as `align` without a log makes them: plan points exactly on the office's straight walls
/// (no noise: many neighbours in a row are collinear), one per 0.1 m, through the exact warp;
/// every other 4 m block is left out, as a blocked cross-validation fold holds it out.
const ReferencePairs& straight_wall_pairs() {
  static const ReferencePairs pairs = [] {
    const SimulatedDataset d = simulate("bent-office", 1);
    const PlanTruth truth = d.truth();
    const Eigen::Matrix2Xd walls = filter_layers(d.plan, {{"WALLS"}, {}}).sample_points(0.1);
    std::vector<Eigen::Index> kept;
    for (Eigen::Index i = 0; i < walls.cols(); ++i) {
      const auto bx = static_cast<long>(std::floor(walls(0, i) / 4.0));
      const auto by = static_cast<long>(std::floor(walls(1, i) / 4.0));
      if ((bx + by) % 2 == 0)
        kept.push_back(i);
    }
    ReferencePairs p;
    p.points_in_plan.resize(2, static_cast<Eigen::Index>(kept.size()));
    p.points_in_grid.resize(2, p.points_in_plan.cols());
    for (std::size_t k = 0; k < kept.size(); ++k) {
      const auto c = static_cast<Eigen::Index>(k);
      p.points_in_plan.col(c) = walls.col(kept[k]);
      p.points_in_grid.col(c) = truth.plan_to_grid(walls.col(kept[k]));
    }
    return p;
  }();
  return pairs;
}

const Eigen::Matrix2Xd& query_points(Eigen::Index n) {
  static Eigen::Matrix2Xd points;
  if (points.cols() != n) {
    Random r(4);
    const Eigen::Vector2d lo = laser_pairs().points_in_plan.rowwise().minCoeff();
    const Eigen::Vector2d hi = laser_pairs().points_in_plan.rowwise().maxCoeff();
    points.resize(2, n);
    for (Eigen::Index i = 0; i < n; ++i)
      points.col(i) << r.uniform(lo.x(), hi.x()), r.uniform(lo.y(), hi.y());
  }
  return points;
}

std::unique_ptr<PointMapping> fitted(const std::string& name) {
  MappingOptions options;
  options.model = name;
  auto m = make_mapping(options);
  m->fit(laser_pairs());
  return m;
}

void BM_Fit(benchmark::State& state, const std::string& name) {
  laser_pairs();
  for (auto _ : state) {
    auto m = fitted(name);
    benchmark::DoNotOptimize(m.get());
    state.counters["pairs_used"] = static_cast<double>(m->summary().pairs_used);
  }
  state.counters["pairs"] = 1e6;
}

void BM_FitStraightWalls(benchmark::State& state, const std::string& name) {
  const ReferencePairs& pairs = straight_wall_pairs();
  for (auto _ : state) {
    MappingOptions options;
    options.model = name;
    auto m = make_mapping(options);
    m->fit(pairs);
    benchmark::DoNotOptimize(m.get());
  }
  state.counters["pairs"] = static_cast<double>(pairs.size());
}

void BM_Forward(benchmark::State& state, const std::string& name) {
  const auto m = fitted(name);
  const Eigen::Matrix2Xd& points = query_points(1'000'000);
  for (auto _ : state) {
    const Eigen::Matrix2Xd out = m->forward_batch(points);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * points.cols());
}

void BM_Inverse(benchmark::State& state, const std::string& name) {
  const auto m = fitted(name);
  const Eigen::Matrix2Xd grid = m->forward_batch(query_points(1'000'000).leftCols(10'000));
  for (auto _ : state) {
    int invertible = 0;
    for (Eigen::Index i = 0; i < grid.cols(); ++i)
      invertible += m->inverse(grid.col(i)).invertible;
    benchmark::DoNotOptimize(invertible);
  }
  state.SetItemsProcessed(state.iterations() * grid.cols());
}

int register_all() {
  for (const auto& name : mapping_model_names()) {
    if (name == "auto")
      continue;  // auto is one of the others, chosen by cross-validation
    benchmark::RegisterBenchmark(("Fit1e6Pairs/" + name).c_str(), BM_Fit, name)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
    benchmark::RegisterBenchmark(("FitStraightWallPairs/" + name).c_str(), BM_FitStraightWalls,
                                 name)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
    benchmark::RegisterBenchmark(("Forward1e6Points/" + name).c_str(), BM_Forward, name)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
    benchmark::RegisterBenchmark(("Inverse1e4Points/" + name).c_str(), BM_Inverse, name)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  }
  return 0;
}
const int registered = register_all();

}  // namespace

BENCHMARK_MAIN();
