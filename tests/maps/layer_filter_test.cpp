#include "floorgrid/maps/layer_filter.hpp"

#include <gtest/gtest.h>

#include <string>

namespace floorgrid {
namespace {

TEST(LayerFilter, GlobMatchesWholeNamesIgnoringCase) {
  EXPECT_TRUE(glob_match("A-WALL", "a-wall"));
  EXPECT_TRUE(glob_match("a-wall", "A-WALL"));
  EXPECT_FALSE(glob_match("A-WALL", "A-WALLS"));  // the whole name, not a prefix
  EXPECT_FALSE(glob_match("A-WALL", "XA-WALL"));
  EXPECT_TRUE(glob_match("A-WALL*", "A-WALL-EXT"));
  EXPECT_TRUE(glob_match("*FURN*", "I-furn-chairs"));
  EXPECT_TRUE(glob_match("*", ""));
  EXPECT_TRUE(glob_match("A-?ALL", "A-HALL"));
  EXPECT_FALSE(glob_match("A-?ALL", "A-ALL"));  // ? is exactly one character
  EXPECT_TRUE(glob_match("*-*-*", "A-B-C"));
  EXPECT_FALSE(glob_match("*-*-*", "A-BC"));
  EXPECT_TRUE(glob_match("**WALL", "WALL"));
  EXPECT_FALSE(glob_match("", "WALL"));
  EXPECT_TRUE(glob_match("", ""));
}

TEST(LayerFilter, GlobHandlesPathologicalPatterns) {
  // Naive recursive matching takes exponential time here and would hit the test timeout; no
  // clock is read, as timings are unreliable on a shared machine.
  const std::string text(2000, 'a');
  EXPECT_FALSE(glob_match("*a*a*a*a*a*a*a*a*a*b", text));
  EXPECT_TRUE(glob_match("*a*a*a*a*a*a*a*a*a*", text));
}

TEST(LayerFilter, StripsBoundAndAttachedXrefPrefixes) {
  EXPECT_EQ(strip_xref_prefix("xref-Plan$0$A-WALL"), "A-WALL");
  EXPECT_EQ(strip_xref_prefix("xref-Bishop-Overland-08$0$S-FOOTER"), "S-FOOTER");
  EXPECT_EQ(strip_xref_prefix("Site$12$Plan$0$A-DOOR"), "A-DOOR");  // nested binding
  EXPECT_EQ(strip_xref_prefix("Plan|A-WALL"), "A-WALL");            // attached, not bound
  EXPECT_EQ(strip_xref_prefix("A-WALL"), "A-WALL");
  EXPECT_EQ(strip_xref_prefix("COST$5"), "COST$5");      // no closing $
  EXPECT_EQ(strip_xref_prefix("A$B$WALL"), "A$B$WALL");  // no digits between the $
  EXPECT_EQ(strip_xref_prefix("$0$WALL"), "$0$WALL");    // no xref name
  EXPECT_EQ(strip_xref_prefix("X$0$"), "X$0$");          // no layer name
}

TEST(LayerFilter, IncludeThenExcludeOnTheStrippedOrFullName) {
  const LayerFilter all;
  EXPECT_TRUE(layer_passes(all, "anything"));
  const LayerFilter walls{{"A-WALL*"}, {"*FURN*"}};
  EXPECT_TRUE(layer_passes(walls, "xref-Plan$0$A-WALL"));
  EXPECT_TRUE(layer_passes(walls, "a-wall-ext"));
  EXPECT_FALSE(layer_passes(walls, "xref-Plan$0$A-DOOR"));
  EXPECT_FALSE(layer_passes(walls, "A-WALL-FURN"));
  EXPECT_FALSE(layer_passes(walls, "xref-FURN$0$A-WALL"));  // the full name matches *FURN*
  const LayerFilter one_xref{{"xref-Plan$*"}, {}};
  EXPECT_TRUE(layer_passes(one_xref, "xref-Plan$0$A-WALL"));
  EXPECT_FALSE(layer_passes(one_xref, "A-WALL"));
  const LayerFilter exclude_only{{}, {"DEFPOINTS", "0"}};
  EXPECT_FALSE(layer_passes(exclude_only, "Defpoints"));
  EXPECT_FALSE(layer_passes(exclude_only, "0"));
  EXPECT_TRUE(layer_passes(exclude_only, "WALLS"));
}

}  // namespace
}  // namespace floorgrid
