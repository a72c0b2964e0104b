#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace floorgrid::server {

/// `text` as an answer may repeat it (a path, a query value): printable ASCII kept, every other
/// byte (a control character, NUL, any byte of UTF-8 or of something that is not) written %XX,
/// and cut to `max_bytes` of `text` with "..." after it. So an answer never carries a raw byte
/// of the request (the JSON library refuses bytes that are not UTF-8; a NUL ends C strings).
std::string printable_text(std::string_view text, std::size_t max_bytes = 200);

/// Whether `text` holds a NUL or another control byte (below 0x20, or 0x7f).
bool has_control_byte(std::string_view text);

}  // namespace floorgrid::server
