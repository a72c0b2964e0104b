// MCAP files (https://mcap.dev/spec): the data section streamed record by record, one chunk in
// memory at a time; the summary section used for contents when the file has a usable one.
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <unordered_map>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/binary_file.hpp"
#include "floorgrid/io/files/decompress.hpp"
#include "floorgrid/io/logs/bag_file.hpp"
#include "floorgrid/io/logs/mcap_records.hpp"
#include "floorgrid/io/logs/mcap_topics.hpp"
#include "floorgrid/io/logs/rosbag2_folder.hpp"

namespace floorgrid::io {
namespace {

using mcap::Opcode;

void check_leading_magic(BinaryFile& file) {
  std::uint8_t magic[sizeof mcap::kMagic];
  if (file.size() < sizeof magic)
    throw InputError("at byte 0: not an MCAP file (shorter than its magic)", file.name());
  file.read(0, std::span<std::uint8_t>(magic), "magic");
  if (std::memcmp(magic, mcap::kMagic, sizeof magic) != 0)
    throw InputError("at byte 0: not an MCAP file (it does not start with MCAP's magic)",
                     file.name());
}

struct RecordHeader {
  Opcode opcode{};
  std::uint64_t offset = 0;  ///< of the opcode
  std::uint64_t length = 0;  ///< of the content
  std::uint64_t content_offset() const { return offset + mcap::kRecordHeaderBytes; }
  std::uint64_t end() const { return content_offset() + length; }
};

// The opcode and length of the record at `offset`, its content checked to lie within `limit`.
RecordHeader read_record_header(BinaryFile& file, std::uint64_t offset, std::uint64_t limit) {
  std::uint8_t raw[mcap::kRecordHeaderBytes];
  if (offset > limit || limit - offset < mcap::kRecordHeaderBytes)
    throw InputError("at byte " + std::to_string(offset) +
                         ": a record's opcode and length reach past the end of the file "
                         "(truncated; an MCAP file ends with a Footer record and the magic)",
                     file.name());
  file.read(offset, std::span<std::uint8_t>(raw), "record header");
  RecordHeader header;
  header.opcode = static_cast<Opcode>(raw[0]);
  header.offset = offset;
  std::memcpy(&header.length, raw + 1, sizeof header.length);
  if (header.length > limit - header.content_offset())
    throw InputError("at byte " + std::to_string(offset) + ": record (opcode " +
                         std::to_string(raw[0]) + ") of " + std::to_string(header.length) +
                         " bytes reaches past the end of the file (" + std::to_string(file.size()) +
                         " bytes; truncated or corrupt)",
                     file.name());
  return header;
}

// The most bytes `compression` can make of `compressed` bytes: a lying uncompressed size is
// caught before anything is allocated for it.
std::uint64_t largest_uncompressed(Compression compression, std::uint64_t compressed) {
  constexpr std::uint64_t kSlack = 1 << 16;
  switch (compression) {
    case Compression::lz4:  // a match adds at most 255 bytes per byte of its length
      return compressed * 256 + kSlack;
    case Compression::zstd:  // an RLE block: 4 bytes give at most 128 KiB
      return compressed * 32768 + kSlack;
    default:
      return compressed;
  }
}

// Streams the data section of one MCAP file.
class DataSectionReader {
 public:
  DataSectionReader(const std::filesystem::path& path, const BagVisitor* visit,
                    const std::set<std::string>* wanted, const BagReadLimits& limits)
      : file_(path), visit_(visit), limits_(limits), topics_(wanted) {}

  BagContents read() {
    try {
      read_data_section();
    } catch (const InputError& e) {
      throw InputError(e.message() + "; read before it: " + topics_.progress(), file_.name());
    }
    return topics_.contents(file_.size());
  }

 private:
  void read_data_section() {
    check_leading_magic(file_);
    std::uint64_t offset = sizeof mcap::kMagic;
    for (;;) {
      const RecordHeader record = read_record_header(file_, offset, file_.size());
      if (record.opcode == Opcode::data_end || record.opcode == Opcode::footer)
        return;
      if (record.opcode == Opcode::message || record.opcode == Opcode::chunk ||
          record.opcode == Opcode::schema || record.opcode == Opcode::channel) {
        file_.read(record.content_offset(), record.length, record_, "record");
        ByteCursor content(record_, file_.name(), record.content_offset());
        if (record.opcode == Opcode::chunk)
          read_chunk(content, record.offset);
        else
          on_record(record.opcode, content, record.offset);
      }
      offset = record.end();
    }
  }

