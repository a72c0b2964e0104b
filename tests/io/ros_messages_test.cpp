// Decoding of LaserScan, Odometry and TFMessage payloads, byte by byte as the two encodings lay
// them out (ROS 1: packed; CDR: aligned after a 4-byte encapsulation header, strings with their
// NUL). The bags written by independent writers are read in the bag tests.
#include "floorgrid/io/logs/ros_messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {
namespace {

/// Bytes laid out by hand, with CDR's alignment counted from after the encapsulation header.
class Bytes {
 public:
  explicit Bytes(bool cdr) : cdr_(cdr) {
    if (cdr_)
      data_ = {0x00, 0x01, 0x00, 0x00};
  }
  template <typename T>
  Bytes& put(T value) {
    pad(sizeof(T));
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    data_.insert(data_.end(), p, p + sizeof(T));
    return *this;
  }
  Bytes& text(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size() + (cdr_ ? 1 : 0)));
    data_.insert(data_.end(), s.begin(), s.end());
    if (cdr_)
      data_.push_back(0);
    return *this;
  }
  Bytes& header(std::int32_t sec, std::uint32_t nsec, const std::string& frame) {
    if (!cdr_)
      put<std::uint32_t>(42);  // seq
    return put(sec).put(nsec).text(frame);
  }
  std::vector<std::uint8_t>& data() { return data_; }

 private:
  void pad(std::size_t size) {
    if (!cdr_)
      return;
    while ((data_.size() - 4) % size != 0)
      data_.push_back(0xee);
  }
  bool cdr_;
  std::vector<std::uint8_t> data_;
};

std::vector<std::uint8_t> laser_scan(bool cdr, std::uint32_t claimed_ranges = 3) {
  Bytes b(cdr);
  b.header(1700000000, 250000000, "laser_front");
  for (float f : {-1.5f, 1.5f, 1.5f, 0.0f, 0.1f, 0.05f, 30.0f})
    b.put(f);
  b.put(claimed_ranges);
  b.put(1.0f)
      .put(std::numeric_limits<float>::infinity())
      .put(-std::numeric_limits<float>::infinity());
  b.put<std::uint32_t>(0);
  return b.data();
}

class RosMessages : public ::testing::TestWithParam<MessageEncoding> {};

