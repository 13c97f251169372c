// Experiment "slack": the index slack swept on the three tasks.

#include "experiments.h"

#include "arm_collision_monitor/core/timing_summary.h"

namespace arm_collision_monitor {
namespace bench {

void ExperimentSlack(const Args& args, const Scenario& s, const Reference& ref,
                     std::uint64_t* missed_total) {
  Csv csv(args.out_dir + "/slack.csv",
          "slack_m,is_default,mean_us,median_us,p99_us,max_us,reindexed_per_cycle,"
          "candidate_pairs_per_cycle,narrow_phase_tests_per_cycle,splits_plus_merges,missed,false");
  const double default_slack_m = DefaultOptions().index_slack_m;
  std::printf("== index slack swept (default %.3f m)\n", default_slack_m);
  const std::vector<double> slacks_m = {0.0, 0.01, 0.02, 0.05, 0.1, 0.2, 0.4, 0.8};
  std::vector<Configuration> configs;
  for (const double slack_m : slacks_m) {
    std::ostringstream name;
    name << "slack " << slack_m << " m";
    configs.push_back({name.str(), DefaultOptions()});
    configs.back().options.broad_phase.method = BroadPhaseMethod::kOctree;
    configs.back().options.index_slack_m = slack_m;
  }
  const std::vector<RunResult> results = RunConfigurations(args.repeats, s, ref, configs);
  for (std::size_t i = 0; i < slacks_m.size(); ++i) {
    const double slack_m = slacks_m[i];
    const RunResult& r = results[i];
    PrintRow(r);
    *missed_total += r.missed;
    const TimingSummary sm = SummarizeTimings(r.t_us);
    const double cycles = static_cast<double>(s.cycles());
    std::printf("    per cycle: %.2f re-indexed, %.2f candidate pairs, %.2f exact tests; %llu "
                "octree splits + merges in all\n",
                r.reindexed / cycles, r.candidate_pairs / cycles, r.narrow_phase_tests / cycles,
                static_cast<unsigned long long>(r.counters.splits + r.counters.merges));
    csv.Row(slack_m, slack_m == default_slack_m ? 1 : 0, sm.mean, sm.median, sm.p99,
            sm.max, r.reindexed / cycles, r.candidate_pairs / cycles,
            r.narrow_phase_tests / cycles, r.counters.splits + r.counters.merges, r.missed,
            r.false_warnings);
  }
}

}  // namespace bench
}  // namespace arm_collision_monitor