  void read_chunk(ByteCursor& content, std::uint64_t chunk_offset) {
    const mcap::Chunk chunk = mcap::parse_chunk(content);
    const Compression compression =
        parse_compression(chunk.compression, ChunkContainer::mcap, file_.name(), chunk_offset);
    if (chunk.uncompressed_size > largest_uncompressed(compression, chunk.records.size()) ||
        (compression == Compression::none && chunk.uncompressed_size != chunk.records.size()))
      throw InputError("at byte " + std::to_string(chunk_offset) + ": chunk says " +
                           std::to_string(chunk.uncompressed_size) + " uncompressed bytes from " +
                           std::to_string(chunk.records.size()) + " bytes of '" +
                           chunk.compression + "' data, which cannot be (corrupt)",
                       file_.name());
    // Before anything is allocated for it: a bomb states its size honestly.
    if (chunk.uncompressed_size > limits_.max_chunk_bytes)
      throw InputError("at byte " + std::to_string(chunk_offset) + ": a chunk of " +
                           std::to_string(chunk.uncompressed_size) +
                           " bytes uncompressed, more than the " +
                           std::to_string(limits_.max_chunk_bytes) +
                           " a chunk may take (256 MiB, or an eighth of the memory limit): a "
                           "decompression bomb, or a file with huge chunks",
                       file_.name());
    std::span<const std::uint8_t> records = chunk.records;
    if (compression != Compression::none) {
      decompress(compression, chunk.records, static_cast<std::size_t>(chunk.uncompressed_size),
                 chunk_, file_.name(), chunk_offset);
      records = chunk_;
    }
    if (chunk.uncompressed_crc != 0) {
      const std::uint32_t crc = static_cast<std::uint32_t>(
          crc32_z(crc32_z(0, nullptr, 0), records.data(), records.size()));
      if (crc != chunk.uncompressed_crc)
        throw InputError("at byte " + std::to_string(chunk_offset) + ": chunk has the wrong CRC (" +
                             std::to_string(crc) + ", its record says " +
                             std::to_string(chunk.uncompressed_crc) + "): corrupt",
                         file_.name());
    }
    try {
      ByteCursor in(records, file_.name());
      while (!in.at_end()) {
        const auto opcode = static_cast<Opcode>(in.read<std::uint8_t>("record opcode"));
        const auto length = in.read<std::uint64_t>("record length");
        if (length > in.remaining())
          in.fail("record of " + std::to_string(length) + " bytes but only " +
                  std::to_string(in.remaining()) + " remain in the chunk");
        ByteCursor record(in.bytes(static_cast<std::size_t>(length), "record"), file_.name(),
                          in.offset() - length);
        on_record(opcode, record, chunk_offset);
      }
    } catch (const InputError& e) {
      throw InputError("at byte " + std::to_string(chunk_offset) +
                           ": in the chunk's uncompressed records, " + e.message(),
                       file_.name());
    }
  }

  // A schema, channel or message record (others are skipped); `offset` is its file offset, or
  // its chunk's.
  void on_record(Opcode opcode, ByteCursor& content, std::uint64_t offset) {
    if (opcode == Opcode::schema) {
      const mcap::Schema schema = mcap::parse_schema(content);
      if (!topics_.add_schema(schema))
        throw InputError("at byte " + std::to_string(offset) + ": schema " +
                             std::to_string(schema.id) + " is defined again as another type (" +
                             schema.name + "): which one its channels use would be a guess",
                         file_.name());
    } else if (opcode == Opcode::channel) {
      const mcap::Channel channel = mcap::parse_channel(content);
      if (!topics_.add_channel(channel))
        throw InputError("at byte " + std::to_string(offset) + ": channel " +
                             std::to_string(channel.id) + " is defined again as another topic (" +
                             channel.topic +
                             "), schema or encoding: which one its messages "
                             "belong to would be a guess",
                         file_.name());
    } else if (opcode == Opcode::message) {
      const mcap::Message message = mcap::parse_message(content);
      BagTopic* topic = topics_.count(message.channel_id, message.log_time);
      if (topic == nullptr)
        throw InputError("at byte " + std::to_string(offset) + ": message on channel " +
                             std::to_string(message.channel_id) +
                             ", which no Channel record before it defines",
                         file_.name());
      if (visit_ != nullptr && topics_.wanted(message.channel_id)) {
        BagMessageView view;
        view.topic_id = topic->id;
        view.log_time_ns = static_cast<std::int64_t>(message.log_time);
        view.data = message.data;
        view.offset = offset;
        (*visit_)(*topic, view);
      }
    }
  }

