// Points CSV of `map --points` (io/points_csv): x,y or x,y,theta.
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/io/formats/points_csv.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const auto path = fuzz::put("points.csv", data, size);
  fuzz::expect_no_crash([&] { io::read_points_csv(path, kMaxCoordinate); });
  return 0;
}
