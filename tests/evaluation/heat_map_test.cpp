// Heat maps against analytic truths: a model that is the truth plus a known offset shows exactly
// that offset everywhere; domains in cells; the uncertainty map; thread independence.
#include "floorgrid/evaluation/heat_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"

namespace floorgrid {
namespace {

/// A gentle bend: smooth, not affine.
Eigen::Vector2d bent(const Eigen::Vector2d& p) {
  return {p.x() + 0.02 * p.y() * p.y() / 10.0 + 1.0, p.y() + 0.3 * std::sin(0.2 * p.x())};
}

ReferencePairs pairs_of(const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& f,
                        int side = 12, double spacing = 1.0) {
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, side * side);
  pairs.points_in_grid.resize(2, side * side);
  for (int i = 0; i < side * side; ++i) {
    // A slightly sheared lattice: no four points on one circle for the Delaunay models.
    const Eigen::Vector2d p(spacing * (i % side) + 0.013 * (i / side),
                            spacing * (i / side) + 0.007 * (i % side));
    pairs.points_in_plan.col(i) = p;
    pairs.points_in_grid.col(i) = f(p);
  }
  return pairs;
}

std::unique_ptr<PointMapping> fitted(const std::string& name, const ReferencePairs& pairs) {
  MappingOptions options;
  options.model = name;
  auto model = make_mapping(options);
  model->fit(pairs);
  return model;
}

GridGeometry raster(int width, int height, double resolution = 0.1) {
  GridGeometry g;
  g.width = width;
  g.height = height;
  g.resolution = resolution;
  g.origin = Pose2{0.5, 0.5, 0.0};
  return g;
}

TEST(HeatMap, TruthPlusAKnownOffsetShowsExactlyThatOffset) {
  const Eigen::Vector2d offset(0.3, -0.4);  // 0.5 m
  const auto truth = [](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(1.02 * p + Eigen::Vector2d(2, 1));
  };
  const auto model = fitted("gt-affine", pairs_of([&](const Eigen::Vector2d& p) {
                              return Eigen::Vector2d(truth(p) + offset);
                            }));
  const GridGeometry g = raster(90, 80);
  const HeatMap map = error_heat_map(*model, batch_of(truth), g, CellMask(g.size(), 1));
  ASSERT_EQ(map.values.size(), g.size());
  EXPECT_EQ(map.known(), g.size());
  EXPECT_EQ(map.quantity, "error_m");
  for (const float v : map.values)
    ASSERT_NEAR(v, 0.5, 1e-6);
  EXPECT_NEAR(map.quantile(0.95), 0.5, 1e-6);
}

TEST(HeatMap, CellsOutsideTheMaskAreUnknown) {
  const auto model = fitted("gt", pairs_of(bent));
  const GridGeometry g = raster(40, 30);
  CellMask mask(g.size(), 0);
  for (std::size_t i = 0; i < mask.size(); i += 3)
    mask[i] = 1;
  const HeatMap map = error_heat_map(*model, batch_of(bent), g, mask);
  for (std::size_t i = 0; i < mask.size(); ++i)
    EXPECT_EQ(std::isfinite(map.values[i]), mask[i] == 1) << i;
  EXPECT_EQ(map.known(), (mask.size() + 2) / 3);
}

TEST(HeatMap, EveryCellIsTheModelsOwnForwardAgainstTheTruth) {
  // gp maps through its prediction lattice in forward() too, tps maps batches of fewer than
  // lattice_from points (these 3,000) exactly: the map must equal their forward() at each cell
  // centre (no further interpolation: the added error is zero).
  const ReferencePairs pairs = pairs_of(bent);
  const GridGeometry g = raster(60, 50, 0.2);
  for (const char* name : {"gt", "dt", "tps", "gp"}) {
    const auto model = fitted(name, pairs);
    const HeatMap map = error_heat_map(*model, batch_of(bent), g, CellMask(g.size(), 1));
    double worst = 0.0;
    for (int iy = 0; iy < g.height; ++iy) {
      for (int ix = 0; ix < g.width; ++ix) {
        const Eigen::Vector2d p = g.cell_center(ix, iy);
        const double exact = (model->forward(p) - bent(p)).norm();
        worst = std::max(worst,
                         std::abs(exact - map.values[static_cast<std::size_t>(iy) * g.width + ix]));
      }
    }
    EXPECT_LE(worst, 1e-6) << name;  // float storage: 1e-6 m on errors below a metre
  }
}

TEST(HeatMap, ResultDoesNotDependOnThreadsOrChunks) {
  const auto model = fitted("tps", pairs_of(bent));
  const GridGeometry g = raster(70, 45);
  const CellMask all(g.size(), 1);
  HeatMapOptions one;
  one.threads = 1;
  one.chunk = 1000;
  HeatMapOptions two;
  two.threads = 2;
  two.chunk = 77;
  const HeatMap a = error_heat_map(*model, batch_of(bent), g, all, one);
  const HeatMap b = error_heat_map(*model, batch_of(bent), g, all, two);
  EXPECT_EQ(a.values, b.values);
}

/// The identity, recording the size of every batch it maps.
class BatchRecorder : public PointMapping {
 public:
  BatchRecorder() : PointMapping(MappingCommonOptions{}) {}
  std::string name() const override { return "recorder"; }
  std::size_t min_pairs() const override { return 1; }
  bool needs_non_collinear() const override { return false; }
  bool reduces_pairs() const override { return false; }
  Eigen::Vector2d forward(const Eigen::Vector2d& p) const override { return p; }
  Eigen::Matrix2Xd forward_batch(const Eigen::Ref<const Eigen::Matrix2Xd>& p) const override {
    const std::lock_guard<std::mutex> lock(mutex_);
    sizes.push_back(p.cols());
    return p;
  }
  mutable std::vector<Eigen::Index> sizes;

