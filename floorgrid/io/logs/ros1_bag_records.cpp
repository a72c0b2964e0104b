#include "floorgrid/io/logs/ros1_bag_records.hpp"

#include <algorithm>
#include <cstring>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io::ros1 {

void RecordHeader::parse(std::span<const std::uint8_t> bytes, std::string_view file,
                         std::uint64_t offset) {
  fields_.clear();
  if (file_ != file)
    file_ = file;
  offset_ = offset;
  ByteCursor cursor(bytes, file, offset);
  while (!cursor.at_end()) {
    const std::uint32_t length = cursor.read<std::uint32_t>("a header field's length");
    const std::span<const std::uint8_t> field = cursor.bytes(length, "a header field");
    const auto* begin = reinterpret_cast<const char*>(field.data());
    const void* equals = std::memchr(begin, '=', field.size());
    if (equals == nullptr)
      cursor.fail("a header field of " + std::to_string(length) + " bytes has no '='");
    const std::size_t name_size =
        static_cast<std::size_t>(static_cast<const char*>(equals) - begin);
    fields_.push_back({std::string_view(begin, name_size), field.subspan(name_size + 1)});
  }
}

std::span<const std::uint8_t> RecordHeader::find(std::string_view name, std::size_t size) const {
  const auto it =
      std::find_if(fields_.begin(), fields_.end(), [&](const Field& f) { return f.name == name; });
  if (it == fields_.end())
    fail("the record header has no '" + std::string(name) + "' field");
  if (size != 0 && it->value.size() != size)
    fail("the record header's '" + std::string(name) + "' field has " +
         std::to_string(it->value.size()) + " bytes, not " + std::to_string(size));
  return it->value;
}

bool RecordHeader::has(std::string_view name) const {
  return std::any_of(fields_.begin(), fields_.end(),
                     [&](const Field& f) { return f.name == name; });
}

Op RecordHeader::op() const {
  return static_cast<Op>(find("op", 1)[0]);
}

std::uint32_t RecordHeader::u32(std::string_view name) const {
  std::uint32_t value;
  std::memcpy(&value, find(name, 4).data(), 4);
  return value;
}

std::uint64_t RecordHeader::u64(std::string_view name) const {
  std::uint64_t value;
  std::memcpy(&value, find(name, 8).data(), 8);
  return value;
}

std::int64_t RecordHeader::time_ns(std::string_view name) const {
  const std::span<const std::uint8_t> raw = find(name, 8);
  std::uint32_t sec, nsec;
  std::memcpy(&sec, raw.data(), 4);
  std::memcpy(&nsec, raw.data() + 4, 4);
  return ros1::time_ns(sec, nsec);
}

std::string RecordHeader::text(std::string_view name) const {
  const std::span<const std::uint8_t> raw = find(name, 0);
  return {reinterpret_cast<const char*>(raw.data()), raw.size()};
}

std::string RecordHeader::text_or(std::string_view name, std::string_view fallback) const {
  return has(name) ? text(name) : std::string(fallback);
}

void RecordHeader::fail(const std::string& message) const {
  throw InputError("at byte " + std::to_string(offset_) + ": " + message, file_);
}

Connection parse_connection(const RecordHeader& header, std::span<const std::uint8_t> data,
                            std::string_view file, std::uint64_t data_offset) {
  Connection connection;
  connection.id = header.u32("conn");
  connection.topic = header.text("topic");
  RecordHeader details;
  details.parse(data, file, data_offset);
  connection.type = details.text("type");
  connection.md5sum = details.text_or("md5sum", "");
  connection.message_definition = details.text_or("message_definition", "");
  connection.callerid = details.text_or("callerid", "");
  connection.latching = details.text_or("latching", "0") == "1";
  return connection;
}

ChunkInfo parse_chunk_info(const RecordHeader& header, std::span<const std::uint8_t> data,
                           std::string_view file, std::uint64_t data_offset) {
  const std::uint32_t version = header.u32("ver");
  if (version != 1)
    header.fail("chunk info version " + std::to_string(version) + " (known: 1)");
  ChunkInfo info;
  info.chunk_pos = header.u64("chunk_pos");
  info.start_ns = header.time_ns("start_time");
  info.end_ns = header.time_ns("end_time");
  const std::uint32_t count = header.u32("count");
  ByteCursor cursor(data, file, data_offset);
  // A lying count is checked against the data before anything is allocated for it.
  cursor.require(static_cast<std::size_t>(count) * 8, "the chunk info's connection counts");
  info.counts.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    const auto id = cursor.read<std::uint32_t>("a connection id");
    const auto messages = cursor.read<std::uint32_t>("a message count");
    info.counts.emplace_back(id, messages);
  }
  return info;
}

}  // namespace floorgrid::io::ros1
