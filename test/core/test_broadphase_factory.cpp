// The factory: names, and auto's rule (ChooseBroadPhaseMethod) on each side of its crossovers,
// its monotonicity in the statics, its crossover rising with the movers, and MakeBroadPhase(kAuto)
// building what the rule names.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/broadphase/grid_broad_phase.h"
#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

constexpr BroadPhaseMethod kAll[] = {BroadPhaseMethod::kAuto,  BroadPhaseMethod::kOctree,
                                     BroadPhaseMethod::kNaive, BroadPhaseMethod::kGrid,
                                     BroadPhaseMethod::kRebuild, BroadPhaseMethod::kReinsert};

TEST(BroadPhaseFactory, NamesRoundTrip) {
  for (const BroadPhaseMethod m : kAll) {
    BroadPhaseMethod parsed = BroadPhaseMethod::kReinsert == m ? BroadPhaseMethod::kAuto
                                                               : BroadPhaseMethod::kReinsert;
    ASSERT_TRUE(ParseBroadPhaseMethod(BroadPhaseMethodName(m), &parsed)) << int(m);
    EXPECT_EQ(parsed, m);
  }
  BroadPhaseMethod unchanged = BroadPhaseMethod::kGrid;
  EXPECT_FALSE(ParseBroadPhaseMethod("Auto", &unchanged));
  EXPECT_FALSE(ParseBroadPhaseMethod("", &unchanged));
  EXPECT_EQ(unchanged, BroadPhaseMethod::kGrid);
  EXPECT_EQ(BroadPhaseOptions{}.method, BroadPhaseMethod::kAuto);
}

TEST(BroadPhaseAuto, CrossoversOnBothSides) {
  // Few statics: all pairs, up to the moving crossover.
  EXPECT_EQ(ChooseBroadPhaseMethod(14, 0), BroadPhaseMethod::kNaive);
  EXPECT_EQ(ChooseBroadPhaseMethod(kAutoGridMinMoving - 1, kAutoGridMinStatics - 1),
            BroadPhaseMethod::kNaive);
  EXPECT_EQ(ChooseBroadPhaseMethod(kAutoGridMinMoving, 0), BroadPhaseMethod::kGrid);
  // More statics: the grid from its crossover, which grows with the movers.
  EXPECT_EQ(ChooseBroadPhaseMethod(0, kAutoGridMinStatics - 1), BroadPhaseMethod::kNaive);
  EXPECT_EQ(ChooseBroadPhaseMethod(0, kAutoGridMinStatics), BroadPhaseMethod::kGrid);
  EXPECT_EQ(ChooseBroadPhaseMethod(10, kAutoGridMinStatics + 18), BroadPhaseMethod::kNaive);
  EXPECT_EQ(ChooseBroadPhaseMethod(10, kAutoGridMinStatics + 19), BroadPhaseMethod::kGrid);
  // The sweep's points where one crossover for all mover counts chose the slower side
  // (core/constants.h): naive at 300+700, 450+1,000 and 1,200+1,000; the grid at 14+2,000,
  // 150+1,000, 300+3,000 and 1,200+3,000.
  EXPECT_EQ(ChooseBroadPhaseMethod(300, 700), BroadPhaseMethod::kNaive);
  EXPECT_EQ(ChooseBroadPhaseMethod(450, 1000), BroadPhaseMethod::kNaive);
  EXPECT_EQ(ChooseBroadPhaseMethod(1200, 1000), BroadPhaseMethod::kNaive);
  EXPECT_EQ(ChooseBroadPhaseMethod(14, 2000), BroadPhaseMethod::kGrid);
  EXPECT_EQ(ChooseBroadPhaseMethod(150, 1000), BroadPhaseMethod::kGrid);
  EXPECT_EQ(ChooseBroadPhaseMethod(300, 3000), BroadPhaseMethod::kGrid);
  EXPECT_EQ(ChooseBroadPhaseMethod(1200, 3000), BroadPhaseMethod::kGrid);
  EXPECT_EQ(ChooseBroadPhaseMethod(1, 100000), BroadPhaseMethod::kGrid);
  EXPECT_EQ(ChooseBroadPhaseMethod(0xffffffffu, 0xffffffffu), BroadPhaseMethod::kGrid);
  EXPECT_EQ(ChooseBroadPhaseMethod(kAutoGridMinMoving - 1, 0xffffffffu),
            BroadPhaseMethod::kGrid);
  // An empty scene still gets a structure.
  EXPECT_EQ(ChooseBroadPhaseMethod(0, 0), BroadPhaseMethod::kNaive);
}

