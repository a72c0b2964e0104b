#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "floorgrid/io/logs/bag_file.hpp"

namespace floorgrid::io {

/// What a rosbag2 folder's metadata.yaml (rosbag2_bagfile_information) says is stored.
struct Rosbag2Metadata {
  std::string storage_identifier;            ///< "sqlite3", "mcap", or "" when not stated
  std::vector<std::filesystem::path> files;  ///< relative_file_paths, resolved, in order
};

/// Reads `folder`/metadata.yaml. Throws InputError naming it when it is missing or not YAML.
Rosbag2Metadata read_rosbag2_metadata(const std::filesystem::path& folder);

/// The storage of a rosbag2 folder: its metadata.yaml's storage_identifier ("sqlite3" ->
/// rosbag2_sqlite, "mcap" -> mcap) or, when that is missing, its files' extension (.db3, .mcap);
/// nullopt when `path` is not a folder with a metadata.yaml, holds a dataset.yaml, or the
/// storage is another. Throws InputError naming the folder when its metadata.yaml is broken, or
/// when it holds .db3 or .mcap files but no metadata.yaml (not "no dataset.yaml"). This is how
/// detect_bag_format tells a folder.
std::optional<BagFormat> rosbag2_folder_format(const std::filesystem::path& path);

/// The files to read for `path`: `path` itself when it is a file; for a rosbag2 folder, the
/// files its metadata.yaml lists (every `*extension` in it, sorted, when it lists none). Throws
/// InputError naming the folder when its storage is not `storage` ("sqlite3", "mcap") or it
/// holds no such file.
std::vector<std::filesystem::path> rosbag2_storage_files(const std::filesystem::path& path,
                                                         const std::string& storage,
                                                         const std::string& extension);

/// Reads one file of a bag (a per-file contents or read function).
using BagFileRead =
    std::function<BagContents(const std::filesystem::path& file, const BagVisitor* visit)>;

/// Reads `files` one after the other with `read` and merges what they hold: a topic of the same
/// name in several files is one topic (counts added, times widened), keeping the id it has in
/// the first file that holds it unless that id is taken (then the next free one). Messages are
/// passed to `visit` (when not null) with the merged topic and id. With one file, its contents
/// as they are.
BagContents read_bag_files(const std::vector<std::filesystem::path>& files, const BagFileRead& read,
                           const BagVisitor* visit);

}  // namespace floorgrid::io
