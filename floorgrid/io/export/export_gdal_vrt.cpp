#include "floorgrid/io/export/export_gdal_vrt.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <fstream>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/export/export_similarity.hpp"
#include "floorgrid/io/report/report_format.hpp"

namespace floorgrid::io {

namespace {

/// The bands GDAL sees in an image: how many and of which type.
struct RasterBands {
  int count = 1;
  std::string data_type = "Byte";
  std::vector<std::string> colours = {"Gray"};
};

/// Reads the image's header: GDAL's PNG driver gives one band per channel (a palette image
/// one band of indices), its PNM driver reads binary PGM only.
RasterBands probe_bands(const std::filesystem::path& image) {
  std::ifstream in(image, std::ios::binary);
  std::string head(1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  RasterBands bands;
  if (head.size() >= 26 && head.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) {
    const int depth = static_cast<unsigned char>(head[24]);
    const int colour_type = static_cast<unsigned char>(head[25]);
    bands.data_type = depth == 16 ? "UInt16" : "Byte";
    switch (colour_type) {
      case 2:
        bands.colours = {"Red", "Green", "Blue"};
        break;
      case 4:
        bands.colours = {"Gray", "Alpha"};
        break;
      case 6:
        bands.colours = {"Red", "Green", "Blue", "Alpha"};
        break;
      default:
        bands.colours = {"Gray"};
        break;  // grey, or palette indices
    }
    bands.count = static_cast<int>(bands.colours.size());
    return bands;
  }
  if (head.size() >= 2 && head[0] == 'P' && head[1] == '5') {
    // Width, height and maxval: the third number after the magic, comments skipped.
    std::size_t at = 2;
    long numbers[3] = {0, 0, 0};
    for (long& number : numbers) {
      while (at < head.size() &&
             (std::isspace(static_cast<unsigned char>(head[at])) || head[at] == '#')) {
        if (head[at] == '#') {
          while (at < head.size() && head[at] != '\n')
            ++at;
        } else {
          ++at;
        }
      }
      while (at < head.size() && std::isdigit(static_cast<unsigned char>(head[at])))
        number = number * 10 + (head[at++] - '0');
    }
    bands.data_type = numbers[2] > 255 ? "UInt16" : "Byte";
    return bands;
  }
  if (head.size() >= 2 && head[0] == 'P' && head[1] == '2') {
    throw InputError(
        "an ASCII PGM (P2), which GDAL does not read: convert it to binary PGM "
        "(P5) or PNG",
        image.string(), 0, "image");
  }
  throw InputError("not a PNG or binary PGM image", image.string(), 0, "image");
}

/// The image as the VRT names it: relative to the VRT's folder when the two share a root.
std::pair<std::string, bool> source_filename(const std::filesystem::path& image,
                                             const std::filesystem::path& vrt_path) {
  std::error_code error;
  const std::filesystem::path image_abs = std::filesystem::absolute(image, error);
  const std::filesystem::path folder = std::filesystem::absolute(vrt_path, error).parent_path();
  const std::filesystem::path relative = std::filesystem::relative(image_abs, folder, error);
  if (!error && !relative.empty())
    return {relative.generic_string(), true};
  return {image_abs.generic_string(), false};
}

/// The lattice of GDAL pixel/line points over a width x height raster, `n` per side.
std::vector<Eigen::Vector2d> lattice(int width, int height, int n) {
  std::vector<Eigen::Vector2d> points;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      points.emplace_back(width * static_cast<double>(i) / (n - 1),
                          height * static_cast<double>(j) / (n - 1));
    }
  }
  return points;
}

}  // namespace

