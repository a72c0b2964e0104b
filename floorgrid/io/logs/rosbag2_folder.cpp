#include "floorgrid/io/logs/rosbag2_folder.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <map>
#include <system_error>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/yaml_document.hpp"

namespace floorgrid::io {

Rosbag2Metadata read_rosbag2_metadata(const std::filesystem::path& folder) {
  const std::filesystem::path file = folder / "metadata.yaml";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw InputError("a rosbag2 folder needs a metadata.yaml, and it has none", folder.string());
  Rosbag2Metadata metadata;
  try {
    const YAML::Node root = load_yaml_file(file);
    const YAML::Node info = root["rosbag2_bagfile_information"];
    if (!info || !info.IsMap())
      throw InputError("has no rosbag2_bagfile_information map", file.string());
    if (const YAML::Node storage = info["storage_identifier"]; storage && storage.IsScalar())
      metadata.storage_identifier = storage.as<std::string>();
    if (const YAML::Node paths = info["relative_file_paths"]; paths && paths.IsSequence())
      for (const YAML::Node& p : paths)
        metadata.files.push_back(folder / p.as<std::string>());
  } catch (const YAML::Exception& e) {
    throw InputError(std::string("not a rosbag2 metadata file: ") + e.what(), file.string());
  }
  return metadata;
}

std::optional<BagFormat> rosbag2_folder_format(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec))
    return std::nullopt;
  // A dataset folder may hold a bag beside its dataset.yaml: it is a dataset, not a bag.
  if (std::filesystem::exists(path / "dataset.yaml", ec))
    return std::nullopt;
  if (!std::filesystem::exists(path / "metadata.yaml", ec)) {
    // Storage files without their metadata: say so, rather than "no dataset.yaml".
    for (const auto& entry : std::filesystem::directory_iterator(path, ec)) {
      const std::string extension = entry.path().extension().string();
      if (extension == ".db3" || extension == ".mcap")
        throw InputError("holds " + entry.path().filename().string() +
                             " but no metadata.yaml: a rosbag2 folder needs its metadata.yaml "
                             "(give the " +
                             extension + " file itself, or restore the file)",
                         path.string());
    }
    return std::nullopt;
  }
  Rosbag2Metadata metadata = read_rosbag2_metadata(path);
  std::string storage = metadata.storage_identifier;
  if (storage.empty() && !metadata.files.empty()) {
    const std::string extension = metadata.files.front().extension().string();
    storage = extension == ".db3" ? "sqlite3" : extension == ".mcap" ? "mcap" : "";
  }
  if (storage == "sqlite3")
    return BagFormat::rosbag2_sqlite;
  if (storage == "mcap")
    return BagFormat::mcap;
  return std::nullopt;
}

std::vector<std::filesystem::path> rosbag2_storage_files(const std::filesystem::path& path,
                                                         const std::string& storage,
                                                         const std::string& extension) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec))
    return {path};
  Rosbag2Metadata metadata = read_rosbag2_metadata(path);
  if (!metadata.storage_identifier.empty() && metadata.storage_identifier != storage)
    throw InputError("its metadata.yaml says storage_identifier '" + metadata.storage_identifier +
                         "', not '" + storage + "'",
                     path.string());
  if (metadata.files.empty()) {
    for (const auto& entry : std::filesystem::directory_iterator(path, ec))
      if (entry.path().extension() == extension)
        metadata.files.push_back(entry.path());
    std::sort(metadata.files.begin(), metadata.files.end());
  }
  if (metadata.files.empty())
    throw InputError("a rosbag2 folder without any " + extension + " file", path.string());
  return metadata.files;
}

namespace {

// Topics of several files merged by name.
class TopicMerger {
 public:
  explicit TopicMerger(BagContents& merged) : merged_(merged) {}

  // The merged topic of `topic` (read from one file), added when new.
  BagTopic& merge(const BagTopic& topic) {
    const auto found = by_name_.find(topic.topic);
    if (found != by_name_.end())
      return merged_.topics[found->second];
    BagTopic added = topic;
    added.messages = 0;
    added.first_ns = added.last_ns = 0;
    while (!used_ids_.insert(added.id).second)
      ++added.id;
    by_name_[topic.topic] = merged_.topics.size();
    merged_.topics.push_back(added);
    return merged_.topics.back();
  }

 private:
  BagContents& merged_;
  std::map<std::string, std::size_t> by_name_;
  std::set<std::uint32_t> used_ids_;
};

void widen(BagTopic& into, std::uint64_t messages, std::int64_t first_ns, std::int64_t last_ns) {
  if (messages == 0)
    return;
  if (into.messages == 0 || first_ns < into.first_ns)
    into.first_ns = first_ns;
  if (into.messages == 0 || last_ns > into.last_ns)
    into.last_ns = last_ns;
  into.messages += messages;
}

}  // namespace

BagContents read_bag_files(const std::vector<std::filesystem::path>& files, const BagFileRead& read,
                           const BagVisitor* visit) {
  if (files.size() == 1)
    return read(files.front(), visit);
  BagContents merged;
  TopicMerger merger(merged);
  for (const std::filesystem::path& file : files) {
    // Ids differ between files: each message is handed on with its merged topic.
    std::map<std::uint32_t, std::size_t> merged_index;
    BagVisitor remap;
    if (visit != nullptr)
      remap = [&](const BagTopic& topic, const BagMessageView& message) {
        auto found = merged_index.find(topic.id);
        if (found == merged_index.end()) {
          const BagTopic& m = merger.merge(topic);
          found = merged_index.emplace(topic.id, &m - merged.topics.data()).first;
        }
        BagMessageView view = message;
        view.topic_id = merged.topics[found->second].id;
        (*visit)(merged.topics[found->second], view);
      };
    const BagContents part = read(file, visit != nullptr ? &remap : nullptr);
    merged.format = part.format;
    for (const BagTopic& topic : part.topics)
      widen(merger.merge(topic), topic.messages, topic.first_ns, topic.last_ns);
    merged.bytes += part.bytes;
    for (const std::string& warning : part.warnings)
      merged.warnings.push_back(file.filename().string() + ": " + warning);
  }
  add_topic_totals(merged);
  return merged;
}

}  // namespace floorgrid::io
