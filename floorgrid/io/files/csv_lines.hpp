#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace floorgrid::io {

/// A small CSV file of numbers read line by line (the pairs and points files): a UTF-8 byte
/// order mark, blank lines and `#` comments are skipped, fields are split at commas and
/// trimmed of blanks.
class CsvLines {
 public:
  /// Reads `path` whole; InputError when it cannot be read.
  explicit CsvLines(const std::filesystem::path& path);

  /// The next line's fields (views into the file's text); false at the end.
  bool next(std::vector<std::string_view>& fields);
  /// The 1-based line of the last line read.
  long line() const { return line_; }
  /// The file, for messages.
  const std::string& file() const { return file_; }

  /// `field` as a finite number whose magnitude is at most `max_abs`; InputError naming the
  /// file, the line and `column` otherwise.
  double number(std::string_view field, const std::string& column, double max_abs) const;

 private:
  std::string file_;
  std::string text_;
  std::string_view rest_;
  long line_ = 0;
};

}  // namespace floorgrid::io
