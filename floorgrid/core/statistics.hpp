#pragma once

#include <vector>

namespace floorgrid {

/// The median of `values`: the middle value, or the mean of the two middle values of an even
/// count; NaN when empty. O(n) (selection, not a sort).
double median(std::vector<double> values);

/// The upper median of `values`: the middle value, or the larger of the two middle values of
/// an even count, so always one of the values (a consensus that is an actual residual, a
/// distance on the grid's own steps); NaN when empty. O(n).
double upper_median(std::vector<double> values);

/// The q-quantile of `values` (q in [0, 1]) by linear interpolation between the sorted values
/// (numpy's default); NaN when empty.
double quantile(std::vector<double> values, double q);

}  // namespace floorgrid
