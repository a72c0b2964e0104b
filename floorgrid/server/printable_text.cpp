#include "floorgrid/server/printable_text.hpp"

namespace floorgrid::server {

namespace {

bool is_control(unsigned char c) {
  return c < 0x20 || c == 0x7f;
}

}  // namespace

std::string printable_text(std::string_view text, std::size_t max_bytes) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  const std::string_view shown = text.substr(0, max_bytes);
  out.reserve(shown.size() + 8);
  for (const char c : shown) {
    const auto u = static_cast<unsigned char>(c);
    if (is_control(u) || u >= 0x80 || c == '%') {
      out += '%';
      out += kHex[u >> 4];
      out += kHex[u & 0x0f];
    } else {
      out += c;
    }
  }
  if (shown.size() < text.size())
    out += "...";
  return out;
}

bool has_control_byte(std::string_view text) {
  for (const char c : text) {
    if (is_control(static_cast<unsigned char>(c)))
      return true;
  }
  return false;
}

}  // namespace floorgrid::server
