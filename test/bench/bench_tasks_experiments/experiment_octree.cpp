// Experiment "octree": the seed's octree statistics and the cycles between splits or merges.

#include "experiments.h"

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/broadphase/octree_broad_phase.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"

namespace arm_collision_monitor {
namespace bench {

void ExperimentOctreeStatistics(const Args& args, const Scenario& s) {
  const Workcell& wc = *s.workcell;
  MonitorOptions mo = DefaultOptions();
  mo.index_slack_m = 0.0;
  BroadPhaseOptions o = mo.broad_phase;
  o.method = BroadPhaseMethod::kOctree;
  o.world_W = wc.world_W;
  o.min_cell_size_m = MinCellSize_m(mo);
  auto bp = MakeBroadPhase(o);
  auto* octree = dynamic_cast<OctreeBroadPhase*>(bp.get());
  WorkcellShapes eval(wc);
  int count = 0;
  for (PrimitiveId id = 0; id < wc.primitives.size(); ++id) {
    if (!eval.is_default_model(id)) continue;
    const PrimitiveSpec& p = wc.primitives[id];
    bp->Add(id, ComputeAabb(eval.shape_W(id)), p.tolerance_m,
            p.is_static ? Motion::kStatic : Motion::kMoving);
    ++count;
  }
  const OctreeStatistics st = octree->ComputeStatistics();
  const RunResult run = RunMonitor(s, SeedLoopOptions(), nullptr, "octree (slack 0)");
  const double events = static_cast<double>(run.counters.splits + run.counters.merges);
  Csv csv(args.out_dir + "/octree_statistics.csv", "statistic,ours,seed");
  csv.Row("primitives", count, 35);
  csv.Row("nodes", st.nodes, 33);
  csv.Row("leaves", st.leaves, 29);
  csv.Row("empty_leaves", st.empty_leaves, 15);
  csv.Row("primitives_per_nonempty_leaf", st.mean_primitives_per_nonempty_leaf, 5);
  csv.Row("leaves_per_primitive", st.mean_leaves_per_primitive, 2);
  csv.Row("depth", st.depth, 2);
  csv.Row("splits_plus_merges_over_tasks", events, "");
  csv.Row("cycles_between_split_or_merge", events > 0 ? s.cycles() / events : -1.0, 600);
  std::printf("== octree: %d primitives, %u nodes, %u leaves (%u empty), %.2f per leaf, %.2f "
              "leaves per primitive, depth %d; %.0f split/merge events in %zu cycles\n",
              count, st.nodes, st.leaves, st.empty_leaves, st.mean_primitives_per_nonempty_leaf,
              st.mean_leaves_per_primitive, st.depth, events, s.cycles());
}

}  // namespace bench
}  // namespace arm_collision_monitor
