#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace floorgrid::io {

/// A tiny 5 x 7 pixel font for labels drawn into PNGs (colour bars): digits, '.', '+', '-', ' '
/// and the lower-case letters of the labels floorgrid writes. Other characters draw as blanks.
struct BitmapFont {
  static constexpr int kWidth = 5;    ///< glyph pixels across
  static constexpr int kHeight = 7;   ///< glyph pixels down
  static constexpr int kAdvance = 6;  ///< pixels from one glyph to the next
  /// Whether glyph `c` has pixel (x, y) set (y from the top).
  static bool pixel(char c, int x, int y);
  /// Whether the font draws `c` (not as a blank).
  static bool has(char c);
};

/// An RGBA picture, rows from the top, 4 bytes per pixel.
struct RgbaImage {
  int width = 0;                   ///< pixels
  int height = 0;                  ///< pixels
  std::vector<std::uint8_t> rgba;  ///< width * height * 4 bytes

  /// Sets pixel (col, row) when it lies in the picture.
  void set(int col, int row, const std::array<std::uint8_t, 4>& colour);
};

/// Draws `text` with its top-left corner at (col, row), each font pixel `scale` x `scale`.
void draw_text(RgbaImage& image, int col, int row, const std::string& text, int scale,
               const std::array<std::uint8_t, 4>& colour);

}  // namespace floorgrid::io
