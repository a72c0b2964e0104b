// The viewer API's request bodies (server/map_request), as a client on the network may send
// them: POST /api/map (read as the server reads it, as it streams, and mapped both ways by a
// small model), /api/pairs, /api/robot_pose and /api/fit. A RequestError (a 4xx) is the expected
// answer to a bad one.
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/server/map_request.hpp"
#include "floorgrid/server/map_request_parser.hpp"
#include "fuzz/fuzz_support.hpp"

namespace {

const floorgrid::PointMapping& small_model() {
  static const std::shared_ptr<floorgrid::PointMapping> model = [] {
    floorgrid::ReferencePairs pairs;
    pairs.points_in_plan = Eigen::Matrix2Xd(2, 4);
    pairs.points_in_plan << 0, 4, 0, 4, 0, 0, 3, 3;
    pairs.points_in_grid = 1.5 * pairs.points_in_plan;
    pairs.points_in_grid.row(0).array() += 2.0;
    floorgrid::MappingOptions options;
    options.model = "gt";
    std::shared_ptr<floorgrid::PointMapping> m = floorgrid::make_mapping(options);
    m->fit(pairs);
    return m;
  }();
  return *model;
}

template <typename Answer>
void answer(const Answer& handle) {
  try {
    floorgrid::fuzz::expect_no_crash(handle);
  } catch (const floorgrid::server::RequestError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floorgrid::server;
  const std::string body(reinterpret_cast<const char*>(data), size);
  RequestLimits limits;
  limits.max_points = 1000;
  answer([&] { parse_map_request(body, limits, small_model().name()); });
  answer([&] { map_points(parse_request(body), small_model(), limits); });
  answer([&] { parse_pair(parse_request(body)); });
  answer([&] { parse_robot_pose(parse_request(body)); });
  answer([&] { parse_fit_model(parse_request(body)); });
  return 0;
}
