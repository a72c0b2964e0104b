#include "floorgrid/evaluation/zone_mask.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {

namespace {

/// Batches of boundary points mapped at once (bounded memory for models with costly batches).
constexpr Eigen::Index kChunk = 65536;

Eigen::Matrix2Xd forward_in_chunks(const PointMapping& model, const Eigen::Matrix2Xd& points) {
  Eigen::Matrix2Xd out(2, points.cols());
  for (Eigen::Index begin = 0; begin < points.cols(); begin += kChunk) {
    const Eigen::Index n = std::min(kChunk, points.cols() - begin);
    out.middleCols(begin, n) = model.forward_batch(points.middleCols(begin, n));
  }
  return out;
}

/// The mask value of a zone: keepout 100; speed its speed through the filter's encoding.
std::int8_t mask_value(const Zone& zone, ZoneMaskKind kind, const Nav2FilterInfo& filter) {
  if (kind == ZoneMaskKind::keepout)
    return kOccupancyOccupied;
  const double speed = zone.speed.percent ? *zone.speed.percent : *zone.speed.metres_per_second;
  const double value = std::round((speed - filter.base) / filter.multiplier);
  return static_cast<std::int8_t>(std::clamp(value, 1.0, 100.0));
}

}  // namespace

void validate(const ZoneMaskOptions& options) {
  require_option(options.margin_sigma >= 0.0 && options.margin_sigma <= 10.0, "zones",
                 "margin_sigma", options.margin_sigma, "in [0, 10]");
  require_option(options.samples_per_cell >= 1.0 && options.samples_per_cell <= 100.0, "zones",
                 "samples_per_cell", options.samples_per_cell, "in [1, 100]");
}

double zone_sample_spacing(const PointMapping& model, const GridGeometry& gridmap,
                           const ZoneMaskOptions& options) {
  const double det = model.support_similarity().topLeftCorner<2, 2>().determinant();
  const double scale = std::sqrt(std::abs(det));
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw InputError("the model's scale is degenerate", {}, 0, "model");
  return gridmap.resolution / scale / options.samples_per_cell;
}

MappedZone map_zone(const PointMapping& model, const Zone& zone, double spacing_in_plan) {
  MappedZone mapped;
  mapped.name = zone.name;
  mapped.index = zone.index;
  std::vector<const Ring*> rings{&zone.outer};
  for (const Ring& hole : zone.holes)
    rings.push_back(&hole);
  double std_sum = 0.0;
  const double far = model.common().extrapolation_distance;
  for (const Ring* ring : rings) {
    const Eigen::Matrix2Xd in_plan = densify_ring(*ring, spacing_in_plan);
    Eigen::Matrix2Xd in_grid = forward_in_chunks(model, in_plan);
    Eigen::VectorXd std_m = Eigen::VectorXd::Zero(in_plan.cols());
    for (Eigen::Index i = 0; i < in_plan.cols(); ++i) {
      const Eigen::Vector2d p = in_plan.col(i);
      const double nearest = model.nearest_pair_in_plan(p);
      if (const auto s = model.error_std(p)) {
        std_m(i) = *s;
        mapped.has_std = true;
        mapped.max_std_m = std::max(mapped.max_std_m, *s);
        std_sum += *s;
      }
      const bool finite = in_grid.col(i).allFinite();
      if (!finite || nearest > far || !model.inside_plan_hull(p))
        ++mapped.extrapolated_points;
    }
    mapped.boundary_points += static_cast<std::size_t>(in_plan.cols());
    mapped.rings.push_back(std::move(in_grid));
    mapped.std_m.push_back(std::move(std_m));
  }
  if (mapped.boundary_points > 0)
    mapped.mean_std_m = std_sum / static_cast<double>(mapped.boundary_points);
  return mapped;
}

Nav2FilterInfo filter_info_for(const std::vector<Zone>& zones, ZoneMaskKind kind,
                               const std::string& where) {
  Nav2FilterInfo info;
  if (kind == ZoneMaskKind::keepout)
    return info;  // type 0, base 0, multiplier 1: the mask value is the cost itself
  bool percent = false, absolute = false;
  double fastest = 0.0;
  for (const Zone& zone : zones) {
    if (zone.speed.percent) {
      percent = true;
    } else if (zone.speed.metres_per_second) {
      absolute = true;
      fastest = std::max(fastest, *zone.speed.metres_per_second);
    } else {
      throw InputError(describe(zone) +
                           ": a speed zone needs its speed: property speed_percent (of the "
                           "robot's maximal speed) or speed_mps (metres per second), or give "
                           "--speed-percent",
                       where, 0, "speed");
    }
  }
  if (percent && absolute) {
    throw InputError(
        "speed zones mix speed_percent and speed_mps: nav2 reads one mask in one "
        "kind (filter type 1 or 2); give all in one",
        where, 0, "speed");
  }
  if (percent) {
    info.type = 1;  // speed limit in % of the maximal speed
    info.multiplier = 1.0;
  } else {
    info.type = 2;  // speed limit in m/s
    info.multiplier = std::max(0.01, fastest / 100.0);
  }
  info.base = 0.0;
  return info;
}

