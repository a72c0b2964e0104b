#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid::io {

/// Reads typed fields from a YAML mapping and turns every failure into an InputError that names
/// the file, the line and the field.
class YamlFields {
 public:
  /// Parses `path`; throws InputError for a missing file, a syntax error (with its line) or a
  /// document that is not a mapping.
  explicit YamlFields(const std::filesystem::path& path);
  /// Wraps an already-parsed mapping `node` of `path` (a nested map such as `laser:`);
  /// `prefix` is put before field names in messages ("laser.").
  YamlFields(YAML::Node node, std::filesystem::path path, std::string prefix);

  /// The file.
  const std::filesystem::path& path() const { return path_; }
  /// Whether `key` is present (and not null).
  bool has(const std::string& key) const;
  /// 1-based line of `key`'s value, or of the document when absent.
  long line_of(const std::string& key) const;
  /// Keys present that are not in `known`, with their lines.
  std::vector<std::pair<std::string, long>> unknown_keys(
      const std::vector<std::string>& known) const;
  /// Throws InputError naming the first key not in `known`.
  void reject_unknown_keys(const std::vector<std::string>& known) const;

  /// A finite number; throws when absent or not a number.
  double number(const std::string& key) const;
  /// A finite number, or nullopt when absent.
  std::optional<double> optional_number(const std::string& key) const;
  /// A string; throws when absent or not a scalar.
  std::string string(const std::string& key) const;
  /// A string, or nullopt when absent.
  std::optional<std::string> optional_string(const std::string& key) const;
  /// A boolean written as 0/1 or true/false; nullopt when absent.
  std::optional<bool> optional_bool(const std::string& key) const;
  /// A sequence of exactly `size` finite numbers (any size when `size` is 0); nullopt when absent.
  std::optional<std::vector<double>> optional_numbers(const std::string& key,
                                                      std::size_t size) const;
  /// A pose [x, y, theta]; nullopt when absent.
  std::optional<Pose2> optional_pose(const std::string& key) const;
  /// A sequence of strings, or a single string taken as a one-element list; nullopt when absent.
  std::optional<std::vector<std::string>> optional_strings(const std::string& key) const;
  /// A nested mapping as fields of its own; nullopt when absent. Throws when not a mapping.
  std::optional<YamlFields> optional_map(const std::string& key) const;

  /// Throws an InputError at `key`'s line with `message`.
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

 private:
  YAML::Node node_;
  std::filesystem::path path_;
  std::string prefix_;
};

}  // namespace floorgrid::io
