#include "floorgrid/io/logs/robot_log_summary.hpp"

#include <cmath>
#include <sstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {

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
    case SettingSource::readings:
      return "readings";
  }
  return "?";
}

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

}  // namespace floorgrid
