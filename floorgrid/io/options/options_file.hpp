#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "floorgrid/core/option_visitor.hpp"

namespace floorgrid::io {

/// A tree of options to print or read: visits its top-level fields and groups.
using OptionTree = std::function<void(OptionVisitor&)>;

/// Every option of `tree` as YAML with its current value, unit and documentation in comments:
/// what `config --dump` prints and `read_options_yaml` reads back.
std::string options_yaml(const OptionTree& tree, const std::string& header = {});

/// Every option of `tree` as JSON: nested objects whose leaves are
/// {"default": value, "unit": "...", "description": "...", "choices": [...]}.
std::string options_json(const OptionTree& tree);

/// Sets the options of `tree` given in the YAML file `path` (options left out keep their
/// values). InputError naming the file, the line and the option's dotted path for a syntax
/// error, an unknown key, a value of the wrong type, a negative count, a text not among its
/// choices, or a group that is not a mapping.
void read_options_yaml(const std::filesystem::path& path, const OptionTree& tree);

/// The same for options given as YAML (or JSON) text; errors name `source` as the file.
void read_options_yaml_text(const std::string& text, const std::string& source,
                            const OptionTree& tree);

}  // namespace floorgrid::io
