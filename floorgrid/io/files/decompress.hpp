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

/// The containers whose chunks are compressed, each with its own names for the compressions.
enum class ChunkContainer {
  ros1,  ///< ROS 1 bag 2.0: "none", "bz2", "lz4"
  mcap,  ///< MCAP: "" (none), "lz4", "zstd"
};

/// The compression a chunk of `container` names. Throws InputError naming `file` and the byte
/// `offset` for a name the container does not define ("unknown compression", with the known
/// ones): a ROS 1 chunk with an empty name, or an MCAP chunk saying "none" or "bz2", is corrupt.
Compression parse_compression(std::string_view name, ChunkContainer container,
                              std::string_view file, std::uint64_t offset);

/// Decompresses one chunk into `out` (resized to `uncompressed_size`). lz4 is the LZ4 frame
/// format (ROS 1's roslz4 and MCAP both write it), bz2 a bzip2 stream, zstd a zstd frame.
/// Throws InputError naming `file` and `offset` when the data is corrupt, ends early, or does not
/// decompress to exactly `uncompressed_size` bytes.
void decompress(Compression compression, std::span<const std::uint8_t> in,
                std::size_t uncompressed_size, std::vector<std::uint8_t>& out,
                std::string_view file, std::uint64_t offset);

}  // namespace floorgrid::io
