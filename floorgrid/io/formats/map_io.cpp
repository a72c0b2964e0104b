#include "floorgrid/io/formats/map_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/geometry/reference_pairs.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/yaml_fields.hpp"

namespace floorgrid::io {

std::string to_string(MapMode mode) {
  switch (mode) {
    case MapMode::scale:
      return "scale";
    case MapMode::raw:
      return "raw";
    case MapMode::trinary:
      break;
  }
  return "trinary";
}

namespace {

const std::vector<std::string> kMapKeys = {"image",           "resolution",  "origin", "negate",
                                           "occupied_thresh", "free_thresh", "mode"};

/// Checks the values any map needs, naming the field.
void validate_metadata(const MapMetadata& m, const std::string& file) {
  if (!(m.resolution >= kMinResolution && m.resolution <= kMaxResolution)) {
    throw InputError(fmt::format("must be {:g} to {:g} metres per pixel (got {:g})", kMinResolution,
                                 kMaxResolution, m.resolution),
                     file, 0, "resolution");
  }
  if (!(std::abs(m.origin.x) <= kMaxCoordinate && std::abs(m.origin.y) <= kMaxCoordinate &&
        std::isfinite(m.origin.theta))) {
    throw InputError(fmt::format("[{:g}, {:g}, {:g}] is not a physical pose (metres within "
                                 "{:g} of 0, a finite yaw)",
                                 m.origin.x, m.origin.y, m.origin.theta, kMaxCoordinate),
                     file, 0, "origin");
  }
  if (!(m.occupied_thresh >= 0.0 && m.occupied_thresh <= 1.0)) {
    throw InputError(fmt::format("must lie in [0, 1] (got {})", m.occupied_thresh), file, 0,
                     "occupied_thresh");
  }
  if (!(m.free_thresh >= 0.0 && m.free_thresh <= 1.0)) {
    throw InputError(fmt::format("must lie in [0, 1] (got {})", m.free_thresh), file, 0,
                     "free_thresh");
  }
  if (!(m.free_thresh < m.occupied_thresh)) {
    throw InputError(
        fmt::format("must be below occupied_thresh ({} >= {})", m.free_thresh, m.occupied_thresh),
        file, 0, "free_thresh");
  }
}

MapMode parse_mode(const YamlFields& yaml) {
  const auto text = yaml.optional_string("mode");
  if (!text || *text == "trinary")
    return MapMode::trinary;
  if (*text == "scale")
    return MapMode::scale;
  if (*text == "raw")
    return MapMode::raw;
  yaml.fail("mode", "expected trinary, scale or raw (got '" + *text + "')");
}

/// Class of a ROS value in scale or raw mode, where values between 0 and 100 are kept.
CellState class_of_value(std::int8_t value, const MapMetadata& m) {
  if (value < 0)
    return CellState::unknown;
  const double p = value / 100.0;
  if (p > m.occupied_thresh)
    return CellState::occupied;
  if (p < m.free_thresh)
    return CellState::free;
  return CellState::unknown;
}

bool is_bare_image(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext == ".pgm" || ext == ".png";
}

}  // namespace

OccupancyGrid image_to_grid(const GreyImage& image, const MapMetadata& m) {
  GridGeometry geometry{image.width, image.height, m.resolution, m.origin};
  OccupancyGrid grid(geometry, CellState::unknown);
  for (int row = 0; row < image.height; ++row) {
    const int iy = geometry.image_row(row);  // rows count from the top, cells from the bottom
    for (int col = 0; col < image.width; ++col) {
      const std::size_t i = static_cast<std::size_t>(row) * image.width + col;
      const double shade = image.shade(i);
      const double occ = m.negate ? shade : 1.0 - shade;
      switch (m.mode) {
        case MapMode::trinary: {
          // Deliberately unlike nav2: alpha is not blended in; a fully transparent pixel is
          // unknown.
          if (image.has_alpha() && image.alpha[i] == 0)
            break;
          if (occ > m.occupied_thresh) {
            grid.set_state(col, iy, CellState::occupied);
          } else if (occ < m.free_thresh) {
            grid.set_state(col, iy, CellState::free);
          }
          break;
        }
        case MapMode::scale: {
          if (image.has_alpha() && image.alpha[i] != 255)
            break;  // nav2: any transparency
          if (occ > m.occupied_thresh) {
            grid.set_state(col, iy, CellState::occupied);
          } else if (occ < m.free_thresh) {
            grid.set_state(col, iy, CellState::free);
          } else {
            const auto value = static_cast<std::int8_t>(
                std::rint((occ - m.free_thresh) / (m.occupied_thresh - m.free_thresh) * 100.0));
            grid.set_cell(col, iy, CellState::unknown, value);
          }
          break;
        }
        case MapMode::raw: {
          if (image.has_alpha() && image.alpha[i] == 0)
            break;
          const double percent = std::round(shade * 255.0);  // nav2: negate does not apply
          if (percent >= 0.0 && percent <= 100.0) {
            const auto value = static_cast<std::int8_t>(percent);
            grid.set_cell(col, iy, class_of_value(value, m), value);
          }
          break;
        }
      }
    }
  }
  return grid;
}

std::vector<std::uint8_t> grid_to_image(const OccupancyGrid& grid, const MapMetadata& m,
                                        std::vector<std::uint8_t>* alpha) {
  const int width = grid.width();
  const int height = grid.height();
  std::vector<std::uint8_t> pixels(grid.geometry().size());
  if (alpha != nullptr)
    alpha->clear();
  if (m.mode == MapMode::scale && alpha != nullptr)
    alpha->assign(pixels.size(), 255);
  // 205 is the conventional unknown grey; keep it only when it reads back as unknown.
  const double occ_205 = (255.0 - 205.0) / 255.0;
  const std::uint8_t unknown_grey =
      occ_205 >= m.free_thresh && occ_205 <= m.occupied_thresh
          ? 205
          : static_cast<std::uint8_t>(
                std::lround(255.0 * (1.0 - 0.5 * (m.free_thresh + m.occupied_thresh))));
  for (int iy = 0; iy < height; ++iy) {
    for (int ix = 0; ix < width; ++ix) {
      const std::size_t i = static_cast<std::size_t>(grid.geometry().image_row(iy)) * width + ix;
      const std::int8_t value = grid.value(ix, iy);
      switch (m.mode) {
        case MapMode::trinary: {
          const CellState s = grid.state(ix, iy);
          pixels[i] = s == CellState::free ? 254 : s == CellState::occupied ? 0 : unknown_grey;
          break;
        }
        case MapMode::scale:
          if (value < 0) {
            pixels[i] = 127;
            if (alpha != nullptr)
              (*alpha)[i] = 0;
          } else {
            pixels[i] = static_cast<std::uint8_t>(std::lround((100.0 - value) / 100.0 * 255.0));
          }
          break;
        case MapMode::raw:
          pixels[i] = value < 0 ? 255 : static_cast<std::uint8_t>(value);
          break;
      }
    }
  }
  if (m.negate && m.mode != MapMode::raw) {
    for (auto& p : pixels)
      p = static_cast<std::uint8_t>(255 - p);
  }
  return pixels;
}

LoadedMap read_map_yaml(const std::filesystem::path& yaml_path) {
  const YamlFields yaml(yaml_path);
  const std::string file = yaml_path.string();
  LoadedMap map;
  map.yaml_path = yaml_path;
  for (const auto& [key, line] : yaml.unknown_keys(kMapKeys)) {
    map.warnings.push_back(fmt::format("{}:{}: unknown key '{}' ignored", file, line, key));
  }
  MapMetadata& m = map.metadata;
  m.image = yaml.string("image");
  if (m.image.empty())
    yaml.fail("image", "the image path is empty");
  m.resolution = yaml.number("resolution");
  const auto origin = yaml.optional_pose("origin");
  if (!origin)
    yaml.fail("origin", "required key is missing (expected [x, y, yaw])");
  m.origin = *origin;
  m.negate = yaml.optional_bool("negate").value_or(false);
  if (!yaml.has("occupied_thresh"))
    yaml.fail("occupied_thresh", "required key is missing");
  if (!yaml.has("free_thresh"))
    yaml.fail("free_thresh", "required key is missing");
  m.occupied_thresh = yaml.number("occupied_thresh");
  m.free_thresh = yaml.number("free_thresh");
  m.mode = parse_mode(yaml);
  try {
    validate_metadata(m, file);
  } catch (const InputError& e) {
    yaml.fail(e.field(), e.message());
  }
  map.image_path = m.image.is_absolute() ? m.image : yaml_path.parent_path() / m.image;
  std::error_code ec;
  if (!std::filesystem::exists(map.image_path, ec)) {
    yaml.fail("image", "image file does not exist: " + map.image_path.string() +
                           (ec ? " (" + ec.message() + ")" : ""));
  }
  const GreyImage image = read_grey_image(map.image_path);
  map.image_description = image.description;
  map.grid = image_to_grid(image, m);
  return map;
}

LoadedMap read_map_image(const std::filesystem::path& image_path, const MapMetadata& settings) {
  validate_metadata(settings, image_path.string());
  LoadedMap map;
  map.metadata = settings;
  map.metadata.image = image_path.filename();
  map.image_path = image_path;
  const GreyImage image = read_grey_image(image_path);
  map.image_description = image.description;
  map.grid = image_to_grid(image, map.metadata);
  return map;
}

LoadedMap read_map(const std::filesystem::path& path, std::optional<double> resolution,
                   std::optional<Pose2> origin, const std::string& what) {
  if (!is_bare_image(path))
    return read_map_yaml(path);
  if (!resolution) {
    throw InputError("a bare image needs a resolution (metres per pixel)", path.string(), 0,
                     what + "_resolution");
  }
  MapMetadata settings;
  settings.resolution = *resolution;
  settings.origin = origin.value_or(Pose2{});
  return read_map_image(path, settings);
}

std::filesystem::path write_map(const OccupancyGrid& grid, const std::filesystem::path& yaml_path,
                                const MapWriteOptions& options) {
  MapMetadata m;
  m.mode = options.mode;
  m.resolution = grid.resolution();
  m.origin = grid.geometry().origin;
  m.occupied_thresh = options.occupied_thresh;
  m.free_thresh = options.free_thresh;
  validate_metadata(m, yaml_path.string());
  std::string format = options.image_format;
  if (format.empty())
    format = options.mode == MapMode::scale ? "png" : "pgm";
  if (format != "pgm" && format != "png") {
    throw InputError("image format must be pgm or png (got '" + format + "')", yaml_path.string(),
                     0, "image_format");
  }
  if (format == "pgm" && options.mode == MapMode::scale) {
    throw InputError("scale mode needs transparency: write png", yaml_path.string(), 0,
                     "image_format");
  }
  std::filesystem::path image_path = yaml_path;
  image_path.replace_extension(format);
  std::vector<std::uint8_t> alpha;
  const auto pixels = grid_to_image(grid, m, &alpha);
  if (format == "pgm") {
    write_pgm(image_path, grid.width(), grid.height(), pixels);
  } else {
    write_png(image_path, grid.width(), grid.height(), pixels, alpha);
  }
  const std::string yaml = fmt::format(
      "image: {}\nmode: {}\nresolution: {}\norigin: [{}, {}, {}]\nnegate: 0\n"
      "occupied_thresh: {}\nfree_thresh: {}\n",
      image_path.filename().string(), to_string(m.mode), m.resolution, m.origin.x, m.origin.y,
      m.origin.theta, m.occupied_thresh, m.free_thresh);
  write_file_atomically(yaml_path, yaml);
  return image_path;
}

}  // namespace floorgrid::io
