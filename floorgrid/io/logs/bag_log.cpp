#include "floorgrid/io/logs/bag_log.hpp"

#include <fmt/format.h>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/logs/bag_message_checks.hpp"
#include "floorgrid/io/logs/ros_messages.hpp"

namespace floorgrid::io {
namespace {

/// One odometry sample of the robot's base in the odometry frame.
struct OdometrySample {
  std::int64_t stamp_ns = 0;
  Pose2 pose;
  double tv = 0.0, rv = 0.0;
};

Eigen::Quaterniond quaternion(const RosQuaternion& q) {
  Eigen::Quaterniond out(q.w, q.x, q.y, q.z);
  if (!(out.norm() > 1e-9) || !std::isfinite(out.norm()))
    return Eigen::Quaterniond::Identity();
  return out.normalized();
}

double yaw_of(const RosQuaternion& q) {
  // A planar robot's quaternion turns about z alone: its yaw directly, to the last bit.
  if (q.x == 0.0 && q.y == 0.0 && (q.z != 0.0 || q.w != 0.0))
    return normalize_angle(2.0 * std::atan2(q.z, q.w));
  const Eigen::Matrix3d R = quaternion(q).toRotationMatrix();
  return std::atan2(R(1, 0), R(0, 0));
}

Eigen::Isometry3d isometry(const RosTransform& t) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = quaternion(t.rotation).toRotationMatrix();
  out.translation() = Eigen::Vector3d(t.translation.x, t.translation.y, t.translation.z);
  return out;
}

std::string strip_slash(std::string frame) {
  if (!frame.empty() && frame.front() == '/')
    frame.erase(0, 1);
  return frame;
}

/// The topics of `kind`, by name.
std::vector<const BagTopic*> topics_of(const BagContents& contents, RosMessageKind kind) {
  std::vector<const BagTopic*> out;
  for (const BagTopic& t : contents.topics)
    if (ros_message_kind(t.type) == kind)
      out.push_back(&t);
  return out;
}

std::string topic_list(const BagContents& contents) {
  std::string out;
  for (const BagTopic& t : contents.topics)
    out += (out.empty() ? "" : ", ") + t.topic + " (" + t.type + ")";
  return out.empty() ? "none" : out;
}

/// The topic named by the manifest, or the only one of its kind.
std::optional<std::string> choose_topic(const BagContents& contents, RosMessageKind kind,
                                        const std::optional<std::string>& chosen,
                                        const std::string& file, const char* key, const char* type,
                                        bool required) {
  const std::vector<const BagTopic*> candidates = topics_of(contents, kind);
  if (chosen) {
    for (const BagTopic& t : contents.topics)
      if (t.topic == *chosen) {
        if (ros_message_kind(t.type) != kind)
          throw InputError(fmt::format("topic {} is a {}, not a {}", *chosen, t.type, type), file,
                           0, key);
        return *chosen;
      }
    throw InputError(
        fmt::format("the bag has no topic {} (topics: {})", *chosen, topic_list(contents)), file, 0,
        key);
  }
  if (candidates.size() == 1)
    return candidates.front()->topic;
  if (candidates.empty()) {
    if (!required)
      return std::nullopt;
    throw InputError(fmt::format("the bag has no {} topic to localize with (topics: {})", type,
                                 topic_list(contents)),
                     file);
  }
  std::string names;
  for (const BagTopic* t : candidates)
    names += (names.empty() ? "" : ", ") + t->topic;
  throw InputError(fmt::format("the bag has {} {} topics ({}): choose one with {} in dataset.yaml",
                               candidates.size(), type, names, key),
                   file);
}

/// Odometry gaps longer than this are reported: a pose interpolated across them is a guess.
constexpr std::int64_t kLongOdometryGapNs = 2'000'000'000;

/// The robot's pose at `stamp` interpolated between the samples around it (sorted by stamp),
/// or nullopt outside their span. `gap_ns` is set to the time between those two samples (0 at a
/// sample).
std::optional<Pose2> interpolate(const std::vector<OdometrySample>& samples, std::int64_t stamp,
                                 std::int64_t& gap_ns) {
  gap_ns = 0;
  if (samples.empty() || stamp < samples.front().stamp_ns || stamp > samples.back().stamp_ns)
    return std::nullopt;
  const auto after =
      std::lower_bound(samples.begin(), samples.end(), stamp,
                       [](const OdometrySample& s, std::int64_t t) { return s.stamp_ns < t; });
  if (after->stamp_ns == stamp || after == samples.begin())
    return after->pose;
  const OdometrySample& a = *(after - 1);
  const OdometrySample& b = *after;
  gap_ns = b.stamp_ns - a.stamp_ns;
  const double f =
      static_cast<double>(stamp - a.stamp_ns) / static_cast<double>(b.stamp_ns - a.stamp_ns);
  return Pose2{a.pose.x + f * (b.pose.x - a.pose.x), a.pose.y + f * (b.pose.y - a.pose.y),
               normalize_angle(a.pose.theta + f * normalize_angle(b.pose.theta - a.pose.theta))};
}

/// One transform read from a TF topic, with where it came from.
struct StampedTransform {
  RosTransform transform;
  bool is_static = false;  ///< from a static topic
  MessagePlace place;      ///< its message
  std::string field;       ///< "transforms[i]" in its message
};

/// The transform tree's parent links: child -> the transform to its parent, first seen kept
/// (mounts do not move; the odometry link is excluded by the caller).
using TransformTree = std::map<std::string, const StampedTransform*>;

/// `frame` in `base`, by walking up from `frame` (every link's values checked as it is used);
/// nullopt when the tree does not reach `base`. A chain may be as long as the tree holds links;
/// one that comes back to a frame it passed loops, and is refused.
std::optional<Eigen::Isometry3d> frame_in(const TransformTree& tree, const std::string& base,
                                          const std::string& frame, const std::string& file) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  std::string at = frame;
  for (std::size_t depth = 0; depth <= tree.size(); ++depth) {
    if (at == base)
      return T;
    const auto link = tree.find(at);
    if (link == tree.end())
      return std::nullopt;
    const StampedTransform& t = *link->second;
    check_transform(t.transform, t.field, t.place);
    T = isometry(t.transform) * T;
    at = t.transform.header.frame_id;
  }
  throw InputError(fmt::format("the transforms from {} towards {} on /tf_static and /tf loop "
                               "(frame {} is its own ancestor): the laser's mount is undefined",
                               frame, base, at),
                   file);
}

