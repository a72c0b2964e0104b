#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace floorgrid {

/// Bits per axis of the grid that hilbert_keys quantizes points into (2^21 cells per axis).
inline constexpr int kHilbertBits = 21;

/// Position of the integer cell (x, y), 0 <= x, y < 2^bits, along the Hilbert curve of that
/// order (0 .. 4^bits - 1). Cells next to each other along the curve are next to each other in
/// the plane, which is what makes walks between consecutive points short.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, int bits);

/// The Hilbert index of every column of `points`, on a grid of 2^kHilbertBits cells per axis
/// spread over the points' bounding box (a square box, so that the curve keeps its shape).
/// Columns with a non-finite coordinate get key 0.
std::vector<std::uint64_t> hilbert_keys(const Eigen::Matrix2Xd& points);

/// Sorts the indices in [first, last) (columns of the points the keys belong to) by increasing
/// key; stable: equal keys keep their order. Linear time (radix sort).
void sort_by_hilbert_key(std::vector<int>::iterator first, std::vector<int>::iterator last,
                         const std::vector<std::uint64_t>& keys);

}  // namespace floorgrid
