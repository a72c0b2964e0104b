// A nav2 mask of an old map carried onto a new map through a known similarity: the migrated
// cells are the old zone's cells moved by it, cells off the old mask are unknown, and a keepout
// is widened by K std_m (a speed mask is not).
#include "floorgrid/evaluation/mask_migration.hpp"

#include <gtest/gtest.h>

#include "floorgrid/core/error.hpp"
#include "tests/io/export_test_support.hpp"

namespace floorgrid {
namespace {

using test::KnownSimilarity;

/// The old mask: 100 x 80 cells of 0.05 m from (0, 0), the square [1, 3) x [1, 2) at `value`.
OccupancyGrid old_mask(std::int8_t value = kOccupancyOccupied) {
  GridGeometry g;
  g.width = 100;
  g.height = 80;
  g.resolution = 0.05;
  OccupancyGrid mask(g, CellState::free);
  for (int iy = 20; iy < 40; ++iy)
    for (int ix = 20; ix < 60; ++ix)
      mask.set_cell(ix, iy, CellState::occupied, value);
  return mask;
}

/// The new map: 120 x 100 cells from (-2, -1), yaw 0.
GridGeometry new_grid() {
  GridGeometry g;
  g.width = 120;
  g.height = 100;
  g.resolution = 0.05;
  g.origin = {-2.0, -1.0, 0.0};
  return g;
}

/// old -> new: a shift by (-1.5, 0.5) (whole cells, so the square lands on cells exactly).
std::unique_ptr<PointMapping> shift(std::optional<double> std_m = std::nullopt) {
  auto model =
      test::fitted("gt", test::lattice_pairs(KnownSimilarity{1.0, 0.0, {-1.5, 0.5}}, -1, 6, -1, 5));
  if (std_m) {
    ErrorModel e;
    e.base_std_m = *std_m;
    e.residuals = 50;
    model->set_error_model(e);
  }
  return model;
}

/// Whether the new cell's centre lies in the square moved: [-0.5, 1.5) x [1.5, 2.5).
bool in_moved_square(const GridGeometry& g, int ix, int iy) {
  const Eigen::Vector2d c = g.cell_center(ix, iy);
  return c.x() > -0.5 && c.x() < 1.5 && c.y() > 1.5 && c.y() < 2.5;
}

TEST(MaskMigration, TheZoneMovesWithTheModelAndCellsOffTheOldMaskAreUnknown) {
  const MigratedMask m = migrate_mask(*shift(), old_mask(), new_grid());
  const GridGeometry& g = m.mask.geometry();
  std::size_t zone = 0, unknown = 0;
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const std::int8_t v = m.mask.value(ix, iy);
      // Old cells cover new x in [-1.5, 3.5), y in [0.5, 4.5).
      const Eigen::Vector2d c = g.cell_center(ix, iy);
      const bool on_old = c.x() > -1.5 && c.x() < 3.5 && c.y() > 0.5 && c.y() < 4.5;
      if (!on_old) {
        ASSERT_EQ(v, -1) << ix << ", " << iy;
        ++unknown;
        continue;
      }
      ASSERT_EQ(v, in_moved_square(g, ix, iy) ? 100 : 0) << ix << ", " << iy;
      zone += v == 100;
    }
  }
  EXPECT_EQ(zone, 40u * 20u);
  EXPECT_EQ(m.cells_off_old_mask, unknown);
  EXPECT_EQ(m.cells_not_invertible, 0u);
  EXPECT_FALSE(m.widened);
  ASSERT_FALSE(m.warnings.empty());
  EXPECT_NE(m.warnings[0].find("no std_m"), std::string::npos) << m.warnings[0];
}

TEST(MaskMigration, AKeepoutIsWidenedByKStdMASpeedMaskIsNot) {
  // std_m 0.05 m, K = 2: 0.1 m = 2 cells on every side (corners rounded).
  const MigratedMask m = migrate_mask(*shift(0.05), old_mask(), new_grid());
  EXPECT_TRUE(m.widened);
  const GridGeometry& g = m.mask.geometry();
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const Eigen::Vector2d c = g.cell_center(ix, iy);
      const double dx = std::max({-0.5 - c.x(), c.x() - 1.5, 0.0});
      const double dy = std::max({1.5 - c.y(), c.y() - 2.5, 0.0});
      const double d = std::hypot(dx, dy);  // from the moved square
      if (d < 0.07) {
        ASSERT_EQ(m.mask.value(ix, iy), 100) << ix << ", " << iy << " d " << d;
      }
      if (d > 0.13) {
        ASSERT_NE(m.mask.value(ix, iy), 100) << ix << ", " << iy << " d " << d;
      }
    }
  }
  const MigratedMask speed = migrate_mask(*shift(0.05), old_mask(40), new_grid());
  EXPECT_FALSE(speed.widened);
  std::size_t forty = 0;
  for (const std::int8_t v : speed.mask.values())
    forty += v == 40;
  EXPECT_EQ(forty, 40u * 20u);
}

TEST(MaskMigration, WithoutANewMapTheGridIsTheOldMasksOutlineMoved) {
  const GridGeometry g = migrated_geometry(*shift(), old_mask().geometry());
  EXPECT_DOUBLE_EQ(g.resolution, 0.05);
  EXPECT_NEAR(g.origin.x, -1.5, 1e-9);
  EXPECT_NEAR(g.origin.y, 0.5, 1e-9);
  EXPECT_EQ(g.width, 100);
  EXPECT_EQ(g.height, 80);
  MaskMigrationOptions bad;
  bad.margin_sigma = 11;
  EXPECT_THROW(migrate_mask(*shift(), old_mask(), g, bad), InputError);
}

}  // namespace
}  // namespace floorgrid
