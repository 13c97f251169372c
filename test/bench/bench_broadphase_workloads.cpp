// Per-cycle broad-phase time (Move of every moving primitive + FindPairs) of naive, grid, octree
// and auto on the inputs that used to be pathological (primitives outside the world cube, steps
// larger than cells, inflated boxes larger than cells, many primitives crowded together) and
// on a sweep of scene sizes that sets auto's crossovers (ChooseBroadPhaseMethod). For each
// workload it prints the median, p99 and max per cycle of each method (the grid with its
// configured 16 cells per axis), auto's choice (gridG: the grid with G cells per axis, sized to
// the movers' boxes, timed as a fourth method) and auto's median over the best of the three;
// the methods are timed in turns (each pass starting one later), kPasses times each, each median
// and p99 the median of the passes' own (SummarizePasses). Seeded (std::mt19937_64, seed
// printed); each trajectory is recorded once and replayed forward and backward.
//
//   $ACM_WS/devel/lib/arm_collision_monitor/bench_broadphase_workloads
//   [--sweep-only|--workloads-only]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "../core/test_broadphase_scene.h"
#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/broadphase/broad_phase_util.h"
#include "arm_collision_monitor/core/timing_summary.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint64_t kSeed = 20261123;
constexpr int kRecordedCycles = 200;

struct Workload {
  std::string name;
  test::SceneConfig config;
  int timed_cycles = 600;
};

// Timed passes per method, taken in turns (naive, grid, octree, auto's grid, then again), so a
// slow spell of the shared machine falls on every method alike instead of on one column; the
// medians of the passes' medians and p99s leave out a pass the spell spoiled (odd: a middle
// pass).
constexpr int kPasses = 7;
// Untimed cycles before each pass's timed ones: enough to warm the caches and let the octree's
// splits settle (its cells then change only where a mover crosses one).
constexpr int kWarmUpCycles = 40;

// Appends the times of `count` cycles of `method` on the recording to `us`: from frame
// `first_frame` on, kWarmUpCycles untimed cycles and then the timed ones.
void TimeMethod(const std::vector<test::SceneOp>& initial,
                const std::vector<std::vector<test::SceneOp>>& cycles,
                const CompatibilityMatrix& compatible, BroadPhaseOptions options,
                int first_frame, int count, std::vector<double>* us) {
  std::unique_ptr<BroadPhase> bp = MakeBroadPhase(options);
  test::RandomScene::Apply(initial, bp.get());
  std::vector<CandidatePair> pairs;
  pairs.reserve(1 << 16);
  const int frames = static_cast<int>(cycles.size());
  int frame = first_frame, step = 1;
  auto advance = [&] {
    if (frame + step < 0 || frame + step >= frames) step = -step;
    frame += step;
  };
  for (int i = 0; i < kWarmUpCycles; ++i) {
    test::RandomScene::Apply(cycles[frame], bp.get());
    bp->FindPairs(compatible, &pairs);
    advance();
  }
  for (int c = 0; c < count; ++c) {
    const auto start = std::chrono::steady_clock::now();
    for (const test::SceneOp& op : cycles[frame]) bp->Move(op.id, op.box_W);
    bp->FindPairs(compatible, &pairs);
    benchmark::DoNotOptimize(pairs.data());
    benchmark::ClobberMemory();
    us->push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
            .count());
    advance();
  }
}

// Runs one workload; returns auto's median over the best median of naive, grid and octree.
double RunWorkload(const Workload& w) {
  test::RandomScene scene(w.config);
  std::vector<test::SceneOp> initial;
  scene.Initial(&initial);
  std::vector<std::vector<test::SceneOp>> cycles(kRecordedCycles);
  for (auto& ops : cycles) scene.Step(&ops);
  std::printf("%-26s %5d %5d", w.name.c_str(), w.config.movers, w.config.statics);
  // auto builds the method it chooses: naive and octree as configured (their time is the
  // column's), the grid with cells sized to the movers' boxes (timed as a fourth method).
  const BroadPhaseOptions auto_options = scene.Options(BroadPhaseMethod::kAuto);
  const BroadPhaseMethod chosen =
      ChooseBroadPhaseMethod(auto_options.auto_moving, auto_options.auto_statics);
  std::vector<BroadPhaseOptions> runs = {scene.Options(BroadPhaseMethod::kNaive),
                                         scene.Options(BroadPhaseMethod::kGrid),
                                         scene.Options(BroadPhaseMethod::kOctree)};
  if (chosen == BroadPhaseMethod::kGrid) runs.push_back(auto_options);
  std::vector<std::vector<double>> us(runs.size());
  const int pass_cycles = w.timed_cycles / kPasses;
  for (int pass = 0; pass < kPasses; ++pass) {
    const int first_frame = pass * kRecordedCycles / kPasses;
    // Each pass starts one method later, so that none is always timed first (RunInTurns).
    for (std::size_t turn = 0; turn < runs.size(); ++turn) {
      const std::size_t r = (turn + static_cast<std::size_t>(pass)) % runs.size();
      TimeMethod(initial, cycles, scene.compatible(), runs[r], first_frame, pass_cycles, &us[r]);
    }
  }
  std::vector<TimingSummary> t(runs.size());
  double best_us = 1e300;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    t[r] = SummarizePasses(us[r], kPasses);
    if (r < 3) {
      best_us = std::min(best_us, t[r].median);
      std::printf(" | %8.2f %8.2f %9.2f", t[r].median, t[r].p99, t[r].max);
    }
  }
  std::string label = BroadPhaseMethodName(chosen);
  double chosen_us = t[chosen == BroadPhaseMethod::kNaive ? 0 : 2].median;
  if (chosen == BroadPhaseMethod::kGrid) {
    const int cells = GridCellsFor(WorldCubeEdge(auto_options.world_W),
                                   auto_options.auto_moving_box_edge_m,
                                   auto_options.grid_cells_per_axis);
    label += std::to_string(cells);
    chosen_us = t[3].median;
  }
  const double ratio = chosen_us / best_us;
  std::printf(" | %-6s %8.2f %5.2f%s\n", label.c_str(), chosen_us, ratio,
              ratio > 1.10 ? "  > 1.10" : "");
  return ratio;
}

