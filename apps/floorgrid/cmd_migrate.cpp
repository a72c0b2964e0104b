// `floorgrid migrate --model OLD_TO_NEW.json FILES... --out DIR`: waypoints, zones and nav2
// filter masks taught on an old gridmap carried onto a new one (after re-mapping), through a
// model fitted between the two maps (`align` with the old map as the plan).
#include <fmt/format.h>

#include <filesystem>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/evaluation/mask_migration.hpp"
#include "floorgrid/evaluation/waypoint_mapping.hpp"
#include "floorgrid/evaluation/zone_mask.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/formats/map_io.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/formats/nav2_filter_mask.hpp"
#include "floorgrid/io/plans/plan_layers_io.hpp"

namespace floorgrid::app {

namespace {

namespace fs = std::filesystem;

constexpr const char* kHelp = R"(Inputs, by extension (all in the OLD map's frame, metres):
  .csv              waypoints name,x,y[,theta] -> DIR/NAME.csv: name,x,y,theta,std_m,
                    nearest_pair_m,flag,extrapolated in the new map's frame (heading through the
                    model's Jacobian; extrapolated waypoints kept and flagged, never dropped)
  .geojson, .json   zones (Polygon) and waypoints (Point) -> DIR/NAME.geojson in the new map's
                    frame, std_m and extrapolated in each feature's properties
  .dxf              zones on --layer -> DIR/NAME.geojson
  .yaml             a nav2 map or filter mask (map YAML + image) -> DIR/NAME.yaml + image: each
                    cell of the new grid mapped back through the model's inverse into the old
                    mask (nearest cell; cells it cannot map back, or that fall off the old mask,
                    are unknown, which nav2's filters leave alone), the old mode and thresholds
                    kept; a keepout (0/100) mask is widened by --margin-sigma K x std_m. The new
                    grid: --gridmap NEW.yaml's size, resolution and origin (what nav2 needs to
                    overlay the mask on the new map), else the old mask's outline mapped forward
                    at its resolution. NAME_filter_info.yaml beside the input is copied.
The model: `floorgrid align` on a dataset whose floorplan is the OLD map (map YAML) and whose
gridmap is the NEW map (maps-only, no log needed) writes it as model.json. Outputs are written
atomically into DIR and never overwrite an input.)";

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string waypoints_csv(const std::vector<MappedWaypoint>& mapped) {
  std::string out = "name,x,y,theta,std_m,nearest_pair_m,flag,extrapolated\n";
  for (const MappedWaypoint& m : mapped) {
    const Waypoint& w = m.waypoint;
    out += fmt::format("{},{},{},{},{},{:.4f},{},{}\n", w.name,
                       w.position.allFinite() ? fmt::format("{:.4f}", w.position.x()) : "",
                       w.position.allFinite() ? fmt::format("{:.4f}", w.position.y()) : "",
                       w.theta ? fmt::format("{:.6f}", *w.theta) : "",
                       m.std_m ? fmt::format("{:.4f}", *m.std_m) : "", m.nearest_pair_m,
                       to_string(m.flag), m.extrapolated ? 1 : 0);
  }
  return out;
}

/// One output: where it goes and its bytes.
struct Output {
  fs::path path;
  std::string bytes;
};

}  // namespace

