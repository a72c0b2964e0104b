#include "floorgrid/core/error.hpp"

#include <sstream>
#include <utility>

namespace floorgrid {

std::string format_location(const std::string& message, const std::string& file, long line,
                            const std::string& field) {
  // A stream, not operator+: GCC 12 warns falsely (-Wrestrict) on chained string concatenation.
  std::ostringstream out;
  if (!file.empty()) {
    out << file;
    if (line > 0)
      out << ':' << line;
    out << ": ";
  } else if (line > 0) {
    out << "line " << line << ": ";
  }
  if (!field.empty())
    out << '\'' << field << "': ";
  out << message;
  return out.str();
}

InputError::InputError(const std::string& message, std::string file, long line, std::string field)
    : std::runtime_error(format_location(message, file, line, field)),
      file_(std::move(file)),
      line_(line),
      field_(std::move(field)),
      message_(message) {}

}  // namespace floorgrid
