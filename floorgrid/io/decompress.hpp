#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace floorgrid::io {

/// Compressions used by bag chunks: ROS 1 bags ("none", "bz2", "lz4"), MCAP ("", "lz4", "zstd").
enum class Compression { none, bz2, lz4, zstd };

/// The compression a container names: "" and "none" -> none, "bz2", "lz4", "zstd". Throws
/// InputError naming `file` and the byte `offset` for any other name ("unknown compression").
Compression parse_compression(std::string_view name, std::string_view file, std::uint64_t offset);

/// Decompresses one chunk into `out` (resized to `uncompressed_size`). lz4 is the LZ4 frame
/// format (ROS 1's roslz4 and MCAP both write it), bz2 a bzip2 stream, zstd a zstd frame.
/// Throws InputError naming `file` and `offset` when the data is corrupt, ends early, or does not
/// decompress to exactly `uncompressed_size` bytes.
void decompress(Compression compression, std::span<const std::uint8_t> in,
                std::size_t uncompressed_size, std::vector<std::uint8_t>& out,
                std::string_view file, std::uint64_t offset);

}  // namespace floorgrid::io
