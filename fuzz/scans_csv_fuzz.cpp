// The run's track as `serve --replay` reads it (io/scans_csv): scans.csv, columns by the header.
#include "floorgrid/io/formats/scans_csv.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const auto path = fuzz::put("scans.csv", data, size);
  fuzz::expect_no_crash([&] { io::read_grid_track(path); });
  return 0;
}
