// Experiment "moving": 1 to 8 arms, the moving primitives scaled.

#include "experiments.h"

#include <algorithm>

#include "arm_collision_monitor/core/timing_summary.h"

namespace arm_collision_monitor {
namespace bench {

void ExperimentMovingScaling(const Args& args, const Scenario& base, std::uint64_t* missed_total) {
  Csv csv(args.out_dir + "/moving_scaling.csv",
          "arms,moving_primitives,impl,mean_us,median_us,p99_us,missed,false");
  std::printf("== moving scaling\n");
  for (const int arms : {1, 2, 4, 6, 8}) {
    const ArmCopies copies = MakeArmCopies(std::max(1, arms / 2));
    const std::string urdf = args.out_dir + "/arms.urdf", scene = args.out_dir + "/arms.yaml";
    WriteFile(urdf, copies.urdf);
    // One arm: the right arm of the pair gets no primitives (its joints still move, unseen).
    std::string right_arm_ignored;
    for (int k = 1; k <= 7; ++k) {
      right_arm_ignored += "  right_link" + std::to_string(k) + ": {ignore: true}\n";
    }
    WriteFile(scene, arms == 1 ? InsertAfterKey(copies.scene, "links", right_arm_ignored)
                               : copies.scene);
    Scenario s;
    s.workcell = std::make_shared<const Workcell>(LoadWorkcell(urdf, scene));
    s.tasks = MapTasks(base.tasks, *base.workcell, *s.workcell);
    const Reference ref = BruteForce(s);
    int moving = 0;
    for (const auto& p : s.workcell->primitives)
      moving += !p.is_static && p.link_index >= 0 && p.variant.empty();
    const std::vector<RunResult> results = RunScalingImplementations(s, ref, DefaultOptions());
    std::printf(" %d arms, %d moving primitives\n", arms, moving);
    for (const RunResult& r : results) {
      PrintRow(r);
      if (r.impl.find('_') == std::string::npos) *missed_total += r.missed;
      const TimingSummary sm = SummarizeTimings(r.t_us);
      csv.Row(arms, moving, r.impl, sm.mean, sm.median, sm.p99, r.missed,
              r.false_warnings);
    }
  }
}

}  // namespace bench
}  // namespace arm_collision_monitor
