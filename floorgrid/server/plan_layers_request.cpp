#include "floorgrid/server/plan_layers_request.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "floorgrid/core/error.hpp"
#include "floorgrid/evaluation/waypoint_mapping.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/formats/nav2_filter_mask.hpp"
#include "floorgrid/io/plans/plan_layers_io.hpp"
#include "floorgrid/server/printable_text.hpp"

namespace floorgrid::server {

namespace {

/// A refusal whose message repeats the request's bytes (a file's or a feature's name) only as
/// printable ASCII (%XX).
RequestError refuse(int status, const std::string& message) {
  return RequestError(status, printable_text(message, 600));
}

RequestError bad(const std::string& message) {
  return refuse(400, message);
}

std::string number_text(double x) {
  return nlohmann::json(x).dump();
}

/// The library's word on the request's layers, every byte it repeats printable (a feature's
/// name may hold any UTF-8, or a control byte).
template <typename Work>
auto reading_layers(Work work) {
  try {
    return work();
  } catch (const InputError& e) {
    throw bad(e.what());
  }
}

/// "file": the name messages give the layers (the file the operator loaded), else "request";
/// repeated as printable text (see refuse).
std::string file_name(const nlohmann::json& request) {
  const auto it = request.find("file");
  if (it == request.end() || it->is_null())
    return "request";
  if (!it->is_string())
    throw bad("'file' must be a string (the loaded file's name)");
  return it->get_ref<const std::string&>().substr(0, 120);
}

/// A number field in [lo, hi], or `fallback` when absent.
std::optional<double> number_field(const nlohmann::json& request, const char* name, double lo,
                                   double hi, bool lo_open) {
  const auto it = request.find(name);
  if (it == request.end() || it->is_null())
    return std::nullopt;
  if (!it->is_number())
    throw bad(std::string("'") + name + "' must be a number (got " +
              printable_text(it->dump(), 80) + ")");
  const double v = it->get<double>();
  if (!(lo_open ? v > lo : v >= lo) || !(v <= hi)) {
    throw bad(std::string("'") + name + "' must be in " + (lo_open ? "(" : "[") + number_text(lo) +
              ", " + number_text(hi) + "] (got " + number_text(v) + ")");
  }
  return v;
}

/// The text of a layers field: a JSON object sent as it is, or a file's text as a string.
std::optional<std::string> layers_text(const nlohmann::json& request, const char* name,
                                       bool object_allowed) {
  const auto it = request.find(name);
  if (it == request.end() || it->is_null())
    return std::nullopt;
  if (it->is_string())
    return it->get<std::string>();
  if (object_allowed && it->is_object())
    return it->dump();
  throw bad(std::string("'") + name + "' must be " +
            (object_allowed ? "a GeoJSON object or its text" : "the file's text"));
}

/// RequestError 400 when `p` lies farther off the plan than the limits allow.
void check_near_plan(const Eigen::Vector2d& p, const PlanLayersContext& context,
                     const std::string& what) {
  if (!(std::abs(p.x()) <= kMaxCoordinate && std::abs(p.y()) <= kMaxCoordinate)) {
    throw bad(what + ": (" + number_text(p.x()) + ", " + number_text(p.y()) +
              ") must be within 1e7 m of the origin: not a coordinate in a building");
  }
  if (!context.plan_bounds || context.plan_bounds->isEmpty())
    return;
  const Eigen::AlignedBox2d& box = *context.plan_bounds;
  const double margin =
      std::max(context.limits.margin_m, context.limits.margin_maps * box.diagonal().norm());
  const double outside = box.exteriorDistance(p);
  if (outside > margin) {
    throw bad(what + ": (" + number_text(p.x()) + ", " + number_text(p.y()) + ") lies " +
              number_text(std::round(outside)) + " m outside the plan ([" +
              number_text(box.min().x()) + ", " + number_text(box.min().y()) + "] to [" +
              number_text(box.max().x()) + ", " + number_text(box.max().y()) +
              "]): layers are drawn on the plan, in plan metres, within " +
              number_text(std::round(margin)) + " m of it");
  }
}

nlohmann::json ring_json(const Ring& ring) {
  nlohmann::json out = nlohmann::json::array();
  for (const Eigen::Vector2d& p : ring)
    out.push_back({p.x(), p.y()});
  return out;
}

nlohmann::json filter_json(const Nav2FilterInfo& f) {
  return {{"type", f.type}, {"base", f.base}, {"multiplier", f.multiplier}};
}

const char* kind_name(ZoneMaskKind kind) {
  return kind == ZoneMaskKind::keepout ? "keepout" : "speed";
}

nlohmann::json nullable(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

/// Plan metres of every ring edge (closed) of the zones.
double boundary_length(const std::vector<Zone>& zones) {
  double length = 0.0;
  for (const Zone& z : zones) {
    std::vector<const Ring*> rings{&z.outer};
    for (const Ring& h : z.holes)
      rings.push_back(&h);
    for (const Ring* r : rings) {
      for (std::size_t i = 0; i < r->size(); ++i)
        length += ((*r)[(i + 1) % r->size()] - (*r)[i]).norm();
    }
  }
  return length;
}

/// The zones mapped, with 413 before the mapping when their boundary samples are too many and
/// before the mask when its margin disks would visit too many cells.
std::vector<MappedZone> mapped_zones(const ZonesRequest& request, const PointMapping& model,
                                     const PlanLayersContext& context) {
  const PlanLayersLimits& limits = context.limits;
  const double spacing = zone_sample_spacing(model, context.gridmap, request.options);
  const double samples = boundary_length(request.zones) / spacing;
  if (!(samples <= static_cast<double>(limits.max_samples))) {
    throw refuse(413, "the zones' boundaries are " +
                          number_text(std::round(boundary_length(request.zones))) +
                          " m long: " + number_text(std::round(samples)) + " samples to map at " +
                          number_text(spacing) + " m, at most " +
                          std::to_string(limits.max_samples) + " per request");
  }
  std::vector<MappedZone> mapped;
  double margin_cells = 0.0;
  const GridGeometry& g = context.gridmap;
  const double grid_cells = static_cast<double>(g.width) * g.height;
  for (const Zone& z : request.zones) {
    mapped.push_back(map_zone(model, z, spacing));
    for (const Eigen::VectorXd& std_m : mapped.back().std_m) {
      for (Eigen::Index i = 0; i < std_m.size(); ++i) {
        const double r = request.options.margin_sigma * std_m(i) / g.resolution;
        if (std::isfinite(r))
          margin_cells += std::min(grid_cells, std::numbers::pi * (r + 1.0) * (r + 1.0));
      }
    }
  }
  if (!(margin_cells <= limits.max_margin_cells)) {
    throw refuse(413, "the zones' margins (" + number_text(request.options.margin_sigma) +
                          " x std_m at every boundary point) would draw " +
                          number_text(std::round(margin_cells)) + " cells; at most " +
                          number_text(limits.max_margin_cells) +
                          ": a smaller margin_sigma, or zones where the model is sure");
  }
  return mapped;
}

/// The mask as the viewer draws it on the gridmap: an RGBA PNG, one pixel a cell, top row
/// first; zone cells tinted (keepout red, speed amber, darker for slower), the rest clear.
std::string mask_png(const ZoneMask& mask) {
  const GridGeometry& g = mask.mask.geometry();
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(g.width) * g.height * 4, 0);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const int v = mask.mask.value(ix, iy);
      if (v <= 0)
        continue;
      std::uint8_t* p = &rgba[(static_cast<std::size_t>(g.height - 1 - iy) * g.width + ix) * 4];
      if (mask.kind == ZoneMaskKind::keepout) {
        p[0] = 215, p[1] = 48, p[2] = 39, p[3] = 140;
      } else {
        p[0] = 230, p[1] = static_cast<std::uint8_t>(90 + v), p[2] = 20,
        p[3] = static_cast<std::uint8_t>(200 - v);
      }
    }
  }
  return "data:image/png;base64," + base64(io::encode_png(g.width, g.height, 4, rgba));
}

