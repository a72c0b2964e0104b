#pragma once

#include <filesystem>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"

namespace floorgrid::io {

/// Reads a pairs CSV: header `plan_x,plan_y,grid_x,grid_y[,weight]`, one pair per row.
/// Coordinates are multiplied by `unit` (metres per file unit; 1 for metres). Blank lines and
/// lines starting with '#' are skipped. Throws InputError naming the file, line and column for
/// a bad header, a short or long row, a bad or non-finite number, a negative weight or no pairs.
/// `pair_lines`, when given, receives each pair's 1-based line in the file.
ReferencePairs read_pairs_csv(const std::filesystem::path& path, double unit = 1.0,
                              std::vector<long>* pair_lines = nullptr);

/// Writes pairs as CSV (atomically), coordinates divided by `unit`, with the weight column when
/// the pairs carry weights. Numbers are written with round-trip precision.
void write_pairs_csv(const ReferencePairs& pairs, const std::filesystem::path& path,
                     double unit = 1.0);

}  // namespace floorgrid::io
