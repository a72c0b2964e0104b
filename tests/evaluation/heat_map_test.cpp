// Heat maps against analytic truths: a model that is the truth plus a known offset shows exactly
// that offset everywhere; domains in cells; the uncertainty map; thread independence.
#include "floorgrid/evaluation/heat_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

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
  // gp and tps map batches through their prediction lattice; the map must equal their
  // forward() at each cell centre (no further interpolation: the added error is zero).
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
