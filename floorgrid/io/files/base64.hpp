#pragma once

#include <string>
#include <string_view>

namespace floorgrid::io {

/// `bytes` in base64 (RFC 4648, standard alphabet, `=` padding, no line breaks): what a data URL
/// holds.
std::string base64_encode(std::string_view bytes);

}  // namespace floorgrid::io
