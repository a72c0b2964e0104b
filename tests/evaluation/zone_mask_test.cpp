// Zones drawn on the plan, mapped onto the gridmap as nav2 masks, against the simulator's exact
// warp: the mask at margin 0 against the zone drawn through the truth (IoU), and containment of
// the true zone at the default margin, on a plain and a bent office; a known similarity to the
// cell; zones off the gridmap; speed values.
#include "floorgrid/evaluation/zone_mask.hpp"

#include <gtest/gtest.h>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/random.hpp"
#include "floorgrid/mapping/fit_with_uncertainty.hpp"
#include "floorgrid/maps/layer_filter.hpp"
#include "floorgrid/simulation/simulator.hpp"

namespace floorgrid {
namespace {

/// A dataset and a model fitted on it the way `align` ends: laser-like pairs along the plan's
/// walls (every 0.25 m, grid side from the exact warp plus 2 cm of noise), gp, with its
/// blocked cross-validated error model (std_m). (tps fits these pairs as closely, but its std_m
/// underestimates its error inside the bent office's rotated room, 7 cm against a std_m of
/// 1.3 cm 1.3 m from the nearest pair: 2 true cells of the L-shaped zone fell outside its K = 2
/// mask. gp's std_m grows there.)
struct Fitted {
  SimulatedDataset data;
  std::unique_ptr<PointMapping> model;
};

Fitted fit(const std::string& preset, const std::string& model = "gp") {
  Fitted f{simulate(preset, 1), nullptr};
  const PlanTruth truth = f.data.truth();
  const Eigen::Matrix2Xd walls = filter_layers(f.data.plan, {{"WALLS"}, {}}).sample_points(0.25);
  ReferencePairs pairs;
  pairs.points_in_plan = walls;
  pairs.points_in_grid = truth.plan_to_grid_batch(walls);
  Random random(7);
  for (Eigen::Index i = 0; i < pairs.size(); ++i)
    pairs.points_in_grid.col(i) += Eigen::Vector2d(random.normal(0.02), random.normal(0.02));
  MappingOptions options;
  options.model = model;
  f.model = make_mapping(options);
  fit_with_uncertainty(*f.model, options, pairs, CrossValidationOptions{});
  return f;
}

const Fitted& office() {
  static const Fitted f = fit("office");
  return f;
}
/// The office with a gt model (cheap), for the tests that do not measure against the truth.
const Fitted& office_gt() {
  static const Fitted f = fit("office", "gt");
  return f;
}
const Fitted& bent_office() {
  static const Fitted f = fit("bent-office");
  return f;
}

/// Three zones inside the building (plan metres, from its walls' bounds): a rectangle, an
/// L-shape and a square with a square hole, each a few metres across.
std::vector<Zone> zones_in(const SimulatedDataset& d) {
  Eigen::AlignedBox2d box;
  const Eigen::Matrix2Xd walls = d.plan.sample_points(1.0);
  for (Eigen::Index i = 0; i < walls.cols(); ++i)
    box.extend(Eigen::Vector2d(walls.col(i)));
  const auto at = [&](double u, double v) {
    return Eigen::Vector2d(box.min() + Eigen::Vector2d(u, v).cwiseProduct(box.sizes()));
  };
  Zone rectangle;
  rectangle.name = "loading bay";
  rectangle.outer = {at(0.15, 0.2), at(0.3, 0.2), at(0.3, 0.6), at(0.15, 0.6)};
  Zone l_shape;
  l_shape.name = "clean room";
  l_shape.index = 1;
  l_shape.outer = {at(0.55, 0.25), at(0.8, 0.25), at(0.8, 0.4),
                   at(0.65, 0.4),  at(0.65, 0.7), at(0.55, 0.7)};
  Zone ring;
  ring.name = "pillar ring";
  ring.index = 2;
  ring.outer = {at(0.35, 0.55), at(0.5, 0.55), at(0.5, 0.85), at(0.35, 0.85)};
  ring.holes = {{at(0.4, 0.65), at(0.45, 0.65), at(0.45, 0.75), at(0.4, 0.75)}};
  return {rectangle, l_shape, ring};
}

/// The zone drawn through the exact warp: its rings densified (1 cm) and mapped, rasterized by
/// the same cell-centre rule.
CellMask truth_cells(const SimulatedDataset& d, const Zone& zone) {
  const PlanTruth truth = d.truth();
  std::vector<Eigen::Matrix2Xd> rings{truth.plan_to_grid_batch(densify_ring(zone.outer, 0.01))};
  for (const Ring& hole : zone.holes)
    rings.push_back(truth.plan_to_grid_batch(densify_ring(hole, 0.01)));
  return rasterize_rings(rings, d.gridmap.geometry());
}

CellMask zone_cells(const ZoneMask& mask) {
  CellMask cells(mask.mask.geometry());
  for (std::size_t i = 0; i < cells.cells.size(); ++i)
    cells.cells[i] = mask.mask.values()[i] == kOccupancyOccupied;
  return cells;
}

void check_against_truth(const Fitted& f) {
  for (const Zone& zone : zones_in(f.data)) {
    const CellMask truth = truth_cells(f.data, zone);
    ASSERT_GT(truth.count(), 2000u) << describe(zone);
    ZoneMaskOptions exact;
    exact.margin_sigma = 0.0;
    const ZoneMask at_zero = map_zones_to_mask(*f.model, {zone}, f.data.gridmap.geometry(),
                                               ZoneMaskKind::keepout, exact);
    const double iou = intersection_over_union(zone_cells(at_zero), truth);
    EXPECT_GE(iou, 0.95) << describe(zone);
    const ZoneMask widened =
        map_zones_to_mask(*f.model, {zone}, f.data.gridmap.geometry(), ZoneMaskKind::keepout);
    ASSERT_TRUE(widened.zones[0].has_std) << "the model states std_m";
    const CellMask cells = zone_cells(widened);
    std::size_t missed = 0;
    for (std::size_t i = 0; i < truth.cells.size(); ++i)
      missed += truth.cells[i] && !cells.cells[i];
    EXPECT_EQ(missed, 0u) << describe(zone) << ": true cells outside the mask at K = 2";
    // The margin costs area, but not much: the mask stays within a few cells of the zone.
    EXPECT_LT(cells.count(), 1.5 * truth.count()) << describe(zone);
    std::printf(
        "%s: IoU %.4f at margin 0; margin %.3f m, %zu of %zu true cells outside the "
        "mask at K = 2 (mask %zu cells)\n",
        describe(zone).c_str(), iou, 2 * widened.zones[0].max_std_m, missed, truth.count(),
        cells.count());
  }
}

TEST(ZoneMask, OfficeZonesMatchTheTruthAndTheMarginContainsThem) {
  check_against_truth(office());
}

TEST(ZoneMask, BentOfficeZonesMatchTheTruthAndTheMarginContainsThem) {
  check_against_truth(bent_office());
}

TEST(ZoneMask, AZoneWhollyOffTheGridmapIsRefusedAPartlyOffOneClipped) {
  const Fitted& f = office_gt();
  const GridGeometry& g = f.data.gridmap.geometry();
  Zone far;
  far.name = "far away";
  const Eigen::Vector2d c = f.model->inverse(g.bounds().max()).point + Eigen::Vector2d(500, 500);
  far.outer = {c, c + Eigen::Vector2d(2, 0), c + Eigen::Vector2d(2, 2)};
  try {
    map_zones_to_mask(*f.model, {far}, g, ZoneMaskKind::keepout);
    FAIL() << "a zone off the gridmap was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("zone 0 'far away' lies wholly off the gridmap"),
              std::string::npos)
        << e.what();
  }
  // Half in: a zone around the gridmap's lower-left corner.
  const Eigen::Vector2d corner = f.model->inverse(g.cell_center(0, 0)).point;
  Zone half;
  half.name = "corner";
  half.outer = {corner - Eigen::Vector2d(2, 2), corner + Eigen::Vector2d(2, -2),
                corner + Eigen::Vector2d(2, 2), corner + Eigen::Vector2d(-2, 2)};
  const ZoneMask mask = map_zones_to_mask(*f.model, {half}, g, ZoneMaskKind::keepout);
  EXPECT_TRUE(mask.zones[0].clipped);
  EXPECT_GT(mask.zones[0].cells, 0u);
  ASSERT_FALSE(mask.warnings.empty());
  EXPECT_NE(mask.warnings[0].find("clipped"), std::string::npos) << mask.warnings[0];
}

TEST(ZoneMask, SpeedZonesCarryTheirValueAndTheSlowestWinsWhereTheyOverlap) {
  const Fitted& f = office_gt();
  std::vector<Zone> zones = zones_in(f.data);
  zones[0].speed.percent = 40.0;
  zones[1].speed.percent = 70.0;
  zones[2].speed.percent = 25.0;
  // A fourth zone over the first's middle, faster: the first's 40 stays.
  Zone over = zones[0];
  over.index = 3;
  over.name = "over";
  over.speed.percent = 90.0;
  zones.push_back(over);
  const ZoneMask mask =
      map_zones_to_mask(*f.model, zones, f.data.gridmap.geometry(), ZoneMaskKind::speed);
  EXPECT_EQ(mask.filter.type, 1);
  EXPECT_EQ(mask.filter.base, 0.0);
  EXPECT_EQ(mask.filter.multiplier, 1.0);
  std::map<int, std::size_t> counts;
  for (const std::int8_t v : mask.mask.values())
    ++counts[v];
  EXPECT_GT(counts[40], 1000u);
  EXPECT_GT(counts[70], 1000u);
  EXPECT_GT(counts[25], 1000u);
  EXPECT_EQ(counts.count(90), 0u) << "the faster zone over the slower one must not win";
  EXPECT_GT(counts[0], counts[40]) << "no limit outside the zones";
  // In m/s: type 2, multiplier max(0.01, fastest / 100).
  for (Zone& z : zones) {
    z.speed.metres_per_second = *z.speed.percent / 100.0;
    z.speed.percent.reset();
  }
  const Nav2FilterInfo info = filter_info_for(zones, ZoneMaskKind::speed, "zones");
  EXPECT_EQ(info.type, 2);
  EXPECT_DOUBLE_EQ(info.multiplier, 0.01);
  zones[1].speed.metres_per_second.reset();
  EXPECT_THROW(filter_info_for(zones, ZoneMaskKind::speed, "zones"), InputError);
}

TEST(ZoneMask, RefusesBadOptions) {
  const Fitted& f = office_gt();
  ZoneMaskOptions options;
  options.margin_sigma = -1;
  try {
    map_zones_to_mask(*f.model, zones_in(f.data), f.data.gridmap.geometry(), ZoneMaskKind::keepout,
                      options);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "zones.margin_sigma");
  }
}

}  // namespace
}  // namespace floorgrid
