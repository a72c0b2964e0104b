#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::server {

/// A request the API refuses: the HTTP status (400 bad request, 413 too large) and a message
/// naming the field.
class RequestError : public std::runtime_error {
 public:
  /// An error answered with `status` and `message`.
  RequestError(int status, const std::string& message)
      : std::runtime_error(message), status_(status) {}
  /// The HTTP status to answer with.
  int status() const { return status_; }

 private:
  int status_;
};

/// How much one request may ask for.
struct RequestLimits {
  std::size_t max_points = 1'000'000;  ///< points of one POST /api/map
};

/// A request body as JSON; RequestError 400 when it is not JSON or not an object.
nlohmann::json parse_request(const std::string& body);

/// One point or pose mapped as the API answers it: {"x", "y" (null where not invertible),
/// "theta" (when `has_theta`; null where it cannot be mapped), "std_m", "nearest_pair_m",
/// "flag", "extrapolated"}; plan to grid when `forward`, else grid to plan.
nlohmann::json mapped_point_json(const PointMapping& model, const Pose2& pose, bool has_theta,
                                 bool forward);

/// POST /api/map: {"from": "plan"|"grid", "points": [[x, y], [x, y, theta], ...], "model"?}
/// mapped by `model` (metres, radians): {"from", "to", "model", "points": [{"x", "y", "theta"
/// (when given), "std_m" (null where the model has none), "nearest_pair_m", "flag",
/// "extrapolated"}]}; a point that cannot be inverted has null x and y and the flag
/// not_invertible. RequestError naming the field on anything else.
nlohmann::json map_points(const nlohmann::json& request, const PointMapping& model,
                          const RequestLimits& limits = {});

/// POST /api/robot_pose: {"x", "y", "theta"} in the grid frame (metres, radians).
Pose2 parse_robot_pose(const nlohmann::json& request);

/// POST /api/pairs: {"plan": [x, y], "grid": [x, y]} (metres).
struct PairRequest {
  Eigen::Vector2d point_in_plan = Eigen::Vector2d::Zero();
  Eigen::Vector2d point_in_grid = Eigen::Vector2d::Zero();
};
/// The pair a POST /api/pairs adds; RequestError naming the field.
PairRequest parse_pair(const nlohmann::json& request);

/// POST /api/fit: {"model": one of mapping_model_names()}; RequestError naming the field.
std::string parse_fit_model(const nlohmann::json& request);

}  // namespace floorgrid::server
