#pragma once

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "floorgrid/core/parallel.hpp"
#include "floorgrid/localization/particle_filter.hpp"
#include "floorgrid/localization/scan_matcher.hpp"
#include "floorgrid/localization/scan_observation.hpp"
#include "floorgrid/localization/wall_field.hpp"
#include "floorgrid/robot/motion_model.hpp"
#include "floorgrid/robot/robot_log.hpp"

namespace floorgrid {

/// How a FilterRunner feeds one particle filter with a log.
struct FilterRunnerOptions {
  /// Metres and radians of odometry before the filter is updated again: updating a standing
  /// robot with the same scan over and over makes a filter overconfident.
  double update_min_translation = 0.05;
  double update_min_rotation = 0.05;  ///< radians
  /// Improved proposal while tracking (Grisetti, Stachniss, Burgard 2007): a converged filter
  /// moves its predicted cloud onto the pose a scan match finds from the cloud's mean (along a
  /// corridor only across it) before weighing it, so it follows the walls, not the drift.
  bool improved_proposal = true;
  /// Match each scan of a converged filter onto the walls from its mean pose (the refined pose
  /// pairs are made from).
  bool refine = true;
  ScanMatchOptions match;  ///< both uses of scan matching
  /// Map metres: with a ray caster (see FilterRunner), only beams whose range reaches the first
  /// wall along them within this are matched (beam_consistent).
  double beam_tolerance = 0.5;
  ObservationOptions match_observation{180};  ///< beams per scan of the matching
  int threads = kDefaultThreads;              ///< threads of the observation model
  /// A guided runner (FilterRunner::guide) moves its filter between two scans that both have
  /// a guide pose by the guide's motion, spread by this noise instead of the odometry's: on a
  /// sparse log (a scan every metre and 20 degrees) the odometry's noise spreads the headings by
  /// several degrees per step, more than a scan that sees few of the map's walls can correct.
  /// About a degree per step of 45 degrees or a metre, 4.5 cm per metre: the gridmap filter's
  /// poses are within a few centimetres and tenths of a degree, and a plan drawn with a bend
  /// strains by about a centimetre per metre.
  MotionNoise guided_noise{.alpha1 = 0.001, .alpha2 = 0.0002, .alpha3 = 0.002, .alpha4 = 0.002};
  /// Only steps of at least this many metres or radians of odometry are guided: over small
  /// steps the odometry is precise enough, and a plan drawn unlike the building (a room drawn
  /// shallower than it is) needs the odometry's looser noise to slide along it (real fr079:
  /// guiding every step lost 3% of its converged scans).
  double guide_min_translation = 0.25;
  double guide_min_rotation = 0.25;  ///< radians
  /// A guide's motion farther from the odometry's than this is not trusted (the guide jumped):
  /// metres plus a share of the odometry's step ...
  double guide_max_translation = 0.3;
  double guide_translation_share = 0.5;
  /// ... and radians plus radians per metre of the step plus a share of the odometry's turn.
  double guide_max_rotation = 0.2;
  double guide_rotation_per_metre = 0.3;
  double guide_rotation_share = 0.3;
};

/// What one filter did on one scan.
struct FilterRecord {
  FilterState state = FilterState::uninitialized;  ///< after this scan
  bool converged = false;  ///< converged after this scan (FilterStatus::converged)
  bool updated = false;    ///< took a measurement update on this scan (else only the motion)
  Pose2 pose;              ///< mean pose of the particles after this scan (map frame)
  PoseEstimate estimate;   ///< at the last update
  ConvergenceCheck check;  ///< the last update's convergence test
  /// The model's mean beam likelihood at the last update; NaN when the map could not tell.
  double fit = 0.0;
  bool diverged = false;  ///< the filter declared itself lost on this scan
  /// The scan matched from `pose` onto the walls (only when converged and refining; its
  /// failure is `too_few_inliers` with no inliers otherwise).
  ScanMatch match;
  bool matched = false;  ///< whether `match` was computed
};

/// Feeds one particle filter the scans of a log in order, one scan per step: the odometry
/// motion since the previous step, a measurement update when the robot has moved enough
/// (with the improved proposal while converged), and, while converged, the scan matched from
/// the mean pose. The filter is the runner's own; callers initialize and re-initialize it.
class FilterRunner {
 public:
  /// A runner over `log` with `model` on the map whose walls are `walls`; each scan is prepared
  /// for `model` as it is stepped (make_observation with `observation`), so a long log's
  /// prepared scans are never all held. Everything given by reference must outlive the runner.
  /// With `caster` (the same map's walls), scans are matched by their beams consistent with
  /// it (for a plan: not the endpoints on furniture it lacks).
  FilterRunner(ParticleFilter filter, const ObservationModel& model, const WallField& walls,
               const RobotLog& log, const ObservationOptions& observation,
               const FilterRunnerOptions& options, const GridRayCaster* caster = nullptr);

