// The dual check on hand-made records: a plan filter a room away from where the gridmap filter
// puts it is re-initialized after a couple of scans; one just beyond the tolerance only after
// consistency_scans.
#include <gtest/gtest.h>

#include "floorgrid/pipeline/plan_tracking.hpp"

namespace floorgrid {
namespace {

/// A scan on which the gridmap filter is converged at the origin and the plan filter, converged
/// too, `off` metres away along x (plan and grid share their frame: the registration is the
/// identity at scale 1).
ScanRecord record_off(double off) {
  ScanRecord r;
  r.grid.converged = true;
  r.grid.pose = {0.0, 0.0, 0.0};
  r.plan.converged = true;
  r.plan.pose = {off, 0.0, 0.0};
  return r;
}

/// The scan on which the check first re-initializes the plan filter (0 when it never does in
/// 20 scans).
std::size_t first_restart(double off, const DualCheckOptions& options) {
  const PlanRegistration identity(Pose2{0.0, 0.0, 0.0}, Pose2{0.0, 0.0, 0.0}, 1.0);
  DualCheck check(options, identity, 1.0);
  for (std::size_t scan = 1; scan <= 20; ++scan) {
    ScanRecord r = record_off(off);
    if (const auto restart = check.judge(scan, r)) {
      EXPECT_EQ(restart->reason, "inconsistent");
      EXPECT_NEAR(restart->start.pose.x, 0.0, 1e-12);
      return scan;
    }
  }
  return 0;
}

TEST(DualCheck, APlanFilterARoomAwayIsReinitializedAtOnce) {
  const DualCheckOptions options;  // consistency_distance 3 m, gross_factor 2, gross_scans 2
  EXPECT_EQ(first_restart(1.0, options), 0u);  // within the tolerance: never
  EXPECT_EQ(first_restart(4.0, options), std::size_t(options.consistency_scans));
  EXPECT_EQ(first_restart(7.0, options), std::size_t(options.gross_scans));
  DualCheckOptions patient = options;
  patient.gross_factor = 1e9;  // gross never: the old patience
  EXPECT_EQ(first_restart(7.0, patient), std::size_t(options.consistency_scans));
  DualCheckOptions never = options;
  never.gross_scans = 0;
  EXPECT_EQ(first_restart(7.0, never), std::size_t(options.consistency_scans));
}

}  // namespace
}  // namespace floorgrid
