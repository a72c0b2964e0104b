#include "floorgrid/simulation/plan_world.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "floorgrid/core/error.hpp"
#include "floorgrid/simulation/drawing_errors.hpp"
#include "floorgrid/simulation/drawing_raster.hpp"
#include "floorgrid/simulation/plan_dataset.hpp"
#include "floorgrid/simulation/raster_outline.hpp"
#include "floorgrid/simulation/room_segmentation.hpp"
#include "floorgrid/simulation/wall_lines.hpp"
#include "floorgrid/simulation/wall_solids.hpp"
#include "floorgrid/simulation/world_fittings.hpp"

namespace floorgrid {

namespace {

using namespace plan_world;

constexpr double kLineLength = 1.5;        // metres: the shortest straight wall looked for
constexpr double kOutlineTolerance = 0.5;  // pixels: wall faces simplified to this
constexpr double kCornerTolerance = 1.0;   // pixels: drawn outlines simplified to this

// The drawing's walls made solid, its inside split into regions.
struct Built {
  WallSolids solids;
  RoomSegmentation rooms;
};

Built build(const cv::Mat& ink, const cv::Mat& unknown, const WallThickness& thickness,
            const GridGeometry& g, const PlanWorldOptions& o) {
  Built b;
  b.solids = build_wall_solids(ink, unknown, thickness, g.resolution, o);
  if (cv::countNonZero(b.solids.inside) == 0)
    throw InputError(
        "the drawing encloses no inside: no free space walled off from the paper's "
        "edge, and no known free space in a raster's unknown surroundings",
        "", 0, "plan");
  b.rooms = segment_rooms(b.solids, g, o);
  return b;
}

void validate_world_options(const PlanWorldOptions& o) {
  const auto positive = [](double v, const char* field) {
    if (!std::isfinite(v) || v <= 0.0)
      throw InputError("must be a finite number > 0", "", 0, std::string("world.") + field);
  };
  positive(o.resolution, "resolution");
  positive(o.max_pixels, "max_pixels");
  positive(o.partition_thickness.min, "partition_thickness");
  positive(o.exterior_thickness.min, "exterior_thickness");
  positive(o.seal_radius, "seal_radius");
  positive(o.door_core_radius, "door_core_radius");
  positive(o.mullion_spacing, "mullion_spacing");
  positive(o.column_spacing, "column_spacing");
  for (const auto* range : {&o.partition_thickness, &o.exterior_thickness, &o.doorway_width,
                            &o.glass_length, &o.column_size, &o.partition_shift, &o.door_shift}) {
    if (!(range->max >= range->min))
      throw InputError("a range's max must be >= its min", "", 0, "world");
  }
}

}  // namespace

std::vector<Segment> PlanWorld::world_segments() const {
  std::vector<Segment> out = walls;
  for (const WorldObject& object : objects) {
    const std::size_t n = object.outline.size();
    for (std::size_t i = 0; i < n; ++i)
      out.push_back(
          {object.outline[i], object.outline[(i + 1) % n], static_cast<int>(object.kind)});
  }
  return out;
}

std::size_t PlanWorld::count(SurfaceKind kind) const {
  return static_cast<std::size_t>(std::count_if(
      objects.begin(), objects.end(), [&](const WorldObject& o) { return o.kind == kind; }));
}

std::size_t PlanWorld::doors_in_state(const std::string& state) const {
  return static_cast<std::size_t>(std::count_if(
      doors.begin(), doors.end(), [&](const WorldDoor& d) { return d.state == state; }));
}

double median_doorway_width(const PlanDrawing& drawing, double plan_scale,
                            const PlanWorldOptions& options) {
  validate_world_options(options);
  PlanWorldOptions coarse = options;
  coarse.resolution = std::max(options.resolution, 0.05);
  coarse.doorway_width = {0.05, 3.0};  // any opening a door could fill, at this scale
  const DrawingRaster raster = rasterize_drawing(drawing, plan_scale, coarse);
  const cv::Mat ink = join_strokes(raster.ink, coarse.stroke_join, raster.geometry.resolution);
  const Built b = build(ink, raster.unknown, {}, raster.geometry, coarse);
  std::vector<double> widths;
  for (const Opening& op : b.rooms.openings) {
    if (op.doorway && op.region_b >= 0)
      widths.push_back(op.width());
  }
  if (widths.empty())
    return 0.0;
  std::nth_element(widths.begin(), widths.begin() + widths.size() / 2, widths.end());
  return widths[widths.size() / 2];
}

PlanWorld build_plan_world(const PlanDrawing& drawing, double plan_scale, const PlanWorldOptions& o,
                           bool drawing_errors, double robot_clearance, Random& random) {
  validate_world_options(o);
  Random choices(random.fork()), errors_random(random.fork()), fittings_random(random.fork());
  PlanWorld world;
  world.partition_thickness = choices.uniform(o.partition_thickness.min, o.partition_thickness.max);
  world.exterior_thickness = choices.uniform(o.exterior_thickness.min, o.exterior_thickness.max);
  const WallThickness thickness{world.partition_thickness, world.exterior_thickness};

  const DrawingRaster raster = rasterize_drawing(drawing, plan_scale, o);
  const GridGeometry& g = raster.geometry;
  world.raster = g;
  world.drawn_ink = set_pixels(raster.ink, g);
  const RasterFrame frame{g.origin.translation(), g.resolution};
  world.drawn_corners = outline_corners(simplified_outlines(raster.ink, kCornerTolerance), frame);
  cv::Mat ink = join_strokes(raster.ink, o.stroke_join, g.resolution);
  if (drawing_errors) {
    const Built drawn = build(ink, raster.unknown, thickness, g, o);
    const std::vector<WallLine> lines = find_wall_lines(ink, g, kLineLength);
    const cv::Mat drawn_ink = ink.clone();
    world.errors = apply_drawing_errors(ink, {drawn_ink, drawn.solids, drawn.rooms, lines, g}, o,
                                        errors_random);
    ink = join_strokes(ink, o.stroke_join, g.resolution);
  }

  Built built = build(ink, raster.unknown, thickness, g, o);
  const std::vector<WallLine> lines = find_wall_lines(ink, g, kLineLength);
  const double main_angle = dominant_angle(lines);
  WorldCanvas canvas;
  canvas.geometry = g;
  canvas.solids = std::move(built.solids);
  canvas.rooms = std::move(built.rooms);
  canvas.glass = cv::Mat(ink.size(), CV_8UC1, cv::Scalar(0));
  canvas.solid = canvas.solids.walls.clone();
  canvas.world = &world;
  canvas.clearance = robot_clearance;
  for (std::size_t r = 0; r < canvas.rooms.regions.size(); ++r) {
    if (canvas.start_region < 0 ||
        canvas.rooms.regions[r].area >
            canvas.rooms.regions[static_cast<std::size_t>(canvas.start_region)].area)
      canvas.start_region = static_cast<int>(r);
  }
  fit_doors(canvas, o, fittings_random);
  fit_glass(canvas, ink, lines, o, fittings_random);
  fit_columns(canvas, main_angle, o, fittings_random);
  furnish(canvas, main_angle, o, fittings_random);

  world.regions = canvas.rooms.regions;
  world.walls = outline_segments(simplified_outlines(canvas.solids.walls, kOutlineTolerance), frame,
                                 static_cast<int>(SurfaceKind::wall));
  world.walkable.assign(g.size(), 0);
  world.region_of.assign(g.size(), -1);
  for (int y = 0; y < g.height; ++y) {
    const auto* inside = canvas.solids.inside.ptr<std::uint8_t>(y);
    const auto* solid = canvas.solid.ptr<std::uint8_t>(y);
    const int* label = canvas.rooms.labels.ptr<int>(y);
    for (int x = 0; x < g.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * g.width + x;
      world.walkable[i] = inside[x] != 0 && solid[x] == 0;
      world.region_of[i] = label[x];
    }
  }
  return world;
}

}  // namespace floorgrid
