#include "floorgrid/io/logs/ros1_bag_scan.hpp"

#include <bzlib.h>

#include <cstdio>
#include <unordered_map>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/decompress.hpp"

namespace floorgrid::io::ros1 {
namespace {

// LZ4 cannot expand a byte into more than 255 (a match length is extended by one byte per 255).
constexpr std::uint64_t kLz4MaxExpansion = 256;
// A bz2 chunk claiming more than this factor is decompressed once to count its bytes before
// its claimed size is allocated (bzip2 can rightly reach far beyond: a map of unknown cells).
constexpr std::uint64_t kBz2TrustedExpansion = 1024;

// The decompressed size of a bzip2 stream, counted without keeping it; stops past `limit`.
std::uint64_t bz2_size(std::span<const std::uint8_t> in, std::uint64_t limit) {
  bz_stream stream{};
  if (BZ2_bzDecompressInit(&stream, 0, 0) != BZ_OK)
    return 0;
  std::vector<char> scratch(1 << 16);
  // bzip2's API takes non-const pointers but does not write through the source.
  stream.next_in = const_cast<char*>(reinterpret_cast<const char*>(in.data()));
  stream.avail_in = static_cast<unsigned int>(in.size());
  std::uint64_t total = 0;
  int status = BZ_OK;
  while (status == BZ_OK && total <= limit) {
    stream.next_out = scratch.data();
    stream.avail_out = static_cast<unsigned int>(scratch.size());
    status = BZ2_bzDecompress(&stream);
    total += scratch.size() - stream.avail_out;
    if (status == BZ_OK && stream.avail_in == 0 && stream.avail_out != 0)
      break;  // the data ends early; decompress() names the error
  }
  BZ2_bzDecompressEnd(&stream);
  return total;
}

class Scan {
 public:
  Scan(BagFile& file, const BagVisitor* visit, const std::set<std::string>* topics,
       const BagReadLimits& limits)
      : file_(file), visit_(visit), topics_(topics), limits_(limits) {
    contents_.format = BagFormat::ros1;
    contents_.bytes = file.size();
  }

  BagContents run() {
    try {
      read_records();
    } catch (const InputError& e) {
      throw InputError(e.message() + "; read before it: " + read_so_far(), e.file(), e.line(),
                       e.field());
    }
    return std::move(contents_);
  }

 private:
  std::string read_so_far() const {
    std::set<std::string> names;
    for (const BagTopic& t : contents_.topics)
      if (t.messages > 0)
        names.insert(t.topic);
    return std::to_string(contents_.messages) + " messages on " + std::to_string(names.size()) +
           " topics";
  }

  void read_records() {
    const bool unindexed = file_.index_pos() == 0;
    std::uint64_t offset = file_.first_record();
    while (offset < file_.size()) {
      const Record& record = file_.read_record(offset);
      if (!record.truncated.empty()) {
        if (!unindexed)
          file_.fail(offset, record.truncated + " (truncated or corrupt)");
        contents_.warnings.push_back("The file ends inside the record at byte " +
                                     std::to_string(offset) +
                                     " (a recording that was cut off): read up to there.");
        return;
      }
      switch (record.header.op()) {
        case Op::chunk:
          if (!read_chunk(record, unindexed))
            return;
          break;
        case Op::connection:
          add_connection(parse_connection(record.header, file_.read_data(data_), file_.name(),
                                          record.data_offset),
                         record.offset);
          break;
        case Op::message_data:
          // Not where rosbag puts them, but what an unfinished uncompressed chunk leaves.
          read_message(record.header, file_.read_data(data_), record.offset);
          break;
        case Op::index_data:
        case Op::chunk_info:
          break;
        case Op::bag_header:
          file_.fail(offset, "a second bag header record");
        default:
          file_.fail(offset, "a record of unknown op 0x" + hex(record.header.op()));
      }
      offset = record.end();
    }
  }

  static std::string hex(Op op) {
    char text[3];
    std::snprintf(text, sizeof text, "%02x", static_cast<unsigned>(op));
    return text;
  }

