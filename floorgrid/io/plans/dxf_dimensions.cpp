#include "floorgrid/io/plans/dxf_dimensions.hpp"

#include <cctype>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

namespace {

constexpr double kInch = 0.0254;

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_alpha(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) != 0;
}

/// A read position in a text.
struct Cursor {
  std::string_view text;
  std::size_t at = 0;

  char peek(std::size_t ahead = 0) const {
    return at + ahead < text.size() ? text[at + ahead] : '\0';
  }
  void skip_spaces() {
    while (peek() == ' ' || peek() == '\t') {
      ++at;
    }
  }
  /// Digits with an optional decimal part (`.`, or `,` when `comma`), as a number.
  std::optional<double> number(bool comma = false) {
    if (!is_digit(peek())) {
      return std::nullopt;
    }
    double value = 0.0;
    while (is_digit(peek())) {
      value = 10.0 * value + (text[at++] - '0');
    }
    if ((peek() == '.' || (comma && peek() == ',')) && is_digit(peek(1))) {
      ++at;
      double scale = 0.1;
      while (is_digit(peek())) {
        value += scale * (text[at++] - '0');
        scale /= 10.0;
      }
    }
    return value;
  }
  /// `a/b` (or `a#b`, as old AutoCAD stacks fractions) with a non-zero b.
  std::optional<double> fraction() {
    const Cursor start = *this;
    const auto a = number();
    if (a && (peek() == '/' || peek() == '#') && is_digit(peek(1))) {
      ++at;
      const auto b = number();
      if (b && *b > 0.0) {
        return *a / *b;
      }
    }
    *this = start;
    return std::nullopt;
  }
};

/// Inches ending in `"`: `7"`, `7.5"`, `7 1/2"`, `1/2"`.
std::optional<double> inches(Cursor& c) {
  const Cursor start = c;
  std::optional<double> value = c.fraction();
  if (!value) {
    value = c.number();
    if (value) {
      const Cursor before = c;
      c.skip_spaces();
      if (const auto part = c.fraction()) {
        *value += *part;
      } else {
        c = before;
      }
    }
  }
  c.skip_spaces();
  if (value && c.peek() == '"') {
    ++c.at;
    return value;
  }
  c = start;
  return std::nullopt;
}

/// A length starting at the cursor, in metres.
std::optional<double> length_at(Cursor c) {
  {
    Cursor feet_cursor = c;
    const auto feet = feet_cursor.number();
    feet_cursor.skip_spaces();
    if (feet && feet_cursor.peek() == '\'' && feet_cursor.peek(1) != '\'') {
      ++feet_cursor.at;
      feet_cursor.skip_spaces();
      if (feet_cursor.peek() == '-') {
        ++feet_cursor.at;
        feet_cursor.skip_spaces();
      }
      const double more = inches(feet_cursor).value_or(0.0);
      return (12.0 * *feet + more) * kInch;
    }
  }
  {
    Cursor inch_cursor = c;
    if (const auto value = inches(inch_cursor)) {
      return *value * kInch;
    }
  }
  const auto value = c.number(true);
  c.skip_spaces();
  if (!value) {
    return std::nullopt;
  }
  const auto unit_is = [&](std::string_view unit) {
    for (std::size_t i = 0; i < unit.size(); ++i) {
      if (std::tolower(static_cast<unsigned char>(c.peek(i))) != unit[i]) {
        return false;
      }
    }
    return !is_alpha(c.peek(unit.size()));
  };
  if (unit_is("mm")) {
    return *value * 0.001;
  }
  if (unit_is("cm")) {
    return *value * 0.01;
  }
  if (unit_is("m")) {
    return *value;
  }
  return std::nullopt;
}

}  // namespace

