#include "floorgrid/io/formats/model_io.hpp"

#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/files/value_json.hpp"
#include "floorgrid/mapping/model_file.hpp"

namespace floorgrid::io {

void write_model(const PointMapping& mapping, const std::filesystem::path& path) {
  write_file_atomically(path, dump_json(mapping.to_model_file(), 1) + "\n");
}

std::unique_ptr<PointMapping> read_model(const std::filesystem::path& path,
                                         const MappingOptions& options) {
  return load_mapping(parse_json(read_whole_file(path, kMaxModelFileBytes), path.string()),
                      path.string(), options);
}

}  // namespace floorgrid::io
