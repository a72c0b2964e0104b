#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"
#include "floorgrid/maps/plan_layers.hpp"
#include "floorgrid/maps/polygon_raster.hpp"

namespace floorgrid {

/// Which nav2 costmap filter a mask is for.
enum class ZoneMaskKind {
  keepout,  ///< KeepoutFilter: mask value 100 (lethal) inside a zone, 0 (free) elsewhere
  speed,    ///< SpeedFilter: mask value 1..100 inside a zone (its speed), 0 = no limit elsewhere
};

/// How zones drawn on the plan become a filter mask on the gridmap. Defaults in one place.
struct ZoneMaskOptions {
  /// K: each zone is widened by K x the model's std_m at each boundary point (metres), so that
  /// the true zone lies inside the mask with about 95% confidence per point at K = 2.
  double margin_sigma = 2.0;
  /// Boundary samples per gridmap cell along each plan edge (at the model's overall scale):
  /// dense enough that a bent model bends the edges.
  double samples_per_cell = 4.0;
  /// Zones partly outside the gridmap are clipped to it (and said so in the result); a zone
  /// with no cell on the gridmap is an InputError unless this is true.
  bool allow_zone_off_map = false;
};

/// Checks the options; InputError naming `zones.<field>`.
void validate(const ZoneMaskOptions& options);

/// nav2's CostmapFilterInfo for a mask (what the costmap_filter_info_server publishes):
/// filter value = base + multiplier * mask value (nav2_msgs/msg/CostmapFilterInfo).
struct Nav2FilterInfo {
  int type = 0;             ///< 0 keepout, 1 speed limit in % of maximal speed, 2 speed in m/s
  double base = 0.0;        ///< see above
  double multiplier = 1.0;  ///< see above
};

/// One zone through the model: its boundary in the gridmap frame and how sure it is.
struct MappedZone {
  std::string name;                       ///< the zone's name
  std::size_t index = 0;                  ///< the zone's index in its file
  std::vector<Eigen::Matrix2Xd> rings;    ///< outer ring then holes, densified, grid metres
  std::vector<Eigen::VectorXd> std_m;     ///< per ring point: std_m (0 where the model has none)
  std::size_t boundary_points = 0;        ///< points mapped along all rings
  std::size_t extrapolated_points = 0;    ///< of those flagged extrapolated/outside_hull or worse
  bool has_std = false;                   ///< the model states a std_m here
  double max_std_m = 0.0;                 ///< largest std_m along the boundary, metres
  double mean_std_m = 0.0;                ///< mean std_m along the boundary, metres
  std::optional<std::int8_t> mask_value;  ///< the value written for it (keepout 100, speed 1..100)
  std::size_t cells = 0;                  ///< mask cells it covers after widening
  std::size_t cells_inside = 0;           ///< of those, inside its mapped boundary (margin 0)
  bool clipped = false;                   ///< part of it lies off the gridmap
};

/// A filter mask on the gridmap's grid, and what went into it.
struct ZoneMask {
  ZoneMaskKind kind = ZoneMaskKind::keepout;  ///< which filter reads it
  /// Same geometry as the gridmap; OccupancyGrid values: keepout 100 in zones, 0 elsewhere;
  /// speed 1..100 in zones (the lowest speed where zones overlap), 0 elsewhere.
  OccupancyGrid mask;
  Nav2FilterInfo filter;              ///< what the filter info server must publish with it
  std::vector<MappedZone> zones;      ///< each zone as mapped
  std::vector<std::string> warnings;  ///< zones clipped, no std_m, extrapolated boundaries
};

/// A zone's rings (in the plan) densified and mapped through `model` forward, with std_m and
/// flags per boundary point. `spacing_in_plan`: metres between samples in the plan.
MappedZone map_zone(const PointMapping& model, const Zone& zone_in_plan, double spacing_in_plan);

/// Plan metres between boundary samples so that there are options.samples_per_cell per gridmap
/// cell at the model's overall scale.
double zone_sample_spacing(const PointMapping& model, const GridGeometry& gridmap,
                           const ZoneMaskOptions& options);

/// nav2's speed encoding of the zones (all in percent: type 1, base 0, multiplier 1, value =
/// percent; all in m/s: type 2, base 0, multiplier = max(0.01, fastest / 100), value = speed /
/// multiplier), each value rounded into 1..100; keepout: type 0, base 0, multiplier 1.
/// InputError naming the zone when a speed zone has no speed or percent and m/s are mixed.
Nav2FilterInfo filter_info_for(const std::vector<Zone>& zones, ZoneMaskKind kind,
                               const std::string& where);

/// The zones (plan metres) drawn through `model` onto a grid of `gridmap`'s geometry: each ring
/// densified and mapped forward, rasterized by cell centre (even-odd), widened by
/// options.margin_sigma x std_m with a disk at every boundary point. Validates every zone
/// (validate_zone) and the options first. InputError naming `where` and the zone for bad zones,
/// a zone wholly off the gridmap, or a speed zone without a speed.
ZoneMask map_zones_to_mask(const PointMapping& model, const std::vector<Zone>& zones_in_plan,
                           const GridGeometry& gridmap, ZoneMaskKind kind,
                           const ZoneMaskOptions& options = {}, const std::string& where = "zones");

/// The same mask from zones already mapped (`mapped[k]` is map_zone of `zones_in_plan[k]`, as
/// a caller that bounds the cost first has them, after validate_zone): rasterized, widened and
/// checked as map_zones_to_mask does, without mapping them again.
ZoneMask mask_of_mapped_zones(std::vector<MappedZone> mapped,
                              const std::vector<Zone>& zones_in_plan, const GridGeometry& gridmap,
                              ZoneMaskKind kind, const ZoneMaskOptions& options = {},
                              const std::string& where = "zones");

}  // namespace floorgrid
