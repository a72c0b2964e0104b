// MCAP files (io/mcap_reader): contents (summary or read through) and every message streamed.
#include "floorgrid/io/logs/bag_file.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const auto path = fuzz::put("run.mcap", data, size);
  const io::BagReadLimits limits{.max_chunk_bytes = fuzz::kFuzzChunkBytes};
  fuzz::expect_no_crash([&] { io::mcap_contents(path, limits); });
  fuzz::expect_no_crash([&] {
    std::size_t bytes = 0;
    io::read_mcap(
        path, [&](const io::BagTopic&, const io::BagMessageView& m) { bytes += m.data.size(); },
        nullptr, limits);
  });
  return 0;
}
