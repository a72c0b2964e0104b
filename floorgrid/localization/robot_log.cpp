#include "floorgrid/localization/robot_log.hpp"

#include <cmath>
#include <sstream>

#include "floorgrid/core/error.hpp"

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

const char* to_string(SettingSource source) {
  switch (source) {
    case SettingSource::manifest:
      return "manifest";
    case SettingSource::message:
      return "message";
    case SettingSource::param:
      return "param";
    case SettingSource::guess:
      return "guess";
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

namespace {
std::string got(double value) {
  std::ostringstream out;
  out << "(got " << value << ")";
  return out.str();
}
}  // namespace

void validate_laser_settings(const LaserSettings& settings) {
  if (settings.max_range && !(std::isfinite(*settings.max_range) && *settings.max_range > 0.0)) {
    throw InputError("must be a finite number > 0 " + got(*settings.max_range), {}, 0,
                     "laser.max_range");
  }
  if (settings.min_range && !(std::isfinite(*settings.min_range) && *settings.min_range >= 0.0)) {
    throw InputError("must be a finite number >= 0 " + got(*settings.min_range), {}, 0,
                     "laser.min_range");
  }
  if (settings.min_range && settings.max_range && *settings.min_range >= *settings.max_range) {
    throw InputError("must be below laser.max_range " + got(*settings.min_range), {}, 0,
                     "laser.min_range");
  }
  if (settings.start_angle && !std::isfinite(*settings.start_angle)) {
    throw InputError("must be a finite number " + got(*settings.start_angle), {}, 0,
                     "laser.start_angle");
  }
  if (settings.angle_increment &&
      !(std::isfinite(*settings.angle_increment) && *settings.angle_increment != 0.0)) {
    throw InputError("must be a finite non-zero number " + got(*settings.angle_increment), {}, 0,
                     "laser.angle_increment");
  }
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