/// The value a float32 field was most likely set from: the shortest decimal (in units of
/// `unit`: degrees for angles, metres for ranges) that rounds to the same float. LaserScan's
/// fields are float32, but drivers are configured in decimal degrees and metres, as CARMEN logs
/// print them; so a bag and the CARMEN log of the same run give the same double.
double decimal_value(float value, double unit) {
  if (!std::isfinite(value))
    return value;
  double power = 1.0;
  for (int digits = 0; digits <= 7; ++digits, power *= 10.0) {
    const double candidate = std::round(static_cast<double>(value) / unit * power) / power * unit;
    if (static_cast<float>(candidate) == value)
      return candidate;
  }
  return value;
}

constexpr double kDegree = std::numbers::pi / 180.0;

/// Seconds since the epoch, correctly rounded (so 227623000 ns is exactly strtod's 0.227623).
double seconds(std::int64_t ns) {
  return static_cast<double>(ns) / 1e9;
}

}  // namespace

BagLog read_bag_log(const std::filesystem::path& path, const BagLogOptions& options) {
  validate_laser_settings(options.laser);
  const std::string file = path.string();
  BagLog log;
  log.contents = bag_contents(path, options.limits);
  log.scan_topic = *choose_topic(log.contents, RosMessageKind::laser_scan, options.scan_topic, file,
                                 "log_topics.scan", "sensor_msgs/LaserScan", true);
  const std::optional<std::string> odom_topic =
      choose_topic(log.contents, RosMessageKind::odometry, options.odom_topic, file,
                   "log_topics.odom", "nav_msgs/Odometry", false);
  std::set<std::string> wanted = {log.scan_topic};
  if (odom_topic)
    wanted.insert(*odom_topic);
  for (const BagTopic* t : topics_of(log.contents, RosMessageKind::tf))
    wanted.insert(t->topic);

  // Decode what is needed, in file order.
  struct StampedScan {
    RosLaserScan scan;
    std::size_t ordinal = 0;
  };
  std::vector<StampedScan> scans;
  std::vector<RosOdometry> odometry;
  std::vector<StampedTransform> transforms;
  std::map<std::string, MessageTypeCount> counts;
  read_bag(
      path,
      [&](const BagTopic& topic, const BagMessageView& message) {
        const PayloadSource source{file, message.offset, topic.topic};
        MessageTypeCount& count = counts[topic.topic];
        ++count.lines;
        const MessagePlace place{file, topic.topic, count.lines, message.offset};
        // Only the scan topic, the odometry topic and the TF topics were asked for.
        if (topic.topic == log.scan_topic) {
          RosLaserScan s = decode_laser_scan(message.data, topic.encoding, source);
          check_scan_settings(s, options.laser, place);
          if (s.header.stamp_ns == 0)
            s.header.stamp_ns = message.log_time_ns;
          scans.push_back({std::move(s), count.lines});
        } else if (odom_topic && topic.topic == *odom_topic) {
          RosOdometry o = decode_odometry(message.data, topic.encoding, source);
          check_odometry(o, place);
          if (o.header.stamp_ns == 0)
            o.header.stamp_ns = message.log_time_ns;
          odometry.push_back(std::move(o));
          ++count.kept;
        } else {
          const bool is_static = topic.topic.find("static") != std::string::npos;
          std::size_t i = 0;
          for (RosTransform& t : decode_tf_message(message.data, topic.encoding, source)) {
            if (t.header.stamp_ns == 0)
              t.header.stamp_ns = message.log_time_ns;
            t.header.frame_id = strip_slash(t.header.frame_id);
            t.child_frame_id = strip_slash(t.child_frame_id);
            // Checked where used: a NaN transform of a frame the run does not need is harmless.
            transforms.push_back(
                {std::move(t), is_static, place, "transforms[" + std::to_string(i++) + "]"});
          }
          ++count.not_data;  // transforms place the laser and may carry odometry: not scans
        }
      },
      &wanted, options.limits);
  // Messages are in file order; scans are used in the order of their stamps.
  std::stable_sort(scans.begin(), scans.end(), [](const StampedScan& a, const StampedScan& b) {
    return a.scan.header.stamp_ns < b.scan.header.stamp_ns;
  });
  log.summary.source = file;
  for (const BagTopic& t : log.contents.topics)
    log.summary.lines += t.messages;
  if (scans.empty())
    throw InputError(fmt::format("topic {} holds no laser scan to localize with", log.scan_topic),
                     file, 0, "log_topics.scan");

  // Frames: the Odometry's own, else the manifest's, else ROS's conventional names.
  std::string base_frame = options.base_frame.value_or("");
  std::string odom_frame = options.odom_frame.value_or("");
  if (!odometry.empty()) {
    if (base_frame.empty())
      base_frame = strip_slash(odometry.front().child_frame_id);
    if (odom_frame.empty())
      odom_frame = strip_slash(odometry.front().header.frame_id);
  }
  if (base_frame.empty())
    base_frame = "base_link";
  if (odom_frame.empty())
    odom_frame = "odom";

  // Odometry samples, sorted by stamp.
  std::vector<OdometrySample> samples;
  if (!odometry.empty()) {
    log.odometry_source = *odom_topic;
    for (const RosOdometry& o : odometry)
      samples.push_back({o.header.stamp_ns,
                         Pose2{o.position.x, o.position.y, yaw_of(o.orientation)},
                         o.linear_velocity.x, o.angular_velocity.z});
  } else {
    log.odometry_source = fmt::format("/tf ({} -> {})", odom_frame, base_frame);
    for (const StampedTransform& s : transforms) {
      const RosTransform& t = s.transform;
      if (!s.is_static && t.header.frame_id == odom_frame && t.child_frame_id == base_frame) {
        check_transform(t, s.field, s.place);
        samples.push_back({t.header.stamp_ns,
                           Pose2{t.translation.x, t.translation.y, yaw_of(t.rotation)}, 0.0, 0.0});
      }
    }
    if (samples.empty())
      throw InputError(fmt::format("the bag has no odometry: no nav_msgs/Odometry topic and no "
                                   "{} -> {} transform on /tf (set log_topics.odom or log_frames)",
                                   odom_frame, base_frame),
                       file);
  }
  std::stable_sort(
      samples.begin(), samples.end(),
      [](const OdometrySample& a, const OdometrySample& b) { return a.stamp_ns < b.stamp_ns; });
  for (const OdometrySample& s : samples)
    log.odometry.push_back({s.pose, s.tv, s.rv, 0.0, seconds(s.stamp_ns), 0});

  // The laser's mount: base -> the scans' frame through the static (and other) transforms.
  TransformTree tree;
  for (const StampedTransform& s : transforms) {
    const RosTransform& t = s.transform;
    if (!(t.header.frame_id == odom_frame && t.child_frame_id == base_frame))
      tree.try_emplace(t.child_frame_id, &s);
  }
  log.laser_frame = strip_slash(scans.front().scan.header.frame_id);
  Eigen::Isometry3d T_base_laser = Eigen::Isometry3d::Identity();
  if (const auto found = frame_in(tree, base_frame, log.laser_frame, file)) {
    T_base_laser = *found;
  } else if (log.laser_frame != base_frame) {
    log.summary.warnings.push_back(fmt::format(
        "no transform from {} to the laser's frame {} on /tf_static or /tf: the laser is taken "
        "to sit at {}",
        base_frame, log.laser_frame, base_frame));
  }
  const Eigen::Vector3d z_axis = T_base_laser.linear().col(2);
  if (std::abs(z_axis.z()) < std::cos(10.0 * std::numbers::pi / 180.0))
    throw InputError(
        fmt::format("the laser frame {} is tilted {:.0f} degrees from level in {}: "
                    "not a planar laser",
                    log.laser_frame,
                    std::acos(std::min(1.0, std::abs(z_axis.z()))) * 180.0 / std::numbers::pi,
                    base_frame),
        file);
  log.laser_upside_down = z_axis.z() < 0.0;
  log.laser_mount = Pose2{T_base_laser.translation().x(), T_base_laser.translation().y(),
                          std::atan2(T_base_laser.linear()(1, 0), T_base_laser.linear()(0, 0))};

  // Scans, each at the robot's interpolated pose.
  std::size_t outside = 0, across_gaps = 0;
  MessageTypeCount& scan_count = counts[log.scan_topic];
  std::map<std::string, std::size_t> config_index;
  for (StampedScan& stamped : scans) {
    RosLaserScan& s = stamped.scan;
    std::int64_t gap_ns = 0;
    const std::optional<Pose2> robot = interpolate(samples, s.header.stamp_ns, gap_ns);
    across_gaps += gap_ns > kLongOdometryGapNs ? 1 : 0;
    if (!robot) {
      ++outside;
      ++scan_count.not_data;
      continue;
    }
    LaserScan scan;
    scan.type = "LaserScan";
    scan.timestamp = seconds(s.header.stamp_ns);
    scan.line = stamped.ordinal;
    scan.robot_pose = *robot;
    scan.laser_pose = robot->compose(log.laser_mount);
    const auto n = static_cast<double>(s.ranges.size());
    const double angle_min = decimal_value(s.angle_min, kDegree);
    const double increment = decimal_value(s.angle_increment, kDegree);
    const double message_start =
        log.laser_upside_down ? -(angle_min + (n - 1.0) * increment) : angle_min;
    scan.start_angle = options.laser.start_angle.value_or(message_start);
    scan.angle_increment = options.laser.angle_increment.value_or(increment);
    scan.max_range = options.laser.max_range.value_or(decimal_value(s.range_max, 1.0));
    scan.min_range = options.laser.min_range.value_or(decimal_value(s.range_min, 1.0));
    if (!(scan.max_range > 0.0) || !(scan.min_range >= 0.0) || scan.min_range >= scan.max_range ||
        !(scan.angle_increment != 0.0) || !std::isfinite(scan.start_angle))
      throw InputError(fmt::format("scan {} on {} has range_min {} and range_max {}, angle_min "
                                   "{} and angle_increment {}: not a usable laser (set laser: "
                                   "in dataset.yaml)",
                                   stamped.ordinal, log.scan_topic, s.range_min, s.range_max,
                                   s.angle_min, s.angle_increment),
                       file, 0, "log_topics.scan");
    scan.ranges = std::move(s.ranges);
    for (float& r : scan.ranges)
      if (std::isinf(r) && r < 0.0f)
        r = 0.0f;  // REP 117: -inf is "too close"
    if (log.laser_upside_down)
      std::reverse(scan.ranges.begin(), scan.ranges.end());
    ++scan_count.kept;

    const std::string key = fmt::format("{} {} {} {} {}", scan.ranges.size(), scan.start_angle,
                                        scan.angle_increment, scan.max_range, scan.min_range);
    auto [it, added] = config_index.try_emplace(key, log.summary.laser_configs.size());
    if (added) {
      const auto used = [&](const std::optional<double>& manifest, double value,
                            const char* field) {
        return manifest ? UsedSetting{*manifest, SettingSource::manifest, "laser"}
                        : UsedSetting{value, SettingSource::message, field};
      };
      LaserConfigUsage c;
      c.type = log.scan_topic;
      c.beams = scan.ranges.size();
      c.start_angle = used(options.laser.start_angle, scan.start_angle, "angle_min");
      c.angle_increment =
          used(options.laser.angle_increment, scan.angle_increment, "angle_increment");
      c.max_range = used(options.laser.max_range, scan.max_range, "range_max");
      c.min_range = used(options.laser.min_range, scan.min_range, "range_min");
      log.summary.laser_configs.push_back(c);
    }
    ++log.summary.laser_configs[it->second].scans;
    ++log.summary.beams_per_scan[scan.ranges.size()];
    log.scans.push_back(std::move(scan));
  }
  log.summary.messages = std::move(counts);
  if (outside > 0)
    log.summary.warnings.push_back(
        fmt::format("{} of {} scans lie outside the odometry's time span and were skipped", outside,
                    scans.size()));
  if (across_gaps > 0)
    log.summary.warnings.push_back(fmt::format(
        "{} scans lie in odometry gaps longer than {} s: their poses are interpolated across "
        "the gap",
        across_gaps, kLongOdometryGapNs / 1'000'000'000));
  if (log.scans.empty())
    throw InputError(fmt::format("no scan on {} lies within the odometry's time span ({})",
                                 log.scan_topic, log.odometry_source),
                     file);
  if (log.laser_upside_down)
    log.summary.warnings.push_back(
        fmt::format("the laser frame {} is mounted upside down: its beams are read clockwise",
                    log.laser_frame));
  log.summary.ranges = count_ranges(log.scans);
  const double first = std::min(log.scans.front().timestamp, log.odometry.front().timestamp);
  const double last = std::max(log.scans.back().timestamp, log.odometry.back().timestamp);
  log.summary.first_timestamp = first;
  log.summary.last_timestamp = last;
  log.summary.duration = last - first;
  return log;
}

}  // namespace floorgrid::io
