// Pairs CSV (io/pairs_csv): plan_x,plan_y,grid_x,grid_y[,weight], in metres and in pixels.
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const auto path = fuzz::put("pairs.csv", data, size);
  fuzz::expect_no_crash([&] { io::read_pairs_csv(path); });
  fuzz::expect_no_crash([&] { io::read_pairs_csv(path, 0.05); });
  return 0;
}
