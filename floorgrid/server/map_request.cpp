#include "floorgrid/server/map_request.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/server/map_request_parser.hpp"

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

/// A coordinate: a finite number within kMaxCoordinate metres of the origin.
double coordinate(const nlohmann::json& value, const std::string& where) {
  const double x = finite_number(value, where);
  if (!(std::abs(x) <= kMaxCoordinate)) {
    throw bad(where + " must be within 1e7 m of the origin (got " + value.dump() +
              "): not a coordinate in a building");
  }
  return x;
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
  if (!request.is_object())
    throw bad("the body must be a JSON object");
  const MapRequest read = parse_map_request(request.dump(), limits, model.name());
  nlohmann::json mapped = nlohmann::json::array();
  for (const RequestPoint& q : read.points)
    mapped.push_back(mapped_point_json(model, q.pose, q.has_theta, read.forward));
  return {{"from", read.forward ? "plan" : "grid"},
          {"to", read.forward ? "grid" : "plan"},
          {"model", model.name()},
          {"points", std::move(mapped)}};
}

std::string mapped_points_head(const MapRequest& request, const PointMapping& model) {
  const nlohmann::json from = request.forward ? "plan" : "grid";
  const nlohmann::json to = request.forward ? "grid" : "plan";
  return "{\"from\":" + from.dump() + ",\"to\":" + to.dump() +
         ",\"model\":" + nlohmann::json(model.name()).dump() + ",\"points\":[";
}

void append_mapped_points(std::string& out, const MapRequest& request, const PointMapping& model,
                          std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    if (i > 0)
      out += ',';
    const RequestPoint& q = request.points[i];
    out += mapped_point_json(model, q.pose, q.has_theta, request.forward).dump();
  }
}

std::string mapped_points_tail() {
  return "]}";
}

std::string mapped_points_text(const MapRequest& request, const PointMapping& model) {
  std::string out = mapped_points_head(request, model);
  append_mapped_points(out, request, model, 0, request.points.size());
  return out + mapped_points_tail();
}

PairRequest parse_pair(const nlohmann::json& request) {
  const auto point = [&](const char* name) {
    const nlohmann::json& p = field(request, name);
    const std::string where = std::string("'") + name + "'";
    if (!p.is_array() || p.size() != 2)
      throw bad(where + " must be [x, y]");
    return Eigen::Vector2d(coordinate(p[0], where + " x"), coordinate(p[1], where + " y"));
  };
  return {point("plan"), point("grid")};
}

void check_pair_near_maps(const PairRequest& pair, const PairBounds& bounds,
                          const RequestLimits& limits) {
  const auto check = [&](const char* side, const Eigen::Vector2d& point,
                         const std::optional<Eigen::AlignedBox2d>& box) {
    if (!box || box->isEmpty())
      return;
    const double margin =
        std::max(limits.pair_margin_m, limits.pair_margin_maps * box->diagonal().norm());
    const double outside = box->exteriorDistance(point);
    if (outside > margin) {
      const auto text = [](double x) { return nlohmann::json(x).dump(); };
      throw bad(std::string("'") + side + "' (" + text(point.x()) + ", " + text(point.y()) +
                ") lies " + text(std::round(outside)) + " m outside the " + side + " map ([" +
                text(box->min().x()) + ", " + text(box->min().y()) + "] to [" +
                text(box->max().x()) + ", " + text(box->max().y()) +
                "]): a pair's point must lie on its map or within " + text(std::round(margin)) +
                " m of it");
    }
  };
  check("plan", pair.point_in_plan, bounds.plan);
  check("grid", pair.point_in_grid, bounds.grid);
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
  pose.x = coordinate(field(request, "x"), "'x'");
  pose.y = coordinate(field(request, "y"), "'y'");
  pose.theta = finite_number(field(request, "theta"), "'theta'");
  return pose;
}

}  // namespace floorgrid::server
