#include "floorgrid/mapping/model_registry.hpp"

#include <algorithm>
#include <array>

#include "floorgrid/mapping/gaussian_process_mapping.hpp"
#include "floorgrid/mapping/global_transform.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/mapping/piecewise_affine.hpp"
#include "floorgrid/mapping/thin_plate_spline_mapping.hpp"

namespace floorgrid {

namespace {

// ---- factories ----

std::unique_ptr<PointMapping> make_global(const MappingOptions& options, TransformKind kind) {
  RansacOptions ransac = options.ransac;
  ransac.kind = kind;
  return std::make_unique<GlobalTransformMapping>(options.common, ransac);
}

std::unique_ptr<PointMapping> make_gp(const MappingOptions& options, bool global) {
  RansacOptions ransac = options.ransac;
  ransac.inlier_threshold = options.gpgt_inlier_threshold;
  return std::make_unique<GaussianProcessMapping>(options.common, options.gp, global, ransac);
}

std::unique_ptr<PointMapping> make_auto(const MappingOptions& options) {
  // Only the candidates this build knows, never auto itself.
  MappingOptions chooser = options;
  std::vector<std::string> known;
  for (const std::string& c : options.auto_select.candidates) {
    if (c != "auto" && find_model(c) != nullptr)
      known.push_back(c);
  }
  chooser.auto_select.candidates = known;
  return std::make_unique<AutoMapping>(chooser);
}

// ---- memory of a fit ----

constexpr std::size_t kDouble = sizeof(double);

/// Linear in the pairs: a few copies of them and an index.
std::size_t linear_bytes(std::size_t pairs, const MappingOptions&) {
  return 64 * kDouble * std::max<std::size_t>(pairs, 1);
}

/// A dense square system over the pairs kept (after the reduction): the kernel matrix, its
/// factor and a work copy, plus the linear part.
std::size_t dense_bytes(std::size_t pairs, const MappingOptions& options) {
  const std::size_t n = std::min(pairs, options.common.reduction.budget) + 3;
  return 4 * kDouble * n * n + linear_bytes(pairs, options);
}

std::size_t auto_bytes(std::size_t pairs, const MappingOptions& options) {
  std::size_t most = linear_bytes(pairs, options);
  for (const std::string& c : options.auto_select.candidates) {
    const ModelEntry* entry = find_model(c);
    if (entry != nullptr && c != "auto")
      most = std::max(most, entry->traits.fit_bytes(pairs, options));
  }
  return most;
}

constexpr std::array<ModelEntry, 10> kModels = {{
    {"lc",
     {.description = "linear combination: the affine frame of a nearby well-shaped triangle of "
                     "pairs (thesis 4.1)",
      .auto_rank = 8,
      .exact_similarity = true,
      .round_trip_share = 0.95,
      .fit_bytes = linear_bytes},
     [](const MappingOptions& o) -> std::unique_ptr<PointMapping> {
       return std::make_unique<LinearCombinationMapping>(o.common, o.lc);
     }},
    {"gt",
     {.description = "global similarity by RANSAC and a least-squares refit (thesis 3.2, 4.2)",
      .auto_rank = 1,
      .exact_similarity = true,
      .fit_bytes = linear_bytes},
     [](const MappingOptions& o) { return make_global(o, TransformKind::similarity); }},
    {"gt-rigid",
     {.description = "global rigid transform (rotation and translation) by RANSAC",
      .fit_bytes = linear_bytes},
     [](const MappingOptions& o) { return make_global(o, TransformKind::rigid); }},
    {"gt-affine",
     {.description = "global affine transform by RANSAC",
      .auto_rank = 2,
      .exact_similarity = true,
      .fit_bytes = linear_bytes},
     [](const MappingOptions& o) { return make_global(o, TransformKind::affine); }},
    {"ct",
     {.description = "clustered local transforms blended by inverse distance (thesis 4.3, 5.1)",
      .auto_rank = 7,
      .non_rigid = true,
      .fit_bytes = linear_bytes},
     [](const MappingOptions& o) -> std::unique_ptr<PointMapping> {
       return std::make_unique<LocalTransformsMapping>(o.common, o.ct);
     }},
    {"gp",
     {.description = "Gaussian-process regression of the grid coordinates (thesis 3.3, 4.4.1)",
      .auto_rank = 3,
      .non_rigid = true,
      .identity_tolerance = 1e-4,
      .fit_bytes = dense_bytes},
     [](const MappingOptions& o) { return make_gp(o, false); }},
    {"gpgt",
     {.description = "global similarity plus a Gaussian process on its residuals (thesis 4.4.2)",
      .auto_rank = 4,
      .non_rigid = true,
      .fit_bytes = dense_bytes},
     [](const MappingOptions& o) { return make_gp(o, true); }},
    {"dt",
     {.description = "Delaunay triangulation, barycentric in the partner triangle (thesis 3.4, "
                     "4.5)",
      .auto_rank = 6,
      .exact_similarity = true,
      .non_rigid = true,
      .fit_bytes = linear_bytes},
     [](const MappingOptions& o) -> std::unique_ptr<PointMapping> {
       return std::make_unique<PiecewiseAffineMapping>(o.common);
     }},
    {"tps",
     {.description = "regularized thin-plate spline, as in QGIS and GDAL georeferencers",
      .auto_rank = 5,
      .exact_similarity = true,
      .non_rigid = true,
      .fit_bytes = dense_bytes},
     [](const MappingOptions& o) -> std::unique_ptr<PointMapping> {
       return std::make_unique<ThinPlateSplineMapping>(o.common, o.tps);
     }},
    {"auto",
     {.description = "the candidate with the lowest spatially blocked cross-validated error",
      .exact_similarity = true,
      .non_rigid = true,
      .fit_bytes = auto_bytes},
     make_auto},
}};

}  // namespace

std::span<const ModelEntry> model_registry() {
  return kModels;
}

const ModelEntry* find_model(std::string_view name) {
  for (const ModelEntry& entry : kModels) {
    if (entry.name == name)
      return &entry;
  }
  return nullptr;
}

const std::vector<std::string>& mapping_model_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const ModelEntry& entry : kModels)
      out.emplace_back(entry.name);
    return out;
  }();
  return names;
}

std::vector<std::string> auto_candidates() {
  std::vector<const ModelEntry*> ranked;
  for (const ModelEntry& entry : kModels) {
    if (entry.traits.auto_rank > 0)
      ranked.push_back(&entry);
  }
  std::sort(ranked.begin(), ranked.end(), [](const ModelEntry* a, const ModelEntry* b) {
    return a->traits.auto_rank < b->traits.auto_rank;
  });
  std::vector<std::string> names;
  for (const ModelEntry* entry : ranked)
    names.emplace_back(entry->name);
  return names;
}

std::size_t fit_memory_bytes(const MappingOptions& options, std::size_t pairs) {
  const ModelEntry* entry = find_model(options.model);
  return entry != nullptr ? entry->traits.fit_bytes(pairs, options) : 0;
}

}  // namespace floorgrid
