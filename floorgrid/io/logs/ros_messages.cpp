#include "floorgrid/io/logs/ros_messages.hpp"

#include <algorithm>
#include <cstring>

#include "floorgrid/io/files/byte_cursor.hpp"

namespace floorgrid::io {
namespace {

/// Reads the fields of one payload in its encoding: ROS 1 (packed) or CDR (each primitive
/// aligned to its size, counted from the byte after the 4-byte encapsulation header; strings
/// carry their terminating NUL in the length).
class PayloadReader {
 public:
  PayloadReader(std::span<const std::uint8_t> data, MessageEncoding encoding,
                const PayloadSource& source)
      : cursor_(data, source.file, source.offset), encoding_(encoding), topic_(source.topic) {
    if (encoding_ == MessageEncoding::cdr) {
      const auto kind = cursor_.read<std::uint8_t>("the CDR encapsulation header");
      const auto endian = cursor_.read<std::uint8_t>("the CDR encapsulation header");
      cursor_.skip(2, "the CDR encapsulation options");
      if (kind != 0 || endian != 1)
        fail("CDR encapsulation " + std::to_string(kind) + "," + std::to_string(endian) +
             " is not little-endian CDR (0,1)");
      origin_ = cursor_.position();
    }
  }

  template <typename T>
  T read(std::string_view what) {
    align(sizeof(T), what);
    return cursor_.read<T>(what);
  }

  std::string string(std::string_view what) {
    const auto length = read<std::uint32_t>(what);
    if (encoding_ == MessageEncoding::ros1)
      return cursor_.string(length, what);
    if (length == 0)
      return {};
    std::string s = cursor_.string(length, what);
    if (s.back() != '\0')
      fail(std::string(what) + " does not end in NUL");
    s.pop_back();
    return s;
  }

  /// A sequence's element count, checked against the bytes left (each element at least
  /// `element_bytes`), so a lying length fails before anything is allocated.
  std::uint32_t count(std::size_t element_bytes, std::string_view what) {
    const auto n = read<std::uint32_t>(what);
    if (element_bytes > 0 && n > cursor_.remaining() / element_bytes)
      fail(std::string(what) + " says " + std::to_string(n) + " elements but only " +
           std::to_string(cursor_.remaining()) + " bytes remain");
    return n;
  }

  template <typename T>
  std::vector<T> sequence(std::string_view what) {
    const std::uint32_t n = count(sizeof(T), what);
    std::vector<T> out(n);
    if (n > 0) {
      align(sizeof(T), what);
      const std::span<const std::uint8_t> raw = cursor_.bytes(n * sizeof(T), what);
      std::memcpy(out.data(), raw.data(), raw.size());
    }
    return out;
  }

  void skip_doubles(std::size_t n, std::string_view what) {
    align(sizeof(double), what);
    cursor_.skip(n * sizeof(double), what);
  }

  RosHeader header() {
    RosHeader h;
    if (encoding_ == MessageEncoding::ros1)
      read<std::uint32_t>("header.seq");
    const auto sec = encoding_ == MessageEncoding::ros1
                         ? std::int64_t{read<std::uint32_t>("header.stamp.sec")}
                         : std::int64_t{read<std::int32_t>("header.stamp.sec")};
    const auto nsec = read<std::uint32_t>("header.stamp.nanosec");
    h.stamp_ns = sec * 1'000'000'000 + nsec;
    h.frame_id = string("header.frame_id");
    return h;
  }

  RosVector3 vector3(std::string_view what) {
    RosVector3 v;
    v.x = read<double>(what);
    v.y = read<double>(what);
    v.z = read<double>(what);
    return v;
  }

  RosQuaternion quaternion(std::string_view what) {
    RosQuaternion q;
    q.x = read<double>(what);
    q.y = read<double>(what);
    q.z = read<double>(what);
    q.w = read<double>(what);
    return q;
  }