GdalVrt gdal_vrt(const PointMapping& model, const MapRaster& raster, VrtSource source,
                 const std::filesystem::path& vrt_path, const GdalVrtOptions& options) {
  if (options.lattice_points < 3 || options.lattice_points > 129) {
    throw InputError(fmt::format("must be in [3, 129] (got {})", options.lattice_points), {}, 0,
                     "lattice_points");
  }
  const RasterBands bands = probe_bands(raster.image);
  const GridGeometry& g = raster.geometry;
  GdalVrt vrt;
  vrt.exact = model_is_affine(model);
  vrt.transformer = vrt.exact ? "-order 1" : "-tps";
  const int n = vrt.exact ? 3 : options.lattice_points;
  for (const Eigen::Vector2d& pixel_line : lattice(g.width, g.height, n)) {
    const Eigen::Vector2d point = image_to_frame(g, pixel_line);
    Eigen::Vector2d target;
    if (source == VrtSource::plan) {
      target = model.forward(point);
    } else {
      const InverseMapping inverse = model.inverse(point);
      if (!inverse.invertible) {
        ++vrt.not_invertible;
        continue;
      }
      target = inverse.point;
    }
    if (!target.allFinite()) {
      ++vrt.not_invertible;
      continue;
    }
    vrt.gcps.push_back({pixel_line.x(), pixel_line.y(), target.x(), target.y()});
  }
  if (vrt.gcps.size() < 3) {
    throw InputError(fmt::format("the {} model maps only {} of the {} GCPs over {}: too few for "
                                 "GDAL",
                                 model.name(), vrt.gcps.size(), n * n, raster.image.string()),
                     {}, 0, "model");
  }
  const std::string to = source == VrtSource::plan ? "grid" : "plan";
  const std::string from = source == VrtSource::plan ? "plan" : "gridmap";
  const auto [filename, relative] = source_filename(raster.image, vrt_path);
  std::string text =
      fmt::format("<VRTDataset rasterXSize=\"{}\" rasterYSize=\"{}\">\n", g.width, g.height);
  text += fmt::format(
      "  <!-- floorgrid export gdal-vrt: the {} image, GCPs from GDAL pixel/line (0,0 = the "
      "top-left corner of the top-left pixel) to {} metres through the {} model. Reproduced by "
      "GDAL's {} transformer: gdalwarp {} {} out.tif{} -->\n",
      from, to, exported_model(model).name(), vrt.exact ? "polynomial" : "thin-plate spline",
      vrt.transformer, html_escape(vrt_path.filename().string()),
      vrt.exact ? " (exact)"
                : ". The spline follows smooth models (tps, gp, gpgt) within about 1 cm and "
                  "smooths the kinks of piecewise ones (ct, dt, lc) between the GCPs");
  text += "  <Metadata>\n";
  text += fmt::format("    <MDI key=\"FLOORGRID_MODEL\">{}</MDI>\n",
                      html_escape(exported_model(model).name()));
  text +=
      fmt::format("    <MDI key=\"FLOORGRID_FRAMES\">{} image -&gt; {} metres</MDI>\n", from, to);
  text += fmt::format("    <MDI key=\"FLOORGRID_GDAL_TRANSFORMER\">{}</MDI>\n", vrt.transformer);
  text += "  </Metadata>\n";
  text += "  <GCPList Projection=\"\">\n";
  for (std::size_t i = 0; i < vrt.gcps.size(); ++i) {
    const GroundControlPoint& p = vrt.gcps[i];
    text += fmt::format("    <GCP Id=\"{}\" Pixel=\"{}\" Line=\"{}\" X=\"{}\" Y=\"{}\"/>\n", i + 1,
                        p.pixel, p.line, p.x, p.y);
  }
  text += "  </GCPList>\n";
  for (int b = 1; b <= bands.count; ++b) {
    text += fmt::format("  <VRTRasterBand dataType=\"{}\" band=\"{}\">\n", bands.data_type, b);
    text += fmt::format("    <ColorInterp>{}</ColorInterp>\n",
                        bands.colours[static_cast<std::size_t>(b - 1)]);
    text += "    <SimpleSource>\n";
    text += fmt::format("      <SourceFilename relativeToVRT=\"{}\">{}</SourceFilename>\n",
                        relative ? 1 : 0, html_escape(filename));
    text += fmt::format("      <SourceBand>{}</SourceBand>\n", b);
    text += fmt::format(
        "      <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"{0}\" ySize=\"{1}\"/>\n"
        "      <DstRect xOff=\"0\" yOff=\"0\" xSize=\"{0}\" ySize=\"{1}\"/>\n",
        g.width, g.height);
    text += "    </SimpleSource>\n";
    text += "  </VRTRasterBand>\n";
  }
  text += "</VRTDataset>\n";
  vrt.text = std::move(text);
  return vrt;
}

}  // namespace floorgrid::io
