// Open-RMF traffic-editor layer: the transform of a known similarity, by hand.
#include "floorgrid/io/export/export_rmf.hpp"

#include <gtest/gtest.h>

#include "floorgrid/core/error.hpp"
#include "tests/io/export_test_support.hpp"

namespace floorgrid {
namespace {

using test::KnownSimilarity;

/// traffic-editor's Transform::forwards: layer pixel -> level metres (y down).
Eigen::Vector2d forwards(const io::RmfLayerTransform& t, const Eigen::Vector2d& p) {
  return {(std::cos(t.yaw) * p.x() + std::sin(t.yaw) * p.y()) * t.scale + t.translation_x,
          (-std::sin(t.yaw) * p.x() + std::cos(t.yaw) * p.y()) * t.scale + t.translation_y};
}

/// The gridmap: 400 x 300 pixels of 0.05 m, origin (-5, -3).
io::MapRaster gridmap() {
  io::MapRaster g;
  g.image = "gridmap.pgm";
  g.geometry.width = 400;
  g.geometry.height = 300;
  g.geometry.resolution = 0.05;
  g.geometry.origin = {-5.0, -3.0, 0.0};
  return g;
}

/// The plan raster: 200 x 100 pixels of 0.1 m, origin (0, 0).
GridGeometry plan_raster() {
  GridGeometry p;
  p.width = 200;
  p.height = 100;
  p.resolution = 0.1;
  return p;
}

TEST(ExportRmf, LayerTransformOfAKnownSimilarityByHand) {
  // grid = 2 R(90 deg) plan + (1, 2).
  const KnownSimilarity truth{2.0, M_PI / 2, {1.0, 2.0}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 16, 0, 8));
  const io::RmfLayer layer =
      io::rmf_layer(*model, Eigen::Matrix2Xd(2, 0), gridmap(), plan_raster(), "gridmap.pgm");
  // The layer's top-left corner: grid (-5, -3 + 300 x 0.05) = (-5, 12); plan R(-90) (-6, 10) / 2
  // = (5, 3); plan pixel (50, 100 - 30) = (50, 70); level metres 0.1 x that = (5, 7).
  EXPECT_NEAR(layer.transform.translation_x, 5.0, 1e-9);
  EXPECT_NEAR(layer.transform.translation_y, 7.0, 1e-9);
  // A gridmap pixel is 0.05 grid m = 0.025 plan m = 0.025 level m.
  EXPECT_NEAR(layer.transform.scale, 0.025, 1e-12);
  // The layer's +x (grid +x) is plan -y, level +y (down): forwards((1, 0)) = s (cos, -sin)
  // = s (0, 1), so yaw = -90 deg.
  EXPECT_NEAR(layer.transform.yaw, -M_PI / 2, 1e-12);
  EXPECT_TRUE(layer.similarity.exact);
  EXPECT_NE(layer.text.find("layers:\n  robot_map:\n    filename: \"gridmap.pgm\"\n"),
            std::string::npos)
      << layer.text;
  EXPECT_NE(layer.text.find("transform: {scale: 0.025"), std::string::npos) << layer.text;
  // Any layer pixel lands where the chain grid -> plan -> plan pixel puts it.
  for (const Eigen::Vector2d& pixel : {Eigen::Vector2d(13.5, 250.25), Eigen::Vector2d(400, 0)}) {
    const Eigen::Vector2d grid(-5.0 + 0.05 * pixel.x(), -3.0 + 0.05 * (300 - pixel.y()));
    const Eigen::Vector2d plan = rotation_2d(-M_PI / 2) * (grid - truth.t) / 2.0;
    const Eigen::Vector2d level(plan.x(), 0.1 * (100 - plan.y() / 0.1));
    EXPECT_LT((forwards(layer.transform, pixel) - level).norm(), 1e-9) << pixel.transpose();
  }
}

TEST(ExportRmf, DxfLevelIsPlanMetresWithYFlipped) {
  const KnownSimilarity truth{2.0, M_PI / 2, {1.0, 2.0}};
  const auto model = test::fitted("gt", test::lattice_pairs(truth, 0, 16, 0, 8));
  const io::RmfLayer layer =
      io::rmf_layer(*model, Eigen::Matrix2Xd(2, 0), gridmap(), std::nullopt, "g.pgm");
  // The top-left corner at plan (5, 3): level (5, -3).
  EXPECT_NEAR(layer.transform.translation_x, 5.0, 1e-9);
  EXPECT_NEAR(layer.transform.translation_y, -3.0, 1e-9);
  EXPECT_NEAR(layer.transform.scale, 0.025, 1e-12);
  EXPECT_NEAR(layer.transform.yaw, -M_PI / 2, 1e-12);
}

TEST(ExportRmf, NonSimilarityModelsGiveTheirLeastSquaresSimilarityAndItsResidual) {
  const test::BentTruth truth{{1.0, 0.0, {0.0, 0.0}}};
  const ReferencePairs pairs = test::lattice_pairs(truth, 0, 20, 0, 10, 21, 11);
  const auto model = test::fitted("tps", pairs);
  const io::RmfLayer layer =
      io::rmf_layer(*model, pairs.points_in_plan, gridmap(), plan_raster(), "g.pgm");
  EXPECT_FALSE(layer.similarity.exact);
  EXPECT_EQ(layer.similarity.points, static_cast<std::size_t>(pairs.size()));
  EXPECT_GT(layer.similarity.rms_m, 0.05);
  EXPECT_LT(layer.similarity.rms_m, 0.3);
  EXPECT_NEAR(layer.transform.scale, 0.05 / 0.1 * 0.1, 0.002);
  EXPECT_NE(layer.text.find("rms residual"), std::string::npos);
}

TEST(ExportRmf, RefusesAMirroredPlan) {
  const auto mirrored = [](const Eigen::Vector2d& p) { return Eigen::Vector2d(-p.x(), p.y()); };
  const auto model = test::fitted("gt", test::lattice_pairs(mirrored, 0, 16, 0, 8));
  EXPECT_THROW(io::rmf_layer(*model, Eigen::Matrix2Xd(2, 0), gridmap(), plan_raster(), "g.pgm"),
               InputError);
}

}  // namespace
}  // namespace floorgrid
