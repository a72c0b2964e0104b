// Delaunay triangulation and point location (the core of the `dt` model), and the exact
// predicates underneath. Targets (single thread): 10^5 uniform points triangulated in <= 150 ms;
// 10^6 random points located in <= 0.5 s.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/predicates.hpp"
#include "floorgrid/mapping/delaunay.hpp"

namespace {

using floorgrid::DelaunayTriangulation;
using floorgrid::Random;

Eigen::Matrix2Xd uniform_points(std::uint64_t seed, Eigen::Index n) {
  Random random(seed);
  Eigen::Matrix2Xd p(2, n);
  for (Eigen::Index i = 0; i < n; ++i)
    p.col(i) << random.uniform(0, 100), random.uniform(0, 100);
  return p;
}

// Laser pairs along walls: points densely along a few hundred segments (axis-aligned or slanted,
// 2-30 m long) with 5 mm of noise across the wall: many nearly collinear points.
Eigen::Matrix2Xd wall_points(std::uint64_t seed, Eigen::Index n, int walls) {
  Random random(seed);
  std::vector<std::array<Eigen::Vector2d, 2>> segments;
  for (int w = 0; w < walls; ++w) {
    const Eigen::Vector2d a(random.uniform(0, 100), random.uniform(0, 100));
    const double length = random.uniform(2, 30);
    const int kind = static_cast<int>(random.integer(0, 2));
    const double angle =
        kind == 0 ? 0.0 : (kind == 1 ? 1.5707963267948966 : random.uniform(0, 3.14));
    segments.push_back({a, a + length * Eigen::Vector2d(std::cos(angle), std::sin(angle))});
  }
  Eigen::Matrix2Xd p(2, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& s = segments[static_cast<std::size_t>(random.integer(0, walls - 1))];
    const Eigen::Vector2d d = s[1] - s[0];
    const Eigen::Vector2d normal = Eigen::Vector2d(-d.y(), d.x()).normalized();
    p.col(i) = s[0] + random.uniform() * d + random.normal(0.005) * normal;
  }
  return p;
}

// A square integer grid of about n points: co-circular quadruples everywhere (exact path).
Eigen::Matrix2Xd grid_points(Eigen::Index n) {
  const auto side = static_cast<Eigen::Index>(std::sqrt(static_cast<double>(n)));
  Eigen::Matrix2Xd p(2, side * side);
  for (Eigen::Index i = 0; i < side; ++i) {
    for (Eigen::Index j = 0; j < side; ++j)
      p.col(i * side + j) << static_cast<double>(i), static_cast<double>(j);
  }
  return p;
}

void triangulate(benchmark::State& state, const Eigen::Matrix2Xd& p) {
  std::size_t triangles = 0;
  for (auto _ : state) {
    const DelaunayTriangulation dt(p);
    triangles = dt.triangles().size();
    benchmark::DoNotOptimize(triangles);
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(p.cols()),
                                                  benchmark::Counter::kIsIterationInvariantRate);
}

void BM_DelaunayUniform(benchmark::State& state) {
  triangulate(state, uniform_points(1, state.range(0)));
}
BENCHMARK(BM_DelaunayUniform)
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMillisecond);

void BM_DelaunayWalls(benchmark::State& state) {
  triangulate(state, wall_points(2, state.range(0), 300));
}
BENCHMARK(BM_DelaunayWalls)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_DelaunayGrid(benchmark::State& state) {
  triangulate(state, grid_points(state.range(0)));
}
BENCHMARK(BM_DelaunayGrid)->Arg(100000)->Unit(benchmark::kMillisecond);

// 10^6 random queries over the points' box grown by 10% (17% outside the hull).
Eigen::Matrix2Xd queries(Eigen::Index n) {
  Eigen::Matrix2Xd q = uniform_points(3, n);
  q = (q.array() * 1.1 - 5.0).matrix();
  return q;
}