  BinaryFile file_;
  const BagVisitor* visit_;
  BagReadLimits limits_;
  mcap::TopicTable topics_;
  std::vector<std::uint8_t> record_;  // reused: the record being read
  std::vector<std::uint8_t> chunk_;   // reused: the chunk decompressed
};

// ---- the summary section ----

// The exact log time of a channel's first (or last) message, from the MessageIndex records of
// the chunks that hold it; nullopt when the chunk indexes do not say where they are.
std::optional<std::uint64_t> channel_time(BinaryFile& file,
                                          const std::vector<mcap::ChunkIndex>& chunks,
                                          std::uint16_t channel, bool first,
                                          std::vector<std::uint8_t>& buffer) {
  std::vector<std::pair<std::uint64_t, std::uint64_t>> candidates;  // chunk bound, index offset
  for (const mcap::ChunkIndex& chunk : chunks)
    for (const auto& [id, offset] : chunk.message_index_offsets)
      if (id == channel)
        candidates.emplace_back(first ? chunk.message_start_time : chunk.message_end_time, offset);
  std::sort(candidates.begin(), candidates.end());
  if (!first)
    std::reverse(candidates.begin(), candidates.end());
  std::optional<std::uint64_t> best;
  for (const auto& [bound, offset] : candidates) {
    if (best && (first ? bound >= *best : bound <= *best))
      break;  // no message of this chunk can be earlier (later) than the best found
    const RecordHeader record = read_record_header(file, offset, file.size());
    if (record.opcode != Opcode::message_index)
      throw InputError("at byte " + std::to_string(offset) +
                           ": a chunk index points here for a MessageIndex record, but it is not",
                       file.name());
    file.read(record.content_offset(), record.length, buffer, "message index");
    ByteCursor in(buffer, file.name(), record.content_offset());
    for (const std::uint64_t t : mcap::parse_message_index(in).log_times)
      if (!best || (first ? t < *best : t > *best))
        best = t;
  }
  return best;
}

// The contents from the summary section, or nullopt (with a warning saying why) when the file
// has none that can be used.
std::optional<BagContents> contents_from_summary(BinaryFile& file,
                                                 std::vector<std::string>& warnings) {
  check_leading_magic(file);
  const std::uint64_t tail = sizeof mcap::kMagic + mcap::kFooterRecordBytes;
  std::vector<std::uint8_t> buffer;
  if (file.size() < sizeof mcap::kMagic + tail) {
    warnings.push_back("the file is too short for a footer: read through");
    return std::nullopt;
  }
  const std::uint64_t footer_offset = file.size() - tail;
  file.read(footer_offset, tail, buffer, "footer");
  if (buffer[0] != static_cast<std::uint8_t>(Opcode::footer) ||
      std::memcmp(buffer.data() + mcap::kFooterRecordBytes, mcap::kMagic, sizeof mcap::kMagic) !=
          0) {
    warnings.push_back(
        "the file does not end with a Footer record and the magic (truncated?): "
        "read through");
    return std::nullopt;
  }
  ByteCursor footer_in(std::span<const std::uint8_t>(buffer).subspan(mcap::kRecordHeaderBytes),
                       file.name(), footer_offset + mcap::kRecordHeaderBytes);
  const mcap::Footer footer = mcap::parse_footer(footer_in);
  if (footer.summary_start == 0) {
    warnings.push_back("the file has no summary section: read through");
    return std::nullopt;
  }
  try {
    if (footer.summary_start < sizeof mcap::kMagic || footer.summary_start > footer_offset)
      throw InputError("at byte " + std::to_string(footer_offset) +
                           ": the footer's summary_start " + std::to_string(footer.summary_start) +
                           " lies outside the file",
                       file.name());
    mcap::TopicTable topics(nullptr);
    std::optional<mcap::Statistics> statistics;
    std::vector<mcap::ChunkIndex> chunks;
    for (std::uint64_t offset = footer.summary_start; offset < footer_offset;) {
      const RecordHeader record = read_record_header(file, offset, footer_offset);
      offset = record.end();
      const Opcode op = record.opcode;
      if (op != Opcode::schema && op != Opcode::channel && op != Opcode::statistics &&
          op != Opcode::chunk_index)
        continue;
      file.read(record.content_offset(), record.length, buffer, "summary record");
      ByteCursor in(buffer, file.name(), record.content_offset());
      if (op == Opcode::schema && !topics.add_schema(mcap::parse_schema(in)))
        throw InputError("at byte " + std::to_string(record.offset) +
                             ": a schema is defined twice as different types",
                         file.name());
      if (op == Opcode::channel && !topics.add_channel(mcap::parse_channel(in)))
        throw InputError("at byte " + std::to_string(record.offset) +
                             ": a channel is defined twice as different topics",
                         file.name());
      if (op == Opcode::schema || op == Opcode::channel)
        continue;
      if (op == Opcode::statistics)
        statistics = mcap::parse_statistics(in);
      else
        chunks.push_back(mcap::parse_chunk_index(in));
    }
    if (!statistics) {
      warnings.push_back("the summary has no Statistics record: read through");
      return std::nullopt;
    }
    for (const auto& [channel, count] : statistics->channel_message_counts) {
      const auto first = channel_time(file, chunks, channel, true, buffer);
      const auto last = channel_time(file, chunks, channel, false, buffer);
      if (count > 0 && (!first || !last)) {
        warnings.push_back("the summary's chunk indexes do not tell the times of channel " +
                           std::to_string(channel) + " (unchunked file?): read through");
        return std::nullopt;
      }
      if (!topics.set_count(channel, count, first.value_or(0), last.value_or(0))) {
        warnings.push_back("the summary's statistics count messages on channel " +
                           std::to_string(channel) + ", which it does not define: read through");
        return std::nullopt;
      }
    }
    BagContents contents = topics.contents(file.size());
    contents.messages = statistics->message_count;
    contents.start_ns = static_cast<std::int64_t>(statistics->message_start_time);
    contents.end_ns = static_cast<std::int64_t>(statistics->message_end_time);
    return contents;
  } catch (const InputError& e) {
    warnings.push_back("the summary section is unusable (" + e.message() + "): read through");
    return std::nullopt;
  }
}

BagContents mcap_file_contents(const std::filesystem::path& path, const BagReadLimits& limits) {
  std::vector<std::string> warnings;
  {
    BinaryFile file(path);
    if (std::optional<BagContents> contents = contents_from_summary(file, warnings)) {
      contents->warnings.insert(contents->warnings.begin(), warnings.begin(), warnings.end());
      return *contents;
    }
  }
  BagContents contents = DataSectionReader(path, nullptr, nullptr, limits).read();
  contents.warnings.insert(contents.warnings.begin(), warnings.begin(), warnings.end());
  return contents;
}

}  // namespace

BagContents mcap_contents(const std::filesystem::path& path, const BagReadLimits& limits) {
  return read_bag_files(
      rosbag2_storage_files(path, "mcap", ".mcap"),
      [&limits](const std::filesystem::path& file, const BagVisitor*) {
        return mcap_file_contents(file, limits);
      },
      nullptr);
}

BagContents read_mcap(const std::filesystem::path& path, const BagVisitor& visit,
                      const std::set<std::string>* topics, const BagReadLimits& limits) {
  return read_bag_files(
      rosbag2_storage_files(path, "mcap", ".mcap"),
      [topics, &limits](const std::filesystem::path& file, const BagVisitor* v) {
        return DataSectionReader(file, v, topics, limits).read();
      },
      &visit);
}

}  // namespace floorgrid::io