TEST_P(RosMessages, LaserScanFieldsAndRangesAsSent) {
  const bool cdr = GetParam() == MessageEncoding::cdr;
  const RosLaserScan s = decode_laser_scan(laser_scan(cdr), GetParam(), {"f", 0, "/scan"});
  EXPECT_EQ(s.header.stamp_ns, 1700000000LL * 1000000000LL + 250000000LL);
  EXPECT_EQ(s.header.frame_id, "laser_front");
  EXPECT_FLOAT_EQ(s.angle_min, -1.5f);
  EXPECT_FLOAT_EQ(s.angle_increment, 1.5f);
  EXPECT_FLOAT_EQ(s.range_min, 0.05f);
  EXPECT_FLOAT_EQ(s.range_max, 30.0f);
  ASSERT_EQ(s.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(s.ranges[0], 1.0f);
  EXPECT_TRUE(std::isinf(s.ranges[1]) && s.ranges[1] > 0);
  EXPECT_TRUE(std::isinf(s.ranges[2]) && s.ranges[2] < 0);
  EXPECT_TRUE(s.intensities.empty());
}

TEST_P(RosMessages, AnArrayWhoseLengthLiesIsRefusedWithTheOffset) {
  const bool cdr = GetParam() == MessageEncoding::cdr;
  try {
    decode_laser_scan(laser_scan(cdr, 1000000), GetParam(), {"run.bag", 4096, "/scan"});
    FAIL() << "a lying array length was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("run.bag"), std::string::npos) << what;
    EXPECT_NE(what.find("at byte 4"), std::string::npos) << what;
    EXPECT_NE(what.find("/scan"), std::string::npos) << what;
    EXPECT_NE(what.find("ranges"), std::string::npos) << what;
  }
  std::vector<std::uint8_t> cut = laser_scan(cdr);
  cut.resize(cut.size() - 6);
  EXPECT_THROW(decode_laser_scan(cut, GetParam(), {"f", 0, "/scan"}), InputError);
}

TEST_P(RosMessages, OdometryPoseAndTwist) {
  const bool cdr = GetParam() == MessageEncoding::cdr;
  Bytes b(cdr);
  b.header(10, 5, "odom").text("base_link");
  for (double v : {1.0, 2.0, 0.0, 0.0, 0.0, std::sin(0.25), std::cos(0.25)})
    b.put(v);
  for (int i = 0; i < 36; ++i)
    b.put(0.5);
  for (double v : {0.3, 0.0, 0.0, 0.0, 0.0, -0.2})
    b.put(v);
  for (int i = 0; i < 36; ++i)
    b.put(0.5);
  const RosOdometry o = decode_odometry(b.data(), GetParam(), {"f", 0, "/odom"});
  EXPECT_EQ(o.header.stamp_ns, 10000000005LL);
  EXPECT_EQ(o.header.frame_id, "odom");
  EXPECT_EQ(o.child_frame_id, "base_link");
  EXPECT_DOUBLE_EQ(o.position.y, 2.0);
  EXPECT_DOUBLE_EQ(o.orientation.w, std::cos(0.25));
  EXPECT_DOUBLE_EQ(o.linear_velocity.x, 0.3);
  EXPECT_DOUBLE_EQ(o.angular_velocity.z, -0.2);
}

TEST_P(RosMessages, TfMessageWithTwoTransforms) {
  const bool cdr = GetParam() == MessageEncoding::cdr;
  Bytes b(cdr);
  b.put<std::uint32_t>(2);
  b.header(1, 0, "odom").text("base_link");
  for (double v : {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0})
    b.put(v);
  b.header(2, 0, "base_link").text("laser");
  for (double v : {0.2, 0.0, 0.3, 1.0, 0.0, 0.0, 0.0})  // upside down: 180 degrees about x
    b.put(v);
  const std::vector<RosTransform> t = decode_tf_message(b.data(), GetParam(), {"f", 0, "/tf"});
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[1].header.frame_id, "base_link");
  EXPECT_EQ(t[1].child_frame_id, "laser");
  EXPECT_DOUBLE_EQ(t[1].translation.z, 0.3);
  EXPECT_DOUBLE_EQ(t[1].rotation.x, 1.0);
}

INSTANTIATE_TEST_SUITE_P(BothEncodings, RosMessages,
                         ::testing::Values(MessageEncoding::ros1, MessageEncoding::cdr),
                         [](const auto& param_info) {
                           return param_info.param == MessageEncoding::cdr ? "cdr" : "ros1";
                         });

TEST(RosMessagesCdr, BigEndianIsRefused) {
  std::vector<std::uint8_t> data = laser_scan(true);
  data[1] = 0x00;  // CDR_BE
  EXPECT_THROW(decode_laser_scan(data, MessageEncoding::cdr, {"f", 0, "/scan"}), InputError);
}

TEST(RosMessagesKinds, BothSpellingsOfEachType) {
  EXPECT_EQ(ros_message_kind("sensor_msgs/LaserScan"), RosMessageKind::laser_scan);
  EXPECT_EQ(ros_message_kind("sensor_msgs/msg/LaserScan"), RosMessageKind::laser_scan);
  EXPECT_EQ(ros_message_kind("nav_msgs/msg/Odometry"), RosMessageKind::odometry);
  EXPECT_EQ(ros_message_kind("tf/tfMessage"), RosMessageKind::tf);
  EXPECT_EQ(ros_message_kind("sensor_msgs/PointCloud2"), RosMessageKind::other);
}

}  // namespace
}  // namespace floorgrid::io
