#include "floorgrid/io/options/options_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "tests/support/expect_error.hpp"
#include "tests/support/field_count.hpp"
#include "tests/support/option_counter.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

enum class Shape { round, square };

struct InnerOptions {
  double radius = 0.25;  ///< m
  Shape shape = Shape::round;
  bool operator==(const InnerOptions&) const = default;
};

struct ToyOptions {
  double threshold = 0.1;  ///< m
  double limit = std::numeric_limits<double>::infinity();
  int steps = -3;
  std::size_t seed = 42;
  bool enabled = true;
  std::string name = "a \"quoted\" name";
  std::optional<double> scale;
  std::vector<std::string> layers{"A-WALL*", "0"};
  InnerOptions inner;
  bool operator==(const ToyOptions&) const = default;
};

void visit(OptionVisitor& v, InnerOptions& o) {
  v.field("radius", o.radius, {.unit = "m", .doc = "how far", .choices = {}});
  enum_field(v, "shape", o.shape, {{"round", Shape::round}, {"square", Shape::square}},
             "its shape");
}

void visit(OptionVisitor& v, ToyOptions& o) {
  v.field("threshold", o.threshold, {.unit = "m", .doc = "a threshold", .choices = {}});
  v.field("limit", o.limit, {.unit = "m", .doc = "no limit by default", .choices = {}});
  v.field("steps", o.steps, {.unit = "", .doc = "steps", .choices = {}});
  v.field("seed", o.seed, {.unit = "", .doc = "randomness", .choices = {}});
  v.field("enabled", o.enabled, {.unit = "", .doc = "on or off", .choices = {}});
  v.field("name", o.name, {.unit = "", .doc = "a name", .choices = {}});
  v.field("scale", o.scale, {.unit = "", .doc = "unset: estimated", .choices = {}});
  v.field("layers", o.layers, {.unit = "", .doc = "globs", .choices = {}});
  v.group("inner", "the inner part", [&] { visit(v, o.inner); });
}

io::OptionTree tree_of(ToyOptions& options) {
  return [&options](OptionVisitor& v) { v.group("toy", "a toy", [&] { visit(v, options); }); };
}

TEST(OptionsFile, FieldCountSeesEveryField) {
  EXPECT_EQ(test::field_count<InnerOptions>(), 2u);
  EXPECT_EQ(test::field_count<ToyOptions>(), 9u);
  ToyOptions toy;
  test::TopLevelCounter counter;
  visit(counter, toy);
  EXPECT_EQ(counter.count, test::field_count<ToyOptions>());
}

TEST(OptionsFile, YamlShowsValuesUnitsAndChoices) {
  ToyOptions toy;
  const std::string yaml = io::options_yaml(tree_of(toy), "# header\n");
  EXPECT_EQ(yaml.rfind("# header\n", 0), 0u);
  EXPECT_NE(yaml.find("# a toy\ntoy:\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("  threshold: 0.1  # [m] a threshold\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("  limit: .inf"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("  scale: null"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("  name: \"a \\\"quoted\\\" name\""), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("    shape: \"round\"  # its shape (one of: round, square)"),
            std::string::npos)
      << yaml;
}

TEST(OptionsFile, DumpedYamlReadsBackToTheSameOptions) {
  test::TempDir dir;
  ToyOptions changed;
  changed.threshold = 1.0 / 3.0;  // needs all 17 digits
  changed.limit = 5e-300;
  changed.steps = 7;
  changed.seed = 18446744073709551615u;
  changed.enabled = false;
  changed.name = "x: y # not a comment";
  changed.scale = 1.07;
  changed.layers = {"A*", "b c"};
  changed.inner = {.radius = 2.0, .shape = Shape::square};
  { std::ofstream(dir / "c.yaml") << io::options_yaml(tree_of(changed)); }
  ToyOptions read;
  ASSERT_NE(read, changed);
  io::read_options_yaml(dir / "c.yaml", tree_of(read));
  EXPECT_EQ(read, changed);
}

TEST(OptionsFile, OptionsLeftOutKeepTheirValues) {
  test::TempDir dir;
  std::ofstream(dir / "c.yaml") << "toy:\n  inner:\n    shape: square\n";
  ToyOptions read;
  io::read_options_yaml(dir / "c.yaml", tree_of(read));
  ToyOptions expected;
  expected.inner.shape = Shape::square;
  EXPECT_EQ(read, expected);
}

TEST(OptionsFile, JsonListsDefaultUnitAndDescription) {
  ToyOptions toy;
  const nlohmann::json j = nlohmann::json::parse(io::options_json(tree_of(toy)));
  EXPECT_DOUBLE_EQ(j["toy"]["threshold"]["default"].get<double>(), 0.1);
  EXPECT_EQ(j["toy"]["threshold"]["unit"], "m");
  EXPECT_EQ(j["toy"]["limit"]["default"], ".inf");
  EXPECT_TRUE(j["toy"]["scale"]["default"].is_null());
  EXPECT_EQ(j["toy"]["inner"]["shape"]["choices"], nlohmann::json({"round", "square"}));
  EXPECT_EQ(j["toy"]["description"], "a toy");
}

void expect_refused(const std::string& yaml, const std::vector<std::string>& parts) {
  test::TempDir dir;
  std::ofstream(dir / "bad.yaml") << yaml;
  ToyOptions read;
  std::vector<std::string> all = parts;
  all.push_back("bad.yaml");
  test::expect_input_error([&] { io::read_options_yaml(dir / "bad.yaml", tree_of(read)); }, all);
}

TEST(OptionsFile, BadValuesAreRefusedNamingLineAndOption) {
  expect_refused("toy:\n  treshold: 1\n", {":2:", "'toy.treshold'", "unknown option"});
  expect_refused("toy:\n  inner:\n    radius: 1\n    size: 2\n", {":4:", "'toy.inner.size'"});
  expect_refused("tooy: {}\n", {":1:", "'tooy'", "unknown option"});
  expect_refused("toy:\n  threshold: abc\n", {":2:", "'toy.threshold'", "must be a number"});
  expect_refused("toy:\n  threshold: [1, 2]\n", {"'toy.threshold'", "must be a number"});
  expect_refused("toy:\n  seed: -5\n", {"'toy.seed'", "whole number >= 0", "-5"});
  expect_refused("toy:\n  steps: 2.5\n", {"'toy.steps'", "integer"});
  expect_refused("toy:\n  steps: 99999999999\n", {"'toy.steps'", "out of range"});
  expect_refused("toy:\n  enabled: maybe\n", {"'toy.enabled'", "true or false"});
  expect_refused("toy:\n  inner:\n    shape: oval\n",
                 {":3:", "'toy.inner.shape'", "round, square"});
  expect_refused("toy: 3\n", {"'toy'", "mapping"});
  expect_refused("toy:\n  threshold: [1\n", {"YAML syntax error"});
  expect_refused("- 1\n- 2\n", {"mapping"});
}

TEST(OptionsFile, EmptyFileChangesNothing) {
  test::TempDir dir;
  std::ofstream(dir / "empty.yaml") << "";
  ToyOptions read;
  io::read_options_yaml(dir / "empty.yaml", tree_of(read));
  EXPECT_EQ(read, ToyOptions{});
}

}  // namespace
}  // namespace floorgrid
