// Plan layers (io/plan_layers_io, io/dxf_zones): zones and waypoints as GeoJSON, waypoints as
// CSV, zones as a DXF layer's closed polylines and hatches. The same bytes go to each reader.
#include <string_view>

#include "floorgrid/io/plans/dxf_zones.hpp"
#include "floorgrid/io/plans/plan_layers_io.hpp"
#include "fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  fuzz::expect_no_crash([&] { io::parse_plan_layers_geojson(text, "zones.geojson"); });
  fuzz::expect_no_crash([&] { io::parse_waypoints_csv(text, "waypoints.csv"); });
  fuzz::expect_no_crash([&] { io::read_dxf_zones(text, "zones.dxf", "*"); });
  return 0;
}
