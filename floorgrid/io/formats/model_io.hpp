#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>

#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::io {

/// Writes a fitted model's file (JSON, SPEC "Model file") atomically.
void write_model(const PointMapping& mapping, const std::filesystem::path& path);

/// Bytes a model file may hold at most (a fitted model keeps at most a few ten thousand points:
/// a few MB).
inline constexpr std::uint64_t kMaxModelFileBytes = 256ull << 20;

/// Reads a model file; InputError naming the file and the field for a file that is not JSON,
/// not a floorgrid model, of another version, of an unknown model, or malformed.
/// `options`: the models' settings the file does not hold, and limits on what loading may
/// derive (see load_mapping).
std::unique_ptr<PointMapping> read_model(const std::filesystem::path& path,
                                         const MappingOptions& options = {});

}  // namespace floorgrid::io
