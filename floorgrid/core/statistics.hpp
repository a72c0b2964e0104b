#pragma once

#include <vector>

namespace floorgrid {

/// The median of `values`: the middle value, or the mean of the two middle values of an even
/// count; NaN when empty. O(n) (selection, not a sort).
double median(std::vector<double> values);

/// The q-quantile of `values` (q in [0, 1]) by linear interpolation between the sorted values
/// (numpy's default); NaN when empty.
double quantile(std::vector<double> values, double q);

}  // namespace floorgrid
