// The wrap-around of the 32-bit stamps of the Monitor's own spatial index, forced mid-run
// (Monitor::ForceIndexStampsNearWrap) between the cycles of smooth trajectories: the reports
// must still equal the independent brute force and Check(), Validate() must hold, and the index
// must keep exactly the cells of a twin Monitor that is fed the same joint positions without
// forcing (the cell structure is a function of the boxes, so lost or stale links show there).
#include "test_monitor_util.h"

namespace arm_collision_monitor {
namespace {

using test::ExpectSameWarnings;
using test::LimitsOf;
using test::LoadBundledWorkcell;
using test::OptionsFor;
using test::ReferenceWarnings;

constexpr std::uint64_t kSeed = 20261122;
constexpr int kTrajectories = 3;
constexpr int kCyclesPerTrajectory = 300;
constexpr int kForceEveryCycles = 5;
// Stamps left before the wrap at each forcing, in turn. 0 .. 5 put the wrap in the next
// cycle's first updates and pair scans (a cycle draws tens of stamps); 500, forced again five
// cycles later before the counter got there, moves the counters back over stamps already
// stored, which only the reset that the hook shares with the wrap handling makes safe.
constexpr std::uint32_t kStepsBeforeWrap[] = {0, 1, 2, 3, 4, 5, 500, 500, 500};
// Peak joint speed as a fraction of the velocity limit: the incremental update, not the
// re-insert fallback, is what follows the arms.
constexpr double kSpeedFraction = 0.3;

void ExpectSameCells(const Monitor& forced, const Monitor& twin, const std::string& context) {
  std::vector<IndexCell> forced_cells, twin_cells;
  forced.CollectIndexCells(&forced_cells);
  twin.CollectIndexCells(&twin_cells);
  ASSERT_EQ(forced_cells.size(), twin_cells.size()) << context;
  for (std::size_t i = 0; i < forced_cells.size(); ++i) {
    const IndexCell& a = forced_cells[i];
    const IndexCell& b = twin_cells[i];
    EXPECT_TRUE(a.box_W.min_W == b.box_W.min_W && a.box_W.max_W == b.box_W.max_W &&
                a.primitive_count == b.primitive_count && a.holds_moving == b.holds_moving)
        << context << ": cell " << i << " holds " << a.primitive_count << " primitives, twin "
        << b.primitive_count;
  }
}

class MonitorStamps : public ::testing::TestWithParam<BroadPhaseMethod> {};

TEST_P(MonitorStamps, ForcedWrapMidRunKeepsReportsAndIndex) {
  const auto wc = LoadBundledWorkcell();
  std::mt19937_64 rng(test::PrintSeed(kSeed));
  const test::JointLimits limits = LimitsOf(*wc);
  const std::string method = BroadPhaseMethodName(GetParam());
  int forcings = 0, cycles_with_warnings = 0;
  for (int trajectory = 0; trajectory < kTrajectories; ++trajectory) {
    Monitor monitor(wc, OptionsFor(GetParam()));
    Monitor twin(wc, OptionsFor(GetParam()));
    ASSERT_EQ(monitor.broad_phase_name(), method);
    const test::SmoothTrajectory path(limits, kSpeedFraction, &rng);
    Eigen::VectorXd q;
    for (int k = 0; k < kCyclesPerTrajectory; ++k) {
      const std::string context =
          method + " trajectory " + std::to_string(trajectory) + " cycle " + std::to_string(k);
      if (k % kForceEveryCycles == 0) {
        const std::size_t turn = static_cast<std::size_t>(forcings++) %
                                 (sizeof(kStepsBeforeWrap) / sizeof(kStepsBeforeWrap[0]));
        monitor.ForceIndexStampsNearWrap(kStepsBeforeWrap[turn]);
      }
      path.At(k * monitor.options().cycle_period_s, &q);
      const CycleReport checked = monitor.Check(q);
      const CycleReport& report = monitor.Update(q);
      twin.Update(q);
      const auto expected = ReferenceWarnings(*wc, q);
      ExpectSameWarnings(*wc, expected, report.warnings, context);
      ExpectSameWarnings(*wc, expected, checked.warnings, context + " (Check)");
      EXPECT_EQ(report.stop, test::ExpectedStop(report, !expected.empty())) << context;
      cycles_with_warnings += expected.empty() ? 0 : 1;
      std::string error;
      EXPECT_TRUE(monitor.Validate(&error)) << context << ": " << error;
      EXPECT_TRUE(monitor.ValidateIndex(&error)) << context << ": " << error;
      ExpectSameCells(monitor, twin, context);
      if (::testing::Test::HasFailure()) return;
    }
  }
  std::printf("[ stamps ] %s: %d forcings, %d cycles with warnings\n", method.c_str(), forcings,
              cycles_with_warnings);
  // The forcings must have met pairs to report, or a lost pair could not show.
  EXPECT_GT(cycles_with_warnings, 0);
}

INSTANTIATE_TEST_SUITE_P(CellBroadPhases, MonitorStamps,
                         ::testing::Values(BroadPhaseMethod::kOctree, BroadPhaseMethod::kGrid),
                         [](const ::testing::TestParamInfo<BroadPhaseMethod>& info) {
                           return BroadPhaseMethodName(info.param);
                         });

}  // namespace
}  // namespace arm_collision_monitor
