#include "floorgrid/server/map_request.hpp"

#include "floorgrid/mapping/mapping_factory.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace floorgrid::server {

namespace {

RequestError bad(const std::string& message) {
  return {400, message};
}

const nlohmann::json& field(const nlohmann::json& request, const char* name) {
  const auto it = request.find(name);
  if (it == request.end())
    throw bad(std::string("'") + name + "' is missing");
  return *it;
}

double finite_number(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number())
    throw bad(where + " must be a number (got " + value.dump() + ")");
  const double x = value.get<double>();
  if (!std::isfinite(x))
    throw bad(where + " must be finite");
  return x;
}

/// One input point: x, y and an optional heading.
struct InputPoint {
  Pose2 pose;
  bool has_theta = false;
};

std::vector<InputPoint> input_points(const nlohmann::json& request, const RequestLimits& limits) {
  const nlohmann::json& points = field(request, "points");
  if (!points.is_array())
    throw bad("'points' must be a list of [x, y] or [x, y, theta]");
  if (points.size() > limits.max_points) {
    throw RequestError(413, "'points' holds " + std::to_string(points.size()) +
                                " points; at most " + std::to_string(limits.max_points) +
                                " per request");
  }
  std::vector<InputPoint> out;
  out.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const nlohmann::json& p = points[i];
    const std::string where = "'points[" + std::to_string(i) + "]'";
    if (!p.is_array() || p.size() < 2 || p.size() > 3)
      throw bad(where + " must be [x, y] or [x, y, theta]");
    InputPoint q;
    q.pose.x = finite_number(p[0], where + " x");
    q.pose.y = finite_number(p[1], where + " y");
    if (p.size() == 3) {
      q.pose.theta = finite_number(p[2], where + " theta");
      q.has_theta = true;
    }
    out.push_back(q);
  }
  return out;
}

nlohmann::json number_or_null(const std::optional<double>& x) {
  return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json parse_request(const std::string& body) {
  nlohmann::json request = nlohmann::json::parse(body, nullptr, false);
  if (request.is_discarded())
    throw bad("the body is not JSON");
  if (!request.is_object())
    throw bad("the body must be a JSON object");
  return request;
}

nlohmann::json mapped_point_json(const PointMapping& model, const Pose2& pose, bool has_theta,
                                 bool forward) {
  const MappedPoint m =
      forward ? model.map_forward(pose.translation()) : model.map_inverse(pose.translation());
  const bool invertible = m.flag != MapFlag::not_invertible;
  nlohmann::json out;
  out["x"] = invertible ? nlohmann::json(m.point.x()) : nlohmann::json(nullptr);
  out["y"] = invertible ? nlohmann::json(m.point.y()) : nlohmann::json(nullptr);
  if (has_theta) {
    // Through the Jacobian at the plan point: the inverse is solved once, by map_inverse.
    std::optional<double> theta;
    if (forward)
      theta = model.heading_in_grid(pose.translation(), pose.theta);
    else if (invertible)
      theta = model.heading_in_plan(m.point, pose.theta);
    out["theta"] = number_or_null(theta);
  }
  out["std_m"] = number_or_null(m.std_m);
  out["nearest_pair_m"] = m.nearest_pair_m;
  out["flag"] = to_string(m.flag);
  out["extrapolated"] = m.flag == MapFlag::extrapolated || m.flag == MapFlag::outside_hull;
  return out;
}

nlohmann::json map_points(const nlohmann::json& request, const PointMapping& model,
                          const RequestLimits& limits) {
  const nlohmann::json& from = field(request, "from");
  if (!from.is_string() || (from != "plan" && from != "grid"))
    throw bad("'from' must be \"plan\" or \"grid\" (got " + from.dump() + ")");
  if (const auto it = request.find("model"); it != request.end()) {
    if (!it->is_string() || it->get<std::string>() != model.name()) {
      throw bad("'model': this session maps with '" + model.name() + "' (got " + it->dump() + ")");
    }
  }
  const bool forward = from == "plan";
  const std::vector<InputPoint> points = input_points(request, limits);
  nlohmann::json mapped = nlohmann::json::array();
  for (const InputPoint& q : points)
    mapped.push_back(mapped_point_json(model, q.pose, q.has_theta, forward));
  return {{"from", from},
          {"to", forward ? "grid" : "plan"},
          {"model", model.name()},
          {"points", std::move(mapped)}};
}

PairRequest parse_pair(const nlohmann::json& request) {
  const auto point = [&](const char* name) {
    const nlohmann::json& p = field(request, name);
    const std::string where = std::string("'") + name + "'";
    if (!p.is_array() || p.size() != 2)
      throw bad(where + " must be [x, y]");
    return Eigen::Vector2d(finite_number(p[0], where + " x"), finite_number(p[1], where + " y"));
  };
  return {point("plan"), point("grid")};
}

std::string parse_fit_model(const nlohmann::json& request) {
  const nlohmann::json& model = field(request, "model");
  const std::vector<std::string> names = mapping_model_names();
  if (!model.is_string() ||
      std::find(names.begin(), names.end(), model.get<std::string>()) == names.end()) {
    std::string known;
    for (const std::string& n : names)
      known += (known.empty() ? "" : ", ") + n;
    throw bad("'model' must be one of " + known + " (got " + model.dump() + ")");
  }
  return model.get<std::string>();
}

Pose2 parse_robot_pose(const nlohmann::json& request) {
  Pose2 pose;
  pose.x = finite_number(field(request, "x"), "'x'");
  pose.y = finite_number(field(request, "y"), "'y'");
  pose.theta = finite_number(field(request, "theta"), "'theta'");
  return pose;
}

}  // namespace floorgrid::server
