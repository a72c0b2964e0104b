#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/maps/occupancy_grid.hpp"

namespace floorgrid::io {

/// How image values become occupancy, as nav2's map_io defines the modes.
enum class MapMode { trinary, scale, raw };

/// The mode's name as written in a map YAML.
std::string to_string(MapMode mode);

/// Metres per pixel a map may have: a tenth of a millimetre (a scanned drawing) to 100 m.
inline constexpr double kMinResolution = 1e-4;
inline constexpr double kMaxResolution = 100.0;

/// A map YAML's fields (ROS map_server), or the settings given for a bare image.
struct MapMetadata {
  std::filesystem::path image;      ///< image path as written (relative to the YAML's folder)
  double resolution = 0.05;         ///< metres per pixel
  Pose2 origin;                     ///< outer corner of the lower-left pixel, metres, and yaw
  bool negate = false;              ///< white is occupied when true
  double occupied_thresh = 0.65;    ///< occupancy above this is occupied
  double free_thresh = 0.196;       ///< occupancy below this is free
  MapMode mode = MapMode::trinary;  ///< trinary, scale or raw
};

/// A map read from disk: the grid and where it came from.
/// A map image on disk and where it lies in its frame (the map YAML's resolution, origin and
/// the image's size), uncropped: what the exports refer to.
struct MapRaster {
  std::filesystem::path image;  ///< the image file (PGM or PNG)
  GridGeometry geometry;        ///< width x height pixels, resolution and origin of the YAML
};

struct LoadedMap {
  OccupancyGrid grid;                 ///< cells, frame from the metadata
  MapMetadata metadata;               ///< the YAML's fields (or the bare image's settings)
  std::filesystem::path yaml_path;    ///< empty for a bare image
  std::filesystem::path image_path;   ///< the image file actually read
  std::string image_description;      ///< e.g. "PNG 8-bit grey"
  std::vector<std::string> warnings;  ///< non-fatal oddities (unknown YAML keys, ...)
};

/// Reads a ROS map_server map: YAML (every field) plus its PGM or PNG image.
/// Throws InputError naming the file, line and field on bad input.
LoadedMap read_map_yaml(const std::filesystem::path& yaml_path);

/// Reads a bare PGM/PNG image as a map, with resolution and origin given by the caller
/// (the manifest or the command line) and the other fields from `settings`.
LoadedMap read_map_image(const std::filesystem::path& image_path, const MapMetadata& settings);

/// Reads a map YAML, or a bare image when `path` ends in .pgm/.png (then `resolution` and `origin`
/// are required and a missing one is an InputError naming `what`).
LoadedMap read_map(const std::filesystem::path& path, std::optional<double> resolution,
                   std::optional<Pose2> origin, const std::string& what = "map");

/// Applies the metadata's mode to an image (rows from the top) and returns the grid.
OccupancyGrid image_to_grid(const GreyImage& image, const MapMetadata& metadata);

/// Encodes a grid as 8-bit image bytes (top row first) in the metadata's mode, as nav2's
/// map_saver does: trinary 0 / 254 / 205 (unknown falls back to the middle grey of the thresholds
/// when 205 would not read back as unknown), scale (100 - value) / 100 with transparent unknowns,
/// raw the value itself with 255 for unknown. `alpha` is filled in scale mode only.
std::vector<std::uint8_t> grid_to_image(const OccupancyGrid& grid, const MapMetadata& metadata,
                                        std::vector<std::uint8_t>* alpha);

/// How to write a map.
struct MapWriteOptions {
  MapMode mode = MapMode::trinary;  ///< the YAML's mode
  std::string image_format;         ///< "pgm" or "png"; empty: png for scale, pgm otherwise
  double occupied_thresh = 0.65;    ///< written to the YAML
  double free_thresh = 0.196;       ///< written to the YAML
};

/// Writes `grid` as a map YAML at `yaml_path` plus an image beside it with the same stem.
/// Both files are written atomically. Returns the image path.
std::filesystem::path write_map(const OccupancyGrid& grid, const std::filesystem::path& yaml_path,
                                const MapWriteOptions& options = {});

}  // namespace floorgrid::io
