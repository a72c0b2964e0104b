// DXF floorplans (io/dxf_reader): entities, blocks, inserts, units, layers.
#include "floorgrid/io/plans/dxf_reader.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const auto path = fuzz::put("plan.dxf", data, size);
  io::DxfReadOptions options;
  options.max_entities = 100'000;  // bounds the work of one input (inserts multiply entities)
  fuzz::expect_no_crash([&] { io::read_dxf(path, options); });
  return 0;
}
