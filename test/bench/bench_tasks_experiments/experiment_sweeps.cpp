// Experiment "sweeps": Figures 5 (N) and 7 (G) of the seed and the technique ablation.

#include "experiments.h"

#include <iterator>

#include "arm_collision_monitor/core/timing_summary.h"

namespace arm_collision_monitor {
namespace bench {

void ExperimentSweeps(const Args& args, const Scenario& s, const Reference& ref,
                      std::uint64_t* missed_total) {
  Csv n_csv(args.out_dir + "/sweep_n.csv",
            "n,mean_us,median_us,p99_us,task1_us,task2_us,task3_us,object_node_tests_per_cycle,"
            "object_object_tests_per_cycle,missed");
  std::printf("== Figure 5: N swept\n");
  const std::vector<int> ns = args.quick ? std::vector<int>{1, 2, 5, 10, 20, 40}
                                         : std::vector<int>{1, 2, 3, 4, 5, 6, 8, 10, 12, 15,
                                                            20, 25, 30, 35, 40};
  std::vector<Configuration> n_configs;
  for (int n : ns) {
    n_configs.push_back({"octree N=" + std::to_string(n), SeedLoopOptions()});
    n_configs.back().options.broad_phase.max_objects_per_leaf = n;
  }
  const std::vector<RunResult> n_results = RunConfigurations(args.repeats, s, ref, n_configs);
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const RunResult& r = n_results[i];
    PrintRow(r);
    *missed_total += r.missed;
    const TimingSummary sm = SummarizeTimings(r.t_us);
    const std::vector<double> task_us = TaskMeans(r, s.tasks.size());
    n_csv.Row(ns[i], sm.mean, sm.median, sm.p99, task_us[0], task_us[1], task_us[2],
              double(r.counters.object_node_tests) / s.cycles(),
              double(r.counters.object_object_tests) / s.cycles(), r.missed);
  }
  Csv g_csv(args.out_dir + "/sweep_g.csv",
            "g,mean_us,median_us,p99_us,task1_us,task2_us,task3_us,missed");
  std::printf("== Figure 7: G swept\n");
  const std::vector<int> gs = args.quick ? std::vector<int>{2, 8, 16, 32, 64}
                                         : std::vector<int>{2, 4, 6, 8, 12, 16, 24, 32, 48, 64};
  std::vector<Configuration> g_configs;
  for (int g : gs) {
    g_configs.push_back({"grid G=" + std::to_string(g), SeedLoopOptions()});
    g_configs.back().options.broad_phase.method = BroadPhaseMethod::kGrid;
    g_configs.back().options.broad_phase.grid_cells_per_axis = g;
  }
  const std::vector<RunResult> g_results = RunConfigurations(args.repeats, s, ref, g_configs);
  for (std::size_t i = 0; i < gs.size(); ++i) {
    const RunResult& r = g_results[i];
    PrintRow(r);
    *missed_total += r.missed;
    const TimingSummary sm = SummarizeTimings(r.t_us);
    const std::vector<double> task_us = TaskMeans(r, s.tasks.size());
    g_csv.Row(gs[i], sm.mean, sm.median, sm.p99, task_us[0], task_us[1], task_us[2],
              r.missed);
  }
  std::printf("== ablation: each technique switched off\n");
  Csv a_csv(args.out_dir + "/ablation.csv",
            "technique,mean_us,median_us,change_percent,seed_change_percent,object_node_tests,"
            "object_object_tests,neighbours_visited,missed");
  struct Off {
    const char* name;
    bool BroadPhaseTechniques::*flag;
    double seed_percent;  // the seed's reduction from using the technique
  };
  const Off offs[] = {{"none", nullptr, 0.0},
                      {"directional_neighbours", &BroadPhaseTechniques::directional_neighbours, 8},
                      {"inside_node_exit", &BroadPhaseTechniques::inside_node_exit, 13},
                      {"pair_deduplication", &BroadPhaseTechniques::pair_deduplication, 4},
                      {"bounding_box_pretests", &BroadPhaseTechniques::bounding_box_pretests, 80}};
  std::vector<Configuration> off_configs;
  for (const Off& off : offs) {
    off_configs.push_back({std::string("without ") + off.name, SeedLoopOptions()});
    if (off.flag != nullptr) off_configs.back().options.broad_phase.techniques.*(off.flag) = false;
  }
  const std::vector<RunResult> off_results = RunConfigurations(args.repeats, s, ref, off_configs);
  double base_us = 0;
  for (std::size_t i = 0; i < std::size(offs); ++i) {
    const Off& off = offs[i];
    const RunResult& r = off_results[i];
    PrintRow(r);
    *missed_total += r.missed;
    const TimingSummary sm = SummarizeTimings(r.t_us);
    if (off.flag == nullptr) base_us = sm.mean;
    // Reduction the technique brings: (time without - time with) / time without.
    const double change = off.flag == nullptr ? 0.0 : 100.0 * (sm.mean - base_us) / sm.mean;
    a_csv.Row(off.name, sm.mean, sm.median, change, off.seed_percent,
              r.counters.object_node_tests, r.counters.object_object_tests,
              r.counters.neighbours_visited, r.missed);
  }
}

}  // namespace bench
}  // namespace arm_collision_monitor
