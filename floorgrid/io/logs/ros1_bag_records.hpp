#pragma once

// The records of a ROS 1 bag, format 2.0, as the format states them: every record is
// `uint32 header_len, header, uint32 data_len, data`, its header a run of fields
// `uint32 field_len, name=value` (the value binary), its `op` field telling the kind.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "floorgrid/io/files/byte_cursor.hpp"

namespace floorgrid::io::ros1 {

/// "#ROSBAG V2.0\n", the first 13 bytes of a ROS 1 bag.
inline constexpr std::string_view kMagic = "#ROSBAG V2.0\n";

/// The kinds of record (the header's `op` field).
enum class Op : std::uint8_t {
  message_data = 0x02,  ///< one message: conn, time; data = the serialized message
  bag_header = 0x03,    ///< the first record: index_pos, conn_count, chunk_count
  index_data = 0x04,    ///< after a chunk, per connection: (time, offset) of its messages
  chunk = 0x05,         ///< compression, size (uncompressed); data = connection + message records
  chunk_info = 0x06,    ///< in the index: chunk_pos, start/end time, per-connection counts
  connection = 0x07,    ///< conn, topic; data = a header with topic, type, md5sum, definition
};

/// A record header's fields, pointing into the bytes it was parsed from (which must outlive it).
/// Parsing reuses the field storage, so one object serves a whole stream of records.
class RecordHeader {
 public:
  /// Parses `bytes`, which lie at byte `offset` of `file` (for errors). Throws InputError on a
  /// field that runs past the end or has no '='.
  void parse(std::span<const std::uint8_t> bytes, std::string_view file, std::uint64_t offset);

  /// The record's kind; throws InputError when there is no `op` field of one byte.
  Op op() const;
  /// True when the header has a field `name`.
  bool has(std::string_view name) const;
  /// A 4-byte field; throws InputError when missing or of another size.
  std::uint32_t u32(std::string_view name) const;
  /// An 8-byte field; throws as u32.
  std::uint64_t u64(std::string_view name) const;
  /// A time field (uint32 sec, uint32 nsec) in ns since the epoch; throws as u32.
  std::int64_t time_ns(std::string_view name) const;
  /// A text field; throws InputError when missing.
  std::string text(std::string_view name) const;
  /// A text field, or `fallback` when missing.
  std::string text_or(std::string_view name, std::string_view fallback) const;

  /// Throws InputError "file: at byte N: message" with N this header's offset.
  [[noreturn]] void fail(const std::string& message) const;

 private:
  struct Field {
    std::string_view name;
    std::span<const std::uint8_t> value;
  };
  std::span<const std::uint8_t> find(std::string_view name, std::size_t size) const;

  std::vector<Field> fields_;
  std::string file_;
  std::uint64_t offset_ = 0;
};

/// A connection record (op 0x07): a topic's id and what its messages are.
struct Connection {
  std::uint32_t id = 0;            ///< `conn`
  std::string topic;               ///< the record header's `topic`
  std::string type;                ///< "sensor_msgs/LaserScan"
  std::string md5sum;              ///< of the message definition
  std::string message_definition;  ///< the full .msg text
  std::string callerid;            ///< the publishing node, when recorded
  bool latching = false;           ///< "latching=1"
};

/// Reads a connection record from its header and data (the data is another header: topic,
/// type, md5sum, message_definition, optional callerid and latching).
Connection parse_connection(const RecordHeader& header, std::span<const std::uint8_t> data,
                            std::string_view file, std::uint64_t data_offset);

/// A chunk info record (op 0x06): where a chunk is, its time span and messages per connection.
struct ChunkInfo {
  std::uint64_t chunk_pos = 0;  ///< file offset of the chunk record
  std::int64_t start_ns = 0;    ///< earliest message time in it
  std::int64_t end_ns = 0;      ///< latest message time in it
  /// (connection id, messages on it in this chunk)
  std::vector<std::pair<std::uint32_t, std::uint32_t>> counts;
};

/// Reads a chunk info record (version 1) from its header and data.
ChunkInfo parse_chunk_info(const RecordHeader& header, std::span<const std::uint8_t> data,
                           std::string_view file, std::uint64_t data_offset);

/// The (uint32 sec, uint32 nsec) of ROS 1 in ns since the epoch.
inline std::int64_t time_ns(std::uint32_t sec, std::uint32_t nsec) {
  return static_cast<std::int64_t>(sec) * 1'000'000'000 + static_cast<std::int64_t>(nsec);
}

}  // namespace floorgrid::io::ros1
