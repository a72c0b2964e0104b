#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>

namespace floorgrid::io {

/// Parses a YAML file of settings (at most kMaxSettingsFileBytes) as one document, strictly:
/// InputError naming the file and the line for a syntax error, a second document (`---`), or a
/// key given twice in one mapping (YAML forbids it; yaml-cpp would keep one silently). An empty
/// file gives a null node.
YAML::Node load_yaml_file(const std::filesystem::path& path);

/// The same for YAML text read from `path`.
YAML::Node load_yaml_text(const std::string& text, const std::filesystem::path& path);

}  // namespace floorgrid::io
