#include "floorgrid/io/formats/nav2_filter_mask.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/image_io.hpp"

namespace floorgrid::io {

namespace {

/// nav2_map_server's map_io (loadMapFromFile) on one opaque grey pixel, negate 0: occ = 1 -
/// pixel / 255; trinary: 100 above occupied_thresh, 0 below free_thresh, else -1; scale: the
/// same outside the thresholds and rint((occ - free) / (occupied - free) x 100) between; raw:
/// the pixel itself when 0..100, else -1.
int nav2_decode(int pixel, const MapMetadata& m) {
  const double shade = pixel / 255.0;
  const double occ = m.negate ? shade : 1.0 - shade;
  switch (m.mode) {
    case MapMode::trinary:
      return m.occupied_thresh < occ ? 100 : (occ < m.free_thresh ? 0 : -1);
    case MapMode::scale:
      if (m.occupied_thresh < occ)
        return 100;
      if (occ < m.free_thresh)
        return 0;
      return static_cast<int>(
          std::rint((occ - m.free_thresh) / (m.occupied_thresh - m.free_thresh) * 100.0));
    case MapMode::raw: {
      const double percent = std::round(shade * 255.0);
      return percent >= 0.0 && percent <= 100.0 ? static_cast<int>(percent) : -1;
    }
  }
  return -1;
}

std::string pgm_bytes(int width, int height, const std::vector<std::uint8_t>& pixels) {
  std::string out = fmt::format("P5\n{} {}\n255\n", width, height);
  out.append(reinterpret_cast<const char*>(pixels.data()), pixels.size());
  return out;
}

std::string topic_of(const std::string& stem) {
  return "/" + stem;
}

std::string params_yaml(const Nav2FilterInfo& filter, const std::string& stem,
                        const std::string& yaml_name) {
  const char* kind = filter.type == 0 ? "keepout zones (KeepoutFilter)"
                     : filter.type == 1
                         ? "speed limits in percent of the maximal speed (SpeedFilter)"
                         : "speed limits in m/s (SpeedFilter)";
  return fmt::format(
      "# nav2 costmap filter: {}. Written by floorgrid.\n"
      "# Run nav2_map_server's map_server as filter_mask_server (publishes the mask) and its\n"
      "# costmap_filter_info_server (publishes this info) with these parameters; the filter "
      "plugin\n"
      "# in the costmap reads filter_info_topic. filter value = base + multiplier * mask value\n"
      "# (nav2_msgs/msg/CostmapFilterInfo); type 0 keepout, 1 speed %, 2 speed m/s.\n"
      "costmap_filter_info_server:\n"
      "  ros__parameters:\n"
      "    type: {}\n"
      "    filter_info_topic: \"/costmap_filter_info\"\n"
      "    mask_topic: \"{}\"\n"
      "    base: {:.6g}\n"
      "    multiplier: {:.6g}\n"
      "filter_mask_server:\n"
      "  ros__parameters:\n"
      "    frame_id: \"map\"\n"
      "    topic_name: \"{}\"\n"
      "    yaml_filename: \"{}\"\n",
      kind, filter.type, topic_of(stem), filter.base, filter.multiplier, topic_of(stem), yaml_name);
}

}  // namespace

MapMetadata nav2_mask_metadata(ZoneMaskKind kind, const GridGeometry& geometry) {
  MapMetadata m;
  m.resolution = geometry.resolution;
  m.origin = geometry.origin;
  m.negate = false;
  if (kind == ZoneMaskKind::keepout) {
    // "Navigating with Keepout Zones": the mask is a copy of the map's YAML (turtlebot3_world:
    // trinary, 0.65 / 0.196) with the zones painted black.
    m.mode = MapMode::trinary;
    m.occupied_thresh = 0.65;
    m.free_thresh = 0.196;
  } else {
    // "Navigating with Speed Limits": scale mode "with no thresholds", free 0.0, occupied 1.0.
    m.mode = MapMode::scale;
    m.occupied_thresh = 1.0;
    m.free_thresh = 0.0;
  }
  return m;
}

std::uint8_t nav2_mask_pixel(std::int8_t value, const MapMetadata& metadata) {
  // The pixels that decode to the value; the middle one is the farthest from a rounding edge.
  // The conventional ones first: 254 free and 0 occupied (map_saver's), 205 unknown.
  const int wanted = value < 0 ? -1 : value;
  for (const int conventional : {254, 0, 205}) {
    if (metadata.mode == MapMode::trinary && nav2_decode(conventional, metadata) == wanted)
      return static_cast<std::uint8_t>(conventional);
  }
  int first = -1, last = -1;
  for (int p = 0; p < 256; ++p) {
    if (nav2_decode(p, metadata) == wanted) {
      if (first < 0)
        first = p;
      last = p;
    }
  }
  if (first < 0) {
    throw InputError(fmt::format("no 8-bit pixel reads as OccupancyGrid value {} in mode {} with "
                                 "free_thresh {} and occupied_thresh {}",
                                 static_cast<int>(value), to_string(metadata.mode),
                                 metadata.free_thresh, metadata.occupied_thresh),
                     {}, 0, "mode");
  }
  return static_cast<std::uint8_t>((first + last) / 2);
}

Nav2MaskFiles nav2_mask_files(const OccupancyGrid& mask, const MapMetadata& metadata,
                              const Nav2FilterInfo& filter, const std::string& stem) {
  Nav2MaskFiles files;
  const GridGeometry& g = mask.geometry();
  bool unknown = false;
  for (const std::int8_t v : mask.values())
    unknown = unknown || v < 0;
  const bool with_alpha = metadata.mode == MapMode::scale && unknown;
  // value + 1 -> pixel, found on first use (a value the mask lacks need not be writable).
  std::array<int, 102> table;
  table.fill(-1);
  const auto pixel_of = [&](int v) {
    int& p = table[static_cast<std::size_t>(v + 1)];
    if (p < 0)
      p = nav2_mask_pixel(static_cast<std::int8_t>(v), metadata);
    return static_cast<std::uint8_t>(p);
  };
  std::vector<std::uint8_t> grey(g.size()), alpha(with_alpha ? g.size() : 0, 255);
  for (int iy = 0; iy < g.height; ++iy) {
    for (int ix = 0; ix < g.width; ++ix) {
      const std::size_t i = static_cast<std::size_t>(g.image_row(iy)) * g.width + ix;
      int v = mask.value(ix, iy);
      if (metadata.mode == MapMode::trinary && v > 0 && v < 100)
        v = v > metadata.occupied_thresh * 100 ? 100 : (v < metadata.free_thresh * 100 ? 0 : -1);
      if (v < 0 && with_alpha) {
        grey[i] = 255;
        alpha[i] = 0;
        continue;
      }
      grey[i] = pixel_of(v);
    }
  }
  if (with_alpha) {
    std::vector<std::uint8_t> pixels(g.size() * 2);
    for (std::size_t i = 0; i < g.size(); ++i) {
      pixels[2 * i] = grey[i];
      pixels[2 * i + 1] = alpha[i];
    }
    files.image_name = stem + ".png";
    files.image = encode_png(g.width, g.height, 2, pixels);
  } else {
    files.image_name = stem + ".pgm";
    files.image = pgm_bytes(g.width, g.height, grey);
  }
  files.yaml = fmt::format(
      "image: {}\nmode: {}\nresolution: {}\norigin: [{}, {}, {}]\nnegate: 0\n"
      "occupied_thresh: {}\nfree_thresh: {}\n",
      files.image_name, to_string(metadata.mode), g.resolution, g.origin.x, g.origin.y,
      g.origin.theta, metadata.occupied_thresh, metadata.free_thresh);
  files.yaml_name = stem + ".yaml";
  files.params_name = stem + "_filter_info.yaml";
  files.params_yaml = params_yaml(filter, stem, stem + ".yaml");
  return files;
}

Nav2MaskFiles nav2_mask_files(const ZoneMask& mask, const std::string& stem) {
  return nav2_mask_files(mask.mask, nav2_mask_metadata(mask.kind, mask.mask.geometry()),
                         mask.filter, stem);
}

std::filesystem::path write_nav2_mask_files(const Nav2MaskFiles& files,
                                            const std::filesystem::path& folder) {
  write_file_atomically(folder / files.image_name, files.image);
  write_file_atomically(folder / files.params_name, files.params_yaml);
  const std::filesystem::path yaml = folder / files.yaml_name;
  write_file_atomically(yaml, files.yaml);
  return yaml;
}

std::string nav2_waypoints_yaml(const std::vector<MappedWaypoint>& waypoints,
                                const std::string& frame_id) {
  std::string out =
      "# nav2 waypoint follower: the goal of nav2_msgs/action/FollowWaypoints, `poses` a list of\n"
      "# geometry_msgs/PoseStamped in the map frame (ros2 action send_goal /follow_waypoints\n"
      "# nav2_msgs/action/FollowWaypoints \"$(cat THIS_FILE)\"). Written by floorgrid; each pose\n"
      "# is preceded by its name, std_m (metres) and flag; extrapolated ones are kept, check "
      "them.\n"
      "poses:\n";
  if (waypoints.empty())
    return out.substr(0, out.size() - 1) + " []\n";
  for (const MappedWaypoint& m : waypoints) {
    const Waypoint& w = m.waypoint;
    out += fmt::format("  # {}: std_m {}, flag {}{}{}\n", w.name,
                       m.std_m ? fmt::format("{:.3f}", *m.std_m) : "none", to_string(m.flag),
                       m.extrapolated ? ", EXTRAPOLATED" : "",
                       w.theta ? "" : ", no heading given (identity orientation)");
    const double theta = w.theta.value_or(0.0);
    if (!w.position.allFinite()) {
      out += "  # (not mapped: the model gives no position here)\n";
      continue;
    }
    const bool finite = true;
    out += fmt::format(
        "  - header: {{frame_id: \"{}\"}}\n"
        "    pose:\n"
        "      position: {{x: {}, y: {}, z: 0.0}}\n"
        "      orientation: {{x: 0.0, y: 0.0, z: {:.9f}, w: {:.9f}}}\n",
        frame_id, finite ? fmt::format("{:.4f}", w.position.x()) : ".nan",
        finite ? fmt::format("{:.4f}", w.position.y()) : ".nan", std::sin(theta / 2),
        std::cos(theta / 2));
  }
  return out;
}

}  // namespace floorgrid::io