 protected:
  void fit_model(const ReferencePairs&, FitSummary&) override {}
  Value parameters() const override { return Value::object(); }
  void load_parameters(const Value&, const std::string&) override {}

 private:
  mutable std::mutex mutex_;
};

TEST(HeatMap, BatchesHoldAtLeastAChunkOfTheMaskAndCoverItOnce) {
  const GridGeometry g = raster(100, 80);
  CellMask sparse(g.size(), 0);
  std::size_t in_mask = 0;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      if ((7 * ix + 3 * iy) % 5 != 0 && !(ix > 20 && ix < 60 && iy > 10 && iy < 50)) {
        sparse[static_cast<std::size_t>(iy) * g.width + ix] = 1;
        ++in_mask;
      }
    }
  }
  const auto offset = [](const Eigen::Ref<const Eigen::Matrix2Xd>& p) {
    return Eigen::Matrix2Xd(p.colwise() + Eigen::Vector2d(0.3, 0.4));
  };
  struct Case {
    CellMask mask;
    std::size_t cells, chunk;
    int threads;
  };
  for (const Case& c : {Case{sparse, in_mask, 1000, 1}, Case{sparse, in_mask, 1000, 2},
                        Case{sparse, in_mask, in_mask + 1, 2}, Case{{}, g.size(), 1000, 2}}) {
    BatchRecorder recorder;
    HeatMapOptions options;
    options.chunk = c.chunk;
    options.threads = c.threads;
    const HeatMap map = error_heat_map(recorder, offset, g, c.mask, options);
    EXPECT_EQ(map.known(), c.cells);
    for (std::size_t i = 0; i < map.values.size(); ++i) {
      if (std::isfinite(map.values[i])) {
        ASSERT_NEAR(map.values[i], 0.5, 1e-6) << i;
      }
    }
    Eigen::Index total = 0;
    for (const Eigen::Index size : recorder.sizes) {
      total += size;
      EXPECT_GE(size, static_cast<Eigen::Index>(std::min(c.chunk, c.cells))) << c.chunk;
      EXPECT_LT(size, static_cast<Eigen::Index>(2 * c.chunk)) << c.chunk;
    }
    EXPECT_EQ(total, static_cast<Eigen::Index>(c.cells));  // each cell once
    EXPECT_EQ(recorder.sizes.size(), std::max<std::size_t>(1, c.cells / c.chunk));
  }
}