  // False when the read ends here (a compressed chunk of a recording that was not closed).
  bool read_chunk(const Record& record, bool unindexed) {
    const std::string compression_name = record.header.text("compression");
    const Compression compression =
        parse_compression(compression_name, ChunkContainer::ros1, file_.name(), record.offset);
    const std::uint32_t size = record.header.u32("size");
    const std::uint64_t chunk_offset = record.offset;
    // Before anything is read or allocated for it (a lie first: it says more than a bomb).
    if (compression == Compression::lz4 &&
        size > static_cast<std::uint64_t>(record.data_len) * kLz4MaxExpansion + 4096)
      file_.fail(chunk_offset, "an lz4 chunk of " + std::to_string(record.data_len) +
                                   " bytes claims " + std::to_string(size) +
                                   " uncompressed bytes, more than lz4 can expand to");
    const std::uint64_t holds = compression == Compression::none ? record.data_len : size;
    if (holds > limits_.max_chunk_bytes)
      file_.fail(chunk_offset, "a " + compression_name + " chunk of " + std::to_string(holds) +
                                   " bytes uncompressed, more than the " +
                                   std::to_string(limits_.max_chunk_bytes) +
                                   " a chunk may take (256 MiB, or an eighth of the memory "
                                   "limit): a decompression bomb, or a bag with huge chunks");
    const std::uint64_t data_offset = record.data_offset;
    if (record.data_len == 0 && size == 0 && compression != Compression::none && unindexed) {
      // rosbag writes a chunk's sizes when it closes the chunk: these are its placeholders,
      // and what follows is compressed data, not records.
      contents_.warnings.push_back("The " + compression_name + " chunk at byte " +
                                   std::to_string(chunk_offset) +
                                   " was never finished (a recording that was cut off): read "
                                   "up to there.");
      return false;
    }
    const std::span<const std::uint8_t> raw = file_.read_data(raw_);
    if (compression == Compression::none) {
      if (size != raw.size())
        file_.fail(chunk_offset, "an uncompressed chunk of " + std::to_string(raw.size()) +
                                     " bytes states its size as " + std::to_string(size));
      read_chunk_records(raw, data_offset);
      return true;
    }
    check_expansion(compression, raw, size, chunk_offset);
    decompress(compression, raw, size, plain_, file_.name(), chunk_offset);
    try {
      read_chunk_records(plain_, 0);
    } catch (const InputError& e) {
      throw InputError("at byte " + std::to_string(chunk_offset) + ": in its " + compression_name +
                           " chunk, uncompressed " + e.message(),
                       e.file());
    }
    return true;
  }

  // A lying size must not allocate what the data cannot hold.
  void check_expansion(Compression compression, std::span<const std::uint8_t> raw,
                       std::uint32_t size, std::uint64_t chunk_offset) {
    const std::uint64_t claimed = size;
    if (compression == Compression::lz4 && claimed > raw.size() * kLz4MaxExpansion + 4096)
      file_.fail(chunk_offset, "an lz4 chunk of " + std::to_string(raw.size()) + " bytes claims " +
                                   std::to_string(claimed) +
                                   " uncompressed bytes, more than lz4 can expand to");
    if (compression == Compression::bz2 && claimed > raw.size() * kBz2TrustedExpansion + 65536) {
      const std::uint64_t actual = bz2_size(raw, claimed);
      if (actual != claimed)
        file_.fail(chunk_offset, "a bz2 chunk claims " + std::to_string(claimed) +
                                     " uncompressed bytes but holds " +
                                     (actual > claimed ? "more" : std::to_string(actual)));
    }
  }