// More statics never choose a lighter index than fewer, for any count of movers; more movers
// raise the statics the grid needs, up to kAutoGridMinMoving, from which it is always the grid.
TEST(BroadPhaseAuto, MonotoneInStaticsCrossoverRisingWithMovers) {
  std::uint32_t previous_crossover = 0;
  for (std::uint32_t moving = 0; moving < kAutoGridMinMoving; moving += 97) {
    std::uint32_t crossover = 0;  // the fewest statics (step 11) that choose the grid
    for (std::uint32_t statics = 0; statics <= 30000; statics += 11) {
      const BroadPhaseMethod m = ChooseBroadPhaseMethod(moving, statics);
      ASSERT_TRUE(m == BroadPhaseMethod::kNaive || m == BroadPhaseMethod::kGrid)
          << moving << " " << statics;
      if (m == BroadPhaseMethod::kGrid && crossover == 0) crossover = statics;
      if (crossover != 0) {
        ASSERT_EQ(m, BroadPhaseMethod::kGrid) << moving << " " << statics;
      }
    }
    ASSERT_GT(crossover, 0u) << moving;
    EXPECT_GE(crossover, previous_crossover) << moving;
    previous_crossover = crossover;
  }
  EXPECT_GT(previous_crossover, 10 * kAutoGridMinStatics);
  for (std::uint32_t statics = 0; statics <= 30000; statics += 997) {
    EXPECT_EQ(ChooseBroadPhaseMethod(kAutoGridMinMoving, statics), BroadPhaseMethod::kGrid);
  }
}

TEST(BroadPhaseAuto, GridCellsAboutTheBoxEdge) {
  EXPECT_EQ(GridCellsFor(6.0, 1.0, 16), 6);
  EXPECT_EQ(GridCellsFor(6.35, 0.5, 16), 13);  // 12.7 rounded
  EXPECT_EQ(GridCellsFor(6.0, 100.0, 16), kAutoGridMinCellsPerAxis);
  EXPECT_EQ(GridCellsFor(6.0, 1e-6, 1000), kAutoGridMaxCellsPerAxis);
  EXPECT_EQ(GridCellsFor(6.0, 0.1, 16), 16);  // never finer than configured
  EXPECT_EQ(GridCellsFor(6.0, 0.1, 40), 40);
  EXPECT_EQ(GridCellsFor(6.0, 0.0, 16), 16);  // unknown edge: the configured G
  EXPECT_EQ(GridCellsFor(6.0, 0.0, 100), 100);
  EXPECT_EQ(GridCellsFor(0.0, 1.0, 9), 9);
  EXPECT_EQ(GridCellsFor(std::nan(""), 1.0, 9), 9);
  EXPECT_EQ(GridCellsFor(6.0, std::numeric_limits<double>::infinity(), 9), 9);
}

TEST(BroadPhaseAuto, MakeBroadPhaseBuildsTheChosenMethod) {
  BroadPhaseOptions options;
  options.method = BroadPhaseMethod::kAuto;
  options.world_W.min_W = Eigen::Vector3d::Constant(-1.0);
  options.world_W.max_W = Eigen::Vector3d::Constant(1.0);
  const std::uint32_t points[][2] = {{14, 21}, {14, 100}, {14, 2000}, {150, 0}};
  for (const auto& p : points) {
    options.auto_moving = p[0];
    options.auto_statics = p[1];
    const auto bp = MakeBroadPhase(options);
    ASSERT_NE(bp, nullptr);
    EXPECT_EQ(bp->name(), BroadPhaseMethodName(ChooseBroadPhaseMethod(p[0], p[1])));
    EXPECT_NE(bp->name(), "auto");
  }
  // The grid it builds has cells of about the movers' box edge: 2 m / 0.5 m = 4 per axis.
  options.auto_moving = 14;
  options.auto_statics = 2000;
  options.auto_moving_box_edge_m = 0.5;
  const auto bp = MakeBroadPhase(options);
  const auto* grid = dynamic_cast<const GridBroadPhase*>(bp.get());
  ASSERT_NE(grid, nullptr);
  EXPECT_DOUBLE_EQ(grid->cell_size_m(), 0.5);
}

}  // namespace
}  // namespace arm_collision_monitor
