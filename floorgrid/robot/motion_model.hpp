#pragma once

#include "floorgrid/core/random.hpp"
#include "floorgrid/geometry/pose2.hpp"

namespace floorgrid {

/// A motion in the odometry model's terms (Thrun, Burgard, Fox, Probabilistic Robotics 5.4):
/// turn by rot1 towards the direction of travel, drive trans, turn by rot2.
struct OdometryMotion {
  double rot1 = 0.0;   ///< radians
  double trans = 0.0;  ///< metres
  double rot2 = 0.0;   ///< radians
};

/// The noise of the odometry motion model: the standard deviation of each part grows with
/// the motion (variances alpha1 rot1^2 + alpha2 trans^2 for the rotations, alpha3 trans^2 +
/// alpha4 (rot1^2 + rot2^2) for the translation), where each rotation's size is capped at the
/// net turn |rot1 + rot2| (see sample_noisy_motion).
struct MotionNoise {
  double alpha1 = 0.05;  ///< rotation noise from rotation (rad^2/rad^2)
  double alpha2 = 0.01;  ///< rotation noise from translation (rad^2/m^2)
  double alpha3 = 0.02;  ///< translation noise from translation (m^2/m^2)
  double alpha4 = 0.05;  ///< translation noise from rotation (m^2/rad^2)
};

/// Below this translation (metres) a motion is a turn on the spot: rot1 is 0 and the whole
/// turn is rot2, since the direction of travel is undefined.
inline constexpr double kTurnOnSpotTranslation = 1e-6;

/// The motion that takes `from` to `to` (both in one frame). Replaces the thesis's
/// eq. 3.39-3.42, which drop the previous position.
OdometryMotion odometry_motion(const Pose2& from, const Pose2& to);

/// `pose` moved by `motion` (rot1 in its frame, then trans along the new heading, then rot2).
Pose2 apply_motion(const Pose2& pose, const OdometryMotion& motion);

/// `motion` with sampled noise added to each part, per MotionNoise. Rotations larger than the
/// net turn (a sideways jump: rot1 and rot2 near +-pi/2 with opposite signs) add noise only as
/// large as the net turn.
OdometryMotion sample_noisy_motion(const OdometryMotion& motion, const MotionNoise& noise,
                                   Random& random);

}  // namespace floorgrid
