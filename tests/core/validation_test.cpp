#include "floorgrid/core/validation.hpp"

#include <gtest/gtest.h>

#include "tests/support/expect_error.hpp"

namespace floorgrid {
namespace {

TEST(RequireOption, PassesAValidValue) {
  EXPECT_NO_THROW(require_option(true, "ransac.inlier_threshold", -1.0, "> 0"));
}

TEST(RequireOption, NamesTheFieldTheRuleAndTheValue) {
  try {
    require_option(false, "ransac.inlier_threshold", -1.0, "> 0");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "ransac.inlier_threshold");
    EXPECT_EQ(e.message(), "must be > 0 (got -1)");
    EXPECT_STREQ(e.what(), "'ransac.inlier_threshold': must be > 0 (got -1)");
  }
}

TEST(RequireOption, JoinsPrefixAndField) {
  test::expect_input_error([] { require_option(false, "beam_model", "z_hit", 1.5, "in [0, 1]"); },
                           {"'beam_model.z_hit'", "must be in [0, 1] (got 1.5)"});
}

TEST(Got, PrintsHugeNumbersShortly) {
  EXPECT_EQ(got(1e300), "(got 1e+300)");
}

}  // namespace
}  // namespace floorgrid
