#include "floorgrid/io/plans/plan_layers_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/plans/dxf_zones.hpp"

namespace floorgrid::io {

namespace {

using nlohmann::json;

/// Whole-file extent below which coordinates are taken for WGS84 degrees: 5 cm is no site, and
/// a site of a kilometre spans about 0.01 degrees.
constexpr double kDegreesExtent = 0.05;

/// How messages name a feature: "feature 3 'dock'".
std::string feature_name(std::size_t index, const std::string& name) {
  return "feature " + std::to_string(index) + (name.empty() ? "" : " '" + name + "'");
}

[[noreturn]] void fail(const std::string& where, const std::string& message,
                       const std::string& field) {
  throw InputError(message, where, 0, field);
}

Eigen::Vector2d position(const json& p, const std::string& where, const std::string& what) {
  if (!p.is_array() || p.size() < 2 || !p[0].is_number() || !p[1].is_number())
    fail(where, what + ": a position must be [x, y] numbers (got " + p.dump() + ")", "coordinates");
  const Eigen::Vector2d v(p[0].get<double>(), p[1].get<double>());
  if (!v.allFinite())
    fail(where, what + ": coordinates are not finite", "coordinates");
  return v;
}

/// A GeoJSON linear ring: closed (first = last, RFC 7946 3.1.6), returned without the repeat.
Ring ring_of(const json& j, const std::string& where, const std::string& what) {
  if (!j.is_array())
    fail(where, what + ": a ring must be an array of positions", "coordinates");
  Ring ring;
  for (const json& p : j)
    ring.push_back(position(p, where, what));
  if (ring.size() < 4) {
    fail(where,
         fmt::format("{}: a ring needs at least 4 positions, the last repeating the first "
                     "(got {})",
                     what, ring.size()),
         "coordinates");
  }
  if (ring.front() != ring.back()) {
    fail(where,
         fmt::format("{}: the ring is open: its last position ({}, {}) is not its first "
                     "({}, {})",
                     what, ring.back().x(), ring.back().y(), ring.front().x(), ring.front().y()),
         "coordinates");
  }
  ring.pop_back();
  return ring;
}

std::optional<double> number_property(const json& properties, const char* key,
                                      const std::string& where, const std::string& what) {
  if (!properties.is_object() || !properties.contains(key) || properties[key].is_null())
    return std::nullopt;
  const json& v = properties[key];
  if (!v.is_number())
    fail(where, what + ": property " + key + " must be a number (got " + v.dump() + ")", key);
  return v.get<double>();
}

std::string name_property(const json& properties) {
  if (properties.is_object() && properties.contains("name") && properties["name"].is_string())
    return properties["name"].get<std::string>();
  if (properties.is_object() && properties.contains("name") && properties["name"].is_number())
    return properties["name"].dump();
  return {};
}

/// Refuses a `crs` that says WGS84 (GeoJSON 2008's member; RFC 7946 dropped it and means WGS84).
void refuse_geographic_crs(const json& root, const std::string& where) {
  if (!root.is_object() || !root.contains("crs"))
    return;
  const std::string text = root["crs"].dump();
  for (const char* geographic : {"4326", "CRS84", "crs84", "4258", "4269"}) {
    if (text.find(geographic) != std::string::npos) {
      fail(where,
           "the crs " + text +
               " is geographic (WGS84 degrees): floorgrid reads plan metres only (the "
               "drawing's own coordinates, as the plan's DXF or map YAML gives them)",
           "crs");
    }
  }
}

void add_geometry(PlanLayers& layers, const json& geometry, const json& properties,
                  std::size_t index, const std::string& where) {
  const std::string name = name_property(properties);
  const std::string what = feature_name(index, name);
  if (!geometry.is_object() || !geometry.contains("type") || !geometry["type"].is_string())
    fail(where, what + ": no geometry type", "geometry");
  const std::string type = geometry["type"].get<std::string>();
  const json coordinates = geometry.value("coordinates", json());
  if (type == "Point") {
    Waypoint w;
    w.name = name.empty() ? "waypoint " + std::to_string(layers.waypoints.size()) : name;
    w.index = index;
    w.position = position(coordinates, where, what);
    w.theta = number_property(properties, "theta", where, what);
    if (const auto deg = number_property(properties, "heading_deg", where, what)) {
      if (w.theta)
        fail(where, what + ": give theta (radians) or heading_deg, not both", "theta");
      w.theta = *deg * M_PI / 180.0;
    }
    validate_waypoint(w, where);
    layers.waypoints.push_back(std::move(w));
    return;
  }
  if (type == "Polygon" || type == "MultiPolygon") {
    const json polygons = type == "Polygon" ? json::array({coordinates}) : coordinates;
    if (!polygons.is_array())
      fail(where, what + ": coordinates must be an array", "coordinates");
    for (std::size_t k = 0; k < polygons.size(); ++k) {
      const json& rings = polygons[k];
      if (!rings.is_array() || rings.empty())
        fail(where, what + ": a polygon needs an outer ring", "coordinates");
      Zone z;
      z.index = index;
      z.name = name.empty() ? "zone " + std::to_string(layers.zones.size()) : name;
      if (polygons.size() > 1)
        z.name += " part " + std::to_string(k);
      z.outer = ring_of(rings[0], where, what + " outer ring");
      for (std::size_t h = 1; h < rings.size(); ++h)
        z.holes.push_back(ring_of(rings[h], where, what + " hole " + std::to_string(h - 1)));
      z.speed.percent = number_property(properties, "speed_percent", where, what);
      z.speed.metres_per_second = number_property(properties, "speed_mps", where, what);
      validate_zone(z, where);
      layers.zones.push_back(std::move(z));
    }
    return;
  }
  if (type == "GeometryCollection") {
    for (const json& g : geometry.value("geometries", json::array()))
      add_geometry(layers, g, properties, index, where);
    return;
  }
  layers.warnings.push_back(
      fmt::format("{}: {} {} skipped (zones are Polygon or MultiPolygon, "
                  "waypoints Point)",
                  where, what, type));
}

/// Refuses coordinates that span less than kDegreesExtent over the whole file.
void refuse_degrees(const PlanLayers& layers, const std::string& where) {
  Eigen::AlignedBox2d box;
  std::size_t points = 0;
  for (const Zone& z : layers.zones) {
    for (const auto& p : z.outer) {
      box.extend(p);
      ++points;
    }
  }
  for (const Waypoint& w : layers.waypoints) {
    box.extend(w.position);
    ++points;
  }
  if (points < 2)
    return;
  const Eigen::Vector2d size = box.sizes();
  const bool in_degree_range =
      box.min().x() >= -180 && box.max().x() <= 180 && box.min().y() >= -90 && box.max().y() <= 90;
  if (in_degree_range && size.maxCoeff() < kDegreesExtent) {
    fail(where,
         fmt::format("the features span only {:.3g} x {:.3g} units around ({:.6f}, {:.6f}): "
                     "that looks like WGS84 degrees (longitude, latitude); floorgrid reads "
                     "plan metres only (the drawing's own coordinates)",
                     size.x(), size.y(), box.center().x(), box.center().y()),
         "coordinates");
  }
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (std::size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',') {
      fields.push_back(trim(line.substr(start, i - start)));
      start = i + 1;
    }
  }
  return fields;
}

double csv_number(std::string_view text, const std::string& where, long line,
                  const std::string& column) {
  const std::string s(text);
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (s.empty() || used != s.size() || !std::isfinite(v))
    throw InputError("expected a finite number (got '" + s + "')", where, line, column);
  return v;
}

json number_or_null(const std::optional<double>& v) {
  return v ? json(*v) : json(nullptr);
}

json ring_json(const Eigen::Matrix2Xd& ring) {
  json out = json::array();
  for (Eigen::Index i = 0; i < ring.cols(); ++i)
    out.push_back({ring(0, i), ring(1, i)});
  if (ring.cols() > 0)
    out.push_back({ring(0, 0), ring(1, 0)});  // GeoJSON rings repeat their first position
  return out;
}

}  // namespace

