#include "floorgrid/io/dataset/dataset_manifest.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/yaml_fields.hpp"
#include "floorgrid/io/formats/map_io.hpp"

namespace floorgrid::io {

namespace {

const std::vector<std::string> kUnits = {"auto", "m", "cm", "mm", "in", "ft"};

std::filesystem::path resolve(const YamlFields& yaml, const std::string& key,
                              const std::filesystem::path& folder) {
  const std::string text = yaml.string(key);
  if (text.empty())
    yaml.fail(key, "the path is empty");
  const std::filesystem::path p(text);
  const std::filesystem::path full = (p.is_absolute() ? p : folder / p).lexically_normal();
  // With an error code: a name too long for the file system is bad input, not an exception.
  std::error_code ec;
  if (!std::filesystem::exists(full, ec)) {
    yaml.fail(key, "file does not exist: " + full.string() + (ec ? " (" + ec.message() + ")" : ""));
  }
  return full;
}

/// A number in [lo, hi] when given.
std::optional<double> within(const YamlFields& yaml, const std::string& key, double lo, double hi,
                             const char* what) {
  const auto value = yaml.optional_number(key);
  if (value && !(*value >= lo && *value <= hi))
    yaml.fail(key, fmt::format("must be {} from {:g} to {:g} (got {:g})", what, lo, hi, *value));
  return value;
}

/// Metres per pixel of a bare image, within the maps' bounds.
std::optional<double> resolution(const YamlFields& yaml, const std::string& key) {
  return within(yaml, key, kMinResolution, kMaxResolution, "metres per pixel");
}

LaserSettings read_laser(const YamlFields& laser) {
  laser.reject_unknown_keys({"max_range", "min_range", "start_angle", "angle_increment"});
  LaserSettings settings;
  settings.max_range = laser.optional_number("max_range");
  settings.min_range = laser.optional_number("min_range");
  settings.start_angle = laser.optional_number("start_angle");
  settings.angle_increment = laser.optional_number("angle_increment");
  try {
    validate_laser_settings(settings);
  } catch (const InputError& e) {
    // The validator names the field as `laser.<key>`; point at the key's line.
    const std::string key = e.field().substr(e.field().find('.') + 1);
    laser.fail(key, e.message());
  }
  return settings;
}

std::string relative_to(const std::filesystem::path& p, const std::filesystem::path& folder) {
  const std::filesystem::path rel = p.lexically_relative(folder);
  return rel.empty() ? p.string() : rel.string();
}

std::string pose_text(const Pose2& p) {
  return fmt::format("[{}, {}, {}]", p.x, p.y, p.theta);
}

/// Quotes a string for YAML when it could be misread.
std::string yaml_quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\')
      out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string string_list(const std::vector<std::string>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i ? ", " : "") + yaml_quoted(items[i]);
  return out + "]";
}

}  // namespace

const std::vector<std::string>& manifest_keys() {
  static const std::vector<std::string> keys = {
      "floorplan", "floorplan_resolution", "floorplan_origin", "floorplan_units", "floorplan_scale",
      "floorplan_layers", "floorplan_layers_exclude", "gridmap", "gridmap_resolution",
      "gridmap_origin", "log", "log_topics", "log_frames", "initial_pose", "laser",
      "odometry_noise", "truth",
      // the project's own keys
      "name", "odometry_noise_seed"};
  return keys;
}

std::filesystem::path find_manifest(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    const auto candidate = path / "dataset.yaml";
    if (!std::filesystem::exists(candidate, ec)) {
      throw InputError("folder holds no dataset.yaml", path.string());
    }
    return candidate;
  }
  if (!std::filesystem::exists(path, ec))
    throw InputError("no such file or folder", path.string());
  return path;
}

