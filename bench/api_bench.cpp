// The integrator's surface (floorgrid/floorgrid.hpp): a million plan points mapped forward
// through a model file, into caller-owned buffers, as the Python module's Model.forward maps a
// numpy array (bench/python_forward.py runs both on the same model and lattice of points).
// FLOORGRID_BENCH_MODEL: the model file (default tests/fixtures/models/tps.json).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "floorgrid/floorgrid.hpp"

namespace {

std::string model_path() {
  const char* path = std::getenv("FLOORGRID_BENCH_MODEL");
  return path ? path : FLOORGRID_SOURCE_DIR "/tests/fixtures/models/tps.json";
}

/// side x side points on a lattice over the box of the model's support plan points grown by
/// 1 m, row by row (x fastest): the points bench/python_forward.py makes with numpy.
Eigen::MatrixXd lattice(const floorgrid::Model& model, int side) {
  const Eigen::Matrix2Xd& plan = model.mapping().support().points_in_plan;
  const Eigen::Vector2d low = plan.rowwise().minCoeff().array() / model.unit() - 1.0;
  const Eigen::Vector2d high = plan.rowwise().maxCoeff().array() / model.unit() + 1.0;
  Eigen::MatrixXd points(2, side * side);
  const Eigen::Vector2d step = (high - low) / (side - 1);
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i)
      points.col(j * side + i) << low.x() + step.x() * i, low.y() + step.y() * j;
  }
  return points;
}

void BM_ModelForwardMillionPoints(benchmark::State& state) {
  const floorgrid::Model model = floorgrid::Model::load(model_path());
  const Eigen::MatrixXd points = lattice(model, 1000);
  const Eigen::Index n = points.cols();
  Eigen::MatrixXd out(2, n);
  Eigen::VectorXd std_m(n), nearest(n);
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 1> flags(n);
  for (auto _ : state) {
    model.map(points, false, out, std_m, nearest, flags);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.SetLabel(model.name());
}
BENCHMARK(BM_ModelForwardMillionPoints)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