PlanLayers parse_plan_layers_geojson(std::string_view text, const std::string& where) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for a number beyond a double (1e444).
    throw InputError(std::string("not JSON: ") + e.what(), where, 0, "");
  }
  refuse_geographic_crs(root, where);
  PlanLayers layers;
  if (!root.is_object() || !root.contains("type") || !root["type"].is_string())
    fail(where, "not GeoJSON: no top-level \"type\"", "type");
  const std::string type = root["type"].get<std::string>();
  if (type == "FeatureCollection") {
    if (!root.contains("features") || !root["features"].is_array())
      fail(where, "a FeatureCollection needs a \"features\" array", "features");
    std::size_t index = 0;
    for (const json& f : root["features"]) {
      if (!f.is_object() || f.value("type", "") != "Feature")
        fail(where, feature_name(index, "") + ": not a Feature", "features");
      add_geometry(layers, f.value("geometry", json()), f.value("properties", json::object()),
                   index, where);
      ++index;
    }
  } else if (type == "Feature") {
    add_geometry(layers, root.value("geometry", json()), root.value("properties", json::object()),
                 0, where);
  } else {
    add_geometry(layers, root, json::object(), 0, where);
  }
  refuse_degrees(layers, where);
  return layers;
}

std::vector<Waypoint> parse_waypoints_csv(std::string_view text, const std::string& where) {
  std::vector<Waypoint> out;
  long line_number = 0;
  bool header_seen = false;
  bool has_theta = false;
  std::size_t columns = 3;
  if (text.substr(0, 3) == "\xEF\xBB\xBF")
    text.remove_prefix(3);
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = trim(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++line_number;
    if (line.empty() || line.front() == '#')
      continue;
    const auto fields = split(line);
    if (!header_seen) {
      std::vector<std::string> names(fields.begin(), fields.end());
      // Columns after name,x,y[,theta] are ignored: a migrated file (with std_m, flag, ...)
      // reads back as waypoints.
      const bool ok = names.size() >= 3 && names[0] == "name" && names[1] == "x" && names[2] == "y";
      if (!ok) {
        throw InputError("expected the header name,x,y[,theta] (got '" + std::string(line) + "')",
                         where, line_number, "header");
      }
      has_theta = names.size() >= 4 && names[3] == "theta";
      columns = names.size();
      header_seen = true;
      continue;
    }
    if (fields.size() != columns && !(columns == 4 && has_theta && fields.size() == 3)) {
      throw InputError(
          fmt::format("expected {} fields as the header (got {})", columns, fields.size()), where,
          line_number, "");
    }
    Waypoint w;
    w.index = out.size();
    w.name = std::string(fields[0]);
    if (w.name.empty())
      w.name = "waypoint " + std::to_string(w.index);
    w.position = {csv_number(fields[1], where, line_number, "x"),
                  csv_number(fields[2], where, line_number, "y")};
    if (has_theta && fields.size() >= 4 && !fields[3].empty())
      w.theta = csv_number(fields[3], where, line_number, "theta");
    out.push_back(std::move(w));
  }
  if (!header_seen)
    throw InputError("empty: expected the header name,x,y[,theta]", where, 0, "header");
  return out;
}

