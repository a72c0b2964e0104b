#include "floorgrid/robot/robot_log.hpp"

#include <cmath>

namespace floorgrid {

const char* to_string(RangeKind kind) {
  switch (kind) {
    case RangeKind::hit:
      return "hit";
    case RangeKind::no_return:
      return "no_return";
    case RangeKind::too_close:
      return "too_close";
    case RangeKind::invalid:
      return "invalid";
  }
  return "?";
}

RangeKind LaserScan::range_kind(std::size_t i) const {
  const float r = ranges[i];
  if (std::isnan(r) || r < 0.0f)
    return RangeKind::invalid;
  // Compared at the readings' own (float) precision: a reading printed as "80.99" in a log whose
  // max range is 80.99 m is at max range, although float(80.99) < 80.99.
  if (r >= static_cast<float>(max_range))
    return RangeKind::no_return;
  // A zero reading is how many lasers say "no echo": never a point at the laser itself.
  if (r == 0.0f || r < static_cast<float>(min_range))
    return RangeKind::too_close;
  return RangeKind::hit;
}

RangeCounts count_ranges(const std::vector<LaserScan>& scans) {
  RangeCounts counts;
  for (const LaserScan& scan : scans) {
    for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
      ++counts.total;
      switch (scan.range_kind(i)) {
        case RangeKind::hit:
          ++counts.hits;
          break;
        case RangeKind::no_return:
          ++counts.no_return;
          break;
        case RangeKind::too_close:
          ++counts.too_close;
          break;
        case RangeKind::invalid:
          ++counts.invalid;
          break;
      }
    }
  }
  return counts;
}

}  // namespace floorgrid
