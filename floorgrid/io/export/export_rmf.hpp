#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "floorgrid/io/export/export_raster.hpp"
#include "floorgrid/io/export/export_similarity.hpp"

namespace floorgrid::io {

/// How the robot map layer is drawn in the traffic-editor.
struct RmfLayerOptions {
  std::string name = "robot_map";                      ///< the layer's key
  std::array<double, 4> color = {0.0, 0.0, 1.0, 0.5};  ///< RGBA, 0..1 (traffic-editor's form)
};

/// An Open-RMF traffic-editor layer transform: a layer image pixel p (x right, y down, 0 at the
/// top-left corner) lands at level metres q = scale * [[cos yaw, sin yaw], [-sin yaw, cos yaw]]
/// * p + (translation_x, translation_y), the level's metres being its drawing's pixels times
/// its metres per pixel, y down (traffic-editor's Transform::forwards and Layer::draw).
struct RmfLayerTransform {
  double scale = 1.0;          ///< level metres per layer pixel
  double translation_x = 0.0;  ///< level metres (the layer image's top-left corner)
  double translation_y = 0.0;  ///< level metres, y down
  double yaw = 0.0;            ///< radians
};

/// What the fragment holds.
struct RmfLayer {
  RmfLayerTransform transform;  ///< the layer's placement
  ModelSimilarity similarity;   ///< the model's similarity it came from
  std::string level_frame;      ///< what the level's metres are (a plan raster's or DXF's)
  std::string text;             ///< the YAML fragment
};

/// The robot's map (`gridmap`, its image the layer's file) as a traffic-editor layer on the
/// plan's level, from the model's similarity (model_similarity over `points_in_plan`). The
/// level is the plan raster's image at its own resolution when `plan_raster` is given (level
/// metres = plan pixel x resolution, y down), else the DXF's metres with y flipped (level
/// metres = (x, -y)). `filename` is written as the layer's file. InputError when the model
/// mirrors the plan (a layer transform cannot mirror).
RmfLayer rmf_layer(const PointMapping& model,
                   const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                   const MapRaster& gridmap, const std::optional<GridGeometry>& plan_raster,
                   const std::string& filename, const RmfLayerOptions& options = {});

}  // namespace floorgrid::io
