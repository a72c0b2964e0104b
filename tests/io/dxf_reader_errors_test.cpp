// DXF reader: bad input fails with InputError naming the file and the line or field, and
// garbage never crashes.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "tests/io/dxf_test_support.hpp"

namespace floorgrid::test {
namespace {

const std::string kLine = "0 LINE\n8 W\n10 0\n20 0\n11 3\n21 4";

/// The InputError that reading `path` throws (fails the test when there is none).
InputError read_error(const std::filesystem::path& path,
                      const io::DxfReadOptions& options = metres()) {
  try {
    io::read_dxf(path, options);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "reading " << path << " did not throw InputError";
  return InputError("none");
}

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "\"" << part << "\" not in: " << text;
}

TEST(DxfReaderErrors, NonexistentFileIsNamed) {
  TempDir dir;
  const InputError e = read_error(dir / "missing.dxf");
  EXPECT_EQ(e.file(), (dir / "missing.dxf").string());
  expect_contains(e.message(), "no such file");
}

TEST(DxfReaderErrors, EmptyAndBlankFilesAreRefused) {
  TempDir dir;
  for (const std::string text : {"", "\n\n  \r\n"}) {
    const auto path = put(dir, text);
    const InputError e = read_error(path);
    EXPECT_EQ(e.file(), path.string());
    expect_contains(e.message(), "empty");
  }
}

TEST(DxfReaderErrors, TruncationInsideEntitiesNamesTheLastLine) {
  TempDir dir;
  const std::string full = dxf_file(kLine + "\n" + kLine);
  // Cut after the first LINE's groups: ENTITIES never ends.
  const std::string cut = full.substr(0, full.find("LINE", full.find("LINE") + 1) - 2);
  const long lines = static_cast<long>(std::count(cut.begin(), cut.end(), '\n'));
  const InputError e = read_error(put(dir, cut));
  expect_contains(e.message(), "ENTITIES");
  expect_contains(e.message(), "truncated");
  EXPECT_EQ(e.line(), lines);
}

TEST(DxfReaderErrors, GroupCodeWithoutValueIsTruncation) {
  TempDir dir;
  // Ends right after a "0" group code: the case that makes libdime 0.20111205 crash.
  const std::string full = dxf_file(kLine);
  const std::string cut = full.substr(0, full.rfind("ENDSEC"));
  const long lines = static_cast<long>(std::count(cut.begin(), cut.end(), '\n'));
  const InputError e = read_error(put(dir, cut));
  expect_contains(e.message(), "no value line");
  EXPECT_EQ(e.line(), lines);
}

TEST(DxfReaderErrors, MissingEofMarkerIsTruncation) {
  TempDir dir;
  std::string text = dxf_file(kLine);
  text = text.substr(0, text.rfind("0\nEOF"));
  const InputError e = read_error(put(dir, text));
  expect_contains(e.message(), "EOF");
  expect_contains(e.message(), "truncated");
}

TEST(DxfReaderErrors, BinaryDxfIsDetectedBeforeParsing) {
  TempDir dir;
  const std::string sentinel("AutoCAD Binary DXF\r\n\x1a\0", 22);
  const auto path = put(dir, sentinel + std::string("\0\x02\0HEADER\0", 10));
  const InputError e = read_error(path);
  EXPECT_EQ(e.file(), path.string());
  expect_contains(e.message(), "binary DXF is not supported");
  expect_contains(e.message(), "ASCII");
}

TEST(DxfReaderErrors, NonNumericGroupCodeNamesItsLine) {
  TempDir dir;
  const std::string text = dxf_file("0 LINE\n8 W\nten 0\n20 0");
  const InputError e = read_error(put(dir, text));
  expect_contains(e.message(), "group code");
  expect_contains(e.message(), "\"ten\"");
  EXPECT_EQ(e.line(), line_of(text, "W") + 2);
}

TEST(DxfReaderErrors, BadNumberNamesTheValueLineAndCode) {
  TempDir dir;
  const std::string text = dxf_file("0 LINE\n8 W\n10 1.5abc\n20 0\n11 1\n21 1");
  const InputError e = read_error(put(dir, text));
  expect_contains(e.message(), "group code 10");
  expect_contains(e.message(), "1.5abc");
  EXPECT_EQ(e.line(), line_of(text, "W") + 3);  // the value line of group 10
  EXPECT_NE(std::string(e.what()).find(":" + std::to_string(e.line()) + ":"), std::string::npos);
}

TEST(DxfReaderErrors, BrokenStructureNamesItsLine) {
  TempDir dir;
  // A block that never ends, and a section holding groups where an entity should start.
  const std::string no_endblk = groups(
      "0 SECTION\n2 BLOCKS\n0 BLOCK\n2 B\n10 0\n20 0\n0 LINE\n8 0\n10 0\n20 0\n11 1\n21 "
      "1\n0 ENDSEC\n0 EOF");
  const InputError a = read_error(put(dir, no_endblk));
  expect_contains(a.message(), "ENDBLK");
  EXPECT_EQ(a.line(), line_of(no_endblk, "ENDSEC"));
  const std::string stray = groups("0 SECTION\n2 ENTITIES\n10 5\n0 ENDSEC\n0 EOF");
  const InputError b = read_error(put(dir, stray));
  expect_contains(b.message(), "expected an entity");
  EXPECT_EQ(b.line(), 5);
  const InputError c = read_error(put(dir, groups("0 LINE\n8 W\n0 EOF")));
  expect_contains(c.message(), "SECTION");
  EXPECT_EQ(c.line(), 1);
}

TEST(DxfReaderErrors, DrawingWithoutGeometryIsAnError) {
  TempDir dir;
  const InputError e =
      read_error(put(dir, dxf_file("0 TEXT\n8 T\n10 0\n20 0\n1 hello\n0 POINT\n8 T\n10 1\n20 1")));
  expect_contains(e.message(), "no geometry");
  expect_contains(e.message(), "2 annotation");
}

TEST(DxfReaderErrors, LayerFiltersLeavingNothingNameTheOption) {
  TempDir dir;
  io::DxfReadOptions options = metres();
  options.include_layers = {"A-WALL"};
  const InputError e = read_error(put(dir, dxf_file(kLine)), options);
  EXPECT_EQ(e.field(), "include_layers");
  expect_contains(e.message(), "1 geometry entities excluded");
}

TEST(DxfReaderErrors, BadOptionsNameTheField) {
  TempDir dir;
  const auto path = put(dir, dxf_file(kLine));
  io::DxfReadOptions options;
  options.units = "furlong";
  const InputError units = read_error(path, options);
  EXPECT_EQ(units.field(), "units");
  expect_contains(units.message(), "furlong");
  options = metres();
  options.curve_tolerance = 0.0;
  EXPECT_EQ(read_error(path, options).field(), "curve_tolerance");
}

TEST(DxfReaderErrors, CoordinatesOverflowingUnderTransformsAreSkippedWithAWarning) {
  TempDir dir;
  const std::string block =
      "0 BLOCK\n2 HUGE\n10 0\n20 0\n0 LINE\n8 0\n10 0\n20 0\n11 1e308\n"
      "21 0\n0 ENDBLK";
  const auto path =
      put(dir, dxf_file(kLine + "\n0 INSERT\n8 X\n2 HUGE\n10 0\n20 0\n41 1e10", block));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  ASSERT_EQ(read.plan.segments().size(), 1u);
  EXPECT_TRUE(read.report.extent_m.min().allFinite() && read.report.extent_m.max().allFinite());
  EXPECT_EQ(read.report.unsupported_skipped.at("LINE (beyond 1e10 units)"), 1u);
  EXPECT_TRUE(std::any_of(read.report.warnings.begin(), read.report.warnings.end(),
                          [](const std::string& w) { return w.find("not finite") != w.npos; }));
}

TEST(DxfReaderErrors, FarOffEntitiesAndNegativeRadiiAreSkippedWithAWarning) {
  // A LINE at 1e300 gave "inf m of walls"; a CIRCLE of radius -3 was drawn with radius 3.
  TempDir dir;
  const auto path = put(dir, dxf_file(kLine + "\n0 LINE\n8 0\n10 1e300\n20 0\n11 1e300\n21 5"
                                              "\n0 CIRCLE\n8 0\n10 2\n20 2\n40 -3"));
  const io::DxfFloorplan read = io::read_dxf(path, metres());
  ASSERT_EQ(read.plan.segments().size(), 1u);
  EXPECT_TRUE(read.plan.arcs().empty());
  EXPECT_LT(read.plan.total_length(), 1e3);
  EXPECT_EQ(read.report.unsupported_skipped.at("LINE (beyond 1e10 units)"), 1u);
  EXPECT_EQ(read.report.unsupported_skipped.at("CIRCLE (radius <= 0)"), 1u);
  const auto warned = [&](const std::string& part) {
    return std::any_of(read.report.warnings.begin(), read.report.warnings.end(),
                       [&](const std::string& w) { return w.find(part) != w.npos; });
  };
  EXPECT_TRUE(warned("beyond 1e10 drawing units"));
  EXPECT_TRUE(warned("radius -3"));
}

/// Reads `text`; success and InputError are fine, anything else fails the test.
void read_survives(const TempDir& dir, const std::string& text, const std::string& what) {
  const auto path = put(dir, text, "garbage.dxf");
  io::DxfReadOptions options;
  options.max_entities = 100'000;
  try {
    io::read_dxf(path, options);
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": " << e.what();
  }
}

TEST(DxfReaderErrors, GarbageNeverCrashes) {
  TempDir dir;
  std::mt19937 rng(20240611);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int i = 0; i < 200; ++i) {
    std::string text(std::uniform_int_distribution<std::size_t>(0, 3000)(rng), '\0');
    for (char& c : text) {
      c = static_cast<char>(byte(rng));
    }
    read_survives(dir, text, "random bytes " + std::to_string(i));
  }
  // Mutations of a valid drawing with blocks, arrays, polylines and splines.
  const std::string valid = dxf_file(
      "0 INSERT\n8 I\n2 B\n10 1\n20 2\n41 2\n42 -1\n50 30\n70 3\n71 2\n44 5\n45 5\n" + kLine +
          "\n0 LWPOLYLINE\n8 P\n90 3\n70 1\n10 0\n20 0\n42 0.5\n10 4\n20 0\n10 4\n20 3\n"
          "0 SPLINE\n8 S\n71 2\n40 0\n40 0\n40 0\n40 1\n40 1\n40 1\n10 0\n20 0\n10 1\n20 1\n10 2\n"
          "20 0\n0 POLYLINE\n8 O\n70 1\n0 VERTEX\n10 0\n20 0\n42 1\n0 VERTEX\n10 1\n20 0\n0 SEQEND",
      "0 BLOCK\n2 B\n10 0\n20 0\n0 ARC\n8 0\n10 0\n20 0\n40 1\n50 0\n51 90\n0 INSERT\n2 C\n10 1\n"
      "20 1\n0 ENDBLK\n0 BLOCK\n2 C\n10 0\n20 0\n0 CIRCLE\n8 0\n10 0\n20 0\n40 2\n0 ENDBLK",
      "9 $INSUNITS\n70 4");
  read_survives(dir, valid, "the valid drawing");
  std::vector<std::string> lines;
  for (std::size_t start = 0; start < valid.size();) {
    const std::size_t end = valid.find('\n', start);
    lines.push_back(valid.substr(start, end - start));
    start = end + 1;
  }
  std::uniform_int_distribution<std::size_t> pick(0, lines.size() - 1);
  for (int i = 0; i < 400; ++i) {
    std::vector<std::string> mutated = lines;
    const int edits = 1 + i % 4;
    for (int k = 0; k < edits; ++k) {
      const std::size_t at = pick(rng) % mutated.size();
      switch ((i + k) % 5) {
        case 0:
          mutated.erase(mutated.begin() + static_cast<long>(at));
          break;
        case 1:
          mutated.insert(mutated.begin() + static_cast<long>(at),
                         mutated[pick(rng) % mutated.size()]);
          break;
        case 2:
          mutated[at] = std::to_string(byte(rng) * 1000 - 5000);
          break;
        case 3:
          mutated[at] = "0";
          break;
        default:
          mutated.resize(at + 1);
          break;
      }
      if (mutated.empty()) {
        mutated.push_back("0");
      }
    }
    std::string text;
    for (const std::string& l : mutated) {
      text += l + "\n";
    }
    read_survives(dir, text, "mutation " + std::to_string(i));
  }
}

TEST(DxfReaderErrors, TruncatedRealFileNeverCrashes) {
  FLOORGRID_REQUIRE_DATA("dxf/sample_r12_ascii.dxf");
  TempDir dir;
  const std::string real = read_file(data_path("dxf/sample_r12_ascii.dxf"));
  std::mt19937 rng(7);
  for (int i = 0; i < 12; ++i) {
    const std::size_t at = std::uniform_int_distribution<std::size_t>(0, real.size() - 1)(rng);
    const auto path = put(dir, real.substr(0, at), "cut.dxf");
    const InputError e = read_error(path);
    EXPECT_EQ(e.file(), path.string());
    EXPECT_GT(e.line(), 0) << e.what();
  }
}

}  // namespace
}  // namespace floorgrid::test