/// A SLAM-like distortion over a 200 m building: a rotation, a shift, a 1 m bend (as
/// bench/heat_map_bench.cpp's).
Eigen::Vector2d slam_warp(const Eigen::Vector2d& p) {
  const double c = std::cos(0.2), s = std::sin(0.2);
  const Eigen::Vector2d b(p.x(), p.y() + 1.0 * std::sin(p.x() / 64.0));
  return {c * b.x() - s * b.y() + 12.0, s * b.x() + c * b.y() - 7.0};
}

TEST(HeatMap, ALargeTpsMapIsWithin1mmOfTheExactSpline) {
  // Laser-like pairs along the walls of 10 m rooms over 200 x 200 m, 2 cm of noise; a map of
  // 10^6 cells is mapped in batches of at least 2^15 cells, through the tps lattice.
  Random random(7);
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, 40000);
  pairs.points_in_grid.resize(2, 40000);
  for (Eigen::Index i = 0; i < 40000; ++i) {
    const double along = random.uniform(0.0, 200.0);
    const double wall = 10.0 * std::floor(random.uniform(0.0, 21.0));
    const Eigen::Vector2d p =
        i % 2 == 0 ? Eigen::Vector2d(along, wall) : Eigen::Vector2d(wall, along);
    pairs.points_in_plan.col(i) = p;
    pairs.points_in_grid.col(i) =
        slam_warp(p) + Eigen::Vector2d(random.normal(0.02), random.normal(0.02));
  }
  const auto model = fitted("tps", pairs);
  GridGeometry g;
  g.width = 1000;
  g.height = 1000;
  g.resolution = 0.2;
  const CellMask all(g.size(), 1);
  const HeatMap map = error_heat_map(*model, batch_of(slam_warp), g, all);
  ASSERT_EQ(map.known(), g.size());
  // Against the exact spline (forward()) at 20,000 random cells.
  double worst = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const auto ix = static_cast<int>(random.integer(0, g.width - 1));
    const auto iy = static_cast<int>(random.integer(0, g.height - 1));
    const Eigen::Vector2d p = g.cell_center(ix, iy);
    const double exact = (model->forward(p) - slam_warp(p)).norm();
    worst =
        std::max(worst, std::abs(exact - map.values[static_cast<std::size_t>(iy) * g.width + ix]));
  }
  EXPECT_LE(worst, 1e-3);
  EXPECT_GT(worst, 0.0);  // the lattice, not the exact spline, mapped the cells
  // The same lattice for every batch: threads and (large) chunks change nothing.
  HeatMapOptions one;
  one.threads = 1;
  one.chunk = 50000;
  EXPECT_EQ(error_heat_map(*model, batch_of(slam_warp), g, all, one).values, map.values);
}

TEST(HeatMap, HullCellsAreInsideThePairsHull) {
  const GridGeometry g = raster(50, 50);  // cells cover [0.5, 5.5]^2
  Eigen::Matrix2Xd square(2, 4);
  square << 1.0, 3.0, 3.0, 1.0,  //
      1.0, 1.0, 3.0, 3.0;
  const CellMask mask = hull_cells(g, square);
  std::size_t inside = 0;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const Eigen::Vector2d c = g.cell_center(ix, iy);
      const bool in = c.x() > 1.0 && c.x() < 3.0 && c.y() > 1.0 && c.y() < 3.0;
      EXPECT_EQ(mask[static_cast<std::size_t>(iy) * g.width + ix] == 1, in) << ix << "," << iy;
      inside += in ? 1 : 0;
    }
  }
  EXPECT_EQ(inside, 400u);
}

