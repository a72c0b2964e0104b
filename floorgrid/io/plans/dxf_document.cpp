#include "floorgrid/io/plans/dxf_document.hpp"

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

namespace {

/// Walks the groups of a file: the position and the end-of-data checks.
class GroupCursor {
 public:
  explicit GroupCursor(const std::vector<DxfGroup>& groups) : groups_(groups) {}

  bool done() const { return pos_ >= groups_.size(); }
  const DxfGroup& peek() const { return groups_[pos_]; }
  const DxfGroup& take() { return groups_[pos_++]; }
  /// Whether the next group is `0 <keyword>`.
  bool at(std::string_view keyword) const {
    return !done() && peek().code == 0 && peek().trimmed() == keyword;
  }
  /// The line of the last group, for "the file ends here" messages.
  long last_line() const { return groups_.empty() ? 1 : groups_.back().line + 1; }
  /// Throws the truncation error when there are no groups left.
  void require_more(const std::string& inside) const {
    if (done()) {
      throw InputError("the file ends inside " + inside + ": it is truncated (no ENDSEC/EOF)", {},
                       last_line());
    }
  }

 private:
  const std::vector<DxfGroup>& groups_;
  std::size_t pos_ = 0;
};

/// Reads one entity starting at its `0 <TYPE>` group.
DxfEntity read_entity(GroupCursor& cursor) {
  const DxfGroup& head = cursor.take();
  DxfEntity entity;
  entity.type = upper_ascii(head.trimmed());
  entity.line = head.line;
  while (!cursor.done() && cursor.peek().code != 0) {
    entity.groups.push_back(cursor.take());
  }
  return entity;
}

/// Reads entities until a `0` group with one of the stop keywords (not consumed). Old-style
/// POLYLINEs take their VERTEXes and INSERTs their ATTRIBs as children, up to SEQEND.
std::vector<DxfEntity> read_entities(GroupCursor& cursor, std::string_view stop,
                                     const std::string& inside,
                                     std::vector<std::string>& warnings) {
  std::vector<DxfEntity> entities;
  for (;;) {
    cursor.require_more(inside);
    if (cursor.at(stop) || cursor.at("ENDSEC")) {
      return entities;
    }
    if (cursor.peek().code != 0) {
      throw InputError("expected an entity (a 0 group) in " + inside + ", got group code " +
                           std::to_string(cursor.peek().code),
                       {}, cursor.peek().line);
    }
    DxfEntity entity = read_entity(cursor);
    const std::string_view child = entity.type == "POLYLINE" ? "VERTEX"
                                   : entity.type == "INSERT" ? "ATTRIB"
                                                             : "";
    if (!child.empty()) {
      while (cursor.at(child)) {
        entity.children.push_back(read_entity(cursor));
      }
      if (cursor.at("SEQEND")) {
        read_entity(cursor);
      } else if (!entity.children.empty() || entity.type == "POLYLINE") {
        warnings.push_back(entity.type + " at line " + std::to_string(entity.line) +
                           " has no SEQEND");
      }
    }
    entities.push_back(std::move(entity));
  }
}

void read_header(GroupCursor& cursor, DxfDocument& doc) {
  std::vector<DxfGroup>* current = nullptr;
  for (;;) {
    cursor.require_more("the HEADER section");
    if (cursor.at("ENDSEC")) {
      return;
    }
    const DxfGroup& group = cursor.take();
    if (group.code == 9) {
      current = &doc.header[std::string(group.trimmed())];
    } else if (current != nullptr) {
      current->push_back(group);
    }
  }
}

void read_tables(GroupCursor& cursor, DxfDocument& doc) {
  bool in_layer_entry = false;
  for (;;) {
    cursor.require_more("the TABLES section");
    if (cursor.at("ENDSEC")) {
      return;
    }
    const DxfGroup& group = cursor.take();
    if (group.code == 0) {
      in_layer_entry = group.trimmed() == "LAYER";
    } else if (in_layer_entry && group.code == 2) {
      doc.layer_table.emplace_back(group.value);
    }
  }
}

void read_blocks(GroupCursor& cursor, DxfDocument& doc) {
  for (;;) {
    cursor.require_more("the BLOCKS section");
    if (cursor.at("ENDSEC")) {
      return;
    }
    if (!cursor.at("BLOCK")) {
      // Stray groups between blocks carry nothing we use; skip them.
      cursor.take();
      continue;
    }
    const DxfEntity head = read_entity(cursor);
    DxfBlock block;
    block.name = head.text(2);
    block.base = head.point(10);
    block.flags = head.integer(70, 0);
    block.line = head.line;
    const std::string inside =
        "block \"" + block.name + "\" (from line " + std::to_string(block.line) + ")";
    block.entities = read_entities(cursor, "ENDBLK", inside, doc.warnings);
    if (!cursor.at("ENDBLK")) {
      throw InputError(inside + " has no ENDBLK", {}, cursor.peek().line);
    }
    read_entity(cursor);
    const std::string key = upper_ascii(block.name);
    if (doc.blocks.count(key) != 0) {
      doc.warnings.push_back("block \"" + block.name + "\" is defined twice (lines " +
                             std::to_string(doc.blocks[key].line) + " and " +
                             std::to_string(block.line) + "); the first definition is used");
      continue;
    }
    doc.blocks.emplace(key, std::move(block));
  }
}

void skip_section(GroupCursor& cursor, const std::string& name) {
  for (;;) {
    cursor.require_more("the " + name + " section");
    if (cursor.at("ENDSEC")) {
      return;
    }
    cursor.take();
  }
}

}  // namespace

