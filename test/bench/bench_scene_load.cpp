// Start-up cost of LoadWorkcell on the bundled files: URDF parsing (twice: kinematics and
// collision geometry), the scene file, compatibility, and the always-overlapping check over
// kAlwaysOverlappingSamples seeded configurations (the dominant part). The machine is printed
// by Google Benchmark's context.
//
//   $ACM_WS/devel/lib/arm_collision_monitor/bench_scene_load
#include <benchmark/benchmark.h>

#include <string>

#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {
namespace {

const std::string kUrdf = std::string(ACM_SOURCE_DIR) + "/urdf/workcell.urdf";
const std::string kScene = std::string(ACM_SOURCE_DIR) + "/config/scene.yaml";

void BM_LoadWorkcell(benchmark::State& state) {
  for (auto _ : state) {
    Workcell w = LoadWorkcell(kUrdf, kScene);
    benchmark::DoNotOptimize(w.primitives.data());
  }
  state.SetLabel("sampling seed " + std::to_string(kAlwaysOverlappingSeed));
}
BENCHMARK(BM_LoadWorkcell)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace arm_collision_monitor

BENCHMARK_MAIN();
