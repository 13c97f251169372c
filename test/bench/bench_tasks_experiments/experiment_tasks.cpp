// Experiment "tasks": per-cycle times of every broad phase and peer on the seed's three tasks.

#include "experiments.h"

#include <functional>

#include "arm_collision_monitor/core/timing_summary.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"

namespace arm_collision_monitor {
namespace bench {

double ExperimentTasks(const Args& args, const Scenario& s, const Reference& ref,
                       std::uint64_t* missed_total) {
  std::printf("== per-cycle times on the three tasks (%zu cycles)\n", s.cycles());
  Csv summary(args.out_dir + "/tasks_summary.csv",
              "impl,task,mean_us,median_us,p99_us,max_us,warning_cycles,cycles_equal_default,"
              "missed_vs_brute,false_vs_brute,object_node_tests,object_object_tests,splits,merges,"
              "samples,median_moving_us,moving_samples");
  Csv diffs(args.out_dir + "/peer_differences.csv",
            "impl,task,cycle,a,b,name_a,name_b,kind,distance_m,threshold_m");
  const Workcell& wc = *s.workcell;
  // One pass of each implementation. results.front() is the default Monitor: the shipped
  // options (config/monitor.yaml, broad phase auto), named by what auto chose on this workcell;
  // beside it the same without the swept check, whose cost is the difference.
  std::vector<std::function<RunResult()>> runs;
  for (const bool swept : {true, false}) {
    runs.push_back([&s, &ref, swept] {
      const MonitorOptions o = swept ? DefaultOptions() : SweptOffOptions();
      RunResult r = RunMonitor(s, o, &ref, "auto");
      r.impl = BroadPhaseMethodName(o.broad_phase.method) + "(" + r.chosen + ")" +
               (swept ? "" : " (swept off)");
      return r;
    });
  }
  for (const char* method : {"octree", "naive", "grid", "rebuild", "reinsert"}) {
    MonitorOptions o = DefaultOptions();
    ParseBroadPhaseMethod(method, &o.broad_phase.method);
    runs.push_back([&s, &ref, o, method] { return RunMonitor(s, o, &ref, method); });
    if (o.broad_phase.method == BroadPhaseMethod::kOctree) {
      // The octree on the seed's loop (index slack 0), and without the swept check.
      runs.push_back(
          [&s, &ref] { return RunMonitor(s, SeedLoopOptions(), &ref, "octree (slack 0)"); });
      MonitorOptions off = SweptOffOptions();
      off.broad_phase.method = o.broad_phase.method;
      runs.push_back([&s, &ref, off] { return RunMonitor(s, off, &ref, "octree (swept off)"); });
    }
  }
#ifdef ACM_HAVE_PEERS
  for (const auto& [name, factory] : Peers()) {
    runs.push_back([&s, &ref, f = factory] { return RunPeer(s, f, &ref); });
  }
#endif
  const std::vector<RunResult> results = RunInTurns(args.repeats, runs);
  const RunResult& dflt = results.front();
  // Task boundaries in the per-cycle warning arrays.
  std::vector<std::size_t> task_of_cycle;
  for (std::size_t ti = 0; ti < s.tasks.size(); ++ti) {
    task_of_cycle.insert(task_of_cycle.end(), s.tasks[ti].q.size(), ti);
  }
  // Per timed sample (each task's first cycle is not timed; the passes repeat the pattern):
  // whether q differs from the previous cycle's. The Monitor answers a repeated q from its last
  // report and the peers have no such shortcut, so the medians are also given over the moving
  // cycles alone.
  std::vector<std::uint8_t> sample_moves;
  for (const TaskRun& task : s.tasks) {
    for (std::size_t c = 1; c < task.q.size(); ++c) {
      sample_moves.push_back(task.q[c] != task.q[c - 1] ? 1 : 0);
    }
  }
  WorkcellShapes eval(wc);
  std::vector<std::size_t> cycle_in_task(task_of_cycle.size());
  for (std::size_t c = 0, k = 0; c < task_of_cycle.size(); ++c) {
    k = (c == 0 || task_of_cycle[c] != task_of_cycle[c - 1]) ? 0 : k + 1;
    cycle_in_task[c] = k;
  }
  for (const RunResult& r : results) {
    PrintRow(r);
    *missed_total += r.missed;
    std::size_t warning_cycles = 0, equal = 0;
    for (std::size_t c = 0; c < r.warnings.size(); ++c) {
      warning_cycles += !r.warnings[c].empty();
      equal += r.warnings[c] == dflt.warnings[c];
    }
    // The samples of task `ti` (every task if ti < 0), and of its moving cycles alone, in pass
    // order, each pass the same cycles: median and p99 the medians of the passes' own.
    auto summarize = [&](int ti, TimingSummary* moving_summary) {
      std::vector<double> slice, moving;
      for (std::size_t i = 0; i < r.t_us.size(); ++i) {
        if (ti >= 0 && r.t_task[i] != ti) continue;
        slice.push_back(r.t_us[i]);
        if (sample_moves[i % sample_moves.size()]) moving.push_back(r.t_us[i]);
      }
      const auto passes = static_cast<std::size_t>(args.repeats);
      *moving_summary = SummarizePasses(moving, passes);
      return SummarizePasses(slice, passes);
    };
    TimingSummary all_moving;
    const TimingSummary all = summarize(-1, &all_moving);
    summary.Row(r.impl, "all", all.mean, all.median, all.p99, all.max,
                warning_cycles, equal, r.missed, r.false_warnings, r.counters.object_node_tests,
                r.counters.object_object_tests, r.counters.splits, r.counters.merges,
                all.count, all_moving.median, all_moving.count);
    for (std::size_t ti = 0; ti < s.tasks.size(); ++ti) {
      TimingSummary task_moving;
      const TimingSummary st = summarize(static_cast<int>(ti), &task_moving);
      summary.Row(r.impl, s.tasks[ti].name, st.mean, st.median, st.p99, st.max, "",
                  "", "", "", "", "", "", "", st.count, task_moving.median,
                  task_moving.count);
    }
    if (r.impl.rfind("fcl", 0) != 0 && r.impl.rfind("bullet", 0) != 0) continue;
    PairSet extra, missing;
    for (std::size_t c = 0; c < r.warnings.size(); ++c) {
      if (r.warnings[c] == dflt.warnings[c]) continue;
      Diff(r.warnings[c], dflt.warnings[c], {}, &extra, &missing);
      const std::size_t ti = task_of_cycle[c];
      eval.Evaluate(s.tasks[ti].q[cycle_in_task[c]]);
      for (int kind = 0; kind < 2; ++kind) {
        for (const CandidatePair& p : kind == 0 ? extra : missing) {
          const double d = ShapeDistance(eval.shape_W(p.a), eval.shape_W(p.b)).distance_m;
          diffs.Row(r.impl, s.tasks[ti].name, cycle_in_task[c], p.a, p.b, wc.primitives[p.a].name,
                    wc.primitives[p.b].name, kind == 0 ? "peer_only" : "ours_only", d,
                    wc.primitives[p.a].tolerance_m + wc.primitives[p.b].tolerance_m);
        }
      }
    }
  }
  return SummarizePasses(dflt.t_us, static_cast<std::size_t>(args.repeats)).median;
}

}  // namespace bench
}  // namespace arm_collision_monitor
