#include "floorgrid/io/logs/bag_file.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/system_memory.hpp"
#include "floorgrid/io/logs/rosbag2_folder.hpp"

namespace floorgrid::io {
namespace {

constexpr std::string_view kRos1Magic = "#ROSBAG V2.0\n";
constexpr std::string_view kMcapMagic = "\x89MCAP0\r\n";
constexpr std::string_view kSqliteMagic{"SQLite format 3\0", 16};

BagFormat require_format(const std::filesystem::path& path) {
  if (const std::optional<BagFormat> format = detect_bag_format(path))
    return *format;
  throw InputError("not a ROS 1 bag, an MCAP file or a rosbag2 bag", path.string());
}

}  // namespace

const char* to_string(BagFormat format) {
  switch (format) {
    case BagFormat::ros1:
      return "ROS 1 bag";
    case BagFormat::mcap:
      return "MCAP";
    case BagFormat::rosbag2_sqlite:
      return "rosbag2 sqlite3";
  }
  return "?";
}

void add_topic_totals(BagContents& contents) {
  for (const BagTopic& topic : contents.topics) {
    if (topic.messages == 0)
      continue;
    if (contents.messages == 0 || topic.first_ns < contents.start_ns)
      contents.start_ns = topic.first_ns;
    if (contents.messages == 0 || topic.last_ns > contents.end_ns)
      contents.end_ns = topic.last_ns;
    contents.messages += topic.messages;
  }
}

std::optional<BagFormat> detect_bag_format(const std::filesystem::path& path) {
  if (std::filesystem::is_directory(path))
    return rosbag2_folder_format(path);
  std::ifstream in(path, std::ios::binary);
  std::array<char, 16> head{};
  in.read(head.data(), head.size());
  const std::string_view got(head.data(), static_cast<std::size_t>(in.gcount()));
  if (got.starts_with(kRos1Magic))
    return BagFormat::ros1;
  if (got.starts_with(kMcapMagic))
    return BagFormat::mcap;
  if (got.starts_with(kSqliteMagic))
    return BagFormat::rosbag2_sqlite;
  return std::nullopt;
}

BagReadLimits bag_read_limits(double memory_gb) {
  const double gib = memory_gb > 0.0 ? memory_gb : default_memory_limit_gb();
  BagReadLimits limits;
  const double eighth = gib * static_cast<double>(1ull << 30) / 8.0;
  if (eighth < static_cast<double>(limits.max_chunk_bytes))
    limits.max_chunk_bytes = static_cast<std::uint64_t>(std::max(eighth, 1.0));
  return limits;
}

BagContents bag_contents(const std::filesystem::path& path, const BagReadLimits& limits) {
  switch (require_format(path)) {
    case BagFormat::ros1:
      return ros1_bag_contents(path, limits);
    case BagFormat::mcap:
      return mcap_contents(path, limits);
    case BagFormat::rosbag2_sqlite:
      return rosbag2_sqlite_contents(path, limits);
  }
  return {};
}

BagContents read_bag(const std::filesystem::path& path, const BagVisitor& visit,
                     const std::set<std::string>* topics, const BagReadLimits& limits) {
  switch (require_format(path)) {
    case BagFormat::ros1:
      return read_ros1_bag(path, visit, topics, limits);
    case BagFormat::mcap:
      return read_mcap(path, visit, topics, limits);
    case BagFormat::rosbag2_sqlite:
      return read_rosbag2_sqlite(path, visit, topics, limits);
  }
  return {};
}

}  // namespace floorgrid::io