ZoneMask map_zones_to_mask(const PointMapping& model, const std::vector<Zone>& zones,
                           const GridGeometry& gridmap, ZoneMaskKind kind,
                           const ZoneMaskOptions& options, const std::string& where) {
  validate(options);
  for (const Zone& zone : zones)
    validate_zone(zone, where);
  const double spacing = zone_sample_spacing(model, gridmap, options);
  std::vector<MappedZone> mapped;
  mapped.reserve(zones.size());
  for (const Zone& zone : zones)
    mapped.push_back(map_zone(model, zone, spacing));
  return mask_of_mapped_zones(std::move(mapped), zones, gridmap, kind, options, where);
}

ZoneMask mask_of_mapped_zones(std::vector<MappedZone> mapped_zones, const std::vector<Zone>& zones,
                              const GridGeometry& gridmap, ZoneMaskKind kind,
                              const ZoneMaskOptions& options, const std::string& where) {
  validate(options);
  if (zones.empty())
    throw InputError("no zones to draw", where, 0, "zones");
  if (mapped_zones.size() != zones.size())
    throw std::invalid_argument("mask_of_mapped_zones: one mapped zone per zone");
  ZoneMask result;
  result.kind = kind;
  result.filter = filter_info_for(zones, kind, where);
  result.mask = OccupancyGrid(gridmap, CellState::free);
  bool any_std = false;
  for (std::size_t k = 0; k < zones.size(); ++k) {
    const Zone& zone = zones[k];
    MappedZone& mapped = mapped_zones[k];
    const CellMask inside = rasterize_rings(mapped.rings, gridmap);
    CellMask cells = inside;
    for (std::size_t r = 0; r < mapped.rings.size(); ++r) {
      const Eigen::VectorXd radii = options.margin_sigma * mapped.std_m[r];
      stamp_disks(cells, mapped.rings[r], radii);
    }
    mapped.cells_inside = inside.count();
    mapped.cells = cells.count();
    // Clipped: some boundary point (or its margin) off the grid.
    for (const Eigen::Matrix2Xd& ring : mapped.rings) {
      for (Eigen::Index i = 0; i < ring.cols() && !mapped.clipped; ++i) {
        int ix = 0, iy = 0;
        mapped.clipped = !gridmap.cell_of(ring.col(i), ix, iy);
      }
    }
    if (mapped.cells == 0 && !options.allow_zone_off_map) {
      throw InputError(fmt::format("{} lies wholly off the gridmap ({} x {} cells of {} m from "
                                   "({}, {})): no cell of the mask would hold it",
                                   describe(zone), gridmap.width, gridmap.height,
                                   gridmap.resolution, gridmap.origin.x, gridmap.origin.y),
                       where, 0, "zones");
    }
    if (mapped.clipped) {
      result.warnings.push_back(
          fmt::format("{} reaches off the gridmap: clipped to it ({} cells "
                      "kept)",
                      describe(zone), mapped.cells));
    }
    if (mapped.extrapolated_points > 0) {
      result.warnings.push_back(fmt::format(
          "{}: {} of {} boundary points are extrapolated (far from every pair or outside their "
          "hull): check it on the map",
          describe(zone), mapped.extrapolated_points, mapped.boundary_points));
    }
    any_std = any_std || mapped.has_std;
    const std::int8_t value = mask_value(zone, kind, result.filter);
    mapped.mask_value = value;
    for (int iy = 0; iy < gridmap.height; ++iy) {
      for (int ix = 0; ix < gridmap.width; ++ix) {
        if (!cells.at(ix, iy))
          continue;
        const std::int8_t old = result.mask.value(ix, iy);
        // Overlaps: keepout is a union; a speed cell keeps the slowest zone's limit (with base
        // 0 and a positive multiplier the smaller value is the slower).
        const std::int8_t v = old == 0 ? value : std::min(old, value);
        result.mask.set_cell(ix, iy, CellState::occupied, v);  // a zone cell, whatever its value
      }
    }
    result.zones.push_back(std::move(mapped));
  }
  if (!any_std && options.margin_sigma > 0.0) {
    result.warnings.push_back(
        "the model states no std_m (no error model: fit it with --cv, or use an `align` "
        "model): the zones are not widened");
  }
  return result;
}

}  // namespace floorgrid
