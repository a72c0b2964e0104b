#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "floorgrid/io/files/byte_cursor.hpp"

namespace floorgrid::io::mcap {

/// MCAP's magic, at the start and at the end of a file.
inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
/// A record's opcode (u8) and content length (u64) before its content.
inline constexpr std::uint64_t kRecordHeaderBytes = 9;
/// The Footer record, opcode and length included.
inline constexpr std::uint64_t kFooterRecordBytes = kRecordHeaderBytes + 20;

/// The record kinds of MCAP; any other opcode is skipped (forward compatibility).
enum class Opcode : std::uint8_t {
  header = 0x01,
  footer = 0x02,
  schema = 0x03,
  channel = 0x04,
  message = 0x05,
  chunk = 0x06,
  message_index = 0x07,
  chunk_index = 0x08,
  attachment = 0x09,
  attachment_index = 0x0A,
  statistics = 0x0B,
  metadata = 0x0C,
  metadata_index = 0x0D,
  summary_offset = 0x0E,
  data_end = 0x0F,
};

/// Footer: where the summary section and its offsets start (0: none).
struct Footer {
  std::uint64_t summary_start = 0;
  std::uint64_t summary_offset_start = 0;
  std::uint32_t summary_crc = 0;
};

/// Schema: what a channel's messages are (the data, the definition text, is not kept).
struct Schema {
  std::uint16_t id = 0;
  std::string name;      ///< e.g. "sensor_msgs/msg/LaserScan"
  std::string encoding;  ///< e.g. "ros2msg"
};

/// Channel: a topic (metadata not kept).
struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  ///< 0: no schema
  std::string topic;
  std::string message_encoding;  ///< e.g. "cdr", "ros1"
};

/// Message: `data` points into the record's content.
struct Message {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  std::span<const std::uint8_t> data;
};

/// Chunk: `records` (compressed) points into the record's content.
struct Chunk {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;  ///< 0: not given
  std::string compression;             ///< "", "lz4", "zstd"
  std::span<const std::uint8_t> records;
  std::uint64_t records_offset = 0;  ///< file offset of `records`
};

/// ChunkIndex: a chunk's times and where each channel's MessageIndex record lies.
struct ChunkIndex {
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::uint64_t chunk_start_offset = 0;
  std::vector<std::pair<std::uint16_t, std::uint64_t>> message_index_offsets;
};

/// MessageIndex: one channel's messages in one chunk, as (log_time, offset) pairs.
struct MessageIndex {
  std::uint16_t channel_id = 0;
  std::vector<std::uint64_t> log_times;
};

/// Statistics: counts and times of the whole file.
struct Statistics {
  std::uint64_t message_count = 0;
  std::uint64_t message_start_time = 0;
  std::uint64_t message_end_time = 0;
  std::vector<std::pair<std::uint16_t, std::uint64_t>> channel_message_counts;
};

// Each parser reads a record's content (after opcode and length) from `in`; a field past the
// end of the content is an InputError at its byte offset.

/// Parses a Footer record's content.
Footer parse_footer(ByteCursor& in);
/// Parses a Schema record's content.
Schema parse_schema(ByteCursor& in);
/// Parses a Channel record's content.
Channel parse_channel(ByteCursor& in);
/// Parses a Message record's content.
Message parse_message(ByteCursor& in);
/// Parses a Chunk record's content.
Chunk parse_chunk(ByteCursor& in);
/// Parses a ChunkIndex record's content.
ChunkIndex parse_chunk_index(ByteCursor& in);
/// Parses a MessageIndex record's content.
MessageIndex parse_message_index(ByteCursor& in);
/// Parses a Statistics record's content.
Statistics parse_statistics(ByteCursor& in);

}  // namespace floorgrid::io::mcap
