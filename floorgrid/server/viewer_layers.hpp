#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::server {

/// A heat map as the viewer lays it over the plan: a picture of exactly the plan's pixels
/// (viridis from 0 to the clip, transparent where unknown, no colour bar: the page draws its
/// legend) and what it shows.
struct HeatLayer {
  std::string kind;      ///< "error" (against the dataset's truth) or "std" (the model's own say)
  std::string quantity;  ///< "error_m", "std_m" or "nearest_pair_m"
  double clip_m = 0.0;   ///< metres at the top colour
  std::string png;       ///< the PNG file's bytes
};

/// What the viewer draws from the dataset through one model.
struct ModelLayers {
  /// The plan's walls through the model on the gridmap's pixels (red, transparent elsewhere;
  /// empty: none).
  std::string overlay_png;
  std::vector<HeatLayer> heat;  ///< the error map first (with a truth), then the uncertainty
  double seconds = 0.0;         ///< how long drawing them took
};

/// Draws a model's layers; may take seconds on large maps.
using LayerRenderer = std::function<ModelLayers(const PointMapping& model)>;

/// The layers of a loaded dataset (kept alive by the renderer): the overlay on its gridmap and
/// the heat maps over its plan grid, on the same cells and with the same truth as `align`'s.
LayerRenderer dataset_layers(std::shared_ptr<const io::LoadedDataset> dataset);

}  // namespace floorgrid::server