DatasetManifest read_manifest(const std::filesystem::path& path) {
  DatasetManifest m;
  m.manifest_path = find_manifest(path);
  const YamlFields yaml(m.manifest_path);
  yaml.reject_unknown_keys(manifest_keys());
  const std::filesystem::path folder = m.manifest_path.parent_path();

  m.name = yaml.optional_string("name").value_or("");
  m.floorplan = resolve(yaml, "floorplan", folder);
  m.floorplan_resolution = resolution(yaml, "floorplan_resolution");
  m.floorplan_origin = yaml.optional_pose("floorplan_origin");
  m.floorplan_units = yaml.optional_string("floorplan_units").value_or("auto");
  if (std::find(kUnits.begin(), kUnits.end(), m.floorplan_units) == kUnits.end()) {
    yaml.fail("floorplan_units",
              "expected auto, m, cm, mm, in or ft (got '" + m.floorplan_units + "')");
  }
  if (yaml.has("floorplan_scale")) {
    const auto text = yaml.optional_string("floorplan_scale");
    if (text && *text == "auto") {
      m.floorplan_scale.reset();
    } else {
      m.floorplan_scale =
          within(yaml, "floorplan_scale", 1e-4, 1e4, "a scale (world metres per plan metre)");
    }
  }
  m.floorplan_layers =
      yaml.optional_strings("floorplan_layers").value_or(std::vector<std::string>{});
  m.floorplan_layers_exclude =
      yaml.optional_strings("floorplan_layers_exclude").value_or(std::vector<std::string>{});
  m.gridmap = resolve(yaml, "gridmap", folder);
  m.gridmap_resolution = resolution(yaml, "gridmap_resolution");
  m.gridmap_origin = yaml.optional_pose("gridmap_origin");
  if (yaml.has("log"))
    m.log = resolve(yaml, "log", folder);
  if (const auto topics = yaml.optional_map("log_topics")) {
    topics->reject_unknown_keys({"scan", "odom"});
    m.log_scan_topic = topics->optional_string("scan");
    m.log_odom_topic = topics->optional_string("odom");
  }
  if (const auto frames = yaml.optional_map("log_frames")) {
    frames->reject_unknown_keys({"base", "odom"});
    m.log_base_frame = frames->optional_string("base");
    m.log_odom_frame = frames->optional_string("odom");
  }

  if (const auto initial = yaml.optional_map("initial_pose")) {
    initial->reject_unknown_keys({"plan", "grid"});
    const auto plan = initial->optional_pose("plan");
    const auto grid = initial->optional_pose("grid");
    if (!plan)
      initial->fail("plan", "required key is missing (expected [x, y, theta])");
    if (!grid)
      initial->fail("grid", "required key is missing (expected [x, y, theta])");
    m.initial_pose = InitialPoses{*plan, *grid};
  }
  if (const auto laser = yaml.optional_map("laser"))
    m.laser = read_laser(*laser);
  if (const auto noise = yaml.optional_numbers("odometry_noise", 4)) {
    std::array<double, 4> alpha{};
    for (std::size_t i = 0; i < 4; ++i) {
      if ((*noise)[i] < 0.0)
        yaml.fail("odometry_noise", "alpha values must be >= 0");
      alpha[i] = (*noise)[i];
    }
    m.odometry_noise = alpha;
  }
  if (const auto seed = yaml.optional_number("odometry_noise_seed")) {
    if (*seed < 0.0 || *seed != static_cast<double>(static_cast<std::uint64_t>(*seed))) {
      yaml.fail("odometry_noise_seed", "must be a whole number >= 0");
    }
    m.odometry_noise_seed = static_cast<std::uint64_t>(*seed);
  }
  if (const auto truth = yaml.optional_map("truth")) {
    truth->reject_unknown_keys({"manual_pairs", "warp"});
    if (truth->has("manual_pairs"))
      m.truth.manual_pairs = resolve(*truth, "manual_pairs", folder);
    if (truth->has("warp"))
      m.truth.warp = resolve(*truth, "warp", folder);
  }
  return m;
}

