#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "floorgrid/io/export/export_raster.hpp"
#include "floorgrid/mapping/point_mapping.hpp"

namespace floorgrid::io {

/// Which raster the VRT wraps, and so which way its GCPs map.
enum class VrtSource {
  plan,     ///< the plan raster; GCP X/Y in the grid frame (model forward)
  gridmap,  ///< the gridmap image; GCP X/Y in the plan frame (model inverse)
};

/// How the GCPs are laid.
struct GdalVrtOptions {
  /// Non-affine models: GCPs on a lattice of this many points per side of the raster (corners
  /// included), for GDAL's thin-plate spline transformer (gdalwarp -tps). 33 x 33 GCPs keep
  /// GDAL's spline solve well under a second.
  int lattice_points = 33;
};

/// One ground control point: GDAL pixel/line in the source raster -> X/Y in the target frame.
struct GroundControlPoint {
  double pixel = 0.0;  ///< GDAL pixel (0 = the left edge of the image)
  double line = 0.0;   ///< GDAL line (0 = the top edge of the image)
  double x = 0.0;      ///< metres, target frame
  double y = 0.0;      ///< metres, target frame
};

/// A VRT written over a raster.
struct GdalVrt {
  std::string text;                      ///< the VRT's XML
  std::vector<GroundControlPoint> gcps;  ///< its GCPs
  bool exact = false;                    ///< the model is affine: `-order 1` reproduces it exactly
  std::string transformer;         ///< the gdalwarp/gdaltransform option reproducing the model
  std::size_t not_invertible = 0;  ///< lattice points left out (the inverse does not exist)
};

/// A GDAL VRT over `raster` (the plan raster or the gridmap image, `source` says which) with a
/// <GCPList> mapping GDAL pixel/line to the other frame through the model, so that
/// `gdalwarp -order 1` (affine models: gt, gt-rigid, gt-affine; GCPs on a 3 x 3 lattice,
/// reproduced exactly) or `gdalwarp -tps` (every other model; GCPs on a lattice of
/// options.lattice_points per side) resamples it into that frame. The image is referenced
/// relative to `vrt_path`'s folder when it can be. The GCPs carry no CRS (a local frame in
/// metres). InputError naming the image when GDAL could not read it (an ASCII PGM).
GdalVrt gdal_vrt(const PointMapping& model, const MapRaster& raster, VrtSource source,
                 const std::filesystem::path& vrt_path, const GdalVrtOptions& options = {});

}  // namespace floorgrid::io
