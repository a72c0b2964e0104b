#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

struct gzFile_s;  // zlib's file handle, declared here so that users need not include zlib.h

namespace floorgrid::io {

/// Options of LineReader.
struct LineReaderOptions {
  std::size_t chunk_bytes = 1 << 20;       ///< bytes decompressed per read
  std::size_t max_line_bytes = 256 << 20;  ///< a longer line is an InputError (not a text file?)
};

/// Reads text lines from a plain or a gzip-compressed file; which one is told by the file's
/// content (the gzip magic bytes), not by its name. A gzip stream that is corrupt or ends
/// early (a truncated download) is an InputError naming the file and the line reached, never
/// a silently shorter file.
class LineReader {
 public:
  /// Opens `path`; throws InputError naming the file when it is missing, a folder or unreadable.
  explicit LineReader(const std::filesystem::path& path, const LineReaderOptions& options = {});
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  /// Reads the next line into `line`, without its "\n" or "\r\n". The view stays valid until the
  /// next call. Returns false at the end of the file. Throws InputError (file, line reached) when
  /// the gzip data is corrupt or ends early, on a read error, or on an overlong line.
  bool next(std::string_view& line);

  /// The 1-based number of the line last returned by next() (0 before the first).
  std::size_t line_number() const { return line_number_; }
  /// True when the file is gzip-compressed.
  bool compressed() const { return compressed_; }
  /// The file's path as given.
  const std::string& file() const { return file_; }

 private:
  void refill();
  [[noreturn]] void fail(const std::string& message) const;

  std::string file_;
  LineReaderOptions options_;
  gzFile_s* gz_ = nullptr;
  std::string buffer_;
  std::size_t begin_ = 0;  // first unread byte in buffer_
  std::size_t end_ = 0;    // one past the last valid byte in buffer_
  std::size_t line_number_ = 0;
  bool eof_ = false;
  bool truncated_ = false;
  bool compressed_ = false;
};

}  // namespace floorgrid::io
