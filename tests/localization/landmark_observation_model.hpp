#pragma once

// A test-only observation model with an analytic likelihood, to test the particle filter
// without maps: the scan's "endpoints" are point landmarks seen from the robot.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <thread>
#include <utility>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/localization/observation_model.hpp"
#include "floorgrid/robot/motion_model.hpp"

namespace floorgrid::test {

/// Landmarks at known map positions; ScanObservation endpoint k is landmark `beam[k]` as seen
/// from the robot (robot frame, world metres). For a particle at pose p with scale s, the
/// endpoint lands at p o (e_k / s); its error |p o (e_k / s) - L| is in map metres, s times
/// that in world metres, and the log-likelihood is the Gaussian
/// -sum_k (s |p o (e_k / s) - L_k|)^2 / (2 sigma^2) (sigma in world metres).
class LandmarkObservationModel : public ObservationModel {
 public:
  LandmarkObservationModel(std::vector<Eigen::Vector2d> landmarks_in_map, double sigma)
      : landmarks_(std::move(landmarks_in_map)), sigma_(sigma) {}

  void log_likelihood(const ScanObservation& scan, const ParticleSet& particles,
                      std::vector<double>& out, int threads = 2) const override {
    out.resize(particles.size());
    const std::size_t n = particles.size();
    auto run = [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        double sum = 0.0;
        for (std::size_t k = 0; k < scan.size(); ++k)
          sum += squared_error(scan, k, particles.pose(i), particles.scale_of(i));
        out[i] = -sum / (2.0 * sigma_ * sigma_);
      }
    };
    // Really threaded, so that a thread-count test means something; each particle's value is
    // computed the same way whatever the split.
    const std::size_t parts = static_cast<std::size_t>(std::max(1, threads));
    std::vector<std::thread> workers;
    for (std::size_t t = 1; t < parts; ++t)
      workers.emplace_back(run, n * t / parts, n * (t + 1) / parts);
    run(0, n / parts);
    for (std::thread& w : workers)
      w.join();
  }

  double mean_beam_likelihood(const ScanObservation& scan, const Pose2& pose,
                              double scale) const override {
    if (scan.size() == 0)
      return 0.0;
    double sum = 0.0;
    for (std::size_t k = 0; k < scan.size(); ++k)
      sum += std::exp(-squared_error(scan, k, pose, scale) / (2.0 * sigma_ * sigma_));
    return sum / static_cast<double>(scan.size());
  }

  /// Every landmark seen from `pose_in_map` when a map metre is `scale` world metres, with
  /// Gaussian noise `noise` (world metres) on each coordinate.
  ScanObservation observe(const Pose2& pose_in_map, double scale, double noise,
                          Random& random) const {
    ScanObservation scan;
    scan.max_range = 100.0;
    for (std::size_t k = 0; k < landmarks_.size(); ++k) {
      const Eigen::Vector2d in_robot = scale * pose_in_map.inverse().transform(landmarks_[k]);
      const double x = in_robot.x() + random.normal(noise), y = in_robot.y() + random.normal(noise);
      scan.end_x.push_back(static_cast<float>(x));
      scan.end_y.push_back(static_cast<float>(y));
      scan.angle.push_back(static_cast<float>(std::atan2(y, x)));
      scan.range.push_back(static_cast<float>(std::hypot(x, y)));
      scan.beam.push_back(static_cast<int>(k));
    }
    return scan;
  }

 private:
  double squared_error(const ScanObservation& scan, std::size_t k, const Pose2& pose,
                       double scale) const {
    const Eigen::Vector2d end(scan.end_x[k], scan.end_y[k]);
    const Eigen::Vector2d error =
        pose.transform(end / scale) - landmarks_[static_cast<std::size_t>(scan.beam[k])];
    return scale * scale * error.squaredNorm();
  }

  std::vector<Eigen::Vector2d> landmarks_;
  double sigma_;
};

/// A simulated run in a map whose metre is `scale` world metres: the true poses (map frame),
/// the noisy odometry between them (world metres) and the landmark scans.
struct LandmarkRun {
  std::vector<Pose2> truth;              ///< true pose at each scan, map frame
  std::vector<OdometryMotion> odometry;  ///< odometry from scan i-1 to i (entry 0: none)
  std::vector<ScanObservation> scans;    ///< the scan at each pose
};

/// Drives a circle of `radius` map metres about `center` (counter-clockwise, `step` radians of
/// arc per scan) for `scans` scans, the odometry disturbed per `noise` (world metres).
inline LandmarkRun circle_run(const LandmarkObservationModel& model, Eigen::Vector2d center,
                              double radius, double step, int scans, double scale,
                              const MotionNoise& noise, double observation_noise,
                              std::uint64_t seed) {
  Random random(seed);
  LandmarkRun run;
  Pose2 previous;
  for (int i = 0; i < scans; ++i) {
    const double phi = step * i;
    const Pose2 pose{center.x() + radius * std::cos(phi), center.y() + radius * std::sin(phi),
                     normalize_angle(phi + std::numbers::pi / 2)};
    OdometryMotion odometry;
    if (i > 0) {
      const Pose2 from{scale * previous.x, scale * previous.y, previous.theta};
      const Pose2 to{scale * pose.x, scale * pose.y, pose.theta};
      odometry = sample_noisy_motion(odometry_motion(from, to), noise, random);
    }
    run.truth.push_back(pose);
    run.odometry.push_back(odometry);
    run.scans.push_back(model.observe(pose, scale, observation_noise, random));
    previous = pose;
  }
  return run;
}

}  // namespace floorgrid::test
