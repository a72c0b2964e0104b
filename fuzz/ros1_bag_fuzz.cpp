// ROS 1 bags (io/ros1_bag): the contents from the index (or read through) and every message.
#include "floorgrid/io/logs/bag_file.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const auto path = fuzz::put("run.bag", data, size);
  const io::BagReadLimits limits{.max_chunk_bytes = fuzz::kFuzzChunkBytes};
  fuzz::expect_no_crash([&] { io::ros1_bag_contents(path, limits); });
  volatile std::size_t bytes = 0;  // keeps the reads of every byte handed out
  fuzz::expect_no_crash([&] {
    io::read_ros1_bag(
        path,
        [&](const io::BagTopic&, const io::BagMessageView& message) {
          for (const std::uint8_t b : message.data)
            bytes = bytes + b;
        },
        nullptr, limits);
  });
  return 0;
}
