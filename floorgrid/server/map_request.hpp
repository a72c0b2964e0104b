#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/server/request_error.hpp"

namespace floorgrid::server {

/// How much one request may ask for.
struct RequestLimits {
  std::size_t max_points = 1'000'000;  ///< points of one POST /api/map
  /// A manual pair's point may lie outside its map by at most this many of the map's diagonals
  /// (or pair_margin_m, whichever is larger): one clicked on the map, or near it.
  double pair_margin_maps = 1.0;
  double pair_margin_m = 50.0;  ///< metres, see pair_margin_maps
};

/// A request body as JSON; RequestError 400 when it is not JSON or not an object.
nlohmann::json parse_request(const std::string& body);

/// One point or pose mapped as the API answers it: {"x", "y" (null where not invertible),
/// "theta" (when `has_theta`; null where it cannot be mapped), "std_m", "nearest_pair_m",
/// "flag", "extrapolated"}; plan to grid when `forward`, else grid to plan.
nlohmann::json mapped_point_json(const PointMapping& model, const Pose2& pose, bool has_theta,
                                 bool forward);

/// One point of a POST /api/map: x, y and an optional heading (metres, radians).
struct RequestPoint {
  Pose2 pose;
  bool has_theta = false;
};

/// A POST /api/map body, read (parse_map_request).
struct MapRequest {
  bool forward = true;  ///< from the plan to the grid ("from": "plan")
  std::vector<RequestPoint> points;
};

/// POST /api/map: {"from": "plan"|"grid", "points": [[x, y], [x, y, theta], ...], "model"?}
/// mapped by `model` (metres, radians): {"from", "to", "model", "points": [{"x", "y", "theta"
/// (when given), "std_m" (null where the model has none), "nearest_pair_m", "flag",
/// "extrapolated"}]}; a point that cannot be inverted has null x and y and the flag
/// not_invertible. RequestError naming the field on anything else (read as
/// parse_map_request reads it; the server streams the answer with mapped_points_text).
nlohmann::json map_points(const nlohmann::json& request, const PointMapping& model,
                          const RequestLimits& limits = {});

/// The answer to `request` as text, as map_points answers it (its fields in another order).
std::string mapped_points_text(const MapRequest& request, const PointMapping& model);
/// The answer in parts, so that a long one is sent while it is made: the head (from, to, model
/// and the opening of points), points [begin, end) (with a comma before each but the first),
/// the tail.
std::string mapped_points_head(const MapRequest& request, const PointMapping& model);
/// See mapped_points_head.
void append_mapped_points(std::string& out, const MapRequest& request, const PointMapping& model,
                          std::size_t begin, std::size_t end);
/// See mapped_points_head.
std::string mapped_points_tail();

/// POST /api/robot_pose: {"x", "y", "theta"} in the grid frame (metres, radians; x and y within
/// kMaxCoordinate of the origin).
Pose2 parse_robot_pose(const nlohmann::json& request);

/// POST /api/pairs: {"plan": [x, y], "grid": [x, y]} (metres).
struct PairRequest {
  Eigen::Vector2d point_in_plan = Eigen::Vector2d::Zero();
  Eigen::Vector2d point_in_grid = Eigen::Vector2d::Zero();
};
/// The pair a POST /api/pairs adds: finite coordinates within kMaxCoordinate metres of the
/// origin; RequestError naming the field.
PairRequest parse_pair(const nlohmann::json& request);

/// Where a session's manual pairs may lie: each side's map, when the session has it.
struct PairBounds {
  std::optional<Eigen::AlignedBox2d> plan, grid;
};

/// RequestError 400 naming 'plan' or 'grid' when that point of `pair` lies farther outside its
/// map than limits.pair_margin_maps of the map's diagonal (and limits.pair_margin_m): a pair
/// far off the maps (a typo, a unit slip) would make every refit about it, not the building.
void check_pair_near_maps(const PairRequest& pair, const PairBounds& bounds,
                          const RequestLimits& limits);

/// POST /api/fit: {"model": one of mapping_model_names()}; RequestError naming the field.
std::string parse_fit_model(const nlohmann::json& request);

}  // namespace floorgrid::server
