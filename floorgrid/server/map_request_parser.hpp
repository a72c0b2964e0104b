#pragma once

#include <string>
#include <string_view>

#include "floorgrid/server/map_request.hpp"

namespace floorgrid::server {

/// Reads a POST /api/map body {"from": "plan"|"grid", "points": [[x, y], [x, y, theta], ...],
/// "model"?} as it streams past (no JSON tree: 32 bytes a point, however the body is written),
/// checking it as map_points does: RequestError 400 naming the field ('from', 'model' when it
/// is not `served_model`, 'points[i]' x, y or theta: a number within kMaxCoordinate of the
/// origin), 413 beyond limits.max_points points, 400 when it is not a JSON object.
MapRequest parse_map_request(std::string_view body, const RequestLimits& limits,
                             const std::string& served_model);

}  // namespace floorgrid::server
