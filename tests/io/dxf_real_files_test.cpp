// DXF reader on real files written by AutoCAD (../shared/data/dxf, see its README), checked
// against ezdxf reading the same files and against what the README says they hold.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "tests/io/dxf_test_support.hpp"

namespace floorgrid::test {
namespace {

bool has_warning(const io::DxfReport& report, const std::string& a, const std::string& b) {
  return std::any_of(report.warnings.begin(), report.warnings.end(), [&](const std::string& w) {
    return w.find(a) != w.npos && w.find(b) != w.npos;
  });
}

/// Compares everything ezdxf can tell about the file with what we read.
void expect_matches_ezdxf(const std::filesystem::path& path, const io::DxfFloorplan& read) {
  const nlohmann::json dump = ezdxf_dump(path, true);
  const double k = read.report.metres_per_unit;
  expect_same_counts(read.report, dump);
  // SOLID/TRACE outlines come as point rings: exact, hence the tiny curve tolerance.
  expect_same_geometry(read.plan, dump, k, 1e-9, 1e-9);
  const nlohmann::json& extent = dump.at("extent");
  ASSERT_TRUE(extent.is_array());
  EXPECT_NEAR(read.report.extent_m.min().x(), extent[0].get<double>() * k, 1e-9);
  EXPECT_NEAR(read.report.extent_m.min().y(), extent[1].get<double>() * k, 1e-9);
  EXPECT_NEAR(read.report.extent_m.max().x(), extent[2].get<double>() * k, 1e-9);
  EXPECT_NEAR(read.report.extent_m.max().y(), extent[3].get<double>() * k, 1e-9);
  std::map<std::string, std::size_t> annotation;
  for (const auto& [type, n] : dump.at("annotation").items()) {
    annotation[type] = n.get<std::size_t>();
  }
  std::map<std::string, std::size_t> ours = read.report.annotation_skipped;
  ours.erase("ATTDEF");  // block attribute templates: ezdxf's virtual_entities() leaves them out
  EXPECT_EQ(ours, annotation);
  EXPECT_EQ(read.report.paper_space_skipped, dump.at("paper_space").get<std::size_t>());
}

TEST(DxfRealFiles, HouseFloorplanHeaderSaysMillimetresButReadsAsInches) {
  FLOORGRID_REQUIRE_DATA("dxf/house_floorplan_r2004.dxf");
  const auto path = data_path("dxf/house_floorplan_r2004.dxf");
  const io::DxfFloorplan read = io::read_dxf(path);
  EXPECT_EQ(read.report.version, "AC1018");
  EXPECT_EQ(read.report.header_units, "mm");
  EXPECT_EQ(read.report.units_used, "in");
  EXPECT_DOUBLE_EQ(read.report.metres_per_unit, 0.0254);
  EXPECT_TRUE(has_warning(read.report, "mm", "reads as in")) << read.report.units_reason;
  // Its 63 feet-inch dimension texts, 10 door swings and 4-inch walls all say inches.
  EXPECT_EQ(read.report.units_source, "header_overruled");
  EXPECT_EQ(read.report.units_confidence, "high");
  EXPECT_NE(read.report.units_reason.find("63 of 63 dimension texts fit (3'-1\" for 37 units)"),
            std::string::npos)
      << read.report.units_reason;
  EXPECT_NE(read.report.units_reason.find("10 door swings 0.61-0.914 m wide"), std::string::npos)
      << read.report.units_reason;
  ASSERT_FALSE(read.report.unit_candidates.empty());
  EXPECT_EQ(read.report.unit_candidates.front().unit, PlanUnit::in);
  EXPECT_GT(read.report.unit_candidates.front().probability, 0.999);
  // A house: its walls span 22.0 x 14.5 m (dimensions and notes reach 24.5 x 23.9 m, the
  // header's $EXTMIN/$EXTMAX, but they are not geometry).
  EXPECT_NEAR(read.report.extent_m.sizes().x(), 22.0, 0.1);
  EXPECT_NEAR(read.report.extent_m.sizes().y(), 14.5, 0.1);
  EXPECT_GT(read.report.entities_by_type.at("LINE"), 600u);
  // The bound-xref layers can be selected by their own names.
  const bool has_xref_layer =
      std::any_of(read.report.entities_by_layer.begin(), read.report.entities_by_layer.end(),
                  [](const auto& entry) { return entry.first.find("$0$") != std::string::npos; });
  EXPECT_TRUE(has_xref_layer);
  if (ezdxf_available()) {
    expect_matches_ezdxf(path, read);
  }
}

TEST(DxfRealFiles, HouseFloorplanWallsByBoundXrefLayerName) {
  FLOORGRID_REQUIRE_DATA("dxf/house_floorplan_r2004.dxf");
  io::DxfReadOptions options;
  options.include_layers = {"a-wall*"};
  const io::DxfFloorplan read = io::read_dxf(data_path("dxf/house_floorplan_r2004.dxf"), options);
  ASSERT_FALSE(read.report.entities_by_layer.empty());
  for (const auto& [layer, types] : read.report.entities_by_layer) {
    EXPECT_NE(layer.find("A-WALL"), std::string::npos) << layer;
  }
  EXPECT_GT(read.report.excluded_by_layer_filter, 0u);
  // The door swings on other layers still reveal inches.
  EXPECT_EQ(read.report.units_used, "in");
}

TEST(DxfRealFiles, HouseSiteIsMetresAbout43By33) {
  FLOORGRID_REQUIRE_DATA("dxf/house_site_r2000.dxf");
  const auto path = data_path("dxf/house_site_r2000.dxf");
  const io::DxfFloorplan read = io::read_dxf(path);
  EXPECT_EQ(read.report.version, "AC1015");
  EXPECT_EQ(read.report.header_units, "m");
  EXPECT_EQ(read.report.units_used, "m");
  EXPECT_NEAR(read.report.extent_m.sizes().x(), 43.1, 0.05);
  EXPECT_NEAR(read.report.extent_m.sizes().y(), 32.6, 0.05);
  EXPECT_FALSE(has_warning(read.report, "INSUNITS", "reads as"));
  EXPECT_EQ(read.report.units_source, "header");
  EXPECT_EQ(read.report.units_confidence, "high");  // three door swings of 0.85 m, 0.25 m walls
  EXPECT_GT(read.report.inserts_expanded, 0u);
  if (ezdxf_available()) {
    expect_matches_ezdxf(path, read);  // with mirrored INSERTs
  }
}

TEST(DxfRealFiles, SampleR12ReadsOldStylePolylinesAndInserts) {
  FLOORGRID_REQUIRE_DATA("dxf/sample_r12_ascii.dxf");
  const auto path = data_path("dxf/sample_r12_ascii.dxf");
  const io::DxfFloorplan read = io::read_dxf(path);
  EXPECT_EQ(read.report.version, "AC1009");
  EXPECT_EQ(read.report.header_units, "none");
  EXPECT_GT(read.report.entities_by_type.at("POLYLINE"), 0u);
  EXPECT_GT(read.report.inserts_expanded, 0u);
  EXPECT_FALSE(read.report.units_reason.empty());
  // An AutoCAD test drawing, not a building: whatever the guess, it is said to be one. Its one
  // dimension text (4'-0 1#4" for 48.36 units) and its spacing of parallel lines hint at inches.
  EXPECT_EQ(read.report.units_source, "guessed");
  EXPECT_EQ(read.report.units_used, "in");
  EXPECT_NE(read.report.units_confidence, "high");
  EXPECT_TRUE(has_warning(read.report, "no $INSUNITS", "guessed")) << read.report.units_reason;
  EXPECT_GT(read.report.unit_candidates.size(), 1u);
  if (ezdxf_available()) {
    expect_matches_ezdxf(path, read);
  }
}

TEST(DxfRealFiles, BinaryR2018IsRefusedClearly) {
  FLOORGRID_REQUIRE_DATA("dxf/sample_r2018_binary.dxf");
  const auto path = data_path("dxf/sample_r2018_binary.dxf");
  ASSERT_EQ(read_file(path).substr(0, 22), std::string("AutoCAD Binary DXF\r\n\x1a\0", 22));
  try {
    io::read_dxf(path);
    FAIL() << "binary DXF was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string());
    EXPECT_NE(e.message().find("binary DXF is not supported; save as ASCII DXF"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace floorgrid::test
