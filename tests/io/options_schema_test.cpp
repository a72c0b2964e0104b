// config --dump's list of options: complete (every field of every options struct is named, so
// a new option cannot be forgotten), and read back to the same options.
#include "floorgrid/io/options/options_schema.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "tests/support/expect_error.hpp"
#include "tests/support/field_count.hpp"
#include "tests/support/option_counter.hpp"
#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

/// Expects visit(v, T&) to name every field of T but the `omitted` ones.
template <typename T>
void expect_complete(const char* name, std::size_t omitted = 0) {
  T options{};
  test::TopLevelCounter counter;
  visit(counter, options);
  EXPECT_EQ(counter.count + omitted, test::field_count<T>())
      << name << ": a field is missing from io/options/options_schema.cpp (or a name is repeated)";
}

TEST(OptionsSchema, EveryFieldOfEveryOptionsStructIsListed) {
  expect_complete<JobOptions>("JobOptions");
  expect_complete<io::PlanRasterOptions>("PlanRasterOptions");
  expect_complete<io::DatasetLimits>("DatasetLimits");
  expect_complete<AlignmentOptions>("AlignmentOptions");
  expect_complete<DualLocalizerOptions>("DualLocalizerOptions");
  expect_complete<MapFilterOptions>("MapFilterOptions");
  expect_complete<ParticleFilterOptions>("ParticleFilterOptions");
  expect_complete<MotionNoise>("MotionNoise");
  expect_complete<FreeSpaceOptions>("FreeSpaceOptions");
  expect_complete<HypothesisSeedingOptions>("HypothesisSeedingOptions");
  expect_complete<ConvergenceOptions>("ConvergenceOptions");
  expect_complete<RecoveryOptions>("RecoveryOptions");
  expect_complete<LikelihoodFieldOptions>("LikelihoodFieldOptions");
  expect_complete<ObservationOptions>("ObservationOptions");
  expect_complete<FilterRunnerOptions>("FilterRunnerOptions");
  expect_complete<ScanMatchOptions>("ScanMatchOptions");
  expect_complete<BeamModelOptions>("BeamModelOptions");
  expect_complete<WallFieldOptions>("WallFieldOptions");
  expect_complete<GridmapLocalizationOptions>("GridmapLocalizationOptions");
  expect_complete<PlanLocationOptions>("PlanLocationOptions");
  expect_complete<VisibleWallsOptions>("VisibleWallsOptions");
  expect_complete<SubmapOptions>("SubmapOptions");
  expect_complete<PlanRegistrationOptions>("PlanRegistrationOptions");
  expect_complete<ScaleSearchOptions>("ScaleSearchOptions");
  expect_complete<ScaleRange>("ScaleRange");
  expect_complete<DualCheckOptions>("DualCheckOptions");
  expect_complete<SubmapCheckOptions>("SubmapCheckOptions");
  expect_complete<ScaleRefitOptions>("ScaleRefitOptions");
  expect_complete<PairExtractionOptions>("PairExtractionOptions");
  expect_complete<OutlierScanOptions>("OutlierScanOptions");
  expect_complete<ModelComparisonOptions>("ModelComparisonOptions");
  expect_complete<MappingOptions>("MappingOptions");
  expect_complete<MappingCommonOptions>("MappingCommonOptions");
  expect_complete<ReductionOptions>("ReductionOptions");
  expect_complete<RansacOptions>("RansacOptions");
  expect_complete<LinearCombinationOptions>("LinearCombinationOptions");
  expect_complete<LocalTransformsOptions>("LocalTransformsOptions");
  // GP hyperparameters are tuned, not set: the one field left out.
  expect_complete<GaussianProcessOptions>("GaussianProcessOptions", 1);
  // RPROP's bounds are set by the GP tuning from its own: two fields left out.
  expect_complete<RpropOptions>("RpropOptions", 2);
  expect_complete<GpTuningOptions>("GpTuningOptions");
  expect_complete<GpPredictionOptions>("GpPredictionOptions");
  expect_complete<GpLatticeOptions>("GpLatticeOptions");
  expect_complete<ThinPlateSplineModelOptions>("ThinPlateSplineModelOptions");
  expect_complete<ThinPlateSplineLatticeOptions>("ThinPlateSplineLatticeOptions");
  expect_complete<AutoOptions>("AutoOptions");
  expect_complete<CrossValidationOptions>("CrossValidationOptions");
  expect_complete<ErrorModelOptions>("ErrorModelOptions");
}

TEST(OptionsSchema, TheDumpReadsBackToTheSameDump) {
  test::TempDir dir;
  JobOptions defaults;
  const std::string dump = io::options_yaml(io::job_option_tree(defaults));
  std::ofstream(dir / "config.yaml") << dump;
  JobOptions read;
  read.align.localization.seed = 99;  // overwritten by the file's default
  io::read_options_yaml(dir / "config.yaml", io::job_option_tree(read));
  EXPECT_EQ(read.align.localization.seed, 1u);
  EXPECT_EQ(io::options_yaml(io::job_option_tree(read)), dump);
}

