#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace floorgrid::io {

/// One group of an ASCII DXF file: a group code line and the value line after it.
struct DxfGroup {
  int code = 0;       ///< the group code
  std::string value;  ///< the value line without its line ending
  long line = 0;      ///< 1-based line of the group code; the value is on `line + 1`

  /// The value without leading and trailing blanks (names, keywords and numbers are compared so).
  std::string_view trimmed() const;
};

/// The sentinel that starts a binary DXF file.
inline constexpr std::string_view kBinaryDxfSentinel{"AutoCAD Binary DXF\r\n\x1a\0", 22};

/// Whether `bytes` start like a binary DXF file.
bool is_binary_dxf(std::string_view bytes);

/// Splits ASCII DXF text into groups, up to and including the `0 EOF` group (anything after it
/// is ignored), or up to the end of the text when there is none. A UTF-8 byte-order mark and
/// `\r\n` line endings are accepted. Throws InputError (line set, file left empty) when a group
/// code is not an integer or the text ends between a group code and its value.
std::vector<DxfGroup> tokenize_dxf(std::string_view text);

/// The value of `group` as a finite double; throws InputError with the value's line otherwise.
double group_double(const DxfGroup& group);
/// The value of `group` as an integer (an integral decimal like `1.0` is accepted, as some
/// writers print them); throws InputError with the value's line otherwise.
long group_integer(const DxfGroup& group);

}  // namespace floorgrid::io
