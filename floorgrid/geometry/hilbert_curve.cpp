#include "floorgrid/geometry/hilbert_curve.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace floorgrid {

std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, int bits) {
  // Descend the quadrant tree from the largest square: each level adds the quadrant's rank along
  // the curve (0 lower left, 1 upper left, 2 upper right, 3 lower right) and then looks at the
  // quadrant in its own frame, which the curve enters transposed (lower left quadrant) or
  // transposed and mirrored in both axes (lower right). The frame is kept as two flags applied
  // to the bits as they are read, so the loop has no data-dependent branches.
  std::uint64_t index = 0;
  std::uint32_t swapped = 0;  // the frame exchanges x and y
  std::uint32_t flipped = 0;  // the frame complements both coordinates
  for (int level = bits - 1; level >= 0; --level) {
    const std::uint32_t bx = (x >> level) & 1u;
    const std::uint32_t by = (y >> level) & 1u;
    const std::uint32_t rx = ((bx & ~swapped) | (by & swapped)) ^ flipped;
    const std::uint32_t ry = ((by & ~swapped) | (bx & swapped)) ^ flipped;
    index = (index << 2) | ((3u * rx) ^ ry);
    const std::uint32_t lower = ry ^ 1u;
    flipped ^= lower & rx;
    swapped ^= lower;
  }
  return index;
}

std::vector<std::uint64_t> hilbert_keys(const Eigen::Matrix2Xd& points) {
  const Eigen::Index n = points.cols();
  std::vector<std::uint64_t> keys(static_cast<std::size_t>(n), 0);
  double min_x = INFINITY, min_y = INFINITY, max_x = -INFINITY, max_y = -INFINITY;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = points(0, i), y = points(1, i);
    if (!std::isfinite(x) || !std::isfinite(y))
      continue;
    min_x = std::min(min_x, x);
    max_x = std::max(max_x, x);
    min_y = std::min(min_y, y);
    max_y = std::max(max_y, y);
  }
  if (!(min_x <= max_x))
    return keys;
  const double side = std::max(max_x - min_x, max_y - min_y);
  const double cells = static_cast<double>(1u << kHilbertBits);
  const double scale = side > 0.0 ? (cells - 1.0) / side : 0.0;
  const double top = cells - 1.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = points(0, i), y = points(1, i);
    if (!std::isfinite(x) || !std::isfinite(y))
      continue;
    const double cx = std::clamp((x - min_x) * scale, 0.0, top);
    const double cy = std::clamp((y - min_y) * scale, 0.0, top);
    keys[static_cast<std::size_t>(i)] =
        hilbert_index(static_cast<std::uint32_t>(cx), static_cast<std::uint32_t>(cy), kHilbertBits);
  }
  return keys;
}

void sort_by_hilbert_key(std::vector<int>::iterator first, std::vector<int>::iterator last,
                         const std::vector<std::uint64_t>& keys) {
  // LSD radix sort of (key, index) pairs, 11 bits per pass: linear time, stable, and the keys
  // travel with the indices (no cache miss per comparison as with keys[index]).
  struct Entry {
    std::uint64_t key;
    int index;
  };
  const std::size_t n = static_cast<std::size_t>(last - first);
  std::vector<Entry> entries(n), buffer(n);
  std::uint64_t all_bits = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int index = first[static_cast<std::ptrdiff_t>(i)];
    entries[i] = {keys[static_cast<std::size_t>(index)], index};
    all_bits |= entries[i].key;
  }
  constexpr int kDigitBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
  for (int shift = 0; shift < 64 && (all_bits >> shift) != 0; shift += kDigitBits) {
    std::vector<std::size_t> start(kBuckets + 1, 0);
    for (const Entry& e : entries)
      ++start[((e.key >> shift) & (kBuckets - 1)) + 1];
    for (std::size_t b = 1; b <= kBuckets; ++b)
      start[b] += start[b - 1];
    for (const Entry& e : entries)
      buffer[start[(e.key >> shift) & (kBuckets - 1)]++] = e;
    entries.swap(buffer);
  }
  for (const Entry& e : entries)
    *first++ = e.index;
}

}  // namespace floorgrid
