#include "floorgrid/io/files/binary_file.hpp"

#include <cerrno>
#include <cstring>
#include <system_error>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

BinaryFile::BinaryFile(const std::filesystem::path& path)
    : name_(path.string()), file_(nullptr, &std::fclose) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError("is a folder, not a file", name_);
  file_.reset(std::fopen(name_.c_str(), "rb"));
  if (!file_)
    throw InputError(std::string("cannot open: ") + std::strerror(errno), name_);
  if (::fseeko(file_.get(), 0, SEEK_END) != 0)
    throw InputError("cannot find its size (not a regular file?)", name_);
  size_ = static_cast<std::uint64_t>(::ftello(file_.get()));
}

void BinaryFile::read(std::uint64_t offset, std::uint64_t count, std::vector<std::uint8_t>& out,
                      const std::string& what) {
  if (offset > size_ || count > size_ - offset)
    throw InputError("at byte " + std::to_string(offset) + ": " + what + " of " +
                         std::to_string(count) + " bytes reaches past the end of the file (" +
                         std::to_string(size_) + " bytes; truncated or corrupt)",
                     name_);
  out.resize(static_cast<std::size_t>(count));
  read(offset, std::span<std::uint8_t>(out), what);
}

void BinaryFile::read(std::uint64_t offset, std::span<std::uint8_t> out, const std::string& what) {
  if (offset > size_ || out.size() > size_ - offset)
    throw InputError("at byte " + std::to_string(offset) + ": " + what + " of " +
                         std::to_string(out.size()) + " bytes reaches past the end of the file (" +
                         std::to_string(size_) + " bytes; truncated or corrupt)",
                     name_);
  if (out.empty())
    return;
  // Sequential reads (a record's length, then its header, then its data) keep stdio's buffer.
  if ((offset != position_ && ::fseeko(file_.get(), static_cast<off_t>(offset), SEEK_SET) != 0) ||
      std::fread(out.data(), 1, out.size(), file_.get()) != out.size()) {
    position_ = ~std::uint64_t{0};
    throw InputError("at byte " + std::to_string(offset) + ": cannot read " + what +
                         " (read error or the file shrank)",
                     name_);
  }
  position_ = offset + out.size();
}

}  // namespace floorgrid::io