TEST(HeatMap, ObservedCellsFollowTheMappingOntoTheGridmap) {
  // A gridmap observed only where x < 3 (grid frame); the plan is shifted by +1 m on the way.
  GridGeometry grid_geometry = raster(60, 60);
  OccupancyGrid gridmap(grid_geometry, CellState::unknown);
  for (int iy = 0; iy < 60; ++iy)
    for (int ix = 0; ix < 60; ++ix)
      if (grid_geometry.cell_center(ix, iy).x() < 3.0)
        gridmap.set_state(ix, iy, CellState::free);
  const GridGeometry g = raster(40, 40);
  const CellMask mask = observed_cells(g, gridmap, [](const Eigen::Ref<const Eigen::Matrix2Xd>& p) {
    return Eigen::Matrix2Xd(p.colwise() + Eigen::Vector2d(1.0, 0.0));
  });
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix)
      EXPECT_EQ(mask[static_cast<std::size_t>(iy) * g.width + ix] == 1,
                g.cell_center(ix, iy).x() + 1.0 < 3.0)
          << ix << "," << iy;
}

TEST(HeatMap, UncertaintyWithoutAnErrorModelIsTheDistanceToTheNearestPair) {
  const ReferencePairs pairs = pairs_of(bent, 4, 2.0);
  const auto model = fitted("gt", pairs);
  ASSERT_FALSE(model->error_model().has_value());
  const GridGeometry g = raster(30, 30, 0.3);
  HeatMapOptions exact;
  exact.uncertainty_step = 1;
  const HeatMap map = uncertainty_map(*model, g, CellMask(g.size(), 1), exact);
  EXPECT_EQ(map.quantity, "nearest_pair_m");
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const Eigen::Vector2d c = g.cell_center(ix, iy);
      double nearest = 1e9;
      for (Eigen::Index k = 0; k < pairs.size(); ++k)
        nearest = std::min(nearest, (pairs.points_in_plan.col(k) - c).norm());
      EXPECT_NEAR(map.values[static_cast<std::size_t>(iy) * g.width + ix], nearest, 1e-5);
    }
  }
}

TEST(HeatMap, UncertaintyWithAnErrorModelIsItsStd) {
  const auto model = fitted("gt", pairs_of(bent, 4, 2.0));
  ErrorModel e;
  e.base_std_m = 0.02;
  e.growth = 0.1;
  model->set_error_model(e);
  const GridGeometry g = raster(20, 20, 0.3);
  HeatMapOptions exact;
  exact.uncertainty_step = 1;
  const HeatMap map = uncertainty_map(*model, g, CellMask(g.size(), 1), exact);
  EXPECT_EQ(map.quantity, "std_m");
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix)
      EXPECT_NEAR(map.values[static_cast<std::size_t>(iy) * g.width + ix],
                  *model->error_std(g.cell_center(ix, iy)), 1e-6);
  // The default lattice (std_m every 4th cell, bilinear between) on 5 cm cells: within
  // 2 cm of it (the kinks of the nearest-pair distance), exact at the nodes.
  const GridGeometry fine = raster(120, 120, 0.05);
  const HeatMap all = uncertainty_map(*model, fine, CellMask(fine.size(), 1), exact);
  const HeatMap coarse = uncertainty_map(*model, fine, CellMask(fine.size(), 1));
  for (std::size_t i = 0; i < all.values.size(); ++i)
    EXPECT_NEAR(coarse.values[i], all.values[i], 0.02) << i;
  EXPECT_FLOAT_EQ(coarse.values[4 * 120 + 8], all.values[4 * 120 + 8]);
}

}  // namespace
}  // namespace floorgrid
