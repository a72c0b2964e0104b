#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "floorgrid/io/plans/dxf_tokens.hpp"

namespace floorgrid::io {

/// One DXF entity as written: its type and groups, read lazily by the geometry code.
struct DxfEntity {
  std::string type;                 ///< upper-case type, e.g. "LINE"
  long line = 0;                    ///< 1-based line of the `0` group that starts it
  std::vector<DxfGroup> groups;     ///< the groups after the type, in file order
  std::vector<DxfEntity> children;  ///< VERTEX of an old-style POLYLINE, ATTRIB of an INSERT

  /// The first group with `code`, or nullptr.
  const DxfGroup* find(int code) const;
  /// The layer (group 8), "0" when absent.
  std::string layer() const;
  /// The string of group `code`, or `fallback`.
  std::string text(int code, std::string_view fallback = {}) const;
  /// The number of group `code`, or `fallback`; InputError with the line when not a number.
  double number(int code, double fallback = 0.0) const;
  /// The integer of group `code`, or `fallback`; InputError with the line when not an integer.
  long integer(int code, long fallback = 0) const;
  /// The point of groups (`x_code`, `x_code + 10`, `x_code + 20`), missing coordinates 0.
  Eigen::Vector3d point(int x_code) const;
  /// The extrusion direction (groups 210/220/230), (0, 0, 1) when absent.
  Eigen::Vector3d extrusion() const;
};

/// A block definition.
struct DxfBlock {
  std::string name;                                ///< as written
  Eigen::Vector3d base = Eigen::Vector3d::Zero();  ///< base point, block coordinates
  long flags = 0;                                  ///< group 70: 4 external reference, 1 anonymous
  long line = 0;                                   ///< line of its BLOCK group
  std::vector<DxfEntity> entities;                 ///< its contents
};

/// An ASCII DXF drawing as groups: what the reader needs of its sections.
struct DxfDocument {
  std::map<std::string, std::vector<DxfGroup>> header;  ///< `$NAME` -> its value groups
  std::vector<std::string> layer_table;                 ///< names in the LAYER table
  std::map<std::string, DxfBlock> blocks;               ///< by upper-case name
  std::vector<DxfEntity> entities;                      ///< the ENTITIES section
  std::vector<std::string> warnings;                    ///< oddities that did not stop reading

  /// The block named `name` (case-insensitive, as in AutoCAD), or nullptr.
  const DxfBlock* find_block(std::string_view name) const;
  /// The first value group of header variable `name`, or nullptr.
  const DxfGroup* header_value(const std::string& name, int code) const;
};

/// Builds the document from groups (see tokenize_dxf). Throws InputError with the line when the
/// structure is broken: groups outside a section, a section or block that never ends, no `0 EOF`
/// (a truncated file).
DxfDocument parse_dxf_document(const std::vector<DxfGroup>& groups);

/// ASCII upper case, for case-insensitive DXF names.
std::string upper_ascii(std::string_view text);

}  // namespace floorgrid::io
