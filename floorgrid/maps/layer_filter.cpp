#include "floorgrid/maps/layer_filter.hpp"

#include <algorithm>
#include <cstddef>

namespace floorgrid {

namespace {

char ascii_lower(char c) {
  return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
}

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

/// Length of the xref prefix `<anything>$<digits>$` ending at the `$` at `close`, or 0.
std::size_t bound_prefix_ending_at(std::string_view layer, std::size_t close) {
  std::size_t open = close;
  while (open > 0 && is_digit(layer[open - 1])) {
    --open;
  }
  if (open == close || open == 0 || layer[open - 1] != '$') {
    return 0;
  }
  return open - 1 > 0 ? close + 1 : 0;  // the xref name before `$n$` must not be empty
}

}  // namespace

std::string_view strip_xref_prefix(std::string_view layer) {
  std::size_t cut = 0;
  const std::size_t bar = layer.rfind('|');
  if (bar != std::string_view::npos && bar > 0) {
    cut = bar + 1;
  }
  // The last `$n$` wins, so prefixes of nested bound xrefs go too.
  for (std::size_t i = layer.size(); i-- > cut;) {
    if (layer[i] != '$') {
      continue;
    }
    const std::size_t end = bound_prefix_ending_at(layer, i);
    if (end > cut && end < layer.size()) {
      cut = end;
      break;
    }
  }
  return layer.substr(cut);
}

bool glob_match(std::string_view pattern, std::string_view text) {
  // Greedy matching with one backtrack point (the last `*`) is exact for `*`/`?` globs and
  // linear in practice, unlike naive recursion, which is exponential on patterns like `*a*a*a*b`.
  std::size_t p = 0, t = 0;
  std::size_t star = std::string_view::npos, star_text = 0;
  while (t < text.size()) {
    if (p < pattern.size() &&
        (pattern[p] == '?' || ascii_lower(pattern[p]) == ascii_lower(text[t]))) {
      ++p;
      ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      star_text = t;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      t = ++star_text;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') {
    ++p;
  }
  return p == pattern.size();
}

bool layer_matches(std::string_view pattern, std::string_view layer) {
  return glob_match(pattern, strip_xref_prefix(layer)) || glob_match(pattern, layer);
}

bool layer_passes(const LayerFilter& filter, std::string_view layer) {
  const auto matches = [&](const std::string& pattern) { return layer_matches(pattern, layer); };
  if (!filter.include.empty() &&
      std::none_of(filter.include.begin(), filter.include.end(), matches)) {
    return false;
  }
  return std::none_of(filter.exclude.begin(), filter.exclude.end(), matches);
}

}  // namespace floorgrid

namespace floorgrid {

VectorFloorplan filter_layers(const VectorFloorplan& plan, const LayerFilter& filter) {
  VectorFloorplan out;
  const auto& layers = plan.layers();
  for (const Segment& s : plan.segments()) {
    const std::string& layer = layers[static_cast<std::size_t>(s.layer)];
    if (layer_passes(filter, layer))
      out.add_segment(s.a, s.b, layer);
  }
  for (const Arc& a : plan.arcs()) {
    const std::string& layer = layers[static_cast<std::size_t>(a.layer)];
    if (layer_passes(filter, layer))
      out.add_arc(a.center, a.radius, a.start_angle, a.end_angle, layer);
  }
  return out;
}

}  // namespace floorgrid