nlohmann::json text_file(const std::string& name, const char* type, const std::string& text) {
  return {{"name", name}, {"media_type", type}, {"text", text}};
}

}  // namespace

std::string base64(const std::string& bytes) {
  static const char* const kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (two ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0u);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += two ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

ZonesRequest parse_zones_request(const nlohmann::json& request, const PlanLayersContext& context) {
  ZonesRequest out;
  out.file = file_name(request);
  if (const auto it = request.find("kind"); it != request.end() && !it->is_null()) {
    if (*it == "keepout")
      out.kind = ZoneMaskKind::keepout;
    else if (*it == "speed")
      out.kind = ZoneMaskKind::speed;
    else
      throw bad("'kind' must be \"keepout\" or \"speed\" (got " + printable_text(it->dump(), 80) +
                ")");
  }
  if (const auto m = number_field(request, "margin_sigma", 0.0, 10.0, false))
    out.options.margin_sigma = *m;
  const std::optional<double> speed_percent =
      number_field(request, "speed_percent", 0.0, 100.0, true);
  out.stem = kind_name(out.kind);
  if (const auto it = request.find("stem"); it != request.end() && !it->is_null()) {
    const bool ok =
        it->is_string() && !it->get_ref<const std::string&>().empty() &&
        it->get_ref<const std::string&>().size() <= 64 &&
        std::all_of(it->get_ref<const std::string&>().begin(),
                    it->get_ref<const std::string&>().end(), [](char c) {
                      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
                    });
    if (!ok)
      throw bad("'stem' must be 1 to 64 of A-Z, a-z, 0-9, _ and - (got " +
                printable_text(it->dump(), 80) + ")");
    out.stem = it->get<std::string>();
  }
  const std::optional<std::string> text = layers_text(request, "geojson", true);
  if (!text)
    throw bad("'geojson' is missing: the zones, a GeoJSON FeatureCollection in plan metres");
  PlanLayers layers =
      reading_layers([&] { return io::parse_plan_layers_geojson(*text, out.file); });
  out.warnings = std::move(layers.warnings);
  if (!layers.waypoints.empty()) {
    out.warnings.push_back(out.file + ": " + std::to_string(layers.waypoints.size()) +
                           " Point features are waypoints, not zones (POST /api/waypoints)");
  }
  out.zones = std::move(layers.zones);
  if (out.zones.empty())
    throw bad(out.file + ": holds no zone (Polygon or MultiPolygon feature)");
  const PlanLayersLimits& limits = context.limits;
  if (out.zones.size() > limits.max_features) {
    throw refuse(413, out.file + ": " + std::to_string(out.zones.size()) + " zones; at most " +
                          std::to_string(limits.max_features) + " per request");
  }
  std::size_t vertices = 0;
  for (const Zone& z : out.zones) {
    vertices += z.outer.size();
    for (const Ring& h : z.holes)
      vertices += h.size();
  }
  if (vertices > limits.max_vertices) {
    throw refuse(413, out.file + ": the zones have " + std::to_string(vertices) +
                          " vertices; at most " + std::to_string(limits.max_vertices) +
                          " per request");
  }
  for (Zone& z : out.zones) {
    const std::string what = out.file + ": " + describe(z);
    for (const Eigen::Vector2d& p : z.outer)
      check_near_plan(p, context, what);
    for (const Ring& h : z.holes) {
      for (const Eigen::Vector2d& p : h)
        check_near_plan(p, context, what);
    }
    if (out.kind == ZoneMaskKind::speed && speed_percent && !z.speed.percent &&
        !z.speed.metres_per_second)
      z.speed.percent = *speed_percent;
  }
  return out;
}

nlohmann::json zones_answer(const ZonesRequest& request, const PointMapping& model,
                            const PlanLayersContext& context) {
  const ZoneMask mask = reading_layers([&] {
    return mask_of_mapped_zones(mapped_zones(request, model, context), request.zones,
                                context.gridmap, request.kind, request.options, request.file);
  });
  nlohmann::json zones = nlohmann::json::array();
  for (std::size_t k = 0; k < mask.zones.size(); ++k) {
    const MappedZone& z = mask.zones[k];
    const Zone& source = request.zones[k];
    nlohmann::json holes = nlohmann::json::array();
    for (const Ring& h : source.holes)
      holes.push_back(ring_json(h));
    nlohmann::json rings = nlohmann::json::array();
    nlohmann::json stds = nlohmann::json::array();
    for (std::size_t r = 0; r < z.rings.size(); ++r) {
      const Eigen::Matrix2Xd& ring = z.rings[r];
      const Eigen::Index n = ring.cols();
      const auto shown =
          std::min<Eigen::Index>(n, static_cast<Eigen::Index>(context.limits.ring_points_shown));
      nlohmann::json points = nlohmann::json::array();
      nlohmann::json std_m = nlohmann::json::array();
      for (Eigen::Index j = 0; j < shown; ++j) {
        const Eigen::Index i = j * n / shown;
        points.push_back({ring(0, i), ring(1, i)});
        std_m.push_back(z.has_std ? nlohmann::json(z.std_m[r](i)) : nlohmann::json(nullptr));
      }
      rings.push_back(std::move(points));
      stds.push_back(std::move(std_m));
    }
    zones.push_back({{"name", z.name},
                     {"index", z.index},
                     {"plan", {{"outer", ring_json(source.outer)}, {"holes", holes}}},
                     {"speed_percent", nullable(source.speed.percent)},
                     {"speed_mps", nullable(source.speed.metres_per_second)},
                     {"rings", std::move(rings)},
                     {"std_m", std::move(stds)},
                     {"boundary_points", z.boundary_points},
                     {"extrapolated_points", z.extrapolated_points},
                     {"has_std", z.has_std},
                     {"max_std_m", z.has_std ? nlohmann::json(z.max_std_m) : nullptr},
                     {"mean_std_m", z.has_std ? nlohmann::json(z.mean_std_m) : nullptr},
                     {"margin_m", request.options.margin_sigma * z.max_std_m},
                     {"mask_value", z.mask_value ? nlohmann::json(static_cast<int>(*z.mask_value))
                                                 : nlohmann::json(nullptr)},
                     {"cells", z.cells},
                     {"cells_inside", z.cells_inside},
                     {"clipped", z.clipped}});
  }
  std::size_t mask_cells = 0;
  const GridGeometry& g = mask.mask.geometry();
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix)
      mask_cells += mask.mask.value(ix, iy) > 0;
  }
  std::vector<std::string> warnings = request.warnings;
  warnings.insert(warnings.end(), mask.warnings.begin(), mask.warnings.end());
  nlohmann::json warning_list = nlohmann::json::array();
  for (const std::string& w : warnings)
    warning_list.push_back(printable_text(w, 400));
  return {{"kind", kind_name(request.kind)},
          {"margin_sigma", request.options.margin_sigma},
          {"filter", filter_json(mask.filter)},
          {"zones", std::move(zones)},
          {"mask", {{"cells", mask_cells}, {"png", mask_png(mask)}}},
          {"warnings", std::move(warning_list)}};
}

