// Map YAML (io/map_io): the ROS map_server fields, with a small valid image beside it
// (`map.pgm`) that the YAML may name, and the occupancy rule applied to it.
#include "floorgrid/io/formats/map_io.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  static const bool image = [] {
    std::string pgm = "P5\n8 6\n255\n";
    for (int i = 0; i < 48; ++i)
      pgm += static_cast<char>(i % 3 == 0 ? 0 : i % 3 == 1 ? 254 : 205);
    fuzz::put("map.pgm", pgm);
    return true;
  }();
  (void)image;
  const auto path = fuzz::put("map.yaml", data, size);
  fuzz::expect_no_crash([&] { io::read_map_yaml(path); });
  return 0;
}
