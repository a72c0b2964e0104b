#include "floorgrid/io/yaml_document.hpp"

#include <map>
#include <utility>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/atomic_file.hpp"

namespace floorgrid::io {

namespace {

long line_of(const YAML::Node& node) {
  return node.Mark().line >= 0 ? node.Mark().line + 1 : 0;
}

/// Refuses a key given twice in any mapping of `root`. Walks with its own stack (no recursion
/// however deep the nesting) and a budget of visits (aliases may share a node many times over).
void reject_duplicate_keys(const YAML::Node& root, const std::string& file,
                           std::size_t max_visits) {
  std::vector<std::pair<YAML::Node, std::string>> stack{{root, ""}};
  std::size_t visits = 0;
  while (!stack.empty()) {
    auto [node, path] = std::move(stack.back());
    stack.pop_back();
    if (++visits > max_visits)
      throw InputError("holds more nodes than its size can (aliases repeated over and over?)",
                       file);
    if (node.IsMap()) {
      std::map<std::string, long> seen;  // key -> its line
      for (const auto& entry : node) {
        const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
        const std::string key_path = path.empty() ? key : path + "." + key;
        if (entry.first.IsScalar()) {
          const auto [first, added] = seen.emplace(key, line_of(entry.first));
          if (!added) {
            throw InputError("key given twice (first on line " + std::to_string(first->second) +
                                 "): YAML allows a key once per mapping",
                             file, line_of(entry.first), key_path);
          }
        }
        stack.emplace_back(entry.second, key_path);
      }
    } else if (node.IsSequence()) {
      for (std::size_t i = 0; i < node.size(); ++i)
        stack.emplace_back(node[i], path + "[" + std::to_string(i) + "]");
    }
  }
}

}  // namespace

YAML::Node load_yaml_text(const std::string& text, const std::filesystem::path& path) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(text);
  } catch (const YAML::Exception& e) {
    throw InputError("YAML syntax error: " + e.msg, path.string(), e.mark.line + 1);
  }
  if (documents.size() > 1) {
    throw InputError(
        "holds " + std::to_string(documents.size()) +
            " YAML documents (separated by ---), but only one is read: put every key in one",
        path.string(), line_of(documents[1]));
  }
  if (documents.empty())
    return YAML::Node();
  reject_duplicate_keys(documents.front(), path.string(), 1000 + 4 * text.size());
  return documents.front();
}

YAML::Node load_yaml_file(const std::filesystem::path& path) {
  return load_yaml_text(read_whole_file(path, kMaxSettingsFileBytes), path);
}

}  // namespace floorgrid::io
