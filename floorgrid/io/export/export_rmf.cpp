#include "floorgrid/io/export/export_rmf.hpp"

#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>

#include "floorgrid/core/error.hpp"

namespace floorgrid::io {

namespace {

/// Level metres (y down) from plan metres.
Eigen::Matrix3d T_level_plan(const std::optional<GridGeometry>& plan_raster) {
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  if (!plan_raster) {
    T(1, 1) = -1.0;
    return T;
  }
  Eigen::Matrix3d T_level_image = Eigen::Matrix3d::Identity();
  T_level_image(0, 0) = T_level_image(1, 1) = plan_raster->resolution;
  return T_level_image * T_frame_image(*plan_raster).inverse();
}

std::string yaml_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\')
      out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

RmfLayer rmf_layer(const PointMapping& model,
                   const Eigen::Ref<const Eigen::Matrix2Xd>& points_in_plan,
                   const MapRaster& gridmap, const std::optional<GridGeometry>& plan_raster,
                   const std::string& filename, const RmfLayerOptions& options) {
  RmfLayer layer;
  layer.similarity = model_similarity(model, points_in_plan);
  if (layer.similarity.reflected) {
    throw InputError(
        "the model mirrors the plan (det < 0): a traffic-editor layer transform (scale, yaw, "
        "translation) cannot mirror; mirror the plan image first",
        {}, 0, "model");
  }
  // Layer pixel -> grid metres -> plan metres -> level metres.
  const Eigen::Matrix3d T_level_layer = T_level_plan(plan_raster) *
                                        layer.similarity.T_grid_plan.inverse() *
                                        T_frame_image(gridmap.geometry);
  const Eigen::Matrix2d A = T_level_layer.topLeftCorner<2, 2>();
  RmfLayerTransform& t = layer.transform;
  // forwards: A = scale * [[cos, sin], [-sin, cos]].
  t.scale = std::sqrt(A.determinant());
  t.yaw = std::atan2(A(0, 1), A(0, 0));
  t.translation_x = T_level_layer(0, 2);
  t.translation_y = T_level_layer(1, 2);
  layer.level_frame = plan_raster
                          ? fmt::format(
                                "the plan raster's pixels x {} m (its resolution), y down; set "
                                "the level's scale to {} m per pixel",
                                plan_raster->resolution, plan_raster->resolution)
                          : "the DXF plan's metres with y flipped (level metres = (x, -y))";
  const ModelSimilarity& s = layer.similarity;
  std::string text;
  text += "# floorgrid export rmf: the robot's map as an Open-RMF traffic-editor layer.\n";
  text += "# Paste under the plan's level in the building YAML (levels: <level>: layers:).\n";
  text += fmt::format("# Level frame: {}.\n", layer.level_frame);
  text += fmt::format("# From the {} model's similarity: {}.\n", exported_model(model).name(),
                      s.source);
  text += fmt::format(
      "# Similarity plan -> grid: scale {:.6f}, yaw {:.6f} rad, rms residual "
      "{:.4f} m.\n",
      s.scale, s.yaw, s.rms_m);
  text += "layers:\n";
  text += fmt::format("  {}:\n", options.name);
  text += fmt::format("    filename: {}\n", yaml_string(filename));
  text += "    visible: true\n";
  text += fmt::format("    color: [{}, {}, {}, {}]\n", options.color[0], options.color[1],
                      options.color[2], options.color[3]);
  text +=
      fmt::format("    transform: {{scale: {}, translation_x: {}, translation_y: {}, yaw: {}}}\n",
                  t.scale, t.translation_x, t.translation_y, t.yaw);
  layer.text = std::move(text);
  return layer;
}

}  // namespace floorgrid::io
