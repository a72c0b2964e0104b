#include "floorgrid/core/error.hpp"

#include <gtest/gtest.h>

namespace floorgrid {
namespace {

TEST(InputError, NamesFileLineAndFieldInThatOrder) {
  const InputError e("must be > 0", "map.yaml", 3, "resolution");
  EXPECT_STREQ(e.what(), "map.yaml:3: 'resolution': must be > 0");
  EXPECT_EQ(e.file(), "map.yaml");
  EXPECT_EQ(e.line(), 3);
  EXPECT_EQ(e.field(), "resolution");
  EXPECT_EQ(e.message(), "must be > 0");
}

TEST(InputError, LeavesOutWhatIsUnknown) {
  EXPECT_STREQ(InputError("bad").what(), "bad");
  EXPECT_STREQ(InputError("bad", "f.csv").what(), "f.csv: bad");
  EXPECT_STREQ(InputError("bad", {}, 7).what(), "line 7: bad");
  EXPECT_STREQ(InputError("bad", {}, 0, "--cv").what(), "'--cv': bad");
}

}  // namespace
}  // namespace floorgrid
