#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace floorgrid::io {

/// A binary file read piece by piece at given offsets (containers too large to hold whole:
/// bags, MCAP). Every read is checked against the file's size, so a length read from the file
/// that points past its end is an InputError naming the file and the offset, never a short read
/// or an absurd allocation.
class BinaryFile {
 public:
  /// Opens `path`; throws InputError naming it when it is missing, a folder or unreadable.
  explicit BinaryFile(const std::filesystem::path& path);

  /// The file's size in bytes.
  std::uint64_t size() const { return size_; }
  /// The file's path as given (named in errors).
  const std::string& name() const { return name_; }

  /// Reads `count` bytes at `offset` into `out` (resized; its capacity is reused). Throws
  /// InputError ("at byte N: <what> ... past the end of the file") when they are not all there.
  void read(std::uint64_t offset, std::uint64_t count, std::vector<std::uint8_t>& out,
            const std::string& what);
  /// Reads exactly `out.size()` bytes at `offset` into `out`. Throws as read().
  void read(std::uint64_t offset, std::span<std::uint8_t> out, const std::string& what);

 private:
  std::string name_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
  std::uint64_t size_ = 0;
  std::uint64_t position_ = ~std::uint64_t{0};  // where the stream stands: seek only when needed
};

}  // namespace floorgrid::io