nlohmann::json zones_nav2_answer(const ZonesRequest& request, const PointMapping& model,
                                 const PlanLayersContext& context) {
  const ZoneMask mask = reading_layers([&] {
    return mask_of_mapped_zones(mapped_zones(request, model, context), request.zones,
                                context.gridmap, request.kind, request.options, request.file);
  });
  const io::Nav2MaskFiles files = io::nav2_mask_files(mask, request.stem);
  const bool png = files.image_name.ends_with(".png");
  nlohmann::json list = nlohmann::json::array();
  list.push_back(text_file(files.yaml_name, "application/yaml", files.yaml));
  list.push_back({{"name", files.image_name},
                  {"media_type", png ? "image/png" : "image/x-portable-graymap"},
                  {"base64", base64(files.image)}});
  list.push_back(text_file(files.params_name, "application/yaml", files.params_yaml));
  list.push_back(text_file(
      request.stem + "_zones_gridmap.geojson", "application/geo+json",
      io::mapped_layers_geojson(mask.zones, {}, "gridmap", request.options.margin_sigma)));
  return {{"kind", kind_name(request.kind)},
          {"filter", filter_json(mask.filter)},
          {"files", std::move(list)}};
}

nlohmann::json waypoints_answer(const nlohmann::json& request, const PointMapping& model,
                                const PlanLayersContext& context) {
  const std::string file = file_name(request);
  std::string frame_id = "map";
  if (const auto it = request.find("frame_id"); it != request.end() && !it->is_null()) {
    const bool ok =
        it->is_string() && !it->get_ref<const std::string&>().empty() &&
        it->get_ref<const std::string&>().size() <= 64 &&
        std::all_of(it->get_ref<const std::string&>().begin(),
                    it->get_ref<const std::string&>().end(), [](char c) {
                      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '/';
                    });
    if (!ok)
      throw bad("'frame_id' must be 1 to 64 of A-Z, a-z, 0-9, _ and / (got " +
                printable_text(it->dump(), 80) + ")");
    frame_id = it->get<std::string>();
  }
  const std::optional<std::string> geojson = layers_text(request, "geojson", true);
  const std::optional<std::string> csv = layers_text(request, "csv", false);
  if (geojson && csv)
    throw bad("give 'geojson' or 'csv', not both");
  if (!geojson && !csv)
    throw bad(
        "'geojson' or 'csv' is missing: the waypoints (Point features, or CSV "
        "name,x,y[,theta]) in plan metres");
  std::vector<std::string> warnings;
  std::vector<Waypoint> waypoints;
  if (geojson) {
    PlanLayers layers =
        reading_layers([&] { return io::parse_plan_layers_geojson(*geojson, file); });
    waypoints = std::move(layers.waypoints);
    warnings = std::move(layers.warnings);
    if (!layers.zones.empty()) {
      warnings.push_back(file + ": " + std::to_string(layers.zones.size()) +
                         " polygons are zones, not waypoints (POST /api/zones)");
    }
  } else {
    waypoints = reading_layers([&] { return io::parse_waypoints_csv(*csv, file); });
  }
  if (waypoints.empty())
    throw bad(file + ": holds no waypoint (Point feature or CSV row)");
  if (waypoints.size() > context.limits.max_features) {
    throw refuse(413, file + ": " + std::to_string(waypoints.size()) + " waypoints; at most " +
                          std::to_string(context.limits.max_features) + " per request");
  }
  for (const Waypoint& w : waypoints)
    check_near_plan(w.position, context, file + ": " + describe(w));
  const std::vector<MappedWaypoint> mapped =
      reading_layers([&] { return map_waypoints(model, waypoints, context.gridmap, file); });
  nlohmann::json list = nlohmann::json::array();
  std::size_t extrapolated = 0;
  for (std::size_t k = 0; k < mapped.size(); ++k) {
    const MappedWaypoint& m = mapped[k];
    const Waypoint& source = waypoints[k];
    extrapolated += m.extrapolated;
    const bool finite = m.waypoint.position.allFinite();
    list.push_back({{"name", m.waypoint.name},
                    {"index", m.waypoint.index},
                    {"plan", {source.position.x(), source.position.y(), nullable(source.theta)}},
                    {"x", finite ? nlohmann::json(m.waypoint.position.x()) : nullptr},
                    {"y", finite ? nlohmann::json(m.waypoint.position.y()) : nullptr},
                    {"theta", m.waypoint.theta && std::isfinite(*m.waypoint.theta)
                                  ? nlohmann::json(*m.waypoint.theta)
                                  : nlohmann::json(nullptr)},
                    {"std_m", nullable(m.std_m)},
                    {"nearest_pair_m", m.nearest_pair_m},
                    {"flag", to_string(m.flag)},
                    {"extrapolated", m.extrapolated},
                    {"on_gridmap", m.on_gridmap}});
  }
  nlohmann::json warning_list = nlohmann::json::array();
  for (const std::string& w : warnings)
    warning_list.push_back(printable_text(w, 400));
  nlohmann::json files = nlohmann::json::array();
  files.push_back(
      text_file("waypoints.yaml", "application/yaml", io::nav2_waypoints_yaml(mapped, frame_id)));
  files.push_back(text_file("waypoints_gridmap.geojson", "application/geo+json",
                            io::mapped_layers_geojson({}, mapped, "gridmap", 0.0)));
  return {{"waypoints", std::move(list)},
          {"extrapolated", extrapolated},
          {"warnings", std::move(warning_list)},
          {"files", std::move(files)}};
}

}  // namespace floorgrid::server
