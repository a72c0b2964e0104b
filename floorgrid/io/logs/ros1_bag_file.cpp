#include "floorgrid/io/logs/ros1_bag_file.hpp"

#include <algorithm>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io::ros1 {
namespace {

// Record headers hold a few short fields (op, conn, topic, times); the long texts of a
// connection are in its data. A header claiming more is corrupt, however large the file.
constexpr std::uint32_t kMaxHeaderBytes = 1u << 20;

std::string printable(std::span<const std::uint8_t> bytes) {
  std::string out;
  for (const std::uint8_t b : bytes)
    out += (b >= 0x20 && b < 0x7f) ? static_cast<char>(b) : '?';
  return out;
}

}  // namespace

BagFile::BagFile(const std::filesystem::path& path) : file_(path) {
  std::vector<std::uint8_t> magic(std::min<std::uint64_t>(size(), kMagic.size()));
  file_.read(0, magic, "the magic");
  if (magic.size() < kMagic.size() ||
      std::string_view(reinterpret_cast<const char*>(magic.data()), magic.size()) != kMagic)
    fail(0, "not a ROS 1 bag of format 2.0: it starts with '" + printable(magic) +
                "', not '#ROSBAG V2.0'");
  const Record& bag_header = require_record(kMagic.size());
  if (bag_header.header.op() != Op::bag_header)
    fail(bag_header.offset, "the first record is not the bag header (op 0x03)");
  index_pos_ = bag_header.header.u64("index_pos");
  conn_count_ = bag_header.header.u32("conn_count");
  chunk_count_ = bag_header.header.u32("chunk_count");
  first_record_ = bag_header.end();
}

std::uint32_t BagFile::read_u32_at(std::uint64_t offset) {
  std::uint8_t raw[4];
  file_.read(offset, raw, "a length");
  return static_cast<std::uint32_t>(raw[0]) | static_cast<std::uint32_t>(raw[1]) << 8 |
         static_cast<std::uint32_t>(raw[2]) << 16 | static_cast<std::uint32_t>(raw[3]) << 24;
}

const Record& BagFile::read_record(std::uint64_t offset) {
  Record& r = record_;
  r.offset = offset;
  r.data_offset = offset;
  r.data_len = 0;
  r.truncated.clear();
  const std::uint64_t left = offset <= size() ? size() - offset : 0;
  if (left < 4) {
    r.truncated = "the file ends inside the record there: its header length needs 4 bytes but " +
                  std::to_string(left) + " remain";
    return r;
  }
  const std::uint32_t header_len = read_u32_at(offset);
  if (header_len > kMaxHeaderBytes)
    fail(offset, "a record header of " + std::to_string(header_len) +
                     " bytes (corrupt: headers are at most " + std::to_string(kMaxHeaderBytes) +
                     ")");
  if (std::uint64_t{header_len} + 8 > left) {
    r.truncated = "the file ends inside the record there: its header of " +
                  std::to_string(header_len) + " bytes and data length need " +
                  std::to_string(std::uint64_t{header_len} + 8) + " bytes but " +
                  std::to_string(left) + " remain";
    return r;
  }
  file_.read(offset + 4, header_len, header_bytes_, "a record header");
  r.header.parse(header_bytes_, name(), offset + 4);
  r.data_len = read_u32_at(offset + 4 + header_len);
  r.data_offset = offset + 8 + header_len;
  if (r.data_len > size() - r.data_offset)
    r.truncated = "the file ends inside the record there: its data of " +
                  std::to_string(r.data_len) + " bytes runs past the end of the file (" +
                  std::to_string(size() - r.data_offset) + " bytes remain)";
  return r;
}

const Record& BagFile::require_record(std::uint64_t offset) {
  const Record& r = read_record(offset);
  if (!r.truncated.empty())
    fail(offset, r.truncated + " (truncated or corrupt)");
  return r;
}

std::span<const std::uint8_t> BagFile::read_data(std::vector<std::uint8_t>& buffer) {
  // read_record checked that the data lies within the file before this allocates for it.
  if (!record_.truncated.empty())
    fail(record_.offset, record_.truncated + " (truncated or corrupt)");
  file_.read(record_.data_offset, record_.data_len, buffer, "a record's data");
  return buffer;
}

void BagFile::fail(std::uint64_t offset, const std::string& message) const {
  throw InputError("at byte " + std::to_string(offset) + ": " + message, name());
}

}  // namespace floorgrid::io::ros1
