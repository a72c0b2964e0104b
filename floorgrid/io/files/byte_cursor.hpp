#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

/// Reads little-endian values from a byte span, checking every read against the end. A read
/// past the end is an InputError naming the file, the absolute byte offset and `what` was
/// being read: binary containers (bags, MCAP) and message payloads are read through it so that
/// a truncated or lying length never reads out of bounds.
class ByteCursor {
 public:
  /// `bytes` is read from `file`, where bytes[0] lies at byte offset `base_offset`.
  ByteCursor(std::span<const std::uint8_t> bytes, std::string_view file,
             std::uint64_t base_offset = 0)
      : bytes_(bytes), file_(file), base_offset_(base_offset) {}

  /// Bytes not read yet.
  std::size_t remaining() const { return bytes_.size() - position_; }
  /// Bytes read so far (relative to the span's start).
  std::size_t position() const { return position_; }
  /// The file offset of the next byte.
  std::uint64_t offset() const { return base_offset_ + position_; }
  /// True when everything was read.
  bool at_end() const { return position_ == bytes_.size(); }
  /// The file named in errors.
  const std::string& file() const { return file_; }

  /// Throws InputError unless `count` more bytes are there.
  void require(std::size_t count, std::string_view what) const {
    if (count > remaining())
      fail(std::string(what) + " needs " + std::to_string(count) + " bytes but only " +
           std::to_string(remaining()) + " remain (truncated or corrupt)");
  }

  /// A little-endian arithmetic value (integers, float, double).
  template <typename T>
  T read(std::string_view what) {
    static_assert(std::is_arithmetic_v<T>);
    require(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + position_,
                sizeof(T));  // this library is little-endian only
    position_ += sizeof(T);
    return value;
  }

  /// The next `count` bytes as a span (no copy).
  std::span<const std::uint8_t> bytes(std::size_t count, std::string_view what) {
    require(count, what);
    std::span<const std::uint8_t> out = bytes_.subspan(position_, count);
    position_ += count;
    return out;
  }

  /// The next `count` bytes as a string.
  std::string string(std::size_t count, std::string_view what) {
    const std::span<const std::uint8_t> raw = bytes(count, what);
    return {reinterpret_cast<const char*>(raw.data()), raw.size()};
  }

  /// Skips `count` bytes.
  void skip(std::size_t count, std::string_view what) { bytes(count, what); }

  /// Moves the read position to `position` (relative to the span's start), at most its size.
  void seek(std::size_t position, std::string_view what) {
    if (position > bytes_.size())
      fail(std::string(what) + " lies beyond the end of the data");
    position_ = position;
  }

  /// Throws InputError: "file: at byte N: message".
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError("at byte " + std::to_string(offset()) + ": " + message, file_);
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::string file_;
  std::uint64_t base_offset_ = 0;
  std::size_t position_ = 0;
};

}  // namespace floorgrid::io
