// A model judged against an analytic truth: its errors, its back-and-forth drift, the error
// histogram, and the overlay picture of the plan through it.
#include "floorgrid/evaluation/model_evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "floorgrid/evaluation/overlay.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"

namespace floorgrid {
namespace {

Eigen::Vector2d similarity(const Eigen::Vector2d& p) {
  const double c = std::cos(0.3), s = std::sin(0.3);
  return 1.05 * Eigen::Vector2d(c * p.x() - s * p.y(), s * p.x() + c * p.y()) +
         Eigen::Vector2d(2.0, -1.0);
}

std::unique_ptr<PointMapping> fitted_gt() {
  ReferencePairs pairs;
  pairs.points_in_plan.resize(2, 40);
  pairs.points_in_grid.resize(2, 40);
  for (int i = 0; i < 40; ++i) {
    const Eigen::Vector2d p(0.37 * i, 5.0 * std::sin(0.9 * i));
    pairs.points_in_plan.col(i) = p;
    pairs.points_in_grid.col(i) = similarity(p);
  }
  MappingOptions options;
  options.model = "gt";
  auto model = make_mapping(options);
  model->fit(pairs);
  return model;
}

TEST(ModelEvaluation, ErrorsAgainstTheTruth) {
  const auto model = fitted_gt();
  Eigen::Matrix2Xd points(2, 3);
  points << 1.0, 4.0, 7.0,  //
      2.0, -1.0, 3.0;
  // The model is the truth: zero errors; a truth shifted by 0.3 m: 0.3 m each.
  for (const double e : model_errors(*model, points, similarity))
    EXPECT_NEAR(e, 0.0, 1e-9);
  const GroundTruth shifted = [](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(similarity(p) + Eigen::Vector2d(0.3, 0.0));
  };
  for (const double e : model_errors(*model, points, shifted))
    EXPECT_NEAR(e, 0.3, 1e-9);
}

TEST(ModelEvaluation, BackAndForthOfAnInvertibleModelDoesNotDrift) {
  const auto model = fitted_gt();
  Eigen::Matrix2Xd points(2, 50);
  for (int i = 0; i < 50; ++i)
    points.col(i) << 0.2 * i, 1.0 + 0.1 * i;
  const BackAndForth drift = back_and_forth(*model, points, 100, 20);
  EXPECT_EQ(drift.points, 20u);
  EXPECT_EQ(drift.not_invertible, 0u);
  EXPECT_LT(drift.max_m, 1e-9);
  EXPECT_LE(drift.min_m, drift.mean_m);
  EXPECT_LE(drift.mean_m, drift.max_m);
}

TEST(ModelEvaluation, HistogramBinsOfFiveCentimetresAndAnOverflowBin) {
  const std::vector<std::size_t> h =
      error_histogram({0.0, 0.01, 0.049, 0.05, 0.12, 0.99, 1.0, 7.0});
  ASSERT_EQ(h.size(), 21u);
  EXPECT_EQ(h[0], 3u);   // [0, 0.05)
  EXPECT_EQ(h[1], 1u);   // [0.05, 0.10)
  EXPECT_EQ(h[2], 1u);   // [0.10, 0.15)
  EXPECT_EQ(h[19], 1u);  // [0.95, 1.0)
  EXPECT_EQ(h[20], 2u);  // 1.0 m and more
}

TEST(Overlay, ThePlanIsDrawnWhereTheMappingPutsIt) {
  GridGeometry g;
  g.width = 60;
  g.height = 40;
  g.resolution = 0.1;
  OccupancyGrid grid(g, CellState::free);
  grid.set_state(5, 5, CellState::occupied);
  RgbImage picture = grid_picture(grid);
  const auto pixel = [&](int ix, int iy) {
    const std::size_t i = 3 * (static_cast<std::size_t>(g.image_row(iy)) * g.width + ix);
    return Colour{picture.rgb[i], picture.rgb[i + 1], picture.rgb[i + 2]};
  };
  EXPECT_EQ(pixel(5, 5), (Colour{0, 0, 0}));
  EXPECT_EQ(pixel(6, 5), (Colour{255, 255, 255}));
  // A wall at plan y = 1, x in [0, 3], mapped 2 m to the right: red on grid row y = 1.05
  // (cell 10), columns 20..50.
  VectorFloorplan plan;
  plan.add_segment({0.0, 1.0}, {3.0, 1.0}, "W");
  draw_plan(
      picture, g, plan,
      [](const Eigen::Vector2d& p) { return Eigen::Vector2d(p + Eigen::Vector2d(2.0, 0.05)); },
      Colour{255, 0, 0});
  for (int ix = 20; ix < 50; ++ix)
    EXPECT_EQ(pixel(ix, 10), (Colour{255, 0, 0})) << ix;
  EXPECT_EQ(pixel(15, 10), (Colour{255, 255, 255}));
  EXPECT_EQ(pixel(30, 20), (Colour{255, 255, 255}));
}

}  // namespace
}  // namespace floorgrid
