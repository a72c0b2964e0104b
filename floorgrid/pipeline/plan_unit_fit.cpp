#include "floorgrid/pipeline/plan_unit_fit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "floorgrid/core/error.hpp"
#include "floorgrid/core/validation.hpp"

namespace floorgrid {

namespace {

/// The gridmap registered on the plan drawn under `unit`, over scales near `expected`.
PlanUnitFit fit_unit(const OccupancyGrid& gridmap, const VectorFloorplan& plan, PlanUnit drawn,
                     const PlanUnitCandidate& candidate, double expected,
                     const RasterizeOptions& raster, const PlanUnitFitOptions& options) {
  PlanUnitFit fit{.unit = candidate.unit, .probability = candidate.probability};
  const double factor = metres_per_unit(candidate.unit) / metres_per_unit(drawn);
  const VectorFloorplan in_unit = factor == 1.0 ? plan : plan.scaled(factor);
  const Eigen::AlignedBox2d bounds = in_unit.bounds();
  const Eigen::Vector2d size = bounds.sizes().array() + 2.0 * raster.margin;
  RasterizeOptions r = raster;
  r.resolution =
      std::max(raster.resolution, std::sqrt(size.x() * size.y() / double(options.max_cells)));
  OccupancyGrid grid;
  try {
    grid = rasterize(in_unit, r);
  } catch (const InputError&) {
    return fit;  // nothing to draw, or too large even coarse: not tried
  }
  MapRegistrationOptions o = options.registration;
  o.min_scale = 1.0 / (expected * options.scale_margin);
  o.max_scale = options.scale_margin / expected;
  const MapRegistration reg = register_maps(gridmap, grid, PlanWalls::vector_lines, o);
  fit.tried = true;
  if (reg.found) {
    fit.score = reg.best.score;
    fit.floorplan_scale = 1.0 / reg.best.transform.scale;
  }
  return fit;
}

}  // namespace

void validate(const PlanUnitFitOptions& o) {
  require_option(o.scale_margin > 1.0 && o.scale_margin <= 100.0, "units", "scale_margin",
                 o.scale_margin, "in (1, 100]");
  require_option(o.min_score >= -1.0 && o.min_score <= 1.0, "units", "min_score", o.min_score,
                 "in [-1, 1]");
  require_option(o.clear_margin >= 0.0 && o.clear_margin <= 2.0, "units", "clear_margin",
                 o.clear_margin, "in [0, 2]");
  require_option(o.max_cells >= 10'000, "units", "max_cells", o.max_cells, ">= 10000");
}

PlanUnitDecision fit_plan_units(const OccupancyGrid& gridmap, const VectorFloorplan& plan,
                                PlanUnit drawn_unit,
                                const std::vector<PlanUnitCandidate>& candidates,
                                std::optional<double> expected_scale,
                                const RasterizeOptions& raster, const PlanUnitFitOptions& options) {
  validate(options);
  PlanUnitDecision d;
  d.drawn = d.unit = drawn_unit;
  const double expected = expected_scale.value_or(1.0);
  std::vector<PlanUnitCandidate> tried = candidates;
  if (std::none_of(tried.begin(), tried.end(),
                   [&](const PlanUnitCandidate& c) { return c.unit == drawn_unit; }))
    tried.insert(tried.begin(), PlanUnitCandidate{drawn_unit, 0.0, 0.0});
  for (const PlanUnitCandidate& c : tried)
    d.fits.push_back(fit_unit(gridmap, plan, drawn_unit, c, expected, raster, options));

  const auto drawn = std::find_if(d.fits.begin(), d.fits.end(),
                                  [&](const PlanUnitFit& f) { return f.unit == drawn_unit; });
  const PlanUnitFit* other = nullptr;
  for (const PlanUnitFit& f : d.fits) {
    if (f.unit != drawn_unit && f.tried && (!other || f.score > other->score))
      other = &f;
  }
  const auto describe = [](const PlanUnitFit& f) {
    return f.tried ? fmt::format("{} fits with score {:.2f} at scale {:.3f}", unit_name(f.unit),
                                 f.score, f.floorplan_scale)
                   : fmt::format("{} could not be tried", unit_name(f.unit));
  };
  const double drawn_score = drawn->tried ? drawn->score : -1.0;
  if (other && other->score >= options.min_score &&
      other->score >= drawn_score + options.clear_margin) {
    d.unit = other->unit;
    d.reason = fmt::format("the gridmap fits the plan in {}, not in the drawing's {}: {}; {}",
                           unit_name(other->unit), unit_name(drawn_unit), describe(*other),
                           describe(*drawn));
  } else if (drawn_score >= options.min_score &&
             (!other || drawn_score >= other->score + options.clear_margin)) {
    d.confirmed = true;
    d.reason = fmt::format("the gridmap confirms the drawing's {}: {}{}", unit_name(drawn_unit),
                           describe(*drawn), other ? "; " + describe(*other) : "");
  } else {
    d.reason = fmt::format(
        "the gridmap fits no unit clearly at scale {:.2f} (x/ {:.2f}): {}{}; the "
        "drawing's {} is kept and the scale search decides",
        expected, options.scale_margin, describe(*drawn), other ? "; " + describe(*other) : "",
        unit_name(drawn_unit));
  }
  return d;
}

}  // namespace floorgrid