PlanLayers read_plan_layers(const std::filesystem::path& path,
                            const PlanLayersReadOptions& options) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::string where = path.string();
  if (ext == ".dxf") {
    if (options.layer.empty()) {
      throw InputError(
          "zones from a DXF need --layer NAME (the layer holding their closed "
          "polylines or hatches)",
          where, 0, "--layer");
    }
    return read_dxf_zones_file(path, options.layer, options.metres_per_unit);
  }
  const std::string text = read_whole_file(path, kMaxSettingsFileBytes);
  if (ext == ".csv") {
    PlanLayers layers;
    layers.waypoints = parse_waypoints_csv(text, where);
    return layers;
  }
  if (ext == ".geojson" || ext == ".json")
    return parse_plan_layers_geojson(text, where);
  throw InputError(
      "unknown kind of file: zones and waypoints are .geojson/.json (GeoJSON), "
      ".csv (waypoints name,x,y,theta) or .dxf (zones, with --layer)",
      where, 0, "");
}

std::string mapped_layers_geojson(const std::vector<MappedZone>& zones,
                                  const std::vector<MappedWaypoint>& waypoints,
                                  const std::string& frame, double margin_sigma) {
  json features = json::array();
  for (const MappedZone& z : zones) {
    json rings = json::array();
    for (const Eigen::Matrix2Xd& r : z.rings)
      rings.push_back(ring_json(r));
    json properties = {{"kind", "zone"},
                       {"name", z.name},
                       {"index", z.index},
                       {"std_m", z.has_std ? json(z.max_std_m) : json(nullptr)},
                       {"max_std_m", z.has_std ? json(z.max_std_m) : json(nullptr)},
                       {"mean_std_m", z.has_std ? json(z.mean_std_m) : json(nullptr)},
                       {"margin_m", margin_sigma * z.max_std_m},
                       {"extrapolated", z.extrapolated_points > 0},
                       {"extrapolated_points", z.extrapolated_points},
                       {"boundary_points", z.boundary_points}};
    features.push_back({{"type", "Feature"},
                        {"geometry", {{"type", "Polygon"}, {"coordinates", rings}}},
                        {"properties", properties}});
  }
  for (const MappedWaypoint& m : waypoints) {
    const Waypoint& w = m.waypoint;
    json coordinates =
        w.position.allFinite() ? json::array({w.position.x(), w.position.y()}) : json(nullptr);
    json properties = {{"kind", "waypoint"},
                       {"name", w.name},
                       {"index", w.index},
                       {"theta", number_or_null(w.theta)},
                       {"std_m", number_or_null(m.std_m)},
                       {"nearest_pair_m", m.nearest_pair_m},
                       {"flag", to_string(m.flag)},
                       {"extrapolated", m.extrapolated},
                       {"on_gridmap", m.on_gridmap}};
    features.push_back({{"type", "Feature"},
                        {"geometry", coordinates.is_null()
                                         ? json(nullptr)
                                         : json{{"type", "Point"}, {"coordinates", coordinates}}},
                        {"properties", properties}});
  }
  const json root = {{"type", "FeatureCollection"},
                     {"floorgrid", {{"frame", frame}, {"units", "m"}}},
                     {"features", features}};
  return root.dump(2) + "\n";
}

}  // namespace floorgrid::io
