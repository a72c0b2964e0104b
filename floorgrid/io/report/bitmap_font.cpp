#include "floorgrid/io/report/bitmap_font.hpp"

#include <map>

namespace floorgrid::io {

namespace {

// Drawn for floorgrid (not taken from a font): 7 rows of 5 columns, '#' set.
using Glyph = std::array<const char*, 7>;

const std::map<char, Glyph>& glyphs() {
  static const std::map<char, Glyph> table = {
      {'0', {" ### ", "#   #", "#  ##", "# # #", "##  #", "#   #", " ### "}},
      {'1', {"  #  ", " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### "}},
      {'2', {" ### ", "#   #", "    #", "   # ", "  #  ", " #   ", "#####"}},
      {'3', {"#####", "   # ", "  #  ", "   # ", "    #", "#   #", " ### "}},
      {'4', {"   # ", "  ## ", " # # ", "#  # ", "#####", "   # ", "   # "}},
      {'5', {"#####", "#    ", "#### ", "    #", "    #", "#   #", " ### "}},
      {'6', {"  ## ", " #   ", "#    ", "#### ", "#   #", "#   #", " ### "}},
      {'7', {"#####", "    #", "   # ", "  #  ", " #   ", " #   ", " #   "}},
      {'8', {" ### ", "#   #", "#   #", " ### ", "#   #", "#   #", " ### "}},
      {'9', {" ### ", "#   #", "#   #", " ####", "    #", "   # ", " ##  "}},
      {'.', {"     ", "     ", "     ", "     ", "     ", " ##  ", " ##  "}},
      {'+', {"     ", "  #  ", "  #  ", "#####", "  #  ", "  #  ", "     "}},
      {'-', {"     ", "     ", "     ", "#####", "     ", "     ", "     "}},
      {'a', {"     ", "     ", " ### ", "    #", " ####", "#   #", " ####"}},
      {'c', {"     ", "     ", " ### ", "#    ", "#    ", "#   #", " ### "}},
      {'d', {"    #", "    #", " ## #", "#  ##", "#   #", "#   #", " ####"}},
      {'e', {"     ", "     ", " ### ", "#   #", "#####", "#    ", " ### "}},
      {'h', {"#    ", "#    ", "# ## ", "##  #", "#   #", "#   #", "#   #"}},
      {'i', {"  #  ", "     ", " ##  ", "  #  ", "  #  ", "  #  ", " ### "}},
      {'l', {" ##  ", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### "}},
      {'m', {"     ", "     ", "## # ", "# # #", "# # #", "#   #", "#   #"}},
      {'n', {"     ", "     ", "# ## ", "##  #", "#   #", "#   #", "#   #"}},
      {'o', {"     ", "     ", " ### ", "#   #", "#   #", "#   #", " ### "}},
      {'p', {"     ", "     ", "#### ", "#   #", "#### ", "#    ", "#    "}},
      {'r', {"     ", "     ", "# ## ", "##  #", "#    ", "#    ", "#    "}},
      {'s', {"     ", "     ", " ####", "#    ", " ### ", "    #", "#### "}},
      {'t', {" #   ", " #   ", "#### ", " #   ", " #   ", " #  #", "  ## "}},
      {'u', {"     ", "     ", "#   #", "#   #", "#   #", "#  ##", " ## #"}},
      {'x', {"     ", "     ", "#   #", " # # ", "  #  ", " # # ", "#   #"}},
  };
  return table;
}

}  // namespace

bool BitmapFont::pixel(char c, int x, int y) {
  if (x < 0 || y < 0 || x >= kWidth || y >= kHeight)
    return false;
  const auto it = glyphs().find(c);
  return it != glyphs().end() && it->second[static_cast<std::size_t>(y)][x] == '#';
}

bool BitmapFont::has(char c) {
  return glyphs().count(c) > 0;
}

void RgbaImage::set(int col, int row, const std::array<std::uint8_t, 4>& colour) {
  if (col < 0 || row < 0 || col >= width || row >= height)
    return;
  const std::size_t i = (static_cast<std::size_t>(row) * width + col) * 4;
  for (std::size_t k = 0; k < 4; ++k)
    rgba[i + k] = colour[k];
}

void draw_text(RgbaImage& image, int col, int row, const std::string& text, int scale,
               const std::array<std::uint8_t, 4>& colour) {
  for (std::size_t n = 0; n < text.size(); ++n) {
    const int left = col + static_cast<int>(n) * BitmapFont::kAdvance * scale;
    for (int y = 0; y < BitmapFont::kHeight; ++y)
      for (int x = 0; x < BitmapFont::kWidth; ++x)
        if (BitmapFont::pixel(text[n], x, y))
          for (int dy = 0; dy < scale; ++dy)
            for (int dx = 0; dx < scale; ++dx)
              image.set(left + x * scale + dx, row + y * scale + dy, colour);
  }
}

}  // namespace floorgrid::io
