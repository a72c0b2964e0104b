// Map images (io/image_io): PGM (P2, P5) and PNG of every colour type and depth.
#include "floorgrid/io/files/image_io.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const auto path = fuzz::put("map.img", data, size);
  io::ImageLimits limits;
  limits.max_pixels = 4'000'000;  // bounds one input's work; the limit itself is tested apart
  fuzz::expect_no_crash([&] { io::read_grey_image(path, limits); });
  return 0;
}
