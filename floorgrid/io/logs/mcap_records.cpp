#include "floorgrid/io/logs/mcap_records.hpp"

namespace floorgrid::io::mcap {
namespace {

std::string read_string(ByteCursor& in, const char* what) {
  const auto length = in.read<std::uint32_t>(what);
  return in.string(length, what);
}

// A map's u32 byte length, then a cursor over its entries.
ByteCursor map_entries(ByteCursor& in, const char* what) {
  const auto length = in.read<std::uint32_t>(what);
  const std::uint64_t offset = in.offset();
  return ByteCursor(in.bytes(length, what), in.file(), offset);
}

}  // namespace

Footer parse_footer(ByteCursor& in) {
  Footer footer;
  footer.summary_start = in.read<std::uint64_t>("footer summary_start");
  footer.summary_offset_start = in.read<std::uint64_t>("footer summary_offset_start");
  footer.summary_crc = in.read<std::uint32_t>("footer summary_crc");
  return footer;
}

Schema parse_schema(ByteCursor& in) {
  Schema schema;
  schema.id = in.read<std::uint16_t>("schema id");
  schema.name = read_string(in, "schema name");
  schema.encoding = read_string(in, "schema encoding");
  in.skip(in.read<std::uint32_t>("schema data length"), "schema data");
  return schema;
}

Channel parse_channel(ByteCursor& in) {
  Channel channel;
  channel.id = in.read<std::uint16_t>("channel id");
  channel.schema_id = in.read<std::uint16_t>("channel schema_id");
  channel.topic = read_string(in, "channel topic");
  channel.message_encoding = read_string(in, "channel message_encoding");
  map_entries(in, "channel metadata");
  return channel;
}

Message parse_message(ByteCursor& in) {
  Message message;
  message.channel_id = in.read<std::uint16_t>("message channel_id");
  message.sequence = in.read<std::uint32_t>("message sequence");
  message.log_time = in.read<std::uint64_t>("message log_time");
  message.publish_time = in.read<std::uint64_t>("message publish_time");
  message.data = in.bytes(in.remaining(), "message data");
  return message;
}

Chunk parse_chunk(ByteCursor& in) {
  Chunk chunk;
  chunk.message_start_time = in.read<std::uint64_t>("chunk message_start_time");
  chunk.message_end_time = in.read<std::uint64_t>("chunk message_end_time");
  chunk.uncompressed_size = in.read<std::uint64_t>("chunk uncompressed_size");
  chunk.uncompressed_crc = in.read<std::uint32_t>("chunk uncompressed_crc");
  chunk.compression = read_string(in, "chunk compression");
  const auto length = in.read<std::uint64_t>("chunk records length");
  chunk.records_offset = in.offset();
  if (length > in.remaining())
    in.fail("chunk records of " + std::to_string(length) + " bytes but only " +
            std::to_string(in.remaining()) + " remain in the record (truncated or corrupt)");
  chunk.records = in.bytes(static_cast<std::size_t>(length), "chunk records");
  return chunk;
}

ChunkIndex parse_chunk_index(ByteCursor& in) {
  ChunkIndex index;
  index.message_start_time = in.read<std::uint64_t>("chunk index message_start_time");
  index.message_end_time = in.read<std::uint64_t>("chunk index message_end_time");
  index.chunk_start_offset = in.read<std::uint64_t>("chunk index chunk_start_offset");
  in.read<std::uint64_t>("chunk index chunk_length");
  ByteCursor offsets = map_entries(in, "chunk index message_index_offsets");
  while (!offsets.at_end()) {
    const auto channel = offsets.read<std::uint16_t>("message index offset channel");
    index.message_index_offsets.emplace_back(channel,
                                             offsets.read<std::uint64_t>("message index offset"));
  }
  // message_index_length, compression and sizes follow; they are not needed.
  return index;
}

MessageIndex parse_message_index(ByteCursor& in) {
  MessageIndex index;
  index.channel_id = in.read<std::uint16_t>("message index channel_id");
  ByteCursor records = map_entries(in, "message index records");
  index.log_times.reserve(records.remaining() / 16);
  while (!records.at_end()) {
    index.log_times.push_back(records.read<std::uint64_t>("message index log_time"));
    records.read<std::uint64_t>("message index offset");
  }
  return index;
}

Statistics parse_statistics(ByteCursor& in) {
  Statistics statistics;
  statistics.message_count = in.read<std::uint64_t>("statistics message_count");
  in.read<std::uint16_t>("statistics schema_count");
  in.read<std::uint32_t>("statistics channel_count");
  in.read<std::uint32_t>("statistics attachment_count");
  in.read<std::uint32_t>("statistics metadata_count");
  in.read<std::uint32_t>("statistics chunk_count");
  statistics.message_start_time = in.read<std::uint64_t>("statistics message_start_time");
  statistics.message_end_time = in.read<std::uint64_t>("statistics message_end_time");
  ByteCursor counts = map_entries(in, "statistics channel_message_counts");
  while (!counts.at_end()) {
    const auto channel = counts.read<std::uint16_t>("channel message count channel");
    statistics.channel_message_counts.emplace_back(
        channel, counts.read<std::uint64_t>("channel message count"));
  }
  return statistics;
}

}  // namespace floorgrid::io::mcap