const DxfGroup* DxfEntity::find(int code) const {
  for (const DxfGroup& g : groups) {
    if (g.code == code) {
      return &g;
    }
  }
  return nullptr;
}

std::string DxfEntity::layer() const {
  const DxfGroup* g = find(8);
  return g != nullptr && !g->trimmed().empty() ? std::string(g->trimmed()) : std::string("0");
}

std::string DxfEntity::text(int code, std::string_view fallback) const {
  const DxfGroup* g = find(code);
  return std::string(g != nullptr ? g->trimmed() : fallback);
}

double DxfEntity::number(int code, double fallback) const {
  const DxfGroup* g = find(code);
  return g != nullptr ? group_double(*g) : fallback;
}

long DxfEntity::integer(int code, long fallback) const {
  const DxfGroup* g = find(code);
  return g != nullptr ? group_integer(*g) : fallback;
}

Eigen::Vector3d DxfEntity::point(int x_code) const {
  return {number(x_code), number(x_code + 10), number(x_code + 20)};
}

Eigen::Vector3d DxfEntity::extrusion() const {
  if (find(210) == nullptr && find(220) == nullptr && find(230) == nullptr) {
    return Eigen::Vector3d::UnitZ();
  }
  return {number(210), number(220), number(230)};
}

const DxfBlock* DxfDocument::find_block(std::string_view name) const {
  const auto it = blocks.find(upper_ascii(name));
  return it == blocks.end() ? nullptr : &it->second;
}

const DxfGroup* DxfDocument::header_value(const std::string& name, int code) const {
  const auto it = header.find(name);
  if (it == header.end()) {
    return nullptr;
  }
  for (const DxfGroup& g : it->second) {
    if (g.code == code) {
      return &g;
    }
  }
  return nullptr;
}

std::string upper_ascii(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'a' && c <= 'z') {
      c = static_cast<char>(c - 'a' + 'A');
    }
  }
  return out;
}

DxfDocument parse_dxf_document(const std::vector<DxfGroup>& groups) {
  DxfDocument doc;
  GroupCursor cursor(groups);
  for (;;) {
    if (cursor.done()) {
      throw InputError("the file ends without the 0/EOF marker: it is truncated", {},
                       cursor.last_line());
    }
    const DxfGroup& group = cursor.take();
    if (group.code == 999) {
      continue;  // comment
    }
    if (group.code == 0 && group.trimmed() == "EOF") {
      return doc;
    }
    if (group.code != 0 || group.trimmed() != "SECTION") {
      throw InputError("expected \"0 SECTION\" or \"0 EOF\", got group code " +
                           std::to_string(group.code) + " \"" +
                           std::string(group.trimmed().substr(0, 40)) + "\"",
                       {}, group.line);
    }
    if (cursor.done() || cursor.peek().code != 2) {
      throw InputError("a SECTION must be followed by its name (group code 2)", {},
                       cursor.done() ? cursor.last_line() : cursor.peek().line);
    }
    const std::string name = upper_ascii(cursor.take().trimmed());
    if (name == "HEADER") {
      read_header(cursor, doc);
    } else if (name == "TABLES") {
      read_tables(cursor, doc);
    } else if (name == "BLOCKS") {
      read_blocks(cursor, doc);
    } else if (name == "ENTITIES") {
      std::vector<DxfEntity> entities =
          read_entities(cursor, "ENDSEC", "the ENTITIES section", doc.warnings);
      for (DxfEntity& e : entities) {
        doc.entities.push_back(std::move(e));
      }
    } else {
      skip_section(cursor, name);
    }
    cursor.take();  // ENDSEC
  }
}

}  // namespace floorgrid::io
