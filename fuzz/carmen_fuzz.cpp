// CARMEN logs (io/carmen_log), plain or gzip-compressed (told by content).
#include "floorgrid/io/logs/carmen_log.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const auto path = fuzz::put("run.log", data, size);
  fuzz::expect_no_crash([&] { io::read_carmen_log(path); });
  return 0;
}
