#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace floorgrid::io {

/// An image reduced to one brightness per pixel, rows from the top as stored in the file.
/// RGB pixels are reduced by the mean of the three channels; alpha is kept when present.
struct GreyImage {
  int width = 0;                     ///< pixels
  int height = 0;                    ///< pixels
  std::vector<std::uint16_t> level;  ///< brightness 0 (black) .. max_level (white), width * height
  int max_level = 255;               ///< white: maxval, 255, or 765 for the sum of R, G and B
  std::vector<std::uint8_t> alpha;   ///< 0 transparent .. 255 opaque; empty when the file has none
  std::string description;           ///< e.g. "PNG 8-bit grey", "PGM P5 maxval 255"

  /// Brightness 0 .. 1 of pixel i (row-major, top row first), exact in double precision.
  double shade(std::size_t i) const { return static_cast<double>(level[i]) / max_level; }
  /// Whether the file carried an alpha channel.
  bool has_alpha() const { return !alpha.empty(); }
};

/// Limits that protect against absurd headers: nothing is allocated past them. An image takes
/// 2-3 bytes per pixel here and its occupancy grid 2 more: at the limit, about 2.5 GB.
struct ImageLimits {
  int max_side = 200'000;  ///< pixels per side
  /// width * height: a 1 km x 1 km site at 5 cm is 4e8 pixels; a larger map must be cropped or
  /// given at a coarser resolution.
  std::size_t max_pixels = 500'000'000;
};

/// Reads a PGM (P2 or P5, any maxval) or PNG (grey, grey+alpha, RGB, RGBA, palette, 1-16 bit)
/// by its content. Throws InputError naming the file for a missing, truncated or malformed file.
GreyImage read_grey_image(const std::filesystem::path& path, const ImageLimits& limits = {});

/// Writes an 8-bit binary PGM (P5) atomically. `pixels` holds width * height bytes, top row first.
void write_pgm(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& pixels);

/// An 8-bit PNG file's bytes: `pixels` holds width * height * channels bytes (1 grey, 2 grey +
/// alpha, 3 RGB, 4 RGBA), top row first. For answers that are not files (the viewer's API).
std::string encode_png(int width, int height, int channels,
                       const std::vector<std::uint8_t>& pixels);

/// Writes an 8-bit PNG atomically: grey, or grey+alpha when `alpha` is not empty.
void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<std::uint8_t>& grey, const std::vector<std::uint8_t>& alpha = {});

/// Writes an 8-bit RGB PNG atomically (overlays, previews). `rgb` holds 3 bytes per pixel.
void write_png_rgb(const std::filesystem::path& path, int width, int height,
                   const std::vector<std::uint8_t>& rgb);

/// Writes an 8-bit RGBA PNG atomically (heat maps: transparent where unknown). `rgba` holds 4
/// bytes per pixel.
void write_png_rgba(const std::filesystem::path& path, int width, int height,
                    const std::vector<std::uint8_t>& rgba);

}  // namespace floorgrid::io
