#pragma once

#include <array>
#include <cstdint>

namespace floorgrid::io {

/// 256 sRGB colours of the viridis colour map (perceptually uniform, lightness rising from dark
/// blue-violet to yellow; readable in grey and by colour-blind readers).
using ColourTable = std::array<std::array<std::uint8_t, 3>, 256>;

/// The viridis table: entry 0 for the smallest value, 255 for the largest.
const ColourTable& viridis();

}  // namespace floorgrid::io