  /// Advances to scan `i` (the motion from the last scan stepped, or none for the first) and
  /// records what the filter did. Scans must come in increasing order.
  FilterRecord step(std::size_t i);
  /// Guides the filter's motion by `poses` (one per scan of the log, the same frame and units
  /// as the odometry; none where unknown): between two scans that both have one and whose
  /// motion agrees with the odometry's (FilterRunnerOptions::guide_max_translation...), the
  /// filter moves by the poses' motion with guided_noise. For the plan filter, the gridmap
  /// filter's poses where it is converged: far more precise than the odometry.
  void guide(std::vector<std::optional<Pose2>> poses) { guide_ = std::move(poses); }
  /// Steps whose motion came from the guide so far.
  std::size_t guided_steps() const { return guided_steps_; }
  /// Takes scan `i` as already used (a filter seeded from its hypotheses): the next step
  /// carries the motion from it.
  void start_at(std::size_t i) { last_ = i; }
  /// The filter, to initialize or re-initialize (a fresh filter may be assigned).
  ParticleFilter& filter() { return filter_; }
  /// Improved-proposal corrections applied so far.
  std::size_t corrections() const { return corrections_; }
  /// Particle-beam evaluations of the measurement updates so far (particles x beams).
  std::size_t evaluations() const { return evaluations_; }

 private:
  ParticleFilter filter_;
  const ObservationModel& model_;
  const WallField& walls_;
  const RobotLog& log_;
  ObservationOptions observation_;  ///< how a scan is prepared for model_
  FilterRunnerOptions options_;
  const GridRayCaster* caster_;
  /// The guide's motion from scan `from` to scan `to`, when both have a guide pose, the
  /// odometry's step is large enough to be guided and the guide's motion agrees with it.
  std::optional<OdometryMotion> guided_motion(std::size_t from, std::size_t to) const;

  std::vector<std::optional<Pose2>> guide_;
  std::size_t guided_steps_ = 0;
  std::optional<std::size_t> last_;    // the last scan stepped
  double moved_ = 0.0, turned_ = 0.0;  // odometry since the last update
  std::size_t corrections_ = 0;
  std::size_t evaluations_ = 0;
};

/// Moves the cloud of a converged, tracking filter onto the pose `match_scan` finds from the
/// cloud's mean (the improved proposal's correction; along a degenerate direction the cloud
/// keeps its own position), when the match is accepted or only degenerate. Returns the match.
/// With `caster`, matches the beams consistent with it (within `tolerance`).
ScanMatch apply_proposal(ParticleFilter& filter, const WallField& walls,
                         const ScanObservation& points, const ScanMatchOptions& options,
                         const GridRayCaster* caster = nullptr, double tolerance = 0.5);

/// match_scan, by the beams consistent with `caster` when one is given.
ScanMatch match_with(const WallField& walls, const ScanObservation& points, const Pose2& pose,
                     double scale, const ScanMatchOptions& options, const GridRayCaster* caster,
                     double tolerance);

}  // namespace floorgrid
