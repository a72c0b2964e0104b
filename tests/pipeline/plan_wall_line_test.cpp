// Where the scan matchers meet a raster plan's walls: at the ink cells' centres, at the ink's
// edges, or decided by the maps' faces fit (the partitions' faces' offset in world metres).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "floorgrid/pipeline/dual_maps.hpp"
#include "floorgrid/pipeline/map_alignment.hpp"

namespace floorgrid {
namespace {

struct Inputs {
  OccupancyGrid plan, gridmap;
  RobotLog log;
  MapAlignment maps;
  VectorFloorplan drawing;

  /// The maps' faces fit found the partitions' faces `offset_world` world metres off their
  /// strokes, with a registration of `plan_per_world` plan metres per world metre.
  Inputs(double offset_world, double plan_per_world) {
    maps.registration.best.transform.scale = plan_per_world;
    maps.faces.partition_points = 300;
    maps.faces.partition_offset = offset_world * plan_per_world;
  }
  DualLocalizerInputs raster() const {
    return {.plan = plan, .gridmap = gridmap, .log = log, .maps = &maps};
  }
};

bool decide(const DualLocalizerInputs& in, PlanWallLine line, std::vector<std::string>& notes) {
  DualLocalizerOptions options;
  options.plan_wall_line = line;
  return plan_walls_at_ink_edges(in, options, notes);
}

TEST(PlanWallLine, AutomaticFollowsThePartitionsFacesInWorldMetres) {
  std::vector<std::string> notes;
  // A plan traced over a gridmap: faces 0.04 m off (at any plan scale) keep the centres.
  for (const double plan_per_world : {0.5, 2.0}) {
    EXPECT_FALSE(decide(Inputs(0.04, plan_per_world).raster(), PlanWallLine::automatic, notes));
  }
  EXPECT_TRUE(notes.empty());
  // Walls built thicker than drawn: 0.08 m off. In plan metres that is 0.04 at a plan scale of
  // 0.5: the offset is compared in world metres.
  EXPECT_TRUE(decide(Inputs(0.08, 0.5).raster(), PlanWallLine::automatic, notes));
  ASSERT_EQ(notes.size(), 1U);
  EXPECT_NE(notes[0].find("0.080 m"), std::string::npos) << notes[0];
  // No faces measured: the centres.
  Inputs unmeasured(0.08, 1.0);
  unmeasured.maps.faces.partition_points = 0;
  EXPECT_FALSE(decide(unmeasured.raster(), PlanWallLine::automatic, notes));
  DualLocalizerInputs no_maps = unmeasured.raster();
  no_maps.maps = nullptr;
  EXPECT_FALSE(decide(no_maps, PlanWallLine::automatic, notes));
}

TEST(PlanWallLine, AnExplicitChoiceWinsAndAVectorPlanIsExact) {
  std::vector<std::string> notes;
  const Inputs thick(0.08, 1.0), traced(0.04, 1.0);
  EXPECT_FALSE(decide(thick.raster(), PlanWallLine::cell_centres, notes));
  EXPECT_TRUE(decide(traced.raster(), PlanWallLine::ink_edges, notes));
  DualLocalizerInputs vector = thick.raster();
  vector.plan_geometry = &thick.drawing;
  for (const PlanWallLine line :
       {PlanWallLine::automatic, PlanWallLine::ink_edges, PlanWallLine::cell_centres}) {
    EXPECT_FALSE(decide(vector, line, notes));
  }
}

}  // namespace
}  // namespace floorgrid
