#pragma once

#include <cstddef>

namespace floorgrid {

/// Bytes the main job derives per cell of a map: the likelihood fields, distance and wall
/// fields, the ray caster, the visible walls and the free-space lists of both filters. Measured:
/// align on the warehouse (a 4.1 M-cell gridmap and a 2.1 M-cell plan) peaks at 221 MB, about
/// 33 bytes per cell; 40 leaves room.
inline constexpr std::size_t kAlignmentBytesPerCell = 40;

/// Bytes `align` (or `pairs`) needs at most for a plan and a gridmap of these many cells and a
/// log of this many laser readings: to refuse, before any work, maps too large for the machine.
std::size_t alignment_memory_bytes(std::size_t plan_cells, std::size_t gridmap_cells,
                                   std::size_t log_readings);

}  // namespace floorgrid
