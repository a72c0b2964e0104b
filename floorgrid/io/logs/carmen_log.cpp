#include "floorgrid/io/logs/carmen_log.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/line_reader.hpp"
#include "floorgrid/io/logs/carmen_parse.hpp"

namespace floorgrid::io {

namespace {

constexpr double degree = std::numbers::pi / 180.0;
constexpr double carmen_default_max_range = 80.0;  // metres, CARMEN's reader for old lasers

// The PARAMs that set one laser's resolution and maximum range, and their values so far.
struct LaserParams {
  const char* resolution_name;        // degrees
  const char* max_range_name;         // metres, the name SPEC.md gives; wins over the next
  const char* carmen_max_range_name;  // metres, the name CARMEN's robot module (and MRPT) use
  std::optional<double> resolution = {};
  std::optional<double> max_range = {};
  std::optional<double> carmen_max_range = {};
};

struct ParamState {
  LaserParams front{.resolution_name = "laser_front_laser_resolution",
                    .max_range_name = "laser_front_laser_maxrange",
                    .carmen_max_range_name = "robot_front_laser_max"};
  LaserParams rear{.resolution_name = "laser_rear_laser_resolution",
                   .max_range_name = "laser_rear_laser_maxrange",
                   .carmen_max_range_name = "robot_rear_laser_max"};
};

// Remembers a laser PARAM's value; other PARAMs are only listed in the summary.
void apply_param(std::string_view name, std::string_view value, FieldCursor& fields,
                 ParamState& state) {
  for (LaserParams* laser : {&state.front, &state.rear}) {
    std::optional<double>* slot = nullptr;
    if (name == laser->resolution_name)
      slot = &laser->resolution;
    if (name == laser->max_range_name)
      slot = &laser->max_range;
    if (name == laser->carmen_max_range_name)
      slot = &laser->carmen_max_range;
    if (slot == nullptr)
      continue;
    double number = 0.0;
    if (!parse_number(value, number) || !std::isfinite(number) || number <= 0.0) {
      fields.fail(
          "PARAM " + std::string(name) + " must be a number > 0 (got '" + std::string(value) + "')",
          "value");
    }
    *slot = number;
  }
}

// CARMEN's guess of the angle between beams from their number (its readlog.c).
UsedSetting guess_angle_increment(std::size_t beams) {
  if (beams == 180 || beams == 181) {
    return {degree, SettingSource::guess, "180/181 beams: 1 deg"};
  }
  if (beams == 360 || beams == 361) {
    return {0.5 * degree, SettingSource::guess, "360/361 beams: 0.5 deg"};
  }
  if (beams == 400 || beams == 401) {
    return {0.25 * degree, SettingSource::guess, "400/401 beams: 0.25 deg"};
  }
  if (beams == 1)
    return {0.0, SettingSource::guess, "one beam: no increment"};
  return {std::numbers::pi / static_cast<double>(beams - 1), SettingSource::guess,
          "180 deg over the beams: pi/(n-1)"};
}

UsedSetting from_manifest(double value, const char* name) {
  return {value, SettingSource::manifest, std::string("laser.") + name};
}

struct ResolvedSettings {
  UsedSetting start_angle, angle_increment, max_range, min_range;
};

ResolvedSettings resolve_old_laser(const LaserScan& scan, const LaserParams& params,
                                   const LaserSettings& manifest) {
  ResolvedSettings used;
  used.start_angle =
      manifest.start_angle
          ? from_manifest(*manifest.start_angle, "start_angle")
          : UsedSetting{-std::numbers::pi / 2.0, SettingSource::guess, "CARMEN's fixed -90 deg"};
  if (manifest.angle_increment) {
    used.angle_increment = from_manifest(*manifest.angle_increment, "angle_increment");
  } else if (params.resolution) {
    used.angle_increment = {*params.resolution * degree, SettingSource::param,
                            params.resolution_name};
  } else {
    used.angle_increment = guess_angle_increment(scan.ranges.size());
  }
  if (manifest.max_range) {
    used.max_range = from_manifest(*manifest.max_range, "max_range");
  } else if (params.max_range) {
    used.max_range = {*params.max_range, SettingSource::param, params.max_range_name};
  } else if (params.carmen_max_range) {
    used.max_range = {*params.carmen_max_range, SettingSource::param, params.carmen_max_range_name};
  } else {
    used.max_range = {carmen_default_max_range, SettingSource::guess, "CARMEN's default 80 m"};
  }
  return used;
}

ResolvedSettings resolve_robot_laser(const LaserScan& scan, const LaserSettings& manifest,
                                     FieldCursor& fields) {
  ResolvedSettings used;
  used.start_angle = manifest.start_angle ? from_manifest(*manifest.start_angle, "start_angle")
                                          : UsedSetting{scan.start_angle, SettingSource::message,
                                                        scan.type + " start_angle"};
  used.angle_increment = manifest.angle_increment
                             ? from_manifest(*manifest.angle_increment, "angle_increment")
                             : UsedSetting{scan.angle_increment, SettingSource::message,
                                           scan.type + " angular_resolution"};
  used.max_range = manifest.max_range ? from_manifest(*manifest.max_range, "max_range")
                                      : UsedSetting{scan.max_range, SettingSource::message,
                                                    scan.type + " maximum_range"};
  // Only the message's own values can still be bad: the manifest's were validated up front.
  if (!std::isfinite(used.start_angle.value))
    fields.fail("must be finite", "start_angle");
  if (!std::isfinite(used.angle_increment.value) || used.angle_increment.value == 0.0) {
    fields.fail("must be finite and non-zero", "angular_resolution");
  }
  if (!std::isfinite(used.max_range.value) || used.max_range.value <= 0.0) {
    fields.fail("must be a finite number > 0", "maximum_range");
  }
  return used;
}

// Counts of one message type, and the last kept timestamp to tell backwards ones.
struct TypeTrack {
  MessageTypeCount count;
  double last_kept = -std::numeric_limits<double>::infinity();
};

using TypeTracks = std::map<std::string, TypeTrack, std::less<>>;

TypeTrack& track_of(TypeTracks& tracks, std::string_view type) {
  auto found = tracks.find(type);
  if (found == tracks.end())
    found = tracks.emplace(std::string(type), TypeTrack{}).first;
  return found->second;
}

enum class Stamp { kept, zero, backwards };

// Zero, negative or non-finite timestamps are not times; earlier than the last kept message of
// the type is backwards. Equal timestamps are kept (CSAIL prints 6 digits: most are equal).
Stamp keep_timestamp(TypeTrack& track, double timestamp) {
  if (!std::isfinite(timestamp) || timestamp <= 0.0) {
    ++track.count.skipped_zero_timestamp;
    return Stamp::zero;
  }
  if (timestamp < track.last_kept) {
    ++track.count.skipped_backwards_timestamp;
    return Stamp::backwards;
  }
  track.last_kept = timestamp;
  ++track.count.kept;
  return Stamp::kept;
}

// Messages skipped for a zero timestamp, kept aside in line order: a log whose scans all lack
// one is read from them instead (scans and odometry then pair up by order).
struct Unstamped {
  RobotLog log;
  std::vector<ResolvedSettings> settings;  // one per scan
};

bool is_type_name(std::string_view type) {
  return std::all_of(type.begin(), type.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

void record_config(RobotLogSummary& summary, const LaserScan& scan, const ResolvedSettings& used) {
  auto same = [&](const LaserConfigUsage& config) {
    return config.beams == scan.ranges.size() && config.type == scan.type &&
           config.start_angle == used.start_angle &&
           config.angle_increment == used.angle_increment && config.max_range == used.max_range &&
           config.min_range == used.min_range;
  };
  auto found = std::find_if(summary.laser_configs.begin(), summary.laser_configs.end(), same);
  if (found == summary.laser_configs.end()) {
    summary.laser_configs.push_back({scan.type, scan.ranges.size(), used.start_angle,
                                     used.angle_increment, used.max_range, used.min_range, 0});
    found = std::prev(summary.laser_configs.end());
  }
  ++found->scans;
  ++summary.beams_per_scan[scan.ranges.size()];
}

void apply_settings(LaserScan& scan, const ResolvedSettings& used) {
  scan.start_angle = used.start_angle.value;
  scan.angle_increment = used.angle_increment.value;
  scan.max_range = used.max_range.value;
  scan.min_range = used.min_range.value;
}

// One laser message: parsed, its settings resolved, kept or set aside by its timestamp.
void read_laser(std::string_view type, FieldCursor& fields, std::size_t line,
                const ParamState& params, const LaserSettings& manifest, TypeTrack& track,
                RobotLog& log, RobotLogSummary& summary, Unstamped& unstamped) {
  const bool old_style = is_old_laser_type(type);
  LaserScan scan = old_style ? parse_old_laser(fields) : parse_robot_laser(fields);
  scan.type = std::string(type);
  scan.line = line;
  const LaserParams& side = type == "RLASER" ? params.rear : params.front;
  ResolvedSettings used = old_style ? resolve_old_laser(scan, side, manifest)
                                    : resolve_robot_laser(scan, manifest, fields);
  used.min_range = manifest.min_range ? from_manifest(*manifest.min_range, "min_range")
                                      : UsedSetting{0.0, SettingSource::guess, "CARMEN has none"};
  apply_settings(scan, used);
  switch (keep_timestamp(track, scan.timestamp)) {
    case Stamp::kept:
      record_config(summary, scan, used);
      log.scans.push_back(std::move(scan));
      break;
    case Stamp::zero:
      unstamped.log.scans.push_back(std::move(scan));
      unstamped.settings.push_back(used);
      break;
    case Stamp::backwards:
      break;
  }
}

// No scan had a valid timestamp: every message set aside is read, in line order.
void read_in_line_order(Unstamped& unstamped, TypeTracks& tracks, RobotLog& log,
                        RobotLogSummary& summary) {
  for (std::size_t i = 0; i < unstamped.log.scans.size(); ++i)
    record_config(summary, unstamped.log.scans[i], unstamped.settings[i]);
  log.scans = std::move(unstamped.log.scans);
  const bool take_odometry = log.odometry.empty();
  if (take_odometry)
    log.odometry = std::move(unstamped.log.odometry);
  for (auto& [type, track] : tracks) {
    if (is_old_laser_type(type) || is_robot_laser_type(type) || (take_odometry && type == "ODOM")) {
      track.count.kept += track.count.skipped_zero_timestamp;
      track.count.skipped_zero_timestamp = 0;
    }
  }
  summary.warnings.push_back(fmt::format(
      "no laser scan has a valid timestamp (all {} are zero or not a number): read in line "
      "order, scans and odometry paired by order",
      log.scans.size()));
}

// The longest readings of some scans: the cluster within a little of the longest one (lasers
// report "no return" as one code, or a few codes close together: Seattle's 81.87-81.91 m), and
// how many readings lie beyond a max range but below that cluster.
struct LongReadings {
  float longest = 0.0f;
  float cluster_low = 0.0f;  // the shortest reading of the cluster
  std::size_t in_cluster = 0;
  std::size_t above = 0;  // > max_range and < cluster_low
  std::size_t total = 0;
};

LongReadings long_readings(const std::vector<LaserScan*>& scans, double max_range) {
  LongReadings r;
  for (const LaserScan* scan : scans) {
    for (const float range : scan->ranges) {
      if (std::isfinite(range)) {
        ++r.total;
        r.longest = std::max(r.longest, range);
      }
    }
  }
  const float low = r.longest - std::max(0.1f, 0.002f * r.longest);
  r.cluster_low = r.longest;
  for (const LaserScan* scan : scans) {
    for (const float range : scan->ranges) {
      if (range >= low && range <= r.longest) {
        ++r.in_cluster;
        r.cluster_low = std::min(r.cluster_low, range);
      }
    }
  }
  for (const LaserScan* scan : scans) {
    for (const float range : scan->ranges) {
      if (range > static_cast<float>(max_range) && range < r.cluster_low)
        ++r.above;
    }
  }
  return r;
}

// The readings win over a PARAM or a guess of the max range that they contradict: when many
// readings lie beyond it (other than at one saturation value), or when they saturate at one
// value below it (ACES at 50 m under CARMEN's 80 m guess: those are no returns, not walls).
// A max range from a float reading is kept as that float, so the reading compares equal.
void check_max_range_against_readings(RobotLog& log, RobotLogSummary& summary) {
  for (LaserConfigUsage& config : summary.laser_configs) {
    const UsedSetting old = config.max_range;
    if (old.source != SettingSource::param && old.source != SettingSource::guess)
      continue;
    std::vector<LaserScan*> scans;
    for (LaserScan& scan : log.scans) {
      if (scan.type == config.type && scan.ranges.size() == config.beams &&
          scan.max_range == old.value) {
        scans.push_back(&scan);
      }
    }
    const LongReadings r = long_readings(scans, old.value);
    if (r.total == 0)
      continue;
    const std::size_t many = std::max<std::size_t>(20, r.total / 1000);
    // Many at the top, but a minority: "no return" codes (all readings alike say nothing).
    const bool saturates = r.in_cluster >= many && 2 * r.in_cluster < r.total;
    double value = old.value;
    std::string why;
    if (r.above >= many) {
      value =
          saturates ? r.cluster_low : std::nextafter(r.longest, std::numeric_limits<float>::max());
      why = fmt::format("{} readings ({:.2f}%) are longer than it, up to {:.6g} m", r.above,
                        100.0 * double(r.above) / double(r.total), r.longest);
    } else if (saturates && r.longest < static_cast<float>(old.value)) {
      value = r.cluster_low;
      why = fmt::format("{} readings saturate at {:.6g}-{:.6g} m, below it", r.in_cluster,
                        r.cluster_low, r.longest);
    }
    if (value == old.value)
      continue;
    for (LaserScan* scan : scans)
      scan->max_range = value;
    config.max_range = {value, SettingSource::readings, why};
    summary.warnings.push_back(fmt::format(
        "{} max range {:.6g} m ({}{}{}) contradicts the readings: {}; the readings win: max range "
        "{:.6g} m{}",
        config.type, old.value, to_string(old.source), old.detail.empty() ? "" : ": ", old.detail,
        why, value, saturates ? " (readings at it count as no return)" : ""));
  }
}

void summarize_time(const RobotLog& log, RobotLogSummary& summary) {
  double first = std::numeric_limits<double>::infinity();
  double last = -std::numeric_limits<double>::infinity();
  for (const OdometryReading& odometry : log.odometry) {
    first = std::min(first, odometry.timestamp);
    last = std::max(last, odometry.timestamp);
  }
  for (const LaserScan& scan : log.scans) {
    first = std::min(first, scan.timestamp);
    last = std::max(last, scan.timestamp);
  }
  summary.first_timestamp = first;
  summary.last_timestamp = last;
  summary.duration = last - first;
}

}  // namespace

CarmenLog read_carmen_log(const std::filesystem::path& path, const CarmenReadOptions& options) {
  validate_laser_settings(options.laser);
  LineReader reader(path);
  CarmenLog result;
  RobotLog& log = result;
  RobotLogSummary& summary = result.summary;
  summary.source = reader.file();
  ParamState params;
  TypeTracks tracks;
  Unstamped unstamped;

  std::string_view line;
  while (reader.next(line)) {
    const std::size_t number = reader.line_number();
    if (number == 1 && line.starts_with("\xEF\xBB\xBF"))
      line.remove_prefix(3);  // UTF-8 BOM
    FieldCursor fields(line, reader.file(), number);
    if (fields.at_end()) {
      TypeTrack& track = track_of(tracks, "(empty)");
      ++track.count.lines;
      ++track.count.not_data;
      continue;
    }
    const std::string_view type = fields.word("type");
    if (type.front() == '#') {
      TypeTrack& track = track_of(tracks, "#");
      ++track.count.lines;
      ++track.count.not_data;
      continue;
    }
    if (!is_type_name(type)) {
      fields.fail("not a CARMEN message type: '" + std::string(type.substr(0, 40)) +
                      "' (is this a CARMEN log?)",
                  "type");
    }
    TypeTrack& track = track_of(tracks, type);
    ++track.count.lines;
    if (type == "ODOM") {
      OdometryReading odometry = parse_odom(fields);
      odometry.line = number;
      const Stamp stamp = keep_timestamp(track, odometry.timestamp);
      if (stamp == Stamp::kept)
        log.odometry.push_back(odometry);
      else if (stamp == Stamp::zero)
        unstamped.log.odometry.push_back(odometry);
    } else if (is_old_laser_type(type) || is_robot_laser_type(type)) {
      read_laser(type, fields, number, params, options.laser, track, log, summary, unstamped);
    } else if (type == "PARAM") {
      const std::string_view name = fields.word("name");
      const std::string_view value = fields.word("value");
      summary.params[std::string(name)] = std::string(value);
      apply_param(name, value, fields, params);
      ++track.count.not_data;
    } else {
      ++track.count.not_data;  // NEFF, SYNC, TRUEPOS, RAWLASER*, ...: nothing to read
    }
  }

  summary.lines = reader.line_number();
  if (log.scans.empty() && !unstamped.log.scans.empty())
    read_in_line_order(unstamped, tracks, log, summary);
  for (auto& [type, track] : tracks)
    summary.messages[type] = track.count;
  if (log.scans.empty()) {
    throw InputError(
        "no laser scan (FLASER, RLASER, ROBOTLASER1) with a valid timestamp in the log: "
        "nothing to localize with",
        reader.file(), static_cast<long>(summary.lines));
  }
  check_max_range_against_readings(log, summary);
  summary.ranges = count_ranges(log.scans);
  summarize_time(log, summary);
  return result;
}

RobotLog read_carmen(const std::filesystem::path& path, const CarmenReadOptions& options) {
  return std::move(read_carmen_log(path, options));
}

}  // namespace floorgrid::io
