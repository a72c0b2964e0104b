#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "floorgrid/evaluation/waypoint_mapping.hpp"
#include "floorgrid/evaluation/zone_mask.hpp"
#include "floorgrid/io/formats/map_io.hpp"

namespace floorgrid::io {

/// The files of a nav2 costmap filter mask, as text and bytes (what a server may send).
/// Conventions (docs.nav2.org, "Navigating with Keepout Zones" / "... with Speed Limits",
/// "Costmap Filter Info Server"): the mask is an ordinary map_server map of the gridmap's size,
/// resolution and origin; keepout: mode trinary, occupied_thresh 0.65, free_thresh 0.196, zones
/// black (OccupancyGrid 100 = lethal for the KeepoutFilter), the rest 254 (0 = free); speed:
/// mode scale with free_thresh 0.0 and occupied_thresh 1.0 (the tutorial's "no thresholds", so
/// darkness d in percent reads as OccupancyGrid value d), 0 = no limit outside zones, filter
/// value = base + multiplier x mask value.
struct Nav2MaskFiles {
  std::string yaml_name;   ///< the mask's map YAML's file name (stem.yaml)
  std::string yaml;        ///< the mask's map YAML (image, mode, resolution, origin, negate,
                           ///< occupied_thresh, free_thresh)
  std::string image_name;  ///< the image's file name, beside the YAML
  /// The image's bytes: an 8-bit PGM (P5), or a grey+alpha PNG for a scale-mode mask with
  /// unknown cells (nav2's scale mode reads any transparency as unknown).
  std::string image;
  std::string params_name;  ///< the filter-info params file's name, beside the YAML
  std::string params_yaml;  ///< ROS 2 params of costmap_filter_info_server (type, base,
                            ///< multiplier, topics) and filter_mask_server (yaml_filename, ...)
};

/// The map metadata nav2's tutorials give each kind of mask (see Nav2MaskFiles).
MapMetadata nav2_mask_metadata(ZoneMaskKind kind, const GridGeometry& geometry);

/// The 8-bit pixel that nav2's map_server (map_io, loadMapFromFile) decodes to OccupancyGrid
/// `value` (0..100, -1 unknown) in `metadata`'s mode and thresholds (negate 0): the exact inverse
/// of its formulas. Trinary: 0 / 254 / 205; scale: the darkness whose rint((occ - free) / (occ_t
/// - free) x 100) is the value; raw: the value itself, 255 unknown. InputError naming the field
/// when a value cannot be written in this mode (scale has no unknown without alpha).
std::uint8_t nav2_mask_pixel(std::int8_t value, const MapMetadata& metadata);

/// The mask's files; `stem` names them (stem.yaml, stem.pgm, stem_filter_info.yaml).
Nav2MaskFiles nav2_mask_files(const ZoneMask& mask, const std::string& stem);

/// A mask of any values in `metadata`'s mode and thresholds (a migrated mask): its files with
/// the filter info given.
Nav2MaskFiles nav2_mask_files(const OccupancyGrid& mask, const MapMetadata& metadata,
                              const Nav2FilterInfo& filter, const std::string& stem);

/// Writes the files into `folder` atomically (the YAML last). Returns the YAML's path.
std::filesystem::path write_nav2_mask_files(const Nav2MaskFiles& files,
                                            const std::filesystem::path& folder);

/// The waypoints as nav2's waypoint follower takes them: `poses:` a YAML list of
/// geometry_msgs/PoseStamped (header.frame_id `frame_id`, position z 0, orientation the
/// quaternion of the heading about z; identity where a waypoint has no heading), i.e. the goal
/// of nav2_msgs/action/FollowWaypoints. Each pose is preceded by a comment with its name,
/// std_m and flag; extrapolated ones are kept and say so.
std::string nav2_waypoints_yaml(const std::vector<MappedWaypoint>& waypoints,
                                const std::string& frame_id = "map");

}  // namespace floorgrid::io
