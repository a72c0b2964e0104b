#include "floorgrid/io/files/decompress.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <cstring>
#include <memory>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {
namespace {

[[noreturn]] void corrupt(std::string_view kind, const std::string& why, std::string_view file,
                          std::uint64_t offset) {
  throw InputError("at byte " + std::to_string(offset) + ": " + std::string(kind) +
                       " chunk does not decompress: " + why,
                   std::string(file));
}

void decompress_lz4(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out,
                    std::string_view file, std::uint64_t offset) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION)))
    throw std::runtime_error("lz4: cannot create a decompression context");
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(
      raw, &LZ4F_freeDecompressionContext);
  std::size_t in_pos = 0, out_pos = 0;
  std::size_t hint = 1;
  while (hint != 0) {
    if (in_pos == in.size())
      corrupt("lz4", "the data ends early", file, offset);
    std::size_t out_size = out.size() - out_pos;
    std::size_t in_size = in.size() - in_pos;
    hint = LZ4F_decompress(context.get(), out.data() + out_pos, &out_size, in.data() + in_pos,
                           &in_size, nullptr);
    if (LZ4F_isError(hint))
      corrupt("lz4", LZ4F_getErrorName(hint), file, offset);
    in_pos += in_size;
    out_pos += out_size;
    if (out_size == 0 && in_size == 0)
      corrupt("lz4", "it holds more than its stated size", file, offset);
  }
  if (out_pos != out.size())
    corrupt("lz4",
            "it gives " + std::to_string(out_pos) + " bytes, not " + std::to_string(out.size()),
            file, offset);
}

void decompress_bz2(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out,
                    std::string_view file, std::uint64_t offset) {
  unsigned int size = static_cast<unsigned int>(out.size());
  if (out.size() > 0xffffffffu)
    corrupt("bz2", "its stated size is over 4 GB", file, offset);
  // bzip2's API takes non-const pointers but does not write through the source.
  const int status =
      BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out.data()), &size,
                                 const_cast<char*>(reinterpret_cast<const char*>(in.data())),
                                 static_cast<unsigned int>(in.size()), 0, 0);
  if (status == BZ_OUTBUFF_FULL)
    corrupt("bz2", "it holds more than its stated size", file, offset);
  if (status != BZ_OK)
    corrupt("bz2", "bzip2 error " + std::to_string(status), file, offset);
  if (size != out.size())
    corrupt("bz2", "it gives " + std::to_string(size) + " bytes, not " + std::to_string(out.size()),
            file, offset);
}

void decompress_zstd(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out,
                     std::string_view file, std::uint64_t offset) {
  const std::size_t size = ZSTD_decompress(out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(size))
    corrupt("zstd", ZSTD_getErrorName(size), file, offset);
  if (size != out.size())
    corrupt("zstd",
            "it gives " + std::to_string(size) + " bytes, not " + std::to_string(out.size()), file,
            offset);
}

}  // namespace

Compression parse_compression(std::string_view name, ChunkContainer container,
                              std::string_view file, std::uint64_t offset) {
  if (container == ChunkContainer::ros1) {
    if (name == "none")
      return Compression::none;
    if (name == "bz2")
      return Compression::bz2;
    if (name == "lz4")
      return Compression::lz4;
  } else {
    if (name.empty())
      return Compression::none;
    if (name == "lz4")
      return Compression::lz4;
    if (name == "zstd")
      return Compression::zstd;
  }
  const bool ros1 = container == ChunkContainer::ros1;
  throw InputError("at byte " + std::to_string(offset) + ": unknown compression '" +
                       std::string(name) + "' for " + (ros1 ? "a ROS 1 bag" : "an MCAP file") +
                       (ros1 ? " (known: none, bz2, lz4)" : " (known: '' for none, lz4, zstd)"),
                   std::string(file));
}

void decompress(Compression compression, std::span<const std::uint8_t> in,
                std::size_t uncompressed_size, std::vector<std::uint8_t>& out,
                std::string_view file, std::uint64_t offset) {
  out.resize(uncompressed_size);
  switch (compression) {
    case Compression::none:
      if (in.size() != uncompressed_size)
        corrupt("uncompressed",
                "it holds " + std::to_string(in.size()) + " bytes, not " +
                    std::to_string(uncompressed_size),
                file, offset);
      if (!in.empty())
        std::memcpy(out.data(), in.data(), in.size());
      return;
    case Compression::bz2:
      return decompress_bz2(in, out, file, offset);
    case Compression::lz4:
      return decompress_lz4(in, out, file, offset);
    case Compression::zstd:
      return decompress_zstd(in, out, file, offset);
  }
}

}  // namespace floorgrid::io
