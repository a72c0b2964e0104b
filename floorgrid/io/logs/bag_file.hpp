#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace floorgrid::io {

/// The robot-log containers read besides CARMEN text logs.
enum class BagFormat {
  ros1,            ///< ROS 1 bag, format 2.0 (`#ROSBAG V2.0`)
  mcap,            ///< MCAP (ROS 2's default since Iron), a file or a rosbag2 folder of them
  rosbag2_sqlite,  ///< rosbag2 sqlite3 storage: a `.db3` file or its folder with metadata.yaml
};

/// "ROS 1 bag", "MCAP" or "rosbag2 sqlite3".
const char* to_string(BagFormat format);

/// How a message's payload is serialized.
enum class MessageEncoding {
  ros1,  ///< ROS 1 serialization: packed little-endian, uint32 length before strings/arrays
  cdr,   ///< ROS 2's CDR (XCDR1) with its 4-byte encapsulation header
};

/// One topic (a ROS 1 connection, an MCAP channel, a rosbag2 topic) as the container states it.
struct BagTopic {
  std::uint32_t id = 0;  ///< the container's id of it, unique within the file
  std::string topic;     ///< e.g. "/scan"
  /// as the file names it: "sensor_msgs/LaserScan" (ROS 1), "sensor_msgs/msg/LaserScan" (ROS 2)
  std::string type;
  MessageEncoding encoding = MessageEncoding::ros1;
  std::uint64_t messages = 0;  ///< messages on it (from the index/summary, or counted)
  /// The container's declared frequency is not used: the rate is messages over the time span.
  std::int64_t first_ns = 0;  ///< log time of its first message, ns since the epoch (0: unknown)
  std::int64_t last_ns = 0;   ///< log time of its last message (0: unknown)
};

/// One message as stored. `data` is valid only during the visitor's call.
struct BagMessageView {
  std::uint32_t topic_id = 0;          ///< BagTopic::id
  std::int64_t log_time_ns = 0;        ///< when it was recorded, ns since the epoch
  std::span<const std::uint8_t> data;  ///< the serialized message (CDR: with its 4-byte header)
  std::uint64_t offset = 0;            ///< byte offset in the file of its record (0 when unknown)
};

/// What a bag holds.
struct BagContents {
  BagFormat format = BagFormat::ros1;
  std::vector<BagTopic> topics;  ///< every topic, in the container's order
  std::uint64_t messages = 0;    ///< sum over topics
  std::int64_t start_ns = 0;     ///< earliest log time (0: no message)
  std::int64_t end_ns = 0;       ///< latest log time
  std::uint64_t bytes = 0;       ///< size of the file(s) read
  /// How the file was read other than it says (no index: scanned; no summary; ...), one
  /// sentence each.
  std::vector<std::string> warnings;
};

/// Sets `contents`' message count and time span from its topics' (topics without messages
/// left out).
void add_topic_totals(BagContents& contents);

/// Bytes one chunk of a bag may hold decompressed, whatever the memory limit: far above the
/// chunks recorders write (rosbag and rosbag2 close a chunk near 768 KiB; one large message, a
/// map or a point cloud, makes a chunk of its size), far below a decompression bomb's gigabytes.
inline constexpr std::uint64_t kMaxChunkBytes = 256ull << 20;

/// What reading a bag may allocate.
struct BagReadLimits {
  /// Bytes one chunk may hold decompressed: a chunk stating more is refused, naming its byte
  /// offset, before anything is allocated or decompressed for it.
  std::uint64_t max_chunk_bytes = kMaxChunkBytes;
};

/// The limits of a job that may allocate `memory_gb` GiB (0: half of this machine's memory):
/// a chunk may take an eighth of it, and never more than kMaxChunkBytes.
BagReadLimits bag_read_limits(double memory_gb);

/// Called once per message whose topic was asked for, in file order.
using BagVisitor = std::function<void(const BagTopic& topic, const BagMessageView& message)>;

/// The format of `path` told by its content (magic bytes), or a folder holding a rosbag2
/// `metadata.yaml`; nullopt when it is none of them (a CARMEN log, say).
std::optional<BagFormat> detect_bag_format(const std::filesystem::path& path);

/// The topics and counts of a bag, from its index/summary where it has one (fast), else by
/// reading it whole. Throws InputError naming the file and the byte offset on a corrupt or
/// truncated file, or a chunk beyond `limits`, saying what was read before it.
BagContents bag_contents(const std::filesystem::path& path, const BagReadLimits& limits = {});

/// Streams every message on `topics` (all topics when null) to `visit`, reading one chunk at a
/// time (memory bounded by the largest chunk, never the whole file). Returns the contents
/// counted while reading. Throws as bag_contents.
BagContents read_bag(const std::filesystem::path& path, const BagVisitor& visit,
                     const std::set<std::string>* topics = nullptr,
                     const BagReadLimits& limits = {});

// ---- one pair per format (bag_file.cpp dispatches to them) ----

/// ROS 1 bag 2.0: chunks uncompressed, bz2 or lz4; connection, chunk info and index records.
BagContents ros1_bag_contents(const std::filesystem::path& path, const BagReadLimits& limits = {});
/// See read_bag.
BagContents read_ros1_bag(const std::filesystem::path& path, const BagVisitor& visit,
                          const std::set<std::string>* topics, const BagReadLimits& limits = {});

/// MCAP: chunks uncompressed, lz4 or zstd; the summary section used when present, a file
/// without one read through. Messages with encoding "cdr" (ROS 2) or "ros1".
BagContents mcap_contents(const std::filesystem::path& path, const BagReadLimits& limits = {});
/// See read_bag.
BagContents read_mcap(const std::filesystem::path& path, const BagVisitor& visit,
                      const std::set<std::string>* topics, const BagReadLimits& limits = {});

/// rosbag2 sqlite3: a `.db3` (with or without its metadata.yaml), querying only the columns
/// every rosbag2 version has (topics: id, name, type, serialization_format; messages: id,
/// topic_id, timestamp, data).
/// `limits.max_chunk_bytes` bounds a row's value (a message's bytes).
BagContents rosbag2_sqlite_contents(const std::filesystem::path& path,
                                    const BagReadLimits& limits = {});
/// See read_bag.
BagContents read_rosbag2_sqlite(const std::filesystem::path& path, const BagVisitor& visit,
                                const std::set<std::string>* topics,
                                const BagReadLimits& limits = {});

}  // namespace floorgrid::io
