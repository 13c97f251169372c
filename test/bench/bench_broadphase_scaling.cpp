// Per-cycle broad-phase time (Move of every moving primitive + FindPairs) with 14 moving
// capsule boxes (arm links, <= 0.61 m/s, 50 ms cycles) among 35 and among 2,000 primitives
// scattered through a 6.35 m world cube, for every implementation; then the seed's ablation
// (each technique of the octree switched off in turn). Seeded: the scene and trajectory come
// from one std::mt19937_64 seed, printed in the context. The trajectory is recorded once and
// replayed forward and backward, so the motion stays smooth however many cycles are timed.
//
//   $ACM_WS/devel/lib/arm_collision_monitor/bench_broadphase_scaling
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "../core/test_broadphase_scene.h"
#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/broadphase/octree_broad_phase.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint64_t kSeed = 20260101;
constexpr int kMovers = 14;
constexpr int kRecordedCycles = 400;

struct Recording {
  test::RandomScene scene;
  std::vector<test::SceneOp> initial;
  std::vector<std::vector<test::SceneOp>> cycles;  // the movers' Move ops, cycle by cycle
};

test::SceneConfig ConfigFor(int primitives) {
  test::SceneConfig config;
  config.seed = kSeed;
  config.statics = primitives - kMovers;
  config.movers = kMovers;
  config.static_half_min_m = 0.02;
  config.static_half_max_m = 0.15;
  return config;
}

const Recording& RecordingFor(int primitives) {
  static std::vector<std::unique_ptr<Recording>> cache;
  for (const auto& r : cache) {
    if (r->scene.Count() == primitives) return *r;
  }
  auto r =
      std::unique_ptr<Recording>(new Recording{test::RandomScene(ConfigFor(primitives)), {}, {}});
  r->scene.Initial(&r->initial);
  r->cycles.resize(kRecordedCycles);
  for (auto& ops : r->cycles) r->scene.Step(&ops);
  cache.push_back(std::move(r));
  return *cache.back();
}

void RunCycles(benchmark::State& state, BroadPhaseOptions options) {
  const int primitives = static_cast<int>(state.range(0));
  const Recording& rec = RecordingFor(primitives);
  options.world_W.min_W = Eigen::Vector3d::Constant(-3.175);
  options.world_W.max_W = Eigen::Vector3d::Constant(3.175);
  options.min_cell_size_m = 0.61 * 0.05;
  options.reserve_primitives = static_cast<std::uint32_t>(primitives);
  std::unique_ptr<BroadPhase> bp = MakeBroadPhase(options);
  test::RandomScene::Apply(rec.initial, bp.get());
  std::vector<CandidatePair> pairs;
  pairs.reserve(4096);
  bp->FindPairs(rec.scene.compatible(), &pairs);
  // Ping-pong through the recording: 0, 1, ..., K-1, K-2, ..., 1, 0, 1, ...
  int frame = 0, step = 1;
  auto advance = [&] {
    if (frame + step < 0 || frame + step >= kRecordedCycles) step = -step;
    frame += step;
  };
  for (int i = 0; i < kRecordedCycles; ++i) {  // warm-up: one pass, pools at high water
    test::RandomScene::Apply(rec.cycles[frame], bp.get());
    bp->FindPairs(rec.scene.compatible(), &pairs);
    advance();
  }
  bp->ResetCounters();
  std::size_t pair_total = 0;
  for (auto _ : state) {
    for (const test::SceneOp& op : rec.cycles[frame]) bp->Move(op.id, op.box_W);
    bp->FindPairs(rec.scene.compatible(), &pairs);
    benchmark::DoNotOptimize(pairs.data());
    pair_total += pairs.size();
    advance();
  }
  const BroadPhaseCounters& c = bp->counters();
  const double n = static_cast<double>(state.iterations());
  state.counters["obj_obj_tests"] = static_cast<double>(c.object_object_tests) / n;
  state.counters["obj_node_tests"] = static_cast<double>(c.object_node_tests) / n;
  state.counters["neighbours"] = static_cast<double>(c.neighbours_visited) / n;
  state.counters["splits+merges"] = static_cast<double>(c.splits + c.merges) / n;
  state.counters["fallbacks"] = static_cast<double>(c.reinsert_fallbacks) / n;
  state.counters["pairs"] = static_cast<double>(pair_total) / n;
  if (const auto* octree = dynamic_cast<const OctreeBroadPhase*>(bp.get())) {
    const OctreeStatistics s = octree->ComputeStatistics();
    state.counters["leaves"] = s.leaves;
    state.counters["empty_leaves"] = s.empty_leaves;
    state.counters["per_leaf"] = s.mean_primitives_per_nonempty_leaf;
    state.counters["leaves_per_prim"] = s.mean_leaves_per_primitive;
    state.counters["depth"] = s.depth;
  }
}

void BM_Cycle(benchmark::State& state, BroadPhaseMethod method) {
  BroadPhaseOptions options;
  options.method = method;
  RunCycles(state, options);
}

void BM_OctreeAblation(benchmark::State& state, int technique_off) {
  BroadPhaseOptions options;
  options.method = BroadPhaseMethod::kOctree;
  BroadPhaseTechniques& t = options.techniques;
  if (technique_off == 0) t.pair_deduplication = false;
  if (technique_off == 1) t.directional_neighbours = false;
  if (technique_off == 2) t.inside_node_exit = false;
  if (technique_off == 3) t.bounding_box_pretests = false;
  RunCycles(state, options);
}

BENCHMARK_CAPTURE(BM_Cycle, octree, BroadPhaseMethod::kOctree)->Arg(35)->Arg(2000);
BENCHMARK_CAPTURE(BM_Cycle, naive, BroadPhaseMethod::kNaive)->Arg(35)->Arg(2000);
BENCHMARK_CAPTURE(BM_Cycle, grid, BroadPhaseMethod::kGrid)->Arg(35)->Arg(2000);
BENCHMARK_CAPTURE(BM_Cycle, reinsert, BroadPhaseMethod::kReinsert)->Arg(35)->Arg(2000);
BENCHMARK_CAPTURE(BM_Cycle, rebuild, BroadPhaseMethod::kRebuild)->Arg(35)->Arg(2000);
BENCHMARK_CAPTURE(BM_OctreeAblation, no_pair_dedup, 0)->Arg(35)->Arg(2000);
BENCHMARK_CAPTURE(BM_OctreeAblation, no_direction, 1)->Arg(35)->Arg(2000);
BENCHMARK_CAPTURE(BM_OctreeAblation, no_inside_exit, 2)->Arg(35)->Arg(2000);
BENCHMARK_CAPTURE(BM_OctreeAblation, no_box_pretest, 3)->Arg(35)->Arg(2000);

}  // namespace
}  // namespace arm_collision_monitor

int main(int argc, char** argv) {
  benchmark::AddCustomContext("scene_seed", std::to_string(arm_collision_monitor::kSeed));
  benchmark::AddCustomContext("scene",
                              "14 moving capsule boxes <= 0.61 m/s, 50 ms cycles, statics "
                              "0.04-0.3 m boxes in a 6.35 m cube; time = Move x14 + FindPairs");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
