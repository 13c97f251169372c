// Experiment "static": Figure 6 of the seed, static boxes added near and far from the arms.

#include "experiments.h"

#include "arm_collision_monitor/core/timing_summary.h"

namespace arm_collision_monitor {
namespace bench {

void ExperimentStaticScaling(const Args& args, const Scenario& base, std::uint64_t* missed_total) {
  Csv csv(args.out_dir + "/static_scaling.csv",
          "placement,added,primitives,active,impl,mean_us,median_us,p99_us,missed,false");
  std::printf("== Figure 6 / static scaling (seed %llu)\n",
              static_cast<unsigned long long>(args.seed));
  std::vector<int> sizes = args.quick ? std::vector<int>{0, 100, 500, 2000, 9965}
                                      : std::vector<int>{0, 25, 50, 100, 200, 500, 1000, 2000,
                                                         5000, 9965};
  const std::string scene = ReadFile(SourcePath("config/scene.yaml"));
  for (const bool near : {true, false}) {
    for (int added : sizes) {
      if (!near && added > 2000) continue;
      std::mt19937_64 rng(args.seed + added);
      const std::string path = args.out_dir + "/scene_extra.yaml";
      WriteFile(path, InsertAfterKey(scene, "objects", ExtraBoxesYaml(&rng, added, near)));
      Scenario s;
      s.label = near ? "near" : "far";
      s.workcell = std::make_shared<const Workcell>(
          LoadWorkcell(SourcePath("urdf/workcell.urdf"), path));
      s.tasks = MapTasks(base.tasks, *base.workcell, *s.workcell);
      // Brute force on every cycle up to 200 added boxes, every 10th up to 2,000, every 50th
      // beyond (its cost grows with the scene; the check is the same).
      const Reference ref = BruteForce(s, added > 2000 ? 50 : added > 200 ? 10 : 1);
      const int total = static_cast<int>(s.workcell->primitives.size());
      std::vector<RunResult> results = RunScalingImplementations(s, ref, SeedLoopOptions());
      if (near) {
        // The default Monitor (index slack) too: where its octree or grid overtakes its naive
        // broad phase are crossovers auto's rule (ChooseBroadPhaseMethod) is checked against.
        for (const char* method : {"octree", "naive", "grid"}) {
          MonitorOptions o = DefaultOptions();
          ParseBroadPhaseMethod(method, &o.broad_phase.method);
          results.push_back(RunMonitor(s, o, &ref, std::string(method) + " (default slack)"));
        }
      }
      std::printf(" %s +%d boxes (%d primitives, %zu active)\n", s.label.c_str(), added, total,
                  results.front().active_primitives);
      for (const RunResult& r : results) {
        PrintRow(r);
        if (r.impl.find('_') == std::string::npos) *missed_total += r.missed;
        const TimingSummary sm = SummarizeTimings(r.t_us);
        csv.Row(s.label, added, total, r.active_primitives, r.impl, sm.mean, sm.median,
                sm.p99, r.missed, r.false_warnings);
      }
    }
  }
}

}  // namespace bench
}  // namespace arm_collision_monitor