void write_manifest(const DatasetManifest& m) {
  const std::filesystem::path folder = m.manifest_path.parent_path();
  std::string out = "# floorgrid dataset manifest\n";
  if (!m.name.empty())
    out += "name: " + yaml_quoted(m.name) + "\n";
  out += "floorplan: " + yaml_quoted(relative_to(m.floorplan, folder)) + "\n";
  if (m.floorplan_resolution)
    out += fmt::format("floorplan_resolution: {}\n", *m.floorplan_resolution);
  if (m.floorplan_origin)
    out += "floorplan_origin: " + pose_text(*m.floorplan_origin) + "\n";
  out += "floorplan_units: " + m.floorplan_units + "\n";
  out += m.floorplan_scale ? fmt::format("floorplan_scale: {}\n", *m.floorplan_scale)
                           : std::string("floorplan_scale: auto\n");
  if (!m.floorplan_layers.empty())
    out += "floorplan_layers: " + string_list(m.floorplan_layers) + "\n";
  if (!m.floorplan_layers_exclude.empty()) {
    out += "floorplan_layers_exclude: " + string_list(m.floorplan_layers_exclude) + "\n";
  }
  out += "gridmap: " + yaml_quoted(relative_to(m.gridmap, folder)) + "\n";
  if (m.gridmap_resolution)
    out += fmt::format("gridmap_resolution: {}\n", *m.gridmap_resolution);
  if (m.gridmap_origin)
    out += "gridmap_origin: " + pose_text(*m.gridmap_origin) + "\n";
  if (m.log)
    out += "log: " + yaml_quoted(relative_to(*m.log, folder)) + "\n";
  const auto map_line = [&](const char* key, const char* a, const std::optional<std::string>& va,
                            const char* b, const std::optional<std::string>& vb) {
    if (!va && !vb)
      return;
    out += fmt::format("{}: {{", key);
    if (va)
      out += fmt::format("{}: {}", a, yaml_quoted(*va));
    if (vb)
      out += fmt::format("{}{}: {}", va ? ", " : "", b, yaml_quoted(*vb));
    out += "}\n";
  };
  map_line("log_topics", "scan", m.log_scan_topic, "odom", m.log_odom_topic);
  map_line("log_frames", "base", m.log_base_frame, "odom", m.log_odom_frame);
  if (m.initial_pose) {
    out += "initial_pose:\n  plan: " + pose_text(m.initial_pose->plan) +
           "\n  grid: " + pose_text(m.initial_pose->grid) + "\n";
  }
  std::vector<std::string> laser;
  if (m.laser.max_range)
    laser.push_back(fmt::format("max_range: {}", *m.laser.max_range));
  if (m.laser.min_range)
    laser.push_back(fmt::format("min_range: {}", *m.laser.min_range));
  if (m.laser.start_angle)
    laser.push_back(fmt::format("start_angle: {}", *m.laser.start_angle));
  if (m.laser.angle_increment) {
    laser.push_back(fmt::format("angle_increment: {}", *m.laser.angle_increment));
  }
  if (!laser.empty()) {
    out += "laser: {";
    for (std::size_t i = 0; i < laser.size(); ++i)
      out += (i ? ", " : "") + laser[i];
    out += "}\n";
  }
  if (m.odometry_noise) {
    const auto& a = *m.odometry_noise;
    out += fmt::format("odometry_noise: [{}, {}, {}, {}]\nodometry_noise_seed: {}\n", a[0], a[1],
                       a[2], a[3], m.odometry_noise_seed);
  }
  if (m.truth.manual_pairs || m.truth.warp) {
    out += "truth:\n";
    if (m.truth.manual_pairs) {
      out += "  manual_pairs: " + yaml_quoted(relative_to(*m.truth.manual_pairs, folder)) + "\n";
    }
    if (m.truth.warp)
      out += "  warp: " + yaml_quoted(relative_to(*m.truth.warp, folder)) + "\n";
  }
  write_file_atomically(m.manifest_path, out);
}

}  // namespace floorgrid::io
