// ROS message payloads (io/ros_messages): LaserScan, Odometry and TFMessage, each in the ROS 1
// and the CDR encoding. The first byte chooses the message and the encoding.
#include "floorgrid/io/ros_messages.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  if (size == 0)
    return 0;
  const std::span<const std::uint8_t> payload(data + 1, size - 1);
  const auto encoding = (data[0] & 1) ? io::MessageEncoding::cdr : io::MessageEncoding::ros1;
  const io::PayloadSource source{"payload", 0, "/topic"};
  fuzz::expect_no_crash([&] {
    switch ((data[0] >> 1) % 3) {
      case 0:
        io::decode_laser_scan(payload, encoding, source);
        break;
      case 1:
        io::decode_odometry(payload, encoding, source);
        break;
      default:
        io::decode_tf_message(payload, encoding, source);
        break;
    }
  });
  return 0;
}