void BM_LocateAll(benchmark::State& state) {
  const DelaunayTriangulation dt(uniform_points(1, state.range(0)));
  const Eigen::Matrix2Xd q = queries(1000000);
  for (auto _ : state) {
    const auto located = dt.locate_all(q);
    benchmark::DoNotOptimize(located.data());
  }
  state.counters["queries/s"] = benchmark::Counter(static_cast<double>(q.cols()),
                                                   benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_LocateAll)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

void BM_LocateAllWalls(benchmark::State& state) {
  const DelaunayTriangulation dt(wall_points(2, state.range(0), 300));
  const Eigen::Matrix2Xd q = queries(1000000);
  for (auto _ : state) {
    const auto located = dt.locate_all(q);
    benchmark::DoNotOptimize(located.data());
  }
  state.counters["queries/s"] = benchmark::Counter(static_cast<double>(q.cols()),
                                                   benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_LocateAllWalls)->Arg(100000)->Unit(benchmark::kMillisecond);

// The same 10^6 queries one by one in random order, each walk starting from the bucket grid.
void BM_LocateOneByOne(benchmark::State& state) {
  const DelaunayTriangulation dt(uniform_points(1, state.range(0)));
  const Eigen::Matrix2Xd q = queries(1000000);
  for (auto _ : state) {
    for (Eigen::Index i = 0; i < q.cols(); ++i) {
      const DelaunayTriangulation::Located r = dt.locate(q.col(i));
      benchmark::DoNotOptimize(r);
    }
  }
  state.counters["queries/s"] = benchmark::Counter(static_cast<double>(q.cols()),
                                                   benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_LocateOneByOne)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

// Predicates: random points (the filter decides) and exactly degenerate ones (exact path).
void BM_Orient2d(benchmark::State& state) {
  const bool degenerate = state.range(0) == 1;
  state.SetLabel(degenerate ? "collinear (exact path)" : "random (filter)");
  const Eigen::Matrix2Xd p = degenerate ? grid_points(1024) : uniform_points(4, 1024);
  std::size_t i = 0;
  for (auto _ : state) {
    const double* a = p.col(static_cast<Eigen::Index>(i % 1024)).data();
    const double* b = p.col(static_cast<Eigen::Index>((i + 1) % 1024)).data();
    const double* c = p.col(static_cast<Eigen::Index>((i + 2) % 1024)).data();
    benchmark::DoNotOptimize(floorgrid::orient2d(a, b, c));
    ++i;
  }
}
BENCHMARK(BM_Orient2d)->Arg(0)->Arg(1);

void BM_Incircle(benchmark::State& state) {
  const int kind = static_cast<int>(state.range(0));
  const char* labels[] = {"random (filter)", "co-circular integers (exact path)",
                          "co-circular with full mantissas (exact path)"};
  state.SetLabel(labels[kind]);
  std::vector<std::array<double, 8>> cases;
  Random random(5);
  for (int k = 0; k < 256; ++k) {
    if (kind == 0) {
      std::array<double, 8> c;
      for (double& v : c)
        v = random.uniform(0, 100);
      cases.push_back(c);
    } else {
      // The corners of a rectangle: exactly co-circular.
      const double x0 =
          kind == 1 ? static_cast<double>(random.integer(0, 1000)) : random.uniform(0, 100);
      const double y0 =
          kind == 1 ? static_cast<double>(random.integer(0, 1000)) : random.uniform(0, 100);
      const double x1 =
          kind == 1 ? x0 + static_cast<double>(random.integer(1, 9)) : random.uniform(0, 100);
      const double y1 =
          kind == 1 ? y0 + static_cast<double>(random.integer(1, 9)) : random.uniform(0, 100);
      cases.push_back({x0, y0, x1, y0, x1, y1, x0, y1});
    }
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& c = cases[i++ % cases.size()];
    benchmark::DoNotOptimize(floorgrid::incircle(&c[0], &c[2], &c[4], &c[6]));
  }
}
BENCHMARK(BM_Incircle)->Arg(0)->Arg(1)->Arg(2);

}  // namespace

BENCHMARK_MAIN();
