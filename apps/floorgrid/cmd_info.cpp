// `floorgrid info PATH [--json] [--resolution R --origin x,y,yaw]`: what a map, plan, log,
// pairs file or dataset holds.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/floorgrid/cli_util.hpp"
#include "apps/floorgrid/commands.hpp"
#include "floorgrid/io/dataset/describe.hpp"

namespace floorgrid::app {

namespace {

using nlohmann::json;

std::string bounds_text(const json& box) {
  if (box.is_null())
    return "(empty)";
  return fmt::format("x {:.3f} .. {:.3f} m, y {:.3f} .. {:.3f} m  ({:.2f} x {:.2f} m)",
                     box["min"][0].get<double>(), box["max"][0].get<double>(),
                     box["min"][1].get<double>(), box["max"][1].get<double>(),
                     box["size"][0].get<double>(), box["size"][1].get<double>());
}

std::string counts_text(const json& counts) {
  std::string out;
  for (const auto& [key, value] : counts.items()) {
    if (!out.empty())
      out += ", ";
    out += fmt::format("{} {}", key, value.dump());
  }
  return out.empty() ? "none" : out;
}

void print_warnings(const json& j, const std::string& indent) {
  if (!j.contains("warnings"))
    return;
  for (const auto& w : j["warnings"])
    fmt::print("{}warning: {}\n", indent, w.get<std::string>());
}

void print_map(const json& j, const std::string& indent) {
  fmt::print("{}image       {} ({})\n", indent, j["image"].get<std::string>(),
             j["image_format"].get<std::string>());
  if (j.contains("resolution_m")) {
    fmt::print("{}size        {} x {} cells at {} m\n", indent, j["width"].get<int>(),
               j["height"].get<int>(), j["resolution_m"].get<double>());
    fmt::print("{}origin      ({}, {}), yaw {} rad\n", indent, j["origin"][0].get<double>(),
               j["origin"][1].get<double>(), j["origin"][2].get<double>());
    fmt::print("{}bounds      {}\n", indent, bounds_text(j["bounds_m"]));
  } else {
    fmt::print("{}size        {} x {} pixels (resolution unknown)\n", indent, j["width"].get<int>(),
               j["height"].get<int>());
  }
  fmt::print("{}cells       occupied {}, free {}, unknown {}\n", indent,
             j["cells"]["occupied"].get<std::size_t>(), j["cells"]["free"].get<std::size_t>(),
             j["cells"]["unknown"].get<std::size_t>());
  fmt::print("{}rule        mode {}, occupied > {}, free < {}, negate {}\n", indent,
             j["mode"].get<std::string>(), j["occupied_thresh"].get<double>(),
             j["free_thresh"].get<double>(), j["negate"].get<bool>() ? 1 : 0);
  print_warnings(j, indent);
}

/// Where a DXF's units came from, in words.
std::string source_text(const json& j) {
  const std::string source = j["units_source"].get<std::string>();
  if (source == "header")
    return "from $INSUNITS, checked against the drawing";
  if (source == "header_overruled")
    return "from the drawing, overruling $INSUNITS";
  if (source == "guessed")
    return "guessed from the drawing (no usable $INSUNITS)";
  return "requested explicitly";
}

void print_dxf(const json& j, const std::string& indent) {
  fmt::print("{}version     {}\n", indent, j["version"].get<std::string>());
  fmt::print("{}units       {} ({} m per unit; header says {})\n", indent,
             j["units_used"].get<std::string>(), j["metres_per_unit"].get<double>(),
             j["header_units"].get<std::string>());
  fmt::print("{}            {}, confidence {}\n", indent, source_text(j),
             j["units_confidence"].get<std::string>());
  fmt::print("{}            {}\n", indent, j["units_reason"].get<std::string>());
  for (const auto& line : j["units_evidence"]) {
    fmt::print("{}  evidence  {}\n", indent, line.get<std::string>());
  }
  std::string candidates;
  for (const auto& c : j["unit_candidates"]) {
    candidates += fmt::format("{}{} {:.3g}% (score {:.1f})", candidates.empty() ? "" : ", ",
                              c["unit"].get<std::string>(), 100.0 * c["probability"].get<double>(),
                              c["score"].get<double>());
  }
  fmt::print("{}candidates  {}\n", indent, candidates);
  fmt::print("{}extent      {}\n", indent, bounds_text(j["extent_m"]));
  if (!j["header_extent_m"].is_null()) {
    fmt::print("{}header ext. {} ($EXTMIN/$EXTMAX, annotation included)\n", indent,
               bounds_text(j["header_extent_m"]));
  }
  fmt::print("{}geometry    {} segments, {} arcs, {:.1f} m of walls\n", indent,
             j["segments"].get<std::size_t>(), j["arcs"].get<std::size_t>(),
             j["wall_length_m"].get<double>());
  fmt::print("{}entities    {}\n", indent, counts_text(j["entities_by_type"]));
  for (const auto& [layer, counts] : j["entities_by_layer"].items()) {
    fmt::print("{}  layer {}: {}\n", indent, layer, counts_text(counts));
  }
  fmt::print("{}skipped     annotation: {}; unsupported: {}; excluded by layer filter: {}\n",
             indent, counts_text(j["annotation_skipped"]), counts_text(j["unsupported_skipped"]),
             j["excluded_by_layer_filter"].get<std::size_t>());
  fmt::print("{}inserts     {} expanded\n", indent, j["inserts_expanded"].get<std::size_t>());
  print_warnings(j, indent);
}

/// A bag's topics, and how its run was read (or why it could not be).
void print_bag(const json& j, const std::string& indent) {
  fmt::print("{}topics      {} messages over {:.1f} s\n", indent,
             j["bag_messages"].get<std::uint64_t>(), j["bag_duration_s"].get<double>());
  for (const json& t : j["topics"]) {
    const std::string rate =
        t["rate_hz"].is_null() ? "" : fmt::format("{:.1f} Hz", t["rate_hz"].get<double>());
    fmt::print("{}  {:<24} {:<32} {:>8} {:>9} {}\n", indent, t["topic"].get<std::string>(),
               t["type"].get<std::string>(), t["messages"].get<std::uint64_t>(), rate,
               t["encoding"].get<std::string>());
  }
  for (const json& w : j["bag_warnings"])
    fmt::print("{}warning     {}\n", indent, w.get<std::string>());
  if (j.contains("run_error")) {
    fmt::print("{}run         not readable as a run: {}\n", indent,
               j["run_error"].get<std::string>());
    return;
  }
  const json& m = j["laser_mount"];
  fmt::print("{}run         scans from {} (frame {}), odometry from {}\n", indent,
             j["scan_topic"].get<std::string>(), j["laser_frame"].get<std::string>(),
             j["odometry_source"].get<std::string>());
  fmt::print("{}laser mount x {:.3f} m, y {:.3f} m, yaw {:.1f} deg{}\n", indent, m[0].get<double>(),
             m[1].get<double>(), m[2].get<double>() * 180.0 / 3.14159265358979,
             j["laser_upside_down"].get<bool>() ? ", upside down" : "");
}

void print_log(const json& j, const std::string& indent) {
  if (j.contains("format")) {
    print_bag(j, indent);
    if (j.contains("run_error"))
      return;
  }
  fmt::print("{}lines       {}, duration {:.1f} s (timestamps {:.3f} .. {:.3f})\n", indent,
             j["lines"].get<std::size_t>(), j["duration_s"].get<double>(),
             j["first_timestamp"].get<double>(), j["last_timestamp"].get<double>());
  fmt::print("{}scans       {} laser scans, {} odometry readings\n", indent,
             j["laser_scans"].get<std::size_t>(), j["odometry"].get<std::size_t>());
  for (const auto& laser : j["lasers"]) {
    const auto setting = [](const json& s, const char* unit) {
      return fmt::format(
          "{:.6g}{} ({}{}{})", s["value"].get<double>(), unit, s["source"].get<std::string>(),
          s["detail"].get<std::string>().empty() ? "" : ": ", s["detail"].get<std::string>());
    };
    fmt::print("{}  {} x {}: {} beams at {}, start {}, max range {}\n", indent,
               laser["type"].get<std::string>(), laser["scans"].get<std::size_t>(),
               laser["beams"].get<std::size_t>(), setting(laser["angle_increment_deg"], " deg"),
               setting(laser["start_angle_deg"], " deg"), setting(laser["max_range_m"], " m"));
  }
  const json& r = j["ranges"];
  fmt::print("{}readings    {} in all: {} hits, {} no return, {} too close, {} invalid\n", indent,
             r["total"].get<std::size_t>(), r["hits"].get<std::size_t>(),
             r["no_return"].get<std::size_t>(), r["too_close"].get<std::size_t>(),
             r["invalid"].get<std::size_t>());
  fmt::print("{}messages    {:<12} {:>8} {:>8} {:>10} {:>10} {:>8}\n", indent, "type", "lines",
             "kept", "ts zero", "ts back", "skipped");
  for (const auto& [type, c] : j["messages"].items()) {
    fmt::print("{}            {:<12} {:>8} {:>8} {:>10} {:>10} {:>8}\n", indent, type,
               c["lines"].get<std::size_t>(), c["kept"].get<std::size_t>(),
               c["skipped_zero_timestamp"].get<std::size_t>(),
               c["skipped_backwards_timestamp"].get<std::size_t>(),
               c["not_data"].get<std::size_t>());
  }
  if (!j["unknown_types"].empty()) {
    fmt::print("{}unknown     {} (skipped)\n", indent,
               fmt::join(j["unknown_types"].get<std::vector<std::string>>(), ", "));
  }
  print_warnings(j, indent);
}

void print_pairs(const json& j, const std::string& indent) {
  fmt::print("{}pairs       {}{}\n", indent, j["count"].get<std::size_t>(),
             j["weighted"].get<bool>() ? " (weighted)" : "");
  fmt::print("{}plan        {}\n", indent, bounds_text(j["plan_bounds"]));
  fmt::print("{}grid        {}\n", indent, bounds_text(j["grid_bounds"]));
}

void print_any(const json& j, const std::string& indent);

void print_dataset(const json& j, const std::string& indent) {
  fmt::print("{}manifest    {}\n", indent, j["manifest"].get<std::string>());
  if (!j["name"].get<std::string>().empty()) {
    fmt::print("{}name        {}\n", indent, j["name"].get<std::string>());
  }
  fmt::print("{}plan scale  {} (units {})\n", indent, j["floorplan_scale"].dump(),
             j["floorplan_units"].get<std::string>());
  fmt::print("{}start       {}\n", indent, j["initial_pose"].dump());
  for (const char* part : {"floorplan", "gridmap", "log"}) {
    if (!j.contains(part))
      continue;
    fmt::print("{}{}: {}\n", indent, part, j[part]["path"].get<std::string>());
    print_any(j[part], indent + "  ");
  }
  if (j["truth"].contains("manual_pairs")) {
    fmt::print("{}truth manual pairs: {}\n", indent,
               j["truth"]["manual_pairs"]["path"].get<std::string>());
    print_pairs(j["truth"]["manual_pairs"], indent + "  ");
  }
  if (j["truth"].contains("warp")) {
    fmt::print("{}truth warp: {}\n", indent, j["truth"]["warp"].get<std::string>());
  }
}

void print_any(const json& j, const std::string& indent) {
  const std::string kind = j["kind"].get<std::string>();
  if (kind == "map" || kind == "image") {
    print_map(j, indent);
  } else if (kind == "dxf") {
    print_dxf(j, indent);
  } else if (kind == "log") {
    print_log(j, indent);
  } else if (kind == "pairs") {
    print_pairs(j, indent);
  } else if (kind == "dataset") {
    print_dataset(j, indent);
  }
}

const char* kind_title(const std::string& kind) {
  if (kind == "map")
    return "ROS map_server map";
  if (kind == "image")
    return "bare map image";
  if (kind == "dxf")
    return "DXF floorplan";
  if (kind == "log")
    return "CARMEN robot log";
  if (kind == "pairs")
    return "reference pairs CSV";
  if (kind == "dataset")
    return "dataset";
  return "file";
}

}  // namespace

void add_info_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("info", "What a map, plan, log, pairs file or dataset holds");
  struct Args {
    std::string path;
    bool json = false;
    std::optional<double> resolution;
    std::string origin;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("PATH", args->path,
                  "map YAML or PGM/PNG image, DXF plan, CARMEN log (.gz), ROS 1 bag, MCAP, rosbag2 "
                  "(.db3 or its folder), pairs CSV, or dataset "
                  "(dataset.yaml or its folder)")
      ->required();
  cmd->add_flag("--json", args->json, "print JSON instead of text");
  cmd->add_option("--resolution", args->resolution, "bare image: metres per pixel")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--origin", args->origin, "bare image: origin x,y,yaw (metres, radians)");
  cmd->callback([args] {
    io::DescribeOptions options;
    options.resolution = args->resolution;
    if (!args->origin.empty())
      options.origin = parse_pose(args->origin, "--origin");
    const json j = io::describe(args->path, options);
    if (args->json) {
      std::cout << j.dump(2) << "\n";
      return;
    }
    fmt::print("{}: {}\n", args->path,
               j.contains("format") ? j["format"].get<std::string>()
                                    : std::string(kind_title(j["kind"].get<std::string>())));
    print_any(j, "  ");
  });
}

}  // namespace floorgrid::app
