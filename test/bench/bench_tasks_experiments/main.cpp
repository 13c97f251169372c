// The seed's experiments (Shaffer & Herb, TR 90-28, section 5) on its three tasks, the peers
// (FCL, Bullet) on the same scene, trajectories and tolerances, the run-time-against-error
// studies and the scaling runs. Every figure is measured in this run; randomness is seeded and
// the seed printed. Writes CSV files into --out (scripts/bench_report.py turns them into
// build/bench/report.md and charts); nothing is asserted on time.
//
// One file per experiment (experiment_<name>.cpp), the shared scenarios and runs in
// experiments.h.
//
//   bench_tasks_experiments --out build/bench [--quick] [--seed S]
//   bench_tasks_experiments --profile WORKLOAD [--quick] [--seed S]   (see scripts/profile)
#include <cstdio>
#include <random>
#include <string>

#include "experiments.h"

#include "arm_collision_monitor/core/timing_summary.h"

int main(int argc, char** argv) {
  using namespace arm_collision_monitor;
  using namespace arm_collision_monitor::bench;
  Args args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick") {
      args.quick = true;
      args.repeats = 1;
    } else if (a == "--out" && i + 1 < argc) {
      args.out_dir = argv[++i];
    } else if (a == "--only" && i + 1 < argc) {
      args.only = argv[++i];
    } else if (a == "--profile" && i + 1 < argc) {
      args.profile = argv[++i];
      args.only = "workloads";
    } else if (a == "--seed" && i + 1 < argc) {
      args.seed = std::stoull(argv[++i]);
    } else {
      std::fprintf(
          stderr,
          "usage: %s [--out DIR] [--quick] [--seed S] [--only tasks,octree,sweeps,slack,static,"
          "moving,workloads,temporal,float,fidelity,cylinders] [--profile WORKLOAD]\n",
          argv[0]);
      return 2;
    }
  }
  std::printf("bench_tasks_experiments: seed %llu, %s, %d timing passes\n",
              static_cast<unsigned long long>(args.seed), args.quick ? "quick" : "full",
              args.repeats);
  const auto t_start = Clock::now();
  Scenario s;
  s.label = "default";
  s.scene_yaml = ReadFile(SourcePath("config/scene.yaml"));
  s.workcell = std::make_shared<const Workcell>(
      LoadWorkcell(SourcePath("urdf/workcell.urdf"), SourcePath("config/scene.yaml")));
  s.tasks = MakeTasks(*s.workcell);
  const bool is_profile = !args.profile.empty();
  const Reference ref = is_profile ? Reference{} : BruteForce(s);
  std::uint64_t missed_total = 0;
  double check_us = 0.0;
  if (args.Runs("tasks")) check_us = ExperimentTasks(args, s, ref, &missed_total);
  if (args.Runs("octree")) ExperimentOctreeStatistics(args, s);
  if (args.Runs("sweeps")) ExperimentSweeps(args, s, ref, &missed_total);
  if (args.Runs("slack")) ExperimentSlack(args, s, ref, &missed_total);
  if (args.Runs("static")) ExperimentStaticScaling(args, s, &missed_total);
  if (args.Runs("moving")) ExperimentMovingScaling(args, s, &missed_total);
  if (args.Runs("workloads")) ExperimentWorkloads(args, s, ref, &missed_total);
  if (is_profile) return 0;
  // The tasks have few close approaches; the error studies also run among 200 boxes added
  // near the arms (seeded), where grazing contacts are frequent.
  std::mt19937_64 clutter_rng(args.seed);
  const Scenario clutter = MakeSceneScenario(
      args, s, "clutter200",
      InsertAfterKey(s.scene_yaml, "objects", ExtraBoxesYaml(&clutter_rng, 200, true)));
  if (args.Runs("temporal")) {
    if (check_us == 0.0) {
      const RunResult octree = RunMonitor(s, DefaultOptions(), nullptr, "octree");
      check_us = SummarizeTimings(octree.t_us).median;
    }
    Csv csv(args.out_dir + "/temporal.csv",
            "scene,speed_mps,checks_per_s,schedule,cpu_us_per_s,events,missed_events,contacts,"
            "missed_contacts,recorded_speed_mps,swept_missed_events,swept_unwarned_contacts,"
            "swept_us_per_cycle,samples_us_per_cycle,swept_path_fraction");
    ExperimentTemporal(args, s, check_us, &csv);
    ExperimentTemporal(args, clutter, check_us, &csv);
  }
  if (args.Runs("float")) ExperimentFloatDouble(args);
#ifdef ACM_HAVE_PEERS
  if (args.Runs("fidelity")) {
    Csv csv(args.out_dir + "/fidelity.csv",
            "scene,model,conservative,arm_capsules,median_us,mean_us,false,missed,"
            "warning_pair_cycles,excess_volume_percent,excess_volume_se_percent,"
            "uncovered_volume_percent,excess_volume_closed_form_percent,mc_samples_per_link,"
            "mc_seed");
    ExperimentFidelity(args, {&s, &clutter}, &csv);
  }
  if (args.Runs("cylinders")) {
    Csv csv(args.out_dir + "/fidelity_cylinders.csv",
            "workload,model,configurations,cans,arm_capsules,pairs,model_warnings,"
            "exact_warnings,false,missed,borderline,reference_accuracy_m,fcl_checked_pairs,"
            "max_fcl_difference_m,seed");
    ExperimentFidelityCylinders(args, s, &csv);
  }
#endif
  Csv meta(args.out_dir + "/meta.csv", "key,value");
  meta.Row("seed", args.seed);
  meta.Row("quick", args.quick ? 1 : 0);
  meta.Row("repeats", args.repeats);
  meta.Row("missed_vs_brute_total", missed_total);
  meta.Row("experiment_seconds", MicrosSince(t_start) * 1e-6);
  std::printf("missed warnings against brute force, all our runs: %llu\n",
              static_cast<unsigned long long>(missed_total));
  return 0;
}
