// DXF writer: what it writes reads back the same through our reader, through ezdxf and through
// libdime (three independent readers), and it writes atomically.

#include "floorgrid/io/plans/dxf_writer.hpp"

#include <dime/Input.h>
#include <dime/Model.h>
#include <dime/entities/Line.h>
#include <dime/sections/EntitiesSection.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "tests/io/dxf_test_support.hpp"

namespace floorgrid::test {
namespace {

constexpr double kPi = std::numbers::pi;

/// A plan with awkward numbers: random segments and arcs (some crossing angle 0, some full
/// circles) on three layers, one with a space in its name.
VectorFloorplan random_plan(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0), radius(0.3, 3.0),
      angle(-kPi, kPi), sweep(0.1, 2.0 * kPi - 0.1);
  const char* const layers[] = {"WALLS", "DOORS", "A-WALL 2"};
  VectorFloorplan plan;
  for (int i = 0; i < 40; ++i) {
    plan.add_segment({coordinate(rng), coordinate(rng)}, {coordinate(rng), coordinate(rng)},
                     layers[i % 3]);
  }
  for (int i = 0; i < 12; ++i) {
    const double start = angle(rng);
    const double end = i % 5 == 4 ? start : start + sweep(rng);  // equal: full circle
    plan.add_arc({coordinate(rng), coordinate(rng)}, radius(rng), start, end, layers[i % 3]);
  }
  return plan;
}

/// Counts per layer and DXF type that writing `plan` must give.
std::map<std::string, std::map<std::string, std::size_t>> expected_counts(
    const VectorFloorplan& plan) {
  std::map<std::string, std::map<std::string, std::size_t>> counts;
  for (const Segment& s : plan.segments()) {
    ++counts[plan.layers()[s.layer]]["LINE"];
  }
  for (const Arc& a : plan.arcs()) {
    ++counts[plan.layers()[a.layer]][a.end_angle - a.start_angle >= 2 * kPi ? "CIRCLE" : "ARC"];
  }
  return counts;
}

TEST(DxfWriter, RoundTripsThroughOurReader) {
  TempDir dir;
  const VectorFloorplan plan = random_plan(1);
  io::write_dxf(plan, dir / "plan.dxf");
  const io::DxfFloorplan read = io::read_dxf(dir / "plan.dxf", metres());
  EXPECT_EQ(read.report.entities_by_layer, expected_counts(plan));
  ASSERT_EQ(read.plan.segments().size(), plan.segments().size());
  for (std::size_t i = 0; i < plan.segments().size(); ++i) {  // 17 digits: bit-exact doubles
    EXPECT_EQ(read.plan.segments()[i].a, plan.segments()[i].a);
    EXPECT_EQ(read.plan.segments()[i].b, plan.segments()[i].b);
  }
  ASSERT_EQ(read.plan.arcs().size(), plan.arcs().size());
  for (std::size_t i = 0; i < plan.arcs().size(); ++i) {
    const Arc& want = plan.arcs()[i];
    const Arc& got = read.plan.arcs()[i];
    EXPECT_EQ(got.center, want.center);
    EXPECT_EQ(got.radius, want.radius);
    EXPECT_NEAR(got.end_angle - got.start_angle, want.end_angle - want.start_angle, 1e-12);
    if (want.end_angle - want.start_angle >= 2 * kPi) {
      continue;  // a CIRCLE has no start point
    }
    EXPECT_LT((got.point_at(got.start_angle) - want.point_at(want.start_angle)).norm(), 1e-9);
    EXPECT_LT((got.point_at(got.end_angle) - want.point_at(want.end_angle)).norm(), 1e-9);
  }
}

TEST(DxfWriter, EzdxfReadsTheSameEntitiesCoordinatesHeaderAndLayers) {
  FLOORGRID_REQUIRE_EZDXF();
  TempDir dir;
  const VectorFloorplan plan = random_plan(2);
  io::DxfWriteOptions options;
  options.header_units = "cm";
  options.units_per_metre = 100.0;
  io::write_dxf(plan, dir / "plan.dxf", options);
  const nlohmann::json dump = ezdxf_dump(dir / "plan.dxf", false);
  EXPECT_EQ(dump.at("version"), "AC1009");
  EXPECT_EQ(dump.at("insunits"), 5);
  std::map<std::string, std::map<std::string, std::size_t>> counts;
  for (const auto& [layer, types] : dump.at("counts_by_layer").items()) {
    for (const auto& [type, n] : types.items()) {
      counts[layer][type] = n.get<std::size_t>();
    }
  }
  EXPECT_EQ(counts, expected_counts(plan));
  expect_same_geometry(plan, dump, 0.01, 1e-9);
  const Eigen::AlignedBox2d bounds = plan.bounds();
  EXPECT_NEAR(vec(dump.at("extmin")).x(), bounds.min().x() * 100.0, 1e-9);
  EXPECT_NEAR(vec(dump.at("extmin")).y(), bounds.min().y() * 100.0, 1e-9);
  EXPECT_NEAR(vec(dump.at("extmax")).x(), bounds.max().x() * 100.0, 1e-9);
  EXPECT_NEAR(vec(dump.at("extmax")).y(), bounds.max().y() * 100.0, 1e-9);
  for (const std::string& layer : plan.layers()) {
    const auto& names = dump.at("layers");
    EXPECT_NE(std::find(names.begin(), names.end(), layer), names.end()) << layer;
  }
}

TEST(DxfWriter, LibdimeReadsTheOutputToFloatPrecision) {
  TempDir dir;
  const VectorFloorplan plan = random_plan(3);
  io::write_dxf(plan, dir / "plan.dxf");
  dimeInput input;
  ASSERT_TRUE(input.setFile((dir / "plan.dxf").c_str()));
  dimeModel model;
  ASSERT_TRUE(model.read(&input));
  auto* entities = static_cast<dimeEntitiesSection*>(model.findSection("ENTITIES"));
  ASSERT_NE(entities, nullptr);
  std::map<std::string, std::size_t> by_type;
  std::size_t line = 0;
  for (int i = 0; i < entities->getNumEntities(); ++i) {
    dimeEntity* e = entities->getEntity(i);
    ++by_type[e->getEntityName()];
    if (e->typeId() != dimeBase::dimeLineType) {
      continue;
    }
    const auto* l = static_cast<dimeLine*>(e);
    const Segment& want = plan.segments()[line++];
    // libdime keeps coordinates as float: about 7 significant digits.
    EXPECT_NEAR(l->getCoords(0).x, want.a.x(), 1e-5);
    EXPECT_NEAR(l->getCoords(1).y, want.b.y(), 1e-5);
  }
  std::map<std::string, std::size_t> expected;
  for (const auto& [layer, types] : expected_counts(plan)) {
    for (const auto& [type, n] : types) {
      expected[type] += n;
    }
  }
  EXPECT_EQ(by_type, expected);
}

TEST(DxfWriter, HeaderCanClaimMillimetresWhileDrawingInInches) {
  TempDir dir;
  // A 20 x 12 m office outline with door swings, as the simulator's office-inches preset needs.
  VectorFloorplan plan;
  plan.add_segment({0, 0}, {20, 0}, "WALLS");
  plan.add_segment({20, 0}, {20, 12}, "WALLS");
  plan.add_segment({20, 12}, {0, 12}, "WALLS");
  plan.add_segment({0, 12}, {0, 0}, "WALLS");
  for (int i = 0; i < 6; ++i) {
    plan.add_arc({2.0 + 3.0 * i, 6.0}, 0.9, 0.0, kPi / 2, "DOORS");
  }
  io::DxfWriteOptions options;
  options.header_units = "mm";
  options.units_per_metre = 1.0 / 0.0254;
  io::write_dxf(plan, dir / "office.dxf", options);

  const io::DxfFloorplan read = io::read_dxf(dir / "office.dxf");
  EXPECT_EQ(read.report.header_units, "mm");
  EXPECT_EQ(read.report.units_used, "in");
  EXPECT_FALSE(read.report.warnings.empty());
  ASSERT_EQ(read.plan.segments().size(), 4u);
  EXPECT_LT((read.plan.segments()[1].b - Eigen::Vector2d(20, 12)).norm(), 1e-9);
  ASSERT_EQ(read.plan.arcs().size(), 6u);
  EXPECT_NEAR(read.plan.arcs()[5].radius, 0.9, 1e-9);
  if (ezdxf_available()) {
    const nlohmann::json dump = ezdxf_dump(dir / "office.dxf", false);
    EXPECT_EQ(dump.at("insunits"), 4);
    expect_same_geometry(plan, dump, 0.0254, 1e-9);  // the coordinates really are inches
  }
}

TEST(DxfWriter, WritesAtomicallyAndValidatesOptionsFirst) {
  TempDir dir;
  const VectorFloorplan plan = random_plan(4);
  io::write_dxf(plan, dir / "plan.dxf");
  io::write_dxf(plan, dir / "plan.dxf");  // replacing works
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "plan.dxf");  // no temporary left behind
  }
  EXPECT_EQ(files, 1u);
  const std::string before = read_file(dir / "plan.dxf");

  io::DxfWriteOptions bad;
  bad.header_units = "furlong";
  try {
    io::write_dxf(VectorFloorplan(), dir / "plan.dxf", bad);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "header_units");
  }
  bad = {};
  bad.units_per_metre = std::nan("");
  EXPECT_THROW(io::write_dxf(plan, dir / "plan.dxf", bad), InputError);
  EXPECT_EQ(read_file(dir / "plan.dxf"), before);  // untouched by the failed writes
  EXPECT_THROW(io::write_dxf(plan, dir / "no-such-folder" / "plan.dxf"), InputError);
}

}  // namespace
}  // namespace floorgrid::test