void PrintHeader(const char* title) {
  std::printf("\n%s\n%-26s %5s %5s | %-28s | %-28s | %-28s | %s\n", title, "workload", "mov",
              "stat", "naive  median p99 max (us)", "grid   median p99 max (us)",
              "octree median p99 max (us)", "auto: choice median /best");
}

test::SceneConfig Base(int movers, int statics) {
  test::SceneConfig c;
  c.seed = kSeed;
  c.movers = movers;
  c.statics = statics;
  c.static_half_min_m = 0.02;
  c.static_half_max_m = 0.15;
  return c;
}

// The inputs of issue 15, item 1, each alone and all together.
std::vector<Workload> PathologyWorkloads() {
  std::vector<Workload> out;
  out.push_back({"tasks-like 14+21", Base(14, 21)});
  out.push_back({"statics 14+2000", Base(14, 2000), 200});
  {
    Workload w{"outside the world cube", Base(14, 200)};
    w.config.index_world_edge_m = 2.0;  // most primitives partly or wholly outside the index
    out.push_back(w);
  }
  {
    Workload w{"large steps (0.6 m/cycle)", Base(14, 200)};
    w.config.max_speed_mps = 12.0;  // steps 20x the minimum cell
    w.config.index_speed_mps = 0.61;
    out.push_back(w);
  }
  {
    Workload w{"inflated boxes > cells", Base(14, 200)};
    w.config.tolerance_max_m = 0.6;
    out.push_back(w);
  }
  {
    // ~75 spheres of a dual-arm robot crowded in 1.2 m, 15 shelf boxes, a 6.35 m index.
    Workload w{"crowded 75 spheres", Base(75, 15)};
    w.config.world_edge_m = 1.2;
    w.config.world_min_W = Eigen::Vector3d::Constant(-0.6);
    w.config.index_world_edge_m = 6.35;
    w.config.mover_length_m = 0.0;
    w.config.mover_radius_m = 0.06;
    w.config.static_half_max_m = 0.4;
    w.config.tolerance_max_m = 0.1;
    out.push_back(w);
  }
  {
    Workload w{"crowded+steps+outside", out.back().config};
    w.config.max_speed_mps = 6.0;
    w.config.index_speed_mps = 0.61;
    w.config.index_world_edge_m = 0.8;
    w.config.leave_probability = 0.05;
    out.push_back(w);
  }
  return out;
}

std::vector<Workload> SweepWorkloads() {
  std::vector<Workload> out;
  for (const int movers : {7, 14, 28, 75, 150, 300, 450, 600, 1200}) {
    for (const int statics : {0, 20, 50, 100, 200, 300, 500, 700, 1000, 3000}) {
      Workload w{"sweep", Base(movers, statics), statics >= 1000 ? 150 : 400};
      w.name = "sweep " + std::to_string(movers) + "+" + std::to_string(statics);
      out.push_back(w);
    }
  }
  return out;
}

}  // namespace
}  // namespace arm_collision_monitor

int main(int argc, char** argv) {
  using namespace arm_collision_monitor;
  const bool sweep = argc < 2 || std::strcmp(argv[1], "--workloads-only") != 0;
  const bool workloads = argc < 2 || std::strcmp(argv[1], "--sweep-only") != 0;
  std::printf("seed %llu; time per cycle = Move of every mover + FindPairs; median, p99: the "
              "medians of the %d passes' own; max: over every timed cycle; machine: see lscpu\n",
              static_cast<unsigned long long>(kSeed), kPasses);
  double worst = 0.0;
  if (workloads) {
    PrintHeader("Workloads (issue 15 item 1)");
    for (const Workload& w : PathologyWorkloads()) worst = std::max(worst, RunWorkload(w));
  }
  if (sweep) {
    PrintHeader("Sweep: movers x statics (sets ChooseBroadPhaseMethod's crossovers)");
    for (const Workload& w : SweepWorkloads()) worst = std::max(worst, RunWorkload(w));
  }
  std::printf("\nauto's worst median over the best of naive/grid/octree: %.2f (goal <= 1.10)\n",
              worst);
  return 0;
}
