#include "floorgrid/pipeline/align.hpp"

#include <algorithm>
#include <chrono>

#include "floorgrid/geometry/point_index.hpp"
#include "floorgrid/mapping/model_selection.hpp"
#include "floorgrid/maps/distance_field.hpp"

namespace floorgrid {

namespace {

double median_of(std::vector<double> v) {
  if (v.empty())
    return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// The truth's domain: where a warp is known to hold (the gridmap saw something near), or
/// inside the manual pairs' hull.
EvaluationDomain truth_domain(const AlignmentInputs& in, const GroundTruth& truth,
                              const std::string& kind) {
  constexpr double spacing = 0.05;
  if (kind == "warp") {
    return in.plan ? warp_domain(*in.plan, in.gridmap, truth, spacing)
                   : warp_domain(in.plan_wall_samples, in.gridmap, truth, spacing);
  }
  return in.plan ? hull_domain(*in.plan, in.manual_pairs->points_in_plan, spacing)
                 : hull_domain(in.plan_wall_samples, in.manual_pairs->points_in_plan, spacing);
}

}  // namespace

WallDistance wall_distance(const Eigen::Matrix2Xd& samples, const Eigen::Matrix2Xd& mapped,
                           const OccupancyGrid& gridmap, const Eigen::Matrix2Xd& pair_points,
                           double near) {
  WallDistance w;
  const DistanceField walls = occupied_distance_field(gridmap, 5.0);
  const PointIndex2D pairs(pair_points);
  std::vector<double> near_distances;
  w.distances.reserve(static_cast<std::size_t>(samples.cols()));
  for (Eigen::Index i = 0; i < samples.cols(); ++i) {
    const double d = walls.at(mapped.col(i));
    w.distances.push_back(d);
    if (pairs.size() > 0 && pairs.nearest(samples.col(i)).distance <= near)
      near_distances.push_back(d);
  }
  w.points = w.distances.size();
  w.median_m = median_of(w.distances);
  w.near_points = near_distances.size();
  w.near_median_m = median_of(near_distances);
  return w;
}

Alignment align(const AlignmentInputs& in, const AlignmentOptions& options,
                const std::function<void(const AlignmentProgress&)>& progress) {
  Alignment a;
  a.localization = localize_dual(
      in.plan_grid, in.gridmap, in.log, in.start, in.plan_scale, options.localization,
      [&](const DualProgress& p) {
        if (progress)
          progress({"localize", p.phase, p.scan, p.scans});
      },
      in.plan);
  const ReferencePairs& pairs = a.localization.pairs;

  // The truth and where it holds.
  std::string kind;
  std::unique_ptr<PointMapping> manual_truth;
  if (in.truth_warp) {
    a.truth = in.truth_warp;
    kind = "warp";
  } else if (in.manual_pairs && in.manual_pairs->size() >= 3) {
    // The thesis's ground truth: the hand-picked pairs through the Delaunay model.
    MappingOptions dt;
    dt.model = "dt";
    manual_truth = make_mapping(dt);
    manual_truth->fit(*in.manual_pairs);
    const PointMapping* m = manual_truth.get();
    a.truth = [m](const Eigen::Vector2d& p) { return m->forward(p); };
    kind = "manual_pairs_hull";
  }
  if (a.truth) {
    a.domain = truth_domain(in, *a.truth, kind);
    if (in.truth_warp && pairs.size() > 0) {
      std::vector<double> errors(static_cast<std::size_t>(pairs.size()));
      for (Eigen::Index i = 0; i < pairs.size(); ++i)
        errors[static_cast<std::size_t>(i)] =
            ((*a.truth)(pairs.points_in_plan.col(i)) - pairs.points_in_grid.col(i)).norm();
      a.pair_errors = error_statistics(std::move(errors));
    }
  } else {
    a.domain = {"none", Eigen::Matrix2Xd(2, 0), 0.05};
  }

  // Every model, fitted and judged.
  if (pairs.size() == 0)
    return a;
  const auto fit_start = std::chrono::steady_clock::now();
  std::vector<ModelReport> reports =
      compare_models(pairs, a.domain, a.truth, options.models,
                     [&](const std::string& model, std::size_t done, std::size_t total) {
                       if (progress)
                         progress({"fit", model, done, total});
                     });
  const double total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - fit_start).count();
  double wall_seconds = 0.0;
  for (ModelReport& r : reports) {
    a.evaluate_seconds += r.evaluate_seconds;
    ModelAlignment m;
    if (r.model) {
      const auto wall_start = std::chrono::steady_clock::now();
      const Eigen::Matrix2Xd mapped = r.model->forward_batch(in.plan_wall_samples);
      m.wall_distance = wall_distance(in.plan_wall_samples, mapped, in.gridmap,
                                      pairs.points_in_plan, options.near_pairs);
      if (const auto* chooser = dynamic_cast<const AutoMapping*>(r.model.get()))
        a.chosen = chooser->chosen().name();
      wall_seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    }
    m.report = std::move(r);
    a.models.push_back(std::move(m));
  }
  a.fit_seconds = total_seconds - a.evaluate_seconds;
  a.evaluate_seconds += wall_seconds;
  return a;
}

}  // namespace floorgrid