  /// CDR may pad the end to a multiple of 4; anything more is a payload of another type.
  void finish(std::string_view type) {
    const std::size_t left = cursor_.remaining();
    if (left == 0 || (encoding_ == MessageEncoding::cdr && left < 4))
      return;
    fail(std::to_string(left) + " bytes left over after a " + std::string(type) +
         " (is the topic's type right?)");
  }

  [[noreturn]] void fail(const std::string& message) const {
    cursor_.fail("topic " + std::string(topic_) + ": " + message);
  }

 private:
  void align(std::size_t size, std::string_view what) {
    if (encoding_ != MessageEncoding::cdr)
      return;
    const std::size_t alignment = std::min<std::size_t>(size, 8);
    const std::size_t misalign = (cursor_.position() - origin_) % alignment;
    if (misalign != 0)
      cursor_.skip(alignment - misalign, what);
  }

  ByteCursor cursor_;
  MessageEncoding encoding_;
  std::string_view topic_;
  std::size_t origin_ = 0;
};

RosTransform transform_stamped(PayloadReader& in) {
  RosTransform t;
  t.header = in.header();
  t.child_frame_id = in.string("child_frame_id");
  t.translation = in.vector3("transform.translation");
  t.rotation = in.quaternion("transform.rotation");
  return t;
}

}  // namespace

RosLaserScan decode_laser_scan(std::span<const std::uint8_t> data, MessageEncoding encoding,
                               const PayloadSource& source) {
  PayloadReader in(data, encoding, source);
  RosLaserScan s;
  s.header = in.header();
  s.angle_min = in.read<float>("angle_min");
  s.angle_max = in.read<float>("angle_max");
  s.angle_increment = in.read<float>("angle_increment");
  s.time_increment = in.read<float>("time_increment");
  s.scan_time = in.read<float>("scan_time");
  s.range_min = in.read<float>("range_min");
  s.range_max = in.read<float>("range_max");
  s.ranges = in.sequence<float>("ranges");
  s.intensities = in.sequence<float>("intensities");
  in.finish("sensor_msgs/LaserScan");
  return s;
}

RosOdometry decode_odometry(std::span<const std::uint8_t> data, MessageEncoding encoding,
                            const PayloadSource& source) {
  PayloadReader in(data, encoding, source);
  RosOdometry o;
  o.header = in.header();
  o.child_frame_id = in.string("child_frame_id");
  o.position = in.vector3("pose.pose.position");
  o.orientation = in.quaternion("pose.pose.orientation");
  in.skip_doubles(36, "pose.covariance");
  o.linear_velocity = in.vector3("twist.twist.linear");
  o.angular_velocity = in.vector3("twist.twist.angular");
  in.skip_doubles(36, "twist.covariance");
  in.finish("nav_msgs/Odometry");
  return o;
}

std::vector<RosTransform> decode_tf_message(std::span<const std::uint8_t> data,
                                            MessageEncoding encoding, const PayloadSource& source) {
  PayloadReader in(data, encoding, source);
  // A transform takes at least its header's stamp, two string lengths and 7 doubles.
  const std::uint32_t n = in.count(8 + 8 + 7 * 8, "transforms");
  std::vector<RosTransform> out;
  out.reserve(n);
  for (std::uint32_t i = 0; i < n; ++i)
    out.push_back(transform_stamped(in));
  in.finish("tf2_msgs/TFMessage");
  return out;
}

RosMessageKind ros_message_kind(std::string_view type) {
  if (type == "sensor_msgs/LaserScan" || type == "sensor_msgs/msg/LaserScan")
    return RosMessageKind::laser_scan;
  if (type == "nav_msgs/Odometry" || type == "nav_msgs/msg/Odometry")
    return RosMessageKind::odometry;
  if (type == "tf2_msgs/TFMessage" || type == "tf2_msgs/msg/TFMessage" || type == "tf/tfMessage")
    return RosMessageKind::tf;
  return RosMessageKind::other;
}

}  // namespace floorgrid::io