void add_migrate_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "migrate",
      "Carry waypoints, zones and nav2 masks from an old gridmap to a new one (after re-mapping) "
      "through a model fitted between the two maps");
  cmd->footer(kHelp);
  struct Args {
    std::string model, gridmap, layer, out;
    std::vector<std::string> files;
    double margin_sigma = MaskMigrationOptions{}.margin_sigma;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--model", args->model,
                  "model from the old map (plan) to the new map (grid): `align` with the old map "
                  "as the floorplan")
      ->required();
  cmd->add_option("files", args->files,
                  "waypoints (.csv, .geojson), zones (.geojson, .dxf) or "
                  "nav2 masks (.yaml) in the old map's frame")
      ->required();
  cmd->add_option("--gridmap", args->gridmap,
                  "the new map's YAML: masks take its size, resolution and origin");
  cmd->add_option("--layer", args->layer, ".dxf zones: the layer (glob) holding them");
  cmd->add_option("--margin-sigma", args->margin_sigma,
                  "keepout masks: widen by K x the model's std_m along the zones' boundary")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--out", args->out, "folder to write into")->required();
  cmd->callback([args] {
    const fs::path out = args->out;
    const auto model = io::read_model(args->model);
    std::optional<GridGeometry> new_grid;
    if (!args->gridmap.empty())
      new_grid = io::read_map_yaml(args->gridmap).grid.geometry();
    // Everything is read and mapped before anything is written: bad input leaves no output.
    std::vector<Output> outputs;
    for (const std::string& file : args->files) {
      const fs::path path = file;
      const std::string ext = lower_extension(path);
      const std::string stem = path.stem().string();
      if (ext == ".csv" || ext == ".geojson" || ext == ".json" || ext == ".dxf") {
        io::PlanLayersReadOptions read;
        read.layer = args->layer;
        const PlanLayers layers = io::read_plan_layers(path, read);
        for (const std::string& w : layers.warnings)
          fmt::print(stderr, "warning: {}\n", w);
        const auto mapped = map_waypoints(*model, layers.waypoints, new_grid, file);
        std::size_t extrapolated = 0;
        for (const MappedWaypoint& m : mapped)
          extrapolated += m.extrapolated;
        if (ext == ".csv") {
          outputs.push_back({out / (stem + ".csv"), waypoints_csv(mapped)});
        } else {
          ZoneMaskOptions options;
          options.margin_sigma = args->margin_sigma;
          const GridGeometry spacing_grid = new_grid.value_or(GridGeometry{0, 0, 0.05, {}});
          const double spacing = zone_sample_spacing(*model, spacing_grid, options);
          std::vector<MappedZone> zones;
          for (const Zone& z : layers.zones)
            zones.push_back(map_zone(*model, z, spacing));
          outputs.push_back(
              {out / (stem + ".geojson"),
               io::mapped_layers_geojson(zones, mapped, "new gridmap", options.margin_sigma)});
        }
        fmt::print("{}: {} waypoints ({} extrapolated, kept and flagged), {} zones\n", file,
                   mapped.size(), extrapolated, layers.zones.size());
        continue;
      }
      if (ext == ".yaml" || ext == ".yml") {
        const io::LoadedMap old = io::read_map_yaml(path);
        const GridGeometry g =
            new_grid ? *new_grid : migrated_geometry(*model, old.grid.geometry());
        MaskMigrationOptions options;
        options.margin_sigma = args->margin_sigma;
        const MigratedMask migrated = migrate_mask(*model, old.grid, g, options);
        for (const std::string& w : migrated.warnings)
          fmt::print(stderr, "warning: {}: {}\n", file, w);
        Nav2FilterInfo filter;
        const fs::path info = path.parent_path() / (stem + "_filter_info.yaml");
        const io::Nav2MaskFiles files =
            io::nav2_mask_files(migrated.mask, old.metadata, filter, stem);
        outputs.push_back({out / files.image_name, files.image});
        if (fs::exists(info))
          outputs.push_back({out / files.params_name, io::read_whole_file(info)});
        outputs.push_back({out / files.yaml_name, files.yaml});
        fmt::print(
            "{}: {} x {} cells at {} m, {} not invertible, {} off the old mask (unknown), "
            "{} cells added by the margin\n",
            file, g.width, g.height, g.resolution, migrated.cells_not_invertible,
            migrated.cells_off_old_mask, migrated.cells_widened);
        continue;
      }
      throw InputError(
          "unknown kind of file: waypoints .csv, zones or waypoints .geojson/.json, "
          "zones .dxf (with --layer), masks .yaml",
          file, 0, "files");
    }
    for (const Output& o : outputs) {
      for (const std::string& input : args->files)
        refuse_overwriting_input(input, o.path.string(), "--out");
      refuse_overwriting_input(args->model, o.path.string(), "--out");
    }
    io::prepare_output_folder(out);
    for (const Output& o : outputs)
      io::write_file_atomically(o.path, o.bytes);
    fmt::print("wrote {} files into {}\n", outputs.size(), out.string());
  });
}

}  // namespace floorgrid::app
