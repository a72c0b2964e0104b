#include "floorgrid/simulation/building.hpp"

#include <gtest/gtest.h>

#include "floorgrid/maps/rasterize.hpp"
#include "floorgrid/simulation/box_union.hpp"
#include "floorgrid/simulation/robot_tour.hpp"

namespace floorgrid {
namespace {

/// Smallest distance from the robot's path to any world surface.
double path_clearance(const Building& b, const std::vector<TimedPose>& path) {
  double best = 1e9;
  const auto surfaces = b.world_segments();
  for (std::size_t i = 0; i < path.size(); i += 2) {
    for (const Segment& s : surfaces) {
      best = std::min(best, distance_to_segment(path[i].pose.translation(), s));
    }
  }
  return best;
}

class BuildingSeeds : public ::testing::TestWithParam<int> {};

TEST_P(BuildingSeeds, OfficeMatchesThePreset) {
  Random random(GetParam());
  const Building b = generate_building({"office"}, random);
  EXPECT_GE(b.rooms.size(), 8u);
  EXPECT_NEAR(b.outline.sizes().x(), 40.0, 5.0);
  EXPECT_NEAR(b.outline.sizes().y(), 20.0, 3.5);
  int unvisited = 0;
  for (const Room& r : b.rooms)
    unvisited += r.visited ? 0 : 1;
  EXPECT_GE(unvisited, 1);
  ASSERT_GE(b.rotated_room, 0);
  EXPECT_TRUE(b.rooms[static_cast<std::size_t>(b.rotated_room)].visited);
  EXPECT_EQ(b.door_swings.size(), b.rooms.size());
  for (const Arc& a : b.door_swings) {
    EXPECT_GE(a.radius, 0.6);  // door swing radii make the plan's units recognisable
    EXPECT_LE(a.radius, 1.2);
  }
  const VectorFloorplan plan = b.plan_in_world();
  EXPECT_EQ(plan.layers(), (std::vector<std::string>{"WALLS", "DOORS"}));
  EXPECT_FALSE(b.furniture.empty());
}

TEST_P(BuildingSeeds, WarehouseMatchesThePreset) {
  Random random(GetParam());
  const Building b = generate_building({"warehouse"}, random);
  EXPECT_NEAR(b.outline.sizes().x(), 100.0, 5.0);
  EXPECT_NEAR(b.outline.sizes().y(), 50.0, 5.0);
  EXPECT_GE(b.rack_boxes.size(), 6u);
  EXPECT_GE(b.rooms.size(), 3u);
  const VectorFloorplan plan = b.plan_in_world();
  EXPECT_EQ(plan.layers(), (std::vector<std::string>{"WALLS", "RACKS", "DOORS"}));
}

TEST_P(BuildingSeeds, TourStaysClearOfEverySurfaceAndInsideTheBuilding) {
  for (const char* kind : {"office", "warehouse"}) {
    Random random(GetParam());
    const Building b = generate_building({kind}, random);
    const auto path = drive_tour(b.tour);
    ASSERT_GT(path.size(), 100u);
    EXPECT_GT(path_clearance(b, path), 0.3) << kind;
    for (const auto& p : path) {
      ASSERT_TRUE(b.outline.contains(p.pose.translation())) << kind;
      ASSERT_FALSE(inside_any(b.wall_boxes, p.pose.translation())) << kind;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, BuildingSeeds, ::testing::Values(1, 2, 3, 4));

TEST(Building, SameSeedSameBuildingOtherSeedOther) {
  Random a(9), b(9), c(10);
  const Building x = generate_building({"office"}, a);
  const Building y = generate_building({"office"}, b);
  const Building z = generate_building({"office"}, c);
  ASSERT_EQ(x.walls.size(), y.walls.size());
  for (std::size_t i = 0; i < x.walls.size(); ++i)
    EXPECT_EQ(x.walls[i].a, y.walls[i].a);
  EXPECT_NE(x.outline.sizes().x(), z.outline.sizes().x());
}

TEST(RobotTour, DrivesThroughEveryWaypoint) {
  const std::vector<Eigen::Vector2d> waypoints{{0, 0}, {3, 0}, {3, 2}, {0, 2}};
  TourOptions options;
  const auto path = drive_tour(waypoints, options);
  for (const auto& w : waypoints) {
    double best = 1e9;
    for (const auto& p : path)
      best = std::min(best, (p.pose.translation() - w).norm());
    EXPECT_LT(best, options.arrive_distance + options.speed * options.tick);
  }
  EXPECT_NEAR(path_length(path), 8.0, 0.3);
  for (std::size_t i = 1; i < path.size(); ++i) {
    EXPECT_NEAR(path[i].time - path[i - 1].time, options.tick, 1e-9);
    EXPECT_LE((path[i].pose.translation() - path[i - 1].pose.translation()).norm(),
              options.speed * options.tick + 1e-12);
  }
}

}  // namespace
}  // namespace floorgrid
