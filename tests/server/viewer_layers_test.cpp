// The viewer's layers of a dataset: the plan's walls drawn through the model on the gridmap's
// pixels (where a known similarity puts them), and heat maps on the plan's pixels without a
// colour bar, the error map first when the dataset has a truth.
#include "floorgrid/server/viewer_layers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/maps/rasterize.hpp"
#include "tests/support/simulated_room.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid::server {
namespace {

/// Plan to grid: scale 1.1, turned by 0.2 rad, shifted.
Eigen::Vector2d similarity(const Eigen::Vector2d& p) {
  return 1.1 * Eigen::Rotation2Dd(0.2).toRotationMatrix() * p + Eigen::Vector2d(-3.0, 2.0);
}

/// The room as a dataset: the plan, and a gridmap of the room moved by the similarity.
std::shared_ptr<io::LoadedDataset> room_dataset(bool with_truth) {
  auto d = std::make_shared<io::LoadedDataset>();
  const VectorFloorplan room = test::asymmetric_room();
  d->plan = room;
  d->plan_grid = test::room_grid(room);
  d->plan_wall_samples = room.sample_points(0.05);
  VectorFloorplan moved;
  for (const auto& s : room.segments())
    moved.add_segment(similarity(s.a), similarity(s.b), "WALLS");
  d->gridmap = test::room_grid(moved);
  if (with_truth) {
    ReferencePairs truth;
    truth.points_in_plan.resize(2, 4);
    truth.points_in_grid.resize(2, 4);
    const Eigen::Vector2d corners[] = {{0.5, 0.5}, {11.5, 0.5}, {0.5, 7.5}, {9.5, 7.5}};
    for (int i = 0; i < 4; ++i) {
      truth.points_in_plan.col(i) = corners[i];
      truth.points_in_grid.col(i) = similarity(corners[i]);
    }
    d->manual_pairs = truth;
  }
  return d;
}

std::shared_ptr<const PointMapping> similarity_model() {
  Eigen::Matrix2Xd points(2, 12);
  for (int i = 0; i < 12; ++i)
    points.col(i) = Eigen::Vector2d(1.0 * i, 0.7 * (i % 5));
  return test::fitted("gt", test::pairs_through(similarity, points));
}

io::GreyImage decoded(const std::string& png, const std::filesystem::path& file) {
  std::ofstream(file, std::ios::binary) << png;
  return io::read_grey_image(file);
}

TEST(ViewerLayers, TheOverlayDrawsThePlansWallsWhereTheModelPutsThem) {
  const std::shared_ptr<io::LoadedDataset> d = room_dataset(false);
  const ModelLayers layers = dataset_layers(d)(*similarity_model());
  test::TempDir dir;
  const io::GreyImage overlay = decoded(layers.overlay_png, dir / "overlay.png");
  const GridGeometry& g = d->gridmap.geometry();
  ASSERT_EQ(overlay.width, g.width);
  ASSERT_EQ(overlay.height, g.height);
  ASSERT_TRUE(overlay.has_alpha());
  // Every wall point of the plan, moved by the similarity, is drawn (its pixel or a neighbour:
  // the line is drawn through cell centres); and the drawn pixels are the gridmap's walls.
  const auto opaque = [&](int col, int row) {
    return col >= 0 && row >= 0 && col < overlay.width && row < overlay.height &&
           overlay.alpha[static_cast<std::size_t>(row) * overlay.width + col] == 255;
  };
  int missed = 0;
  for (Eigen::Index i = 0; i < d->plan_wall_samples.cols(); ++i) {
    int ix = 0, iy = 0;
    ASSERT_TRUE(g.cell_of(similarity(d->plan_wall_samples.col(i)), ix, iy));
    const int row = g.image_row(iy);
    bool drawn = false;
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc)
        drawn = drawn || opaque(ix + dc, row + dr);
    missed += drawn ? 0 : 1;
  }
  EXPECT_EQ(missed, 0);
  int on_walls = 0, drawn = 0;
  for (int row = 0; row < overlay.height; ++row) {
    for (int col = 0; col < overlay.width; ++col) {
      if (!opaque(col, row))
        continue;
      ++drawn;
      bool wall = false;
      for (int dr = -2; dr <= 2; ++dr)
        for (int dc = -2; dc <= 2; ++dc)
          wall = wall || d->gridmap.is_occupied(col + dc, g.image_row(row) + dr);
      on_walls += wall ? 1 : 0;
    }
  }
  EXPECT_GT(drawn, 100);
  EXPECT_EQ(on_walls, drawn);
}

TEST(ViewerLayers, HeatMapsCoverThePlansPixelsWithoutAColourBar) {
  for (const bool with_truth : {false, true}) {
    const std::shared_ptr<io::LoadedDataset> d = room_dataset(with_truth);
    const ModelLayers layers = dataset_layers(d)(*similarity_model());
    ASSERT_EQ(layers.heat.size(), with_truth ? 2u : 1u);
    EXPECT_EQ(layers.heat.front().kind, with_truth ? "error" : "std");
    EXPECT_EQ(layers.heat.back().kind, "std");
    test::TempDir dir;
    for (const HeatLayer& heat : layers.heat) {
      EXPECT_GT(heat.clip_m, 0.0) << heat.kind;
      const io::GreyImage image = decoded(heat.png, dir / (heat.kind + ".png"));
      EXPECT_EQ(image.width, d->plan_grid.width()) << heat.kind;
      EXPECT_EQ(image.height, d->plan_grid.height()) << heat.kind;
      ASSERT_TRUE(image.has_alpha());
      std::size_t known = 0;
      for (const std::uint8_t a : image.alpha)
        known += a == 255 ? 1 : 0;
      // Some cells are known, not all: the margin around the room is outside every domain.
      EXPECT_GT(known, image.alpha.size() / 10) << heat.kind;
      EXPECT_LT(known, image.alpha.size()) << heat.kind;
    }
  }
}

}  // namespace
}  // namespace floorgrid::server
