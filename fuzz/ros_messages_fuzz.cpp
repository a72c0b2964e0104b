// ROS message payloads (io/ros_messages): LaserScan, Odometry and TFMessage, each in the ROS 1
// and the CDR encoding, and the checks of their values (io/bag_message_checks). The first byte
// chooses the message and the encoding.
#include "floorgrid/io/logs/bag_message_checks.hpp"
#include "floorgrid/io/logs/ros_messages.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  if (size == 0)
    return 0;
  const std::span<const std::uint8_t> payload(data + 1, size - 1);
  const auto encoding = (data[0] & 1) ? io::MessageEncoding::cdr : io::MessageEncoding::ros1;
  const io::PayloadSource source{"payload", 0, "/topic"};
  const io::MessagePlace place{"payload", "/topic", 1, 0};
  fuzz::expect_no_crash([&] {
    switch ((data[0] >> 1) % 3) {
      case 0:
        io::check_scan_settings(io::decode_laser_scan(payload, encoding, source), {}, place);
        break;
      case 1:
        io::check_odometry(io::decode_odometry(payload, encoding, source), place);
        break;
      default:
        for (const io::RosTransform& t : io::decode_tf_message(payload, encoding, source))
          io::check_transform(t, "transforms[0]", place);
        break;
    }
  });
  return 0;
}
