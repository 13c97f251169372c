// Shared by the seed's experiments (bench_tasks_experiments: one .cpp per experiment, main.cpp
// runs them): the arguments, the CSV output, the scenarios (a workcell and the three tasks' joint
// trajectories), the brute-force reference, and the timed runs of the Monitor and of the peers,
// taken in turns. Times are summarized by SummarizeTimings (core/timing_summary.h), the
// package's one percentile rule.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/broadphase/compatibility_matrix.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "arm_collision_monitor/tasks/task_trajectories.h"
#ifdef ACM_HAVE_PEERS
#include "arm_collision_monitor/peers/peer_checker.h"
#endif

namespace arm_collision_monitor {
namespace bench {

using Clock = std::chrono::steady_clock;
using PairSet = std::vector<CandidatePair>;

struct Args {
  std::string out_dir = "build/bench";
  bool quick = false;
  std::uint64_t seed = 20261121;
  int repeats = 3;  // passes over each task for timing
  std::string only;  // comma-separated experiment names; empty: all
  // --profile W: workload W's default Monitor only, one untimed pass, no reference (the A/B
  // run that scripts/profile counts instructions of); empty: the experiments as usual.
  std::string profile;
  bool Runs(const std::string& name) const {
    return only.empty() || ("," + only + ",").find("," + name + ",") != std::string::npos;
  }
  bool RunsWorkload(const std::string& name) const { return profile.empty() || profile == name; }
};

// ------------------------------------------------------------------------------------------
// Output: one CSV per experiment, header first.
class Csv {
 public:
  Csv(const std::string& path, const std::string& header) : out_(path) {
    if (!out_) {
      std::fprintf(stderr, "cannot write %s\n", path.c_str());
      std::exit(1);
    }
    out_ << header << "\n";
  }
  template <typename... T>
  void Row(const T&... v) {
    std::ostringstream line;
    line.precision(9);
    int i = 0;
    ((line << (i++ ? "," : "") << v), ...);
    out_ << line.str() << "\n";
    out_.flush();
  }

