#include "floorgrid/io/model_io.hpp"

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/atomic_file.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid::io {

void write_model(const PointMapping& mapping, const std::filesystem::path& path) {
  write_file_atomically(path, mapping.to_json().dump(1) + "\n");
}

std::unique_ptr<PointMapping> read_model(const std::filesystem::path& path) {
  const std::string text = read_whole_file(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann reports a byte offset; turn it into a line for the message.
    const std::size_t offset = std::min<std::size_t>(e.byte, text.size());
    const long line =
        1 + static_cast<long>(
                std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
    throw InputError("not valid JSON (" + std::string(e.what()) + ")", path.string(), line);
  }
  return load_mapping(j, path.string());
}

}  // namespace floorgrid::io
