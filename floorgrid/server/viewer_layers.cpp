#include "floorgrid/server/viewer_layers.hpp"

#include <chrono>
#include <utility>

#include "floorgrid/evaluation/overlay.hpp"
#include "floorgrid/io/files/image_io.hpp"
#include "floorgrid/io/jobs/alignment_writer.hpp"
#include "floorgrid/io/report/heat_map_files.hpp"
#include "floorgrid/io/report/heat_map_png.hpp"

namespace floorgrid::server {

namespace {

constexpr std::array<std::uint8_t, 4> kWallColour{220, 0, 0, 255};

/// The plan's walls through `model`, drawn on a transparent picture of the gridmap's pixels.
std::string overlay_png(const AlignmentInputs& in, const PointMapping& model) {
  const GridGeometry& g = in.gridmap.geometry();
  RgbImage drawn{g.width, g.height, {}};
  drawn.rgb.assign(static_cast<std::size_t>(g.width) * g.height * 3, 0);
  io::draw_plan_walls(drawn, in, [&model](const Eigen::Vector2d& p) { return model.forward(p); },
                      {255, 255, 255});
  std::vector<std::uint8_t> rgba(drawn.rgb.size() / 3 * 4, 0);
  for (std::size_t i = 0; i * 3 < drawn.rgb.size(); ++i) {
    if (drawn.rgb[i * 3] != 0)
      std::copy(kWallColour.begin(), kWallColour.end(), rgba.begin() + 4 * i);
  }
  return io::encode_png(g.width, g.height, 4, rgba);
}

HeatLayer heat_layer(std::string kind, const HeatMap& map) {
  io::HeatMapStyle style;
  style.legend = false;
  const double clip = io::heat_map_clip(map, style);
  style.clip_m = clip;
  const io::RgbaImage image = io::render_heat_map(map, style);
  return {std::move(kind), map.quantity, clip,
          io::encode_png(image.width, image.height, 4, image.rgba)};
}

}  // namespace

LayerRenderer dataset_layers(std::shared_ptr<const io::LoadedDataset> dataset) {
  static const RobotLog no_run;  // the layers judge the maps, never the run
  const io::LoadedDataset& d = *dataset;
  auto inputs = std::make_shared<const AlignmentInputs>(
      AlignmentInputs{d.plan_grid, d.plan ? &*d.plan : nullptr, d.plan_wall_samples, d.gridmap,
                      no_run, std::nullopt, d.manifest.floorplan_scale, io::warp_truth(d),
                      d.manual_pairs ? &*d.manual_pairs : nullptr});
  // The truth and its cells do not depend on the model: found once, as `align` finds them.
  auto truth = std::make_shared<const DatasetTruth>(dataset_truth(*inputs));
  auto domain = std::make_shared<const io::HeatMapDomain>(
      io::heat_map_domain(*inputs, truth->plan_to_grid, truth->kind));
  // `dataset` is captured to keep what `inputs` refers to alive.
  return [dataset, inputs, truth, domain](const PointMapping& model) {
    const auto start = std::chrono::steady_clock::now();
    ModelLayers layers;
    layers.overlay_png = overlay_png(*inputs, model);
    const io::ModelHeatMapValues maps =
        io::model_heat_maps(model, *inputs, truth->plan_to_grid, *domain);
    if (maps.error)
      layers.heat.push_back(heat_layer("error", *maps.error));
    layers.heat.push_back(heat_layer("std", maps.uncertainty));
    layers.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return layers;
  };
}

}  // namespace floorgrid::server
