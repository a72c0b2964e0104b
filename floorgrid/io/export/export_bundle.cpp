#include "floorgrid/io/export/export_bundle.hpp"

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/export/export_gdal_vrt.hpp"
#include "floorgrid/io/export/export_nav2_map.hpp"
#include "floorgrid/io/export/export_qgis_points.hpp"
#include "floorgrid/io/export/export_rmf.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/mapping/pair_preparation.hpp"

namespace floorgrid::io {

namespace {

/// The plan points the rmf layer's least-squares similarity is fitted on: the pairs binned.
Eigen::Matrix2Xd similarity_points(const ReferencePairs& pairs) {
  ReductionOptions reduction;
  reduction.budget = 2000;
  return reduce_pairs(pairs, reduction).points_in_plan;
}

}  // namespace

ExportFiles write_exports(const PointMapping& model, const ReferencePairs& pairs,
                          const ExportMaps& maps, const std::filesystem::path& folder) {
  prepare_output_folder(folder);
  ExportFiles out;
  // One export that cannot be made (a mirrored plan for rmf, an image GDAL cannot read) is
  // reported, not fatal: the others are still worth having.
  const auto attempt = [&](const std::string& format, const auto& write) {
    try {
      write();
    } catch (const InputError& e) {
      out.skipped.push_back(format + ": " + e.message());
    }
  };
  const std::optional<GridGeometry> plan_raster =
      maps.plan_raster ? std::optional<GridGeometry>(maps.plan_raster->geometry) : std::nullopt;
  if (!pairs.empty()) {
    attempt("qgis-points", [&] {
      write_file_atomically(folder / "plan.points", qgis_points(model, pairs, plan_raster).text);
      out.files.emplace_back("plan.points");
    });
  } else {
    out.skipped.emplace_back("qgis-points: no pairs");
  }
  if (maps.plan_raster) {
    attempt("gdal-vrt", [&] {
      const auto path = folder / "plan.vrt";
      write_file_atomically(path, gdal_vrt(model, *maps.plan_raster, VrtSource::plan, path).text);
      out.files.emplace_back("plan.vrt");
    });
  } else {
    out.skipped.emplace_back("gdal-vrt of the plan: the plan is DXF, not a raster");
  }
  if (maps.gridmap) {
    attempt("gdal-vrt", [&] {
      const auto path = folder / "gridmap.vrt";
      write_file_atomically(path, gdal_vrt(model, *maps.gridmap, VrtSource::gridmap, path).text);
      out.files.emplace_back("gridmap.vrt");
    });
    if (!pairs.empty()) {
      attempt("rmf", [&] {
        const auto path = folder / "rmf-layer.yaml";
        std::error_code error;
        auto filename = std::filesystem::relative(std::filesystem::absolute(maps.gridmap->image),
                                                  std::filesystem::absolute(folder), error);
        if (error || filename.empty())
          filename = std::filesystem::absolute(maps.gridmap->image);
        write_file_atomically(path, rmf_layer(model, similarity_points(pairs), *maps.gridmap,
                                              plan_raster, filename.generic_string())
                                        .text);
        out.files.emplace_back("rmf-layer.yaml");
      });
    }
    attempt("nav2-map", [&] {
      const OccupancyGrid walls =
          maps.plan_vector ? plan_walls_in_grid(model, *maps.plan_vector, maps.gridmap->geometry)
          : maps.plan_grid ? plan_walls_in_grid(model, *maps.plan_grid, maps.gridmap->geometry)
                           : throw InputError("no plan walls to draw");
      const auto image = write_nav2_map(walls, folder / "plan-walls.yaml");
      out.files.emplace_back("plan-walls.yaml");
      out.files.push_back(image.filename());
    });
  }
  return out;
}

}  // namespace floorgrid::io
