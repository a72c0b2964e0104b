#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "floorgrid/evaluation/waypoint_mapping.hpp"
#include "floorgrid/evaluation/zone_mask.hpp"
#include "floorgrid/maps/plan_layers.hpp"

namespace floorgrid::io {

/// Parses GeoJSON text (a FeatureCollection, a Feature or a bare geometry) in plan metres:
/// Polygon and MultiPolygon features become zones (property `name`; `speed_percent` or
/// `speed_mps` for speed zones), Point features waypoints (`name`; heading `theta` in radians or
/// `heading_deg` in degrees). Rings must be closed (first position = last) and simple
/// (validate_zone). Refuses a `crs` naming WGS84 (EPSG:4326, CRS84) and coordinates that look
/// like degrees (the whole file spanning less than 5 cm): "plan metres only". Other geometry
/// types are skipped with a warning. InputError naming `where`, the feature (index and name) and
/// the member on anything malformed.
PlanLayers parse_plan_layers_geojson(std::string_view text, const std::string& where);

/// Parses waypoints CSV: header `name,x,y[,theta]` (metres, radians; theta may be empty), one
/// waypoint a row; further columns are ignored (a `migrate` output reads back). InputError naming
/// `where`, the line and the column.
std::vector<Waypoint> parse_waypoints_csv(std::string_view text, const std::string& where);

/// How plan layers are read from a file.
struct PlanLayersReadOptions {
  std::string layer;             ///< DXF: the layer (case-insensitive glob) holding the zones
  double metres_per_unit = 1.0;  ///< DXF: metres per drawing unit (the plan's)
};

/// Reads zones and/or waypoints by the file's extension: .geojson/.json (GeoJSON), .csv
/// (waypoints), .dxf (zones on options.layer: closed LWPOLYLINE/POLYLINE and HATCH boundaries).
/// InputError naming the file on anything malformed or unknown.
PlanLayers read_plan_layers(const std::filesystem::path& path,
                            const PlanLayersReadOptions& options = {});

/// The mapped zones (as polygons of their densified boundary, margin 0) and waypoints as a
/// GeoJSON FeatureCollection in the target frame's metres (`frame` names it, e.g. "gridmap"),
/// each feature's properties holding name, index, std_m (null without error model),
/// extrapolated and flag (waypoints: theta, nearest_pair_m, on_gridmap; zones: max_std_m,
/// mean_std_m, margin_m, extrapolated_points, boundary_points).
std::string mapped_layers_geojson(const std::vector<MappedZone>& zones,
                                  const std::vector<MappedWaypoint>& waypoints,
                                  const std::string& frame, double margin_sigma);

}  // namespace floorgrid::io
