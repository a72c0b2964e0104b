// Dimension texts as unit evidence: MTEXT codes removed, stated lengths parsed.

#include "floorgrid/io/plans/dxf_dimensions.hpp"

#include <gtest/gtest.h>

namespace floorgrid::io {
namespace {

constexpr double kInch = 0.0254;

TEST(DxfDimensions, PlainTextDropsMtextFormattingAndControlCodes) {
  EXPECT_EQ(plain_dxf_text("\\A1;3'-1\""), "3'-1\"");  // as AutoCAD draws dimension texts
  EXPECT_EQ(plain_dxf_text("{\\H0.7x;\\C1;12'-6 \\S1/2;\"}"), "12'-6  1/2\"");
  EXPECT_EQ(plain_dxf_text("2'-0\\S3#4;\""), "2'-0 3/4\"");
  EXPECT_EQ(plain_dxf_text("%%u2 CAR GARAGE\\PLINE"), "2 CAR GARAGE LINE");
  EXPECT_EQ(plain_dxf_text("45%%d"), "45 deg");
  EXPECT_EQ(plain_dxf_text("\\fArial|b0|i0;3.60 m"), "3.60 m");
  EXPECT_EQ(plain_dxf_text("a\\\\b\\{c\\}"), "a\\b{c}");
  EXPECT_EQ(plain_dxf_text("\\U+00D8600"), "?600");
  EXPECT_EQ(plain_dxf_text("unterminated \\H2.5"), "unterminated ");
}

TEST(DxfDimensions, FeetAndInches) {
  EXPECT_NEAR(*stated_length_m("3'-1\""), 37 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("12'-6 1/2\""), 150.5 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("12'-6  1/2\""), 150.5 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("10' 3\""), 123 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("16'"), 192 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("16' CLR"), 192 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("7\""), 7 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("7.5\""), 7.5 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("1/2\""), 0.5 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("4'-0 1#4\""), 48.25 * kInch, 1e-12);  // an R12 stacked fraction
  EXPECT_NEAR(*stated_length_m("R 3'-0\""), 36 * kInch, 1e-12);
  EXPECT_NEAR(*stated_length_m("141\""), 141 * kInch, 1e-12);
}

TEST(DxfDimensions, MetricWithItsUnit) {
  EXPECT_DOUBLE_EQ(*stated_length_m("3.60 m"), 3.6);
  EXPECT_DOUBLE_EQ(*stated_length_m("3,60m"), 3.6);
  EXPECT_DOUBLE_EQ(*stated_length_m("360 cm"), 3.6);
  EXPECT_DOUBLE_EQ(*stated_length_m("3600MM"), 3.6);
  EXPECT_DOUBLE_EQ(*stated_length_m("approx. 12 m"), 12.0);
}

TEST(DxfDimensions, BareNumbersAndOtherTextsStateNoLength) {
  EXPECT_FALSE(stated_length_m("3600"));  // in the drawing's own unit: no evidence
  EXPECT_FALSE(stated_length_m("4.30"));
  EXPECT_FALSE(stated_length_m("EQ"));
  EXPECT_FALSE(stated_length_m("2x4 STUDS"));
  EXPECT_FALSE(stated_length_m("3 mil"));
  EXPECT_FALSE(stated_length_m("45 deg"));
  EXPECT_FALSE(stated_length_m("0'-0\""));  // zero is no length
  EXPECT_FALSE(stated_length_m(""));
}

}  // namespace
}  // namespace floorgrid::io
