#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::io {

/// Points (or poses) read from a `map --points` CSV: header `x,y` or `x,y,theta`.
struct PointsTable {
  Eigen::Matrix2Xd points;   ///< 2 x N, in the file's units
  Eigen::VectorXd headings;  ///< N radians when the file has `theta`, else empty
  bool has_headings() const { return headings.size() != 0; }
};

/// Reads a points CSV; InputError naming the file, line and column for a bad header, row or
/// number, or a coordinate beyond `max_abs`. Blank lines and `#` comments are skipped.
PointsTable read_points_csv(const std::filesystem::path& path, double max_abs);

/// One output row of `map`: the mapped point (and heading) or nothing when not invertible.
struct MappedRow {
  MappedPoint mapped;             ///< point in the output's units, std and distance in metres
  std::optional<double> heading;  ///< radians, when the input had headings
};

/// One point mapped as `map` maps it: plan to grid (or back when `inverse`), in the model's
/// pair units (PointMapping::unit()), and its heading through the Jacobian when `heading` is not
/// null (a pointer, not std::optional: GCC 12 warns falsely about optional<double> copies).
MappedRow map_row(const PointMapping& model, const Eigen::Vector2d& point, const double* heading,
                  bool inverse);

/// Writes `map`'s output CSV atomically: header `x,y[,theta],std_m,nearest_pair_m,flag`, one
/// row per input row in order; empty x, y (and theta) where not invertible, empty std_m where
/// the model has no predictive variance.
void write_mapped_csv(const std::vector<MappedRow>& rows, bool with_headings,
                      const std::filesystem::path& path);

}  // namespace floorgrid::io
