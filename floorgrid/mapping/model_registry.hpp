#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace floorgrid {

class PointMapping;
struct MappingOptions;

/// What a mapping model promises, read by the CLI's help, `auto` and the contract suite.
struct ModelTraits {
  std::string_view description;  ///< one line for --help
  /// Its place among `auto`'s candidates, cheapest first (ties go to the earlier one); 0: not
  /// a candidate.
  int auto_rank = 0;
  bool exact_similarity = false;      ///< recovers a similarity exactly (1e-10 of the extent)
  bool non_rigid = false;             ///< follows local distortions (beats a global transform)
  double identity_tolerance = 1e-10;  ///< identity pairs map to identity within this x extent
  /// Share of points that come back from a round trip on noisy pairs (the rest lie where the
  /// map folds or, for a discontinuous model, beside a seam: not invertible, never elsewhere).
  double round_trip_share = 0.99;
  /// Bytes a fit may need at most for `pairs` pairs (after its reduction), dense matrices
  /// dominating: a budget the machine cannot hold is refused before the fit starts.
  std::size_t (*fit_bytes)(std::size_t pairs, const MappingOptions& options) = nullptr;
};

/// One model: its name (SPEC), what it promises, and how to make it.
struct ModelEntry {
  std::string_view name;  ///< lc, gt, gt-rigid, gt-affine, ct, gp, gpgt, dt, tps, auto
  ModelTraits traits;     ///< its promises
  /// A new, unfitted model with `options` (InputError on bad options).
  std::unique_ptr<PointMapping> (*make)(const MappingOptions& options);
};

/// Every model, in the SPEC's order: adding a model is one entry here plus its files.
std::span<const ModelEntry> model_registry();

/// The entry named `name`, or null.
const ModelEntry* find_model(std::string_view name);

/// The model names, in the SPEC's order.
const std::vector<std::string>& mapping_model_names();

/// The names of `auto`'s candidates, cheapest first.
std::vector<std::string> auto_candidates();

/// Bytes fitting `options.model` to `pairs` pairs may need at most (its reduction applied).
std::size_t fit_memory_bytes(const MappingOptions& options, std::size_t pairs);

}  // namespace floorgrid
