// Start-up cost of LoadWorkcell:
//  - on the bundled files: URDF parsing, the scene file, compatibility, and the
//    always-overlapping check over kAlwaysOverlappingSamples seeded configurations (the dominant
//    part);
//  - on a generated robot of 20 mesh links (binary STL, ~3000 triangles each: tessellated
//    capsules of seeded sizes with 2 % radial noise), cold (empty fit cache: every mesh read and
//    fitted) and cached (every fit taken from the cache after its vertex check). Goals (issue 13):
//    <= 1 s cold, <= 0.2 s cached. Run with --benchmark_repetitions=5 for medians.
// The machine is printed by Google Benchmark's context.
//
//   $ACM_WS/devel/lib/arm_collision_monitor/bench_scene_load (one command line with)
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <string>

#include "../core/mesh_file_writers.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {
namespace {

const std::string kUrdf = std::string(ACM_SOURCE_DIR) + "/urdf/workcell.urdf";
const std::string kScene = std::string(ACM_SOURCE_DIR) + "/config/scene.yaml";

constexpr int kMeshLinks = 20;
constexpr std::uint64_t kMeshSeed = 13;

void BM_LoadWorkcell(benchmark::State& state) {
  for (auto _ : state) {
    Workcell w = LoadWorkcell(kUrdf, kScene);
    benchmark::DoNotOptimize(w.primitives.data());
  }
  state.SetLabel("sampling seed " + std::to_string(kAlwaysOverlappingSeed));
}
BENCHMARK(BM_LoadWorkcell)->Unit(benchmark::kMillisecond);

// The mesh robot's files, written once: a chain of kMeshLinks revolute links, link k holding
// mesh k.stl.
struct MeshRobot {
  std::string dir;
  std::string urdf;
  std::string scene;
  int triangles = 0;
};

const MeshRobot& GeneratedMeshRobot() {
  static const MeshRobot robot = [] {
    MeshRobot r;
    r.dir = (std::filesystem::temp_directory_path() / "acm_bench_mesh_robot").string() + "/";
    std::filesystem::remove_all(r.dir);
    std::filesystem::create_directories(r.dir);
    std::mt19937_64 rng(kMeshSeed);
    std::uniform_real_distribution<double> radius_m(0.04, 0.08), length_m(0.1, 0.3);
    std::string urdf = "<robot name=\"mesh_robot\"><link name=\"base_link\"/>\n";
    std::string parent = "base_link";
    for (int k = 0; k < kMeshLinks; ++k) {
      const TriangleMesh mesh =
          TessellatedCapsuleMesh(radius_m(rng), length_m(rng), 48, 16, 0.02, &rng);
      r.triangles += static_cast<int>(mesh.triangles.size());
      WriteBytes(r.dir + std::to_string(k) + ".stl", BinaryStl(mesh));
      const std::string link = "link" + std::to_string(k);
      urdf += "<link name=\"" + link +
              "\"><collision><origin xyz=\"0 0 0.2\"/><geometry><mesh "
              "filename=\"" +
              std::to_string(k) +
              ".stl\"/></geometry></collision></link>\n"
              "<joint name=\"j" +
              std::to_string(k) + "\" type=\"revolute\"><parent link=\"" + parent +
              "\"/><child link=\"" + link +
              "\"/><origin xyz=\"0 0 0.4\"/><axis xyz=\"0 "
              "1 0\"/><limit lower=\"-0.5\" upper=\"0.5\" effort=\"1\" velocity=\"1\"/></joint>\n";
      parent = link;
    }
    r.urdf = r.dir + "robot.urdf";
    r.scene = r.dir + "scene.yaml";
    WriteBytes(r.urdf, urdf + "</robot>\n");
    WriteBytes(r.scene, "world: {center_m: [0, 0, 4], edge_m: 20}\n");
    return r;
  }();
  return robot;
}

void LoadMeshRobot(benchmark::State& state, bool is_cached) {
  const MeshRobot& robot = GeneratedMeshRobot();
  WorkcellLoadOptions options;
  options.mesh_fit_cache_dir = robot.dir + "cache";
  std::filesystem::remove_all(options.mesh_fit_cache_dir);
  if (is_cached) LoadWorkcell(robot.urdf, robot.scene, options);  // fills the cache
  MeshFitCounts counts;
  for (auto _ : state) {
    if (!is_cached) {
      state.PauseTiming();
      std::filesystem::remove_all(options.mesh_fit_cache_dir);
      state.ResumeTiming();
    }
    Workcell w = LoadWorkcell(robot.urdf, robot.scene, options);
    counts = w.mesh_fits;
    benchmark::DoNotOptimize(w.primitives.data());
  }
  state.counters["fits_computed"] = counts.computed;
  state.counters["fits_cached"] = counts.from_cache;
  state.SetLabel(std::to_string(kMeshLinks) + " mesh links, " + std::to_string(robot.triangles) +
                 " triangles, seed " + std::to_string(kMeshSeed));
}

void BM_LoadMeshRobotCold(benchmark::State& state) { LoadMeshRobot(state, false); }
void BM_LoadMeshRobotCached(benchmark::State& state) { LoadMeshRobot(state, true); }
BENCHMARK(BM_LoadMeshRobotCold)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LoadMeshRobotCached)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace arm_collision_monitor

BENCHMARK_MAIN();
