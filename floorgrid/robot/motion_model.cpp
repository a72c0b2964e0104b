#include "floorgrid/robot/motion_model.hpp"

#include <algorithm>

#include <cmath>
#include <numbers>

namespace floorgrid {

OdometryMotion odometry_motion(const Pose2& from, const Pose2& to) {
  const double dx = to.x - from.x, dy = to.y - from.y;
  OdometryMotion m;
  m.trans = std::hypot(dx, dy);
  if (m.trans < kTurnOnSpotTranslation) {
    m.trans = 0.0;
    m.rot2 = normalize_angle(to.theta - from.theta);
    return m;
  }
  m.rot1 = normalize_angle(std::atan2(dy, dx) - from.theta);
  // Driving backwards is a short reverse, not a half turn and back.
  if (std::abs(m.rot1) > std::numbers::pi / 2) {
    m.rot1 = normalize_angle(m.rot1 + std::numbers::pi);
    m.trans = -m.trans;
  }
  m.rot2 = normalize_angle(to.theta - from.theta - m.rot1);
  return m;
}

Pose2 apply_motion(const Pose2& pose, const OdometryMotion& m) {
  const double heading = pose.theta + m.rot1;
  return {pose.x + m.trans * std::cos(heading), pose.y + m.trans * std::sin(heading),
          normalize_angle(heading + m.rot2)};
}

OdometryMotion sample_noisy_motion(const OdometryMotion& m, const MotionNoise& n, Random& random) {
  // Over one odometry period a differential-drive robot turns about half the net turn before
  // and after driving; rotations much larger than the net turn, of opposite signs, only come
  // from a sideways jump (a SLAM correction in a corrected log, wheel slip), where they are
  // artefacts of the decomposition. Their noise is capped at the net turn, or a 2 cm sideways
  // jump would scatter the headings by half a radian.
  const double net = std::abs(m.rot1 + m.rot2);
  const double a1 = std::min(std::abs(m.rot1), net), a2 = std::min(std::abs(m.rot2), net);
  const double r1 = a1 * a1, r2 = a2 * a2, t = m.trans * m.trans;
  OdometryMotion noisy;
  noisy.rot1 = m.rot1 + random.normal(std::sqrt(n.alpha1 * r1 + n.alpha2 * t));
  noisy.trans = m.trans + random.normal(std::sqrt(n.alpha3 * t + n.alpha4 * (r1 + r2)));
  noisy.rot2 = m.rot2 + random.normal(std::sqrt(n.alpha1 * r2 + n.alpha2 * t));
  return noisy;
}

}  // namespace floorgrid