std::string plain_dxf_text(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const char next = i + 1 < text.size() ? text[i + 1] : '\0';
    if (c == '\\' && next != '\0') {
      ++i;
      switch (next) {
        case 'P':
        case '~':
        case 'X':
          out += ' ';
          break;
        case '\\':
        case '{':
        case '}':
          out += next;
          break;
        case 'S': {  // stacked fraction up to ';': "1/2", "1#2" or "1^2"
          const std::size_t end = text.find(';', i + 1);
          std::string stack(text.substr(i + 1, end == std::string_view::npos ? end : end - i - 1));
          for (char& s : stack) {
            s = s == '#' || s == '^' ? '/' : s;
          }
          out += " " + stack;
          i = end == std::string_view::npos ? text.size() : end;
          break;
        }
        case 'A':
        case 'C':
        case 'c':
        case 'H':
        case 'W':
        case 'Q':
        case 'T':
        case 'F':
        case 'f':
        case 'p':
        case 'a': {  // a formatting code with a value up to ';'
          const std::size_t end = text.find(';', i + 1);
          i = end == std::string_view::npos ? text.size() : end;
          break;
        }
        case 'U':  // \U+XXXX: a character that no length uses
          out += '?';
          i += text.substr(i + 1, 1) == "+" ? 5 : 0;
          break;
        default:  // \L \l \O \o \K \k and unknown codes: on/off switches
          break;
      }
    } else if (c == '{' || c == '}') {
      continue;
    } else if (c == '%' && next == '%' && i + 2 < text.size()) {
      const char code = static_cast<char>(std::tolower(static_cast<unsigned char>(text[i + 2])));
      i += 2;
      if (code == 'd') {
        out += " deg";
      } else if (code == '%') {
        out += '%';
      } else if (is_digit(code)) {
        while (i + 1 < text.size() && is_digit(text[i + 1])) {
          ++i;
        }
      }
    } else {
      out += c;
    }
  }
  return out;
}

std::optional<double> stated_length_m(std::string_view plain_text) {
  for (std::size_t i = 0; i < plain_text.size(); ++i) {
    const char before = i > 0 ? plain_text[i - 1] : ' ';
    if (!is_digit(plain_text[i]) || is_digit(before) || before == '.' || before == ',' ||
        before == '/' || is_alpha(before)) {
      continue;
    }
    if (const auto metres = length_at(Cursor{plain_text, i}); metres && *metres > 0.0) {
      return metres;
    }
  }
  return std::nullopt;
}

std::optional<StatedLength> dimension_stated_length(const DxfEntity& e, const DxfDocument& doc,
                                                    const Eigen::Affine3d& T) {
  const auto world_xy = [&](const Eigen::Vector3d& p) -> Eigen::Vector2d {
    return (T * p).head<2>();
  };
  const Eigen::Matrix2d A = T.linear().topLeftCorner<2, 2>();
  long kind = 0;
  double measured = 0.0;
  try {
    kind = e.integer(70, 0) & 7;  // 0 rotated, 1 aligned, 2 angular, 3 diameter, 4 radius, ...
    if (kind != 0 && kind != 1 && kind != 3 && kind != 4) {
      return std::nullopt;  // angles and ordinates are no lengths between points
    }
    if (e.find(42) != nullptr) {
      measured = e.number(42) * std::sqrt(std::abs(A.determinant()));
    } else if (kind == 0 || kind == 1) {
      const Eigen::Vector2d d = world_xy(e.point(14)) - world_xy(e.point(13));
      const double a = e.number(50) * std::numbers::pi / 180.0;
      const Eigen::Vector2d along = A * Eigen::Vector2d(std::cos(a), std::sin(a));
      measured = kind == 0 ? std::abs(d.dot(along.normalized())) : d.norm();
    } else {
      measured = (world_xy(e.point(15)) - world_xy(e.point(10))).norm();
    }
  } catch (const InputError&) {
    return std::nullopt;
  }
  if (!(measured > 0.0) || !std::isfinite(measured)) {
    return std::nullopt;
  }
  std::vector<std::string> texts;
  const std::string override_text = e.text(1);
  if (!override_text.empty() && override_text.find("<>") == std::string::npos) {
    texts.push_back(override_text);
  } else if (const DxfBlock* block = doc.find_block(e.text(2))) {
    for (const DxfEntity& inner : block->entities) {
      if (inner.type == "TEXT") {
        texts.push_back(inner.text(1));
      } else if (inner.type == "MTEXT") {
        std::string text;  // chunks in groups 3, the last in group 1, in file order
        for (const DxfGroup& g : inner.groups) {
          text += g.code == 3 || g.code == 1 ? g.value : std::string();
        }
        texts.push_back(text);
      }
    }
  }
  for (const std::string& text : texts) {
    std::string plain = plain_dxf_text(text);
    if (const auto stated = stated_length_m(plain)) {
      return StatedLength{measured, *stated, std::move(plain)};
    }
  }
  return std::nullopt;
}

}  // namespace floorgrid::io
