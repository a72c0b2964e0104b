#include "floorgrid/io/files/yaml_document.hpp"

#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"

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

/// Where each document of a YAML text starts (its first node's mark), from the parser's events.
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> documents;  // where each `---` (or the text) starts one
  std::vector<YAML::Mark> first_nodes;

  void OnDocumentStart(const YAML::Mark& mark) override { documents.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string&) override {
    node(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnMapEnd() override {}

 private:
  void node(const YAML::Mark& mark) {
    if (first_nodes.size() < documents.size())
      first_nodes.push_back(mark);
  }
};

/// Counts the documents of `text`, refusing a token the parser cannot move past. yaml-cpp 0.7's
/// LoadAll never returns on a ',' outside [ ] or { } (",a", "[a],b"): it starts one empty
/// document after another at the same place. Here a document that starts where the one before
/// it started is that stray token, and a syntax error.
std::size_t count_documents(const std::string& text, const std::filesystem::path& path) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DocumentStarts starts;
  while (parser.HandleNextDocument(starts)) {
    const auto& docs = starts.documents;
    if (docs.size() >= 2 && docs.back().pos <= docs[docs.size() - 2].pos) {
      const auto at = static_cast<std::size_t>(std::max(docs.back().pos, 0));
      const std::string token = at < text.size() ? std::string(1, text[at]) : "end of text";
      throw InputError(
          "YAML syntax error: unexpected '" + token + "' (a ',' belongs inside [ ] or { })",
          path.string(), docs.back().line + 1);
    }
  }
  if (starts.documents.size() > 1) {
    const YAML::Mark& second =
        starts.first_nodes.size() > 1 ? starts.first_nodes[1] : starts.documents[1];
    throw InputError(
        "holds " + std::to_string(starts.documents.size()) +
            " YAML documents (separated by ---), but only one is read: put every key in one",
        path.string(), second.line + 1);
  }
  return starts.documents.size();
}

}  // namespace

YAML::Node load_yaml_text(const std::string& text, const std::filesystem::path& path) {
  YAML::Node document;
  try {
    if (count_documents(text, path) == 0)
      return YAML::Node();
    // A second parse builds the node: yaml-cpp keeps its node builder (the event handler
    // LoadAll uses) out of its installed headers. Settings files are small.
    document = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError("YAML syntax error: " + e.msg, path.string(), e.mark.line + 1);
  }
  reject_duplicate_keys(document, path.string(), 1000 + 4 * text.size());
  return document;
}

YAML::Node load_yaml_file(const std::filesystem::path& path) {
  return load_yaml_text(read_whole_file(path, kMaxSettingsFileBytes), path);
}

}  // namespace floorgrid::io
