#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/evaluation/zone_mask.hpp"
#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/plan_layers.hpp"
#include "floorgrid/server/map_request.hpp"

namespace floorgrid::server {

/// What one zones or waypoints request may ask for: each bounds a cost a hostile or mistaken
/// request could otherwise make unbounded (a ring's self-intersection check, the boundary
/// samples mapped through the model, the margin disks stamped on the mask).
struct PlanLayersLimits {
  std::size_t max_features = 500;       ///< zones or waypoints in one request
  std::size_t max_vertices = 20'000;    ///< ring vertices in one request (all zones)
  std::size_t max_samples = 1'000'000;  ///< boundary samples mapped (perimeter / spacing)
  /// Cells the margin disks may visit in all (each disk's area, at most the grid's).
  double max_margin_cells = 4e8;
  /// A vertex or waypoint may lie outside the plan by at most this many of its diagonals (or
  /// margin_m, whichever is larger): drawn on the plan, or near it.
  double margin_maps = 1.0;
  double margin_m = 50.0;                ///< metres, see margin_maps
  std::size_t ring_points_shown = 2000;  ///< points per mapped ring in an answer (thinned)
};

/// Where the session's maps lie and how a request's layers are checked against them.
struct PlanLayersContext {
  std::optional<Eigen::AlignedBox2d> plan_bounds;  ///< none: the session has no plan picture
  GridGeometry gridmap;                            ///< the mask's grid (the session's gridmap)
  PlanLayersLimits limits;
};

/// A POST /api/zones or /api/zones/nav2 body, read and checked.
struct ZonesRequest {
  std::vector<Zone> zones;  ///< plan metres, validated
  ZoneMaskKind kind = ZoneMaskKind::keepout;
  ZoneMaskOptions options;            ///< margin_sigma from the body
  std::string file;                   ///< what messages name ("file" or "request")
  std::string stem;                   ///< nav2 files' stem ("keepout" or "speed" by default)
  std::vector<std::string> warnings;  ///< from reading the GeoJSON
};

/// Reads {"geojson": FeatureCollection (an object, or its text), "file"?: name for messages,
/// "kind"?: "keepout"|"speed", "margin_sigma"?: [0, 10], "speed_percent"?: (0, 100] for speed
/// zones without their own, "stem"?: [A-Za-z0-9_-]{1,64}}: RequestError 400 naming the field
/// (413 beyond limits), InputError 400 from the library naming the file and feature (open or
/// self-intersecting rings, degrees, NaN), and 400 for a vertex far off the plan.
ZonesRequest parse_zones_request(const nlohmann::json& request, const PlanLayersContext& context);

/// POST /api/zones: the zones mapped and drawn as the nav2 mask would be: {"kind",
/// "margin_sigma", "filter": {"type", "base", "multiplier"}, "zones": [{"name", "index",
/// "plan": {"outer", "holes"}, "speed_percent", "speed_mps", "rings" (grid metres, thinned),
/// "std_m" (per shown ring point, null without error model), "boundary_points",
/// "extrapolated_points", "has_std", "max_std_m", "mean_std_m", "margin_m", "mask_value",
/// "cells", "cells_inside", "clipped"}], "mask": {"cells", "png" (data: URL, RGBA on the
/// gridmap's pixels, top row first)}, "warnings"}. InputError 400 for a zone wholly off the
/// gridmap; RequestError 413 when the boundary or its margin would be too costly to draw.
nlohmann::json zones_answer(const ZonesRequest& request, const PointMapping& model,
                            const PlanLayersContext& context);

/// POST /api/zones/nav2: the nav2 files of the mask: {"kind", "filter", "files": [{"name",
/// "media_type", "text" or "base64"}]}: the mask's map YAML, its image, the filter-info params
/// YAML and the zones' mapped boundary as GeoJSON in gridmap metres.
nlohmann::json zones_nav2_answer(const ZonesRequest& request, const PointMapping& model,
                                 const PlanLayersContext& context);

/// POST /api/waypoints: {"geojson": Point features (object or text)} or {"csv": "name,x,y[,theta]
/// text"}, "file"?, "frame_id"?: the nav2 frame (default "map") -> {"waypoints": [{"name",
/// "index", "plan": [x, y, theta|null], "x", "y", "theta" (null without heading), "std_m",
/// "nearest_pair_m", "flag", "extrapolated", "on_gridmap"}], "extrapolated", "warnings",
/// "files": [nav2 waypoints YAML, GeoJSON in gridmap metres]}. Errors as parse_zones_request.
nlohmann::json waypoints_answer(const nlohmann::json& request, const PointMapping& model,
                                const PlanLayersContext& context);

/// The text of standard base64 (RFC 4648, padded) of `bytes`.
std::string base64(const std::string& bytes);

}  // namespace floorgrid::server
