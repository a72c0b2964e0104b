#pragma once

#include <stdexcept>
#include <string>

namespace floorgrid {

/// Bad input from outside (a file, a manifest field, a command-line value). The message names
/// where: the file, the line (1-based, 0 when not applicable) and the field, when known.
/// The CLI maps it to exit status 2.
class InputError : public std::runtime_error {
 public:
  /// `message` says what is wrong; `file`, `line` and `field` say where (empty/0 when unknown).
  explicit InputError(const std::string& message, std::string file = {}, long line = 0,
                      std::string field = {});

  /// The file the bad input came from, or empty.
  const std::string& file() const { return file_; }
  /// The 1-based line in `file`, or 0.
  long line() const { return line_; }
  /// The field (YAML key, CSV column, option name), or empty.
  const std::string& field() const { return field_; }
  /// The message without the location prefix.
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  long line_;
  std::string field_;
  std::string message_;
};

/// The input was read, but the job found no answer in it (an alignment that made no reference
/// pairs). The message says what failed and what to try. The CLI maps it to exit status 3.
class AlignmentFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Formats "file:line: field: message" leaving out the parts that are empty.
std::string format_location(const std::string& message, const std::string& file, long line,
                            const std::string& field);

}  // namespace floorgrid
