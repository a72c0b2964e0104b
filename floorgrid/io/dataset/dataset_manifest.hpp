#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"
#include "floorgrid/io/logs/robot_log_summary.hpp"

namespace floorgrid::io {

/// The robot's start in both maps (dataset.yaml `initial_pose`).
struct InitialPoses {
  Pose2 plan;  ///< in the plan's own coordinates
  Pose2 grid;  ///< in the gridmap frame
};

/// Ground truth a dataset may carry (dataset.yaml `truth`). Paths are resolved.
struct DatasetTruth {
  std::optional<std::filesystem::path> manual_pairs;  ///< hand-picked pairs CSV
  std::optional<std::filesystem::path> warp;          ///< a simulator's truth.json
};

/// A dataset manifest, `dataset.yaml` (a contract: keys are extended, never renamed).
/// Every path is resolved against the manifest's folder.
struct DatasetManifest {
  std::filesystem::path manifest_path;                ///< the dataset.yaml read or to write
  std::string name;                                   ///< optional display name (project key)
  std::filesystem::path floorplan;                    ///< DXF, map YAML, or a bare image
  std::optional<double> floorplan_resolution;         ///< bare image only: metres per pixel
  std::optional<Pose2> floorplan_origin;              ///< bare image only
  std::string floorplan_units = "auto";               ///< DXF: auto | m | cm | mm | in | ft
  std::optional<double> floorplan_scale = 1.0;        ///< a factor, or nullopt for `auto`
  std::vector<std::string> floorplan_layers;          ///< DXF include globs (empty: all)
  std::vector<std::string> floorplan_layers_exclude;  ///< DXF exclude globs
  std::filesystem::path gridmap;                      ///< map YAML or a bare image
  std::optional<double> gridmap_resolution;           ///< bare image only: metres per pixel
  std::optional<Pose2> gridmap_origin;                ///< bare image only
  std::optional<std::filesystem::path> log;           ///< CARMEN log, .gz allowed
  /// `log_topics: {scan, odom}` and `log_frames: {base, odom}` of a bag log (absent: found)
  std::optional<std::string> log_scan_topic, log_odom_topic, log_base_frame, log_odom_frame;
  std::optional<InitialPoses> initial_pose;             ///< absent: global localization
  LaserSettings laser;                                  ///< overrides of the log's laser settings
  std::optional<std::array<double, 4>> odometry_noise;  ///< alpha1..alpha4 added to the log
  std::uint64_t odometry_noise_seed = 1;                ///< seed of that noise (project key)
  DatasetTruth truth;                                   ///< optional ground truth

  /// The folder the manifest lives in.
  std::filesystem::path folder() const { return manifest_path.parent_path(); }
  /// What the dataset is called: its `name`, else its folder's name.
  std::string display_name() const { return name.empty() ? folder().filename().string() : name; }
};

/// The manifest's top-level keys (SPEC's and the project's own).
const std::vector<std::string>& manifest_keys();

/// Resolves `path`: a dataset.yaml, or a folder holding one.
std::filesystem::path find_manifest(const std::filesystem::path& path);

/// Reads and checks a manifest (file or folder). Unknown keys, bad values and referenced files
/// that do not exist are InputErrors naming the file, line and key.
DatasetManifest read_manifest(const std::filesystem::path& path);

/// Writes the manifest atomically to `manifest.manifest_path`, paths relative to its folder.
void write_manifest(const DatasetManifest& manifest);

}  // namespace floorgrid::io
