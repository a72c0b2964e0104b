// `floorgrid config --dump` and `--config FILE`: the dump is valid YAML and JSON that names
// every option with its default, and align/pairs read it back, refusing what they do not know.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/support/test_data.hpp"

namespace floorgrid {
namespace {

using test::quoted;
using test::run_floorgrid;

TEST(ConfigCommand, DumpsEveryOptionAsYamlAndJson) {
  const auto yaml = run_floorgrid("config --dump");
  ASSERT_EQ(yaml.status, 0) << yaml.err;
  EXPECT_NE(yaml.out.find("\n  localization:\n"), std::string::npos);
  EXPECT_NE(yaml.out.find("tracking_particles: 2000"), std::string::npos);
  // null: the gt models adapt the threshold to the pairs' noise.
  EXPECT_NE(yaml.out.find("  inlier_threshold: null  # [m]"), std::string::npos);
  const auto json = run_floorgrid("config --dump --json");
  ASSERT_EQ(json.status, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["align"]["localization"]["seed"]["default"], 1);
  EXPECT_EQ(j["align"]["localization"]["plan"]["model"]["choices"],
            nlohmann::json({"likelihood_field", "beam"}));
  EXPECT_EQ(j["raster"]["resolution"]["unit"], "m");
}

TEST(ConfigCommand, JobsReadTheDumpBackAndRefuseUnknownOptions) {
  test::TempDir dir;
  const auto dump = run_floorgrid("config --dump");
  test::write_file(dir / "config.yaml", dump.out);
  // A bad option is refused before any work, naming the file, the line and the option.
  test::write_file(dir / "bad.yaml", "align:\n  localization:\n    sead: 3\n");
  for (const std::string verb : {"align", "pairs"}) {
    const std::string out =
        verb == "align" ? " --out " + quoted(dir / "out") : " --out " + quoted(dir / "pairs.csv");
    const auto bad = run_floorgrid(verb + " " + quoted(dir / "missing") + out + " --config " +
                                   quoted(dir / "bad.yaml"));
    EXPECT_EQ(bad.status, 2) << bad.err;
    EXPECT_NE(bad.err.find("bad.yaml:3: 'align.localization.sead': unknown option"),
              std::string::npos)
        << bad.err;
    // The full dump is accepted: what fails then is the missing dataset.
    const auto good = run_floorgrid(verb + " " + quoted(dir / "missing") + out + " --config " +
                                    quoted(dir / "config.yaml"));
    EXPECT_EQ(good.status, 2);
    EXPECT_NE(good.err.find("missing"), std::string::npos) << good.err;
    EXPECT_EQ(good.err.find("config.yaml"), std::string::npos) << good.err;
  }
}

}  // namespace
}  // namespace floorgrid