 private:
  std::ofstream out_;
};

double MicrosSince(Clock::time_point t0);

// ------------------------------------------------------------------------------------------
// Scenarios: a workcell and the three tasks' joint trajectories (Monitor q order).
struct TaskRun {
  int number = 0;                  // the seed's task 1..3
  std::string name;
  std::vector<Eigen::VectorXd> q;  // one per 50 ms cycle
  std::vector<TaskGraspTarget> grasp_targets;  // declared before the first cycle
};

struct Scenario {
  std::string label;
  std::string scene_yaml;  // the scene file's text
  std::shared_ptr<const Workcell> workcell;
  std::vector<TaskRun> tasks;
  std::size_t cycles() const {
    std::size_t n = 0;
    for (const auto& t : tasks) n += t.q.size();
    return n;
  }
};

// A path relative to the package's source directory.
std::string SourcePath(const std::string& rel);
std::string ReadFile(const std::string& path);
void WriteFile(const std::string& path, const std::string& text);

// The seed's three tasks on the default workcell, from the tasks library.
std::vector<TaskRun> MakeTasks(const Workcell& workcell);

// The start-up compatibility matrix plus the task's grasp targets (what Monitor::SetGraspTarget
// excuses), for brute force and the peers.
CompatibilityMatrix TaskCompatibility(const Workcell& wc, const TaskRun& task);

// Inserts `extra_yaml` lines right after the line `key:` of a scene file.
std::string InsertAfterKey(const std::string& yaml, const std::string& key,
                           const std::string& extra_yaml);

// Static boxes (2 .. 8 cm edges) added to the default scene: "near" the arms (where they work)
// or "far" (out of every arm's reach, e.g. overhead).
std::string ExtraBoxesYaml(std::mt19937_64* rng, int count, bool near);

// A workcell with `pairs` copies of the two-arm set (2 * pairs arms), copy k's pedestals
// shifted; each copy follows the tasks' trajectory shifted in time.
struct ArmCopies {
  std::string urdf, scene;
};
ArmCopies MakeArmCopies(int pairs);

// Trajectories for a workcell whose joints are the default ones, possibly with copies
// ("c<k>" + name): copy k runs the same task 37 k cycles later (wrapping around).
std::vector<TaskRun> MapTasks(const std::vector<TaskRun>& base, const Workcell& base_wc,
                              const Workcell& wc);

// A scenario on the default URDF with scene text `yaml` (the tasks mapped onto it).
Scenario MakeSceneScenario(const Args& args, const Scenario& base, const std::string& label,
                           const std::string& yaml);

// The options of config/monitor.yaml.
MonitorOptions DefaultOptions();

// The seed's loop: the default options with index slack 0 (every moved primitive re-indexed,
// every candidate pair tested each cycle), for the experiments that reproduce the seed's.
MonitorOptions SeedLoopOptions();

// The default options with the swept check off, to measure its cost: swept_check false needs a
// tolerance above the per-cycle motion the URDF velocity limits allow, so the cycle period is
// cut 25-fold and the speed bound raised as much (their product, hence the smallest octree
// cell, is unchanged).
MonitorOptions SweptOffOptions();

// Brute force: every present, non-compatible pair, not both static, tested with the exact
// distance. `borderline`: pairs within 1e-9 m of their threshold (either answer is right).
struct Reference {
  std::vector<PairSet> warnings;    // per cycle, all tasks in order
  std::vector<PairSet> borderline;  // per cycle
  std::vector<char> checked;        // per cycle: brute force ran (see `stride`)
};

// `stride` > 1: only every stride-th cycle is checked (large scenes).
Reference BruteForce(const Scenario& s, int stride = 1);

// Differences of `got` against `want` (both sorted) outside `border`.
void Diff(const PairSet& got, const PairSet& want, const PairSet& border, PairSet* extra,
          PairSet* missing);

// ------------------------------------------------------------------------------------------
// A timed run of one implementation over every task of a scenario.
struct RunResult {
  std::string impl;
  std::vector<double> t_us;            // per timed cycle (cycle 0 of each task excluded)
  std::vector<std::uint8_t> t_task;    // the task of each sample
  std::vector<PairSet> warnings;       // per cycle, last pass
  BroadPhaseCounters counters;         // summed over one pass
  // Summed over the last pass's cycles (CycleReport): index work and narrow-phase work.
  std::uint64_t reindexed = 0, candidate_pairs = 0, narrow_phase_tests = 0;
  std::uint64_t missed = 0, false_warnings = 0;  // against brute force, all passes' last
  std::size_t active_primitives = 0;
  std::string chosen;  // the Monitor's broad phase name
};

// Untimed cycles that RunMonitor and RunPeer run on a throwaway instance before each task's
// timed one: every row starts with its code and its allocator's blocks warm, not only those that
// follow a row of the same code (identical code measured 21 % apart at p99 by position alone:
// the first row of a turn runs after the peers).
inline constexpr std::size_t kWarmUpCycles = 100;

// One timing pass over every task (RunInTurns merges passes). `variant` non-empty: every link
// that has a model variant of that name is switched to it before the first cycle
// (Monitor::SwitchModel).
RunResult RunMonitor(const Scenario& s, const MonitorOptions& options, const Reference* ref,
                     const std::string& impl, const std::string& variant = "");

// The mean per-cycle time of each of `tasks` tasks, over every timed sample of r.
std::vector<double> TaskMeans(const RunResult& r, std::size_t tasks);

// `repeats` rounds of one pass of each of `runs` in turn, so that a slow spell of a shared
// machine falls on every variant alike rather than on the few running at the time. Round r
// starts with run r (mod their number): the first run of a round was measured slower by
// position alone (the default sphere_robot row's median 0.27 us against 0.18 for the identical
// naive row after it; 0.17 against 0.20 once rotated), so no run keeps that place. Each result
// holds the per-cycle times of every pass; everything else (warnings, counters, brute-force
// comparison) is its last pass's.
std::vector<RunResult> RunInTurns(int repeats,
                                  const std::vector<std::function<RunResult()>>& runs);

// One labelled Monitor configuration of a sweep.
struct Configuration {
  std::string label;
  MonitorOptions options;
};

// A sweep's configurations, run in turns (RunInTurns); the results are in their order.
std::vector<RunResult> RunConfigurations(int repeats, const Scenario& s, const Reference& ref,
                                         const std::vector<Configuration>& configs);

#ifdef ACM_HAVE_PEERS
using PeerFactory = std::function<std::unique_ptr<PeerChecker>(
    const std::vector<PeerPrimitive>&, const CompatibilityMatrix&)>;

// A peer's cycle: the same forward kinematics as the Monitor, the moving shapes handed over,
// then its query. One timing pass over every task, as RunMonitor. `idle_skip`: a cycle whose q
// is bit-identical to the previous one keeps the previous warnings and does nothing else, the
// Monitor's idle-cycle shortcut (impl "<peer> (idle skip)").
RunResult RunPeer(const Scenario& s, const PeerFactory& factory, const Reference* ref,
                  bool idle_skip = false);

// The four peers by name: FCL and Bullet, each with sharp and rounded grown boxes.
std::vector<std::pair<std::string, PeerFactory>> Peers();
#endif

// The implementations the scaling runs compare: three of our broad phases (on `base` options)
// and two peers, one timing pass each.
std::vector<RunResult> RunScalingImplementations(const Scenario& s, const Reference& ref,
                                                 const MonitorOptions& base);

// One line of a run's timing summary, missed and false warnings.
void PrintRow(const RunResult& r);

// ------------------------------------------------------------------------------------------
// The experiments, one file each (experiment_<name>.cpp). Those given `missed_total` add the
// warnings their runs of our broad phases missed against brute force.

// Per-cycle times for every broad phase and peer on the three tasks; warnings cycle by cycle
// against the default Monitor and brute force; every peer difference listed with its distance.
// Returns the default Monitor's median cycle time (us).
double ExperimentTasks(const Args& args, const Scenario& s, const Reference& ref,
                       std::uint64_t* missed_total);

// The seed's octree statistics on the default scene at the home pose, and the cycles between a
// split or merge over the three tasks (the seed's loop, index slack 0).
void ExperimentOctreeStatistics(const Args& args, const Scenario& s);

// Figure 5 (N swept), Figure 7 (G swept) and the technique ablation, on the seed's loop (index
// slack 0).
void ExperimentSweeps(const Args& args, const Scenario& s, const Reference& ref,
                      std::uint64_t* missed_total);

// The index slack swept on the three tasks (default Monitor, octree): time against the work it
// saves (re-indexed primitives, candidate pairs, exact distance tests per cycle); the warnings
// checked against brute force at every slack.
void ExperimentSlack(const Args& args, const Scenario& s, const Reference& ref,
                     std::uint64_t* missed_total);

// Figure 6 and static scaling: boxes added near the arms and far from them, on the seed's loop
// (index slack 0); near the arms also the default Monitor's octree and naive broad phases.
void ExperimentStaticScaling(const Args& args, const Scenario& base, std::uint64_t* missed_total);

// Moving primitives: 1, 2, 4, 6, 8 arms (copies of the arm pair on shifted pedestals, each copy
// on the tasks shifted in time; one arm: the pair with the right arm's links ignored).
void ExperimentMovingScaling(const Args& args, const Scenario& base, std::uint64_t* missed_total);

// Check rate and sub-stepping against missed warnings (3b), on scenario `s`; `check_us` is the
// default Monitor's median cycle time, to price each schedule. Rows into `csv` (temporal.csv).
void ExperimentTemporal(const Args& args, const Scenario& s, double check_us, Csv* csv);

// Issue 15 item 4: the default Monitor, naive, grid, octree and the peers (also with the
// Monitor's idle-cycle skip) on the tasks, every joint moving every cycle, a sphere-model
// dual-arm robot in a shelf scene, large steps, primitives outside the world cube and 2,000
// statics (workloads_summary.csv).
void ExperimentWorkloads(const Args& args, const Scenario& tasks, const Reference& tasks_ref,
                         std::uint64_t* missed_total);

// Float against double: seeded capsule pairs (a fifth nearly parallel and close), the distance
// in float, in double and by the library, against long double (float_double.csv).
void ExperimentFloatDouble(const Args& args);

#ifdef ACM_HAVE_PEERS
// Model fidelity (3a): cylinder models of the arm links against the exact URDF geometry (FCL)
// on each scenario. Rows into `csv` (fidelity.csv).
void ExperimentFidelity(const Args& args, const std::vector<const Scenario*>& scenarios,
                        Csv* csv);

// Minimum of a unimodal f on [lo, hi] (golden-section search; Press et al., Numerical Recipes,
// 3rd ed., 10.2): the midpoint of a final bracket 1e-12 (hi - lo) wide that holds a minimiser.
double GoldenSectionMinimum(const std::function<double(double)>& f, double lo, double hi);

// Model fidelity (3a) of scene cylinders: cans near the tasks' paths (base's tasks) and in
// seeded random configurations, cylinder_model capsule and box against the exact cylinder
// (golden-section reference, checked against FCL). Rows into `csv` (fidelity_cylinders.csv).
void ExperimentFidelityCylinders(const Args& args, const Scenario& base, Csv* csv);
#endif

}  // namespace bench
}  // namespace arm_collision_monitor