TEST(OptionsSchema, AFileChangesOnlyWhatItNames) {
  test::TempDir dir;
  std::ofstream(dir / "config.yaml")
      << "align:\n  localization:\n    seed: 7\n    plan:\n      model: beam\n"
         "    scale_search:\n      range: {min: 0.5, max: 2}\n  models:\n"
         "    models: [gt, tps]\n    mapping:\n      tps:\n        regularization: 0.1\n";
  JobOptions read;
  io::read_options_yaml(dir / "config.yaml", io::job_option_tree(read));
  EXPECT_EQ(read.align.localization.seed, 7u);
  EXPECT_EQ(read.align.localization.plan.model, ObservationModelKind::beam);
  EXPECT_EQ(read.align.localization.grid.model, ObservationModelKind::likelihood_field);
  EXPECT_DOUBLE_EQ(read.align.localization.scale_search.range.min, 0.5);
  EXPECT_EQ(read.align.models.models, (std::vector<std::string>{"gt", "tps"}));
  ASSERT_TRUE(read.align.models.mapping.tps.regularization.has_value());
  EXPECT_DOUBLE_EQ(*read.align.models.mapping.tps.regularization, 0.1);
  // Everything else keeps its default.
  EXPECT_EQ(read.align.localization.plan.filter.tracking_particles,
            JobOptions{}.align.localization.plan.filter.tracking_particles);
}

/// Every number option with its range and default, and every rule between options that the
/// defaults break.
class RangeAudit final : public OptionVisitor {
 public:
  std::vector<std::string> unranged;      ///< number options without a range
  std::vector<std::string> outside;       ///< defaults outside their range
  std::vector<std::string> rules_broken;  ///< rules the defaults break
  std::size_t numbers = 0;                ///< number options seen

  void field(std::string_view name, double& value, const OptionInfo& info) override {
    number(name, value, info);
  }
  void field(std::string_view name, int& value, const OptionInfo& info) override {
    number(name, value, info);
  }
  void field(std::string_view name, long& value, const OptionInfo& info) override {
    number(name, static_cast<double>(value), info);
  }
  void field(std::string_view name, std::size_t& value, const OptionInfo& info) override {
    number(name, static_cast<double>(value), info);
  }
  void field(std::string_view, bool&, const OptionInfo&) override {}
  void field(std::string_view, std::string&, const OptionInfo&) override {}
  void field(std::string_view name, std::optional<double>& value, const OptionInfo& info) override {
    if (value)
      number(name, *value, info);
    else if (!info.range)
      unranged.push_back(path(name));
  }
  void field(std::string_view, std::vector<std::string>&, const OptionInfo&) override {}
  void group(std::string_view name, std::string_view,
             const std::function<void()>& members) override {
    prefix_.push_back(std::string(name));
    members();
    prefix_.pop_back();
  }
  void require(bool holds, std::string_view field, std::string_view rule) override {
    if (!holds)
      rules_broken.push_back(path(field) + " " + std::string(rule));
  }

 private:
  void number(std::string_view name, double value, const OptionInfo& info) {
    ++numbers;
    if (!info.range)
      unranged.push_back(path(name));
    else if (!info.range->contains(value))
      outside.push_back(path(name) + " = " + std::to_string(value) + " not " + info.range->text());
  }
  std::string path(std::string_view name) const {
    std::string p;
    for (const std::string& part : prefix_)
      p += part + ".";
    return p + std::string(name);
  }
  std::vector<std::string> prefix_;
};

TEST(OptionsSchema, EveryNumberOptionStatesARangeHoldingItsDefault) {
  // An options file is checked where it is read (file, line, option) against these ranges: an
  // option without one would be trusted, a range without its default refuses the dump.
  JobOptions options;
  RangeAudit audit;
  visit(audit, options);
  EXPECT_GT(audit.numbers, 250u);
  EXPECT_TRUE(audit.unranged.empty()) << "no range: " << ::testing::PrintToString(audit.unranged);
  EXPECT_TRUE(audit.outside.empty()) << ::testing::PrintToString(audit.outside);
  EXPECT_TRUE(audit.rules_broken.empty()) << ::testing::PrintToString(audit.rules_broken);
}

TEST(OptionsSchema, TheDumpStatesEachRange) {
  JobOptions options;
  const std::string yaml = io::options_yaml(io::job_option_tree(options));
  EXPECT_NE(yaml.find("resolution: 0.05  # [m] Cell size of a rasterized DXF plan (in [0.001, "
                      "10])"),
            std::string::npos);
  const std::string json = io::options_json(io::job_option_tree(options));
  EXPECT_NE(json.find("\"range\": \"a whole number in [1, 1000000]\""), std::string::npos);
}

TEST(OptionsSchema, UnknownOrMisspeltOptionsNameTheirPathAndLine) {
  test::TempDir dir;
  std::ofstream(dir / "config.yaml") << "align:\n  localization:\n    sead: 7\n";
  JobOptions read;
  test::expect_input_error(
      [&] { io::read_options_yaml(dir / "config.yaml", io::job_option_tree(read)); },
      {"config.yaml:3:", "'align.localization.sead'", "unknown option"});
}

}  // namespace
}  // namespace floorgrid