  // The connection and message records of one chunk's (uncompressed) data; `base` is its file
  // offset, 0 when it was decompressed (offsets are then within the uncompressed data).
  void read_chunk_records(std::span<const std::uint8_t> data, std::uint64_t base) {
    ByteCursor cursor(data, file_.name(), base);
    while (!cursor.at_end()) {
      const std::uint64_t record_offset = cursor.offset();
      const auto header_len = cursor.read<std::uint32_t>("a record's header length");
      if (header_len > cursor.remaining())
        file_.fail(record_offset, "a record's header of " + std::to_string(header_len) +
                                      " bytes runs past the end of its chunk (" +
                                      std::to_string(cursor.remaining()) + " bytes remain)");
      header_.parse(cursor.bytes(header_len, "a record header"), file_.name(), record_offset + 4);
      const auto data_len = cursor.read<std::uint32_t>("a record's data length");
      if (data_len > cursor.remaining())
        file_.fail(record_offset, "a record's data of " + std::to_string(data_len) +
                                      " bytes runs past the end of its chunk (" +
                                      std::to_string(cursor.remaining()) + " bytes remain)");
      const std::uint64_t data_offset = cursor.offset();
      const std::span<const std::uint8_t> record_data = cursor.bytes(data_len, "a record's data");
      switch (header_.op()) {
        case Op::connection:
          add_connection(parse_connection(header_, record_data, file_.name(), data_offset),
                         base == 0 ? 0 : record_offset);
          break;
        case Op::message_data:
          read_message(header_, record_data, base == 0 ? 0 : record_offset);
          break;
        default:
          header_.fail("a record of op 0x" + hex(header_.op()) +
                       " inside a chunk (only connections and messages belong there)");
      }
    }
  }

  // `offset`: the record's, 0 inside a compressed chunk (the error then names the chunk).
  void add_connection(Connection connection, std::uint64_t offset) {
    if (const auto known = index_of_.find(connection.id); known != index_of_.end()) {
      // rosbag writes each connection twice, in its first chunk and in the index: the same.
      const BagTopic& topic = contents_.topics[known->second];
      if (topic.topic != connection.topic || topic.type != connection.type)
        file_.fail(offset, "connection " + std::to_string(connection.id) +
                               " is declared again as another topic or type (" + connection.topic +
                               ", " + connection.type +
                               "): which one its messages belong to would be a guess");
      return;
    }
    index_of_.emplace(connection.id, contents_.topics.size());
    wanted_.push_back(topics_ == nullptr || topics_->contains(connection.topic));
    BagTopic topic;
    topic.id = connection.id;
    topic.topic = std::move(connection.topic);
    topic.type = std::move(connection.type);
    topic.encoding = MessageEncoding::ros1;
    contents_.topics.push_back(std::move(topic));
  }

  void read_message(const RecordHeader& header, std::span<const std::uint8_t> data,
                    std::uint64_t record_offset) {
    const std::uint32_t conn = header.u32("conn");
    const std::int64_t time = header.time_ns("time");
    const auto found = index_of_.find(conn);
    if (found == index_of_.end())
      header.fail("a message on connection " + std::to_string(conn) +
                  ", which no connection record declares before it");
    BagTopic& topic = contents_.topics[found->second];
    if (topic.messages++ == 0) {
      topic.first_ns = topic.last_ns = time;
    } else {
      topic.first_ns = std::min(topic.first_ns, time);
      topic.last_ns = std::max(topic.last_ns, time);
    }
    if (contents_.messages++ == 0) {
      contents_.start_ns = contents_.end_ns = time;
    } else {
      contents_.start_ns = std::min(contents_.start_ns, time);
      contents_.end_ns = std::max(contents_.end_ns, time);
    }
    if (visit_ != nullptr && wanted_[found->second])
      (*visit_)(topic, BagMessageView{conn, time, data, record_offset});
  }

  BagFile& file_;
  const BagVisitor* visit_;
  const std::set<std::string>* topics_;
  BagReadLimits limits_;
  BagContents contents_;
  std::unordered_map<std::uint32_t, std::size_t> index_of_;  // connection id -> topics index
  std::vector<bool> wanted_;
  RecordHeader header_;
  std::vector<std::uint8_t> raw_;    // one chunk as stored
  std::vector<std::uint8_t> plain_;  // one chunk decompressed
  std::vector<std::uint8_t> data_;   // a top-level record's data
};

}  // namespace

BagContents scan_bag(BagFile& file, const BagVisitor* visit, const std::set<std::string>* topics,
                     const BagReadLimits& limits) {
  return Scan(file, visit, topics, limits).run();
}

}  // namespace floorgrid::io::ros1
