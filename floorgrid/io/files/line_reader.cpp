#include "floorgrid/io/files/line_reader.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <fstream>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

namespace {
// zlib decides the same way (gzip magic bytes, else plain), but gzdirect() cannot tell for an
// empty stream, so look at the bytes directly.
bool has_gzip_magic(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[2] = {0, 0};
  in.read(magic, 2);
  return in.gcount() == 2 && magic[0] == '\x1f' && magic[1] == '\x8b';
}
}  // namespace

LineReader::LineReader(const std::filesystem::path& path, const LineReaderOptions& options)
    : file_(path.string()), options_(options) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError("no such file", file_);
  if (std::filesystem::is_directory(path, ec))
    throw InputError("is a folder, not a file", file_);
  errno = 0;
  gz_ = gzopen(file_.c_str(), "rb");
  if (gz_ == nullptr) {
    throw InputError(
        std::string("cannot open: ") + (errno != 0 ? std::strerror(errno) : "out of memory"),
        file_);
  }
  // Buffers for the file's size: a small file (a fuzzer's input, a test's log) costs little,
  // a large one reads in chunks of chunk_bytes (a gzip file decompresses to a few times its
  // size; the buffer grows for a longer line).
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  const std::size_t expected =
      ec ? options_.chunk_bytes : static_cast<std::size_t>(8 * size + 4096);
  gzbuffer(gz_, static_cast<unsigned>(std::min<std::size_t>(256 * 1024, expected)));
  options_.chunk_bytes =
      std::clamp<std::size_t>(std::min(options_.chunk_bytes, expected), 16, INT_MAX / 2);
  buffer_.resize(options_.chunk_bytes);
  try {
    refill();
  } catch (...) {
    gzclose(gz_);
    gz_ = nullptr;
    throw;
  }
  compressed_ = has_gzip_magic(path);
}

LineReader::~LineReader() {
  if (gz_ != nullptr)
    gzclose(gz_);
}

void LineReader::fail(const std::string& message) const {
  // The line being read when the data ran out or broke: past the lines returned and the
  // complete lines still waiting in the buffer.
  const auto waiting = std::count(buffer_.data() + begin_, buffer_.data() + end_, '\n');
  throw InputError(message, file_, static_cast<long>(line_number_) + waiting + 1);
}

void LineReader::refill() {
  // Keep the unread tail, then append freshly decompressed bytes behind it.
  if (begin_ > 0) {
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (buffer_.size() - end_ < options_.chunk_bytes) {
    if (buffer_.size() >= options_.max_line_bytes) {
      fail("line longer than " + std::to_string(options_.max_line_bytes) +
           " bytes: not a text log?");
    }
    buffer_.resize(std::min(buffer_.size() * 2, options_.max_line_bytes + options_.chunk_bytes));
  }
  const auto room = static_cast<unsigned>(std::min<std::size_t>(buffer_.size() - end_, INT_MAX));
  const int got = gzread(gz_, buffer_.data() + end_, room);
  int code = Z_OK;
  const char* what = gzerror(gz_, &code);
  if (got < 0 || (code != Z_OK && code != Z_BUF_ERROR)) {
    if (code == Z_ERRNO)
      fail(std::string("read error: ") + std::strerror(errno));
    fail(std::string("corrupt gzip data (") + what + ")");
  }
  end_ += static_cast<std::size_t>(got);
  // zlib hands out what it could decompress and flags the missing rest as Z_BUF_ERROR: the
  // complete lines before the break are still returned, the error comes where the data ends.
  if (code == Z_BUF_ERROR)
    truncated_ = true;
  if (got == 0 || truncated_)
    eof_ = true;
}

bool LineReader::next(std::string_view& line) {
  for (;;) {
    const char* start = buffer_.data() + begin_;
    const std::size_t available = end_ - begin_;
    const void* newline = std::memchr(start, '\n', available);
    if (newline == nullptr && eof_ && truncated_)
      fail("gzip stream ends early (truncated file?)");
    if (newline != nullptr || (eof_ && available > 0)) {
      const std::size_t length =
          newline != nullptr ? static_cast<std::size_t>(static_cast<const char*>(newline) - start)
                             : available;
      begin_ += newline != nullptr ? length + 1 : length;
      line = std::string_view(start, length);
      if (!line.empty() && line.back() == '\r')
        line.remove_suffix(1);
      ++line_number_;
      return true;
    }
    if (eof_)
      return false;
    refill();
  }
}

}  // namespace floorgrid::io
