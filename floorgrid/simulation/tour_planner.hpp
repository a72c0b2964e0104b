#pragma once

#include <Eigen/Core>
#include <vector>

#include "floorgrid/core/random.hpp"
#include "floorgrid/simulation/plan_world.hpp"

namespace floorgrid {

/// Where the robot of a drawing's world drives. Lengths in world metres.
struct TourPlanOptions {
  double clearance = 0.3;      ///< metres from the robot's centre to anything solid
  double resolution = 0.05;    ///< metres per cell of the planning grid
  double goal_spacing = 4.0;   ///< metres between the places visited in one region
  double max_length = 240.0;   ///< metres: the tour stops once it is this long
  double wall_distance = 0.8;  ///< metres: paths keep this far from walls where they can
  double wall_penalty = 3.0;   ///< extra cost per metre driven right at the clearance
};

/// The robot's tour: waypoints for drive_tour and what they visit.
struct TourPlan {
  std::vector<Eigen::Vector2d> waypoints;  ///< world metres, in order
  std::vector<int> visited;                ///< regions the tour enters
  std::vector<int> skipped;                ///< reachable regions it leaves out on purpose
  std::vector<int> unreachable;            ///< regions the robot cannot reach
  double length = 0.0;                     ///< metres along the waypoints
  double reachable_area = 0.0;             ///< square metres the robot's centre can reach
};

/// Plans a tour through the reachable inside of `world`: the robot's centre keeps `clearance`
/// from everything solid; it starts in the largest region, then goes to the nearest place not
/// yet visited (each region's point farthest from its walls, and more points `goal_spacing`
/// apart in large ones) along the cheapest path (which keeps `wall_distance` from walls where
/// it can), until every place is visited or the tour is `max_length` long. One reachable room
/// is left out when every region would be visited. Paths are shortened to straight legs that
/// keep as far from obstacles as the path did. Deterministic for a `random` state. InputError
/// (field "plan") when the robot can reach less than 4 square metres.
TourPlan plan_tour(const PlanWorld& world, const TourPlanOptions& options, Random& random);

}  // namespace floorgrid
