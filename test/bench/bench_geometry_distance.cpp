// Micro-benchmarks of the narrow phase: ns per call of each pairwise routine and of
// IsCloserThan, on seeded pools of pairs that are separated (beyond the threshold and its AABB
// test), near (within 5 cm: the exact test decides) or overlapping.
//
//   $ACM_WS/devel/lib/arm_collision_monitor/bench_geometry_distance [--benchmark_filter=...]
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "arm_collision_monitor/geometry/distance.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Vector3d;

constexpr uint64_t kSeed = 20261121;
constexpr double kThreshold_m = 0.05;  // IsCloserThan threshold; "near" pairs are closer
constexpr int kPoolSize = 512;          // pairs per pool, cycled (fits in L1/L2 with the code)

enum class Kind { kCapsuleCapsule, kCapsuleBox, kBoxBox };
enum class Band { kSeparated, kNear, kOverlapping };

Shape RandomShape(std::mt19937_64& rng, bool capsule) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vector3d c(u(rng), u(rng), u(rng));
  if (capsule) {
    // A link-sized capsule: 0.1-0.5 m long, radius 3-8 cm.
    const Vector3d dir = Vector3d(u(rng), u(rng), u(rng)).normalized();
    const double half = 0.05 + 0.2 * (u(rng) + 1.0) / 2;
    Capsule cap;
    cap.p0_W = c - half * dir;
    cap.p1_W = c + half * dir;
    cap.radius_m = 0.03 + 0.025 * (u(rng) + 1.0);
    return cap;
  }
  Box box;
  box.X_WB.linear() =
      Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  box.X_WB.translation() = c;
  box.half_extents_m = Vector3d(0.05 + 0.2 * std::abs(u(rng)), 0.05 + 0.2 * std::abs(u(rng)),
                                0.05 + 0.2 * std::abs(u(rng)));
  return box;
}

// A seeded pool of pairs of one kind whose distance falls in the band.
const std::vector<std::pair<Shape, Shape>>& Pool(Kind kind, Band band) {
  static std::vector<std::pair<Shape, Shape>> pools[3][3];
  auto& pool = pools[static_cast<int>(kind)][static_cast<int>(band)];
  if (!pool.empty()) return pool;
  std::mt19937_64 rng(kSeed + 10 * static_cast<int>(kind) + static_cast<int>(band));
  while (static_cast<int>(pool.size()) < kPoolSize) {
    Shape a = RandomShape(rng, kind != Kind::kBoxBox);
    Shape b = RandomShape(rng, kind == Kind::kCapsuleCapsule);
    const double d = ShapeDistance(a, b).distance_m;
    const bool keep = band == Band::kOverlapping ? d == 0.0
                      : band == Band::kNear      ? (d > 0.0 && d < kThreshold_m)
                                                 : d > 2 * kThreshold_m;
    if (keep) pool.emplace_back(std::move(a), std::move(b));
  }
  return pool;
}

void BM_SegmentSegmentClosestPoints(benchmark::State& state) {
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vector3d> points(4 * kPoolSize);
  for (Vector3d& p : points) p = Vector3d(u(rng), u(rng), u(rng));
  // Every 8th pair parallel, as at the arms' home pose (the error-free cross product path).
  for (int i = 0; i < kPoolSize; i += 8) {
    points[4 * i + 3] = points[4 * i + 2] + (points[4 * i + 1] - points[4 * i]);
  }
  size_t i = 0;
  for (auto _ : state) {
    const Vector3d* p = &points[4 * i];
    benchmark::DoNotOptimize(SegmentSegmentClosestPoints(p[0], p[1], p[2], p[3]));
    i = (i + 1) % kPoolSize;
  }
}
BENCHMARK(BM_SegmentSegmentClosestPoints);

template <Kind kind>
void BM_Distance(benchmark::State& state) {
  const auto& pool = Pool(kind, static_cast<Band>(state.range(0)));
  size_t i = 0;
  for (auto _ : state) {
    const auto& [a, b] = pool[i];
    if constexpr (kind == Kind::kCapsuleCapsule) {
      benchmark::DoNotOptimize(CapsuleCapsuleDistance(std::get<Capsule>(a), std::get<Capsule>(b)));
    } else if constexpr (kind == Kind::kCapsuleBox) {
      benchmark::DoNotOptimize(CapsuleBoxDistance(std::get<Capsule>(a), std::get<Box>(b)));
    } else {
      benchmark::DoNotOptimize(BoxBoxDistance(std::get<Box>(a), std::get<Box>(b)));
    }
    i = (i + 1) % pool.size();
  }
}

template <Kind kind>
void BM_IsCloserThan(benchmark::State& state) {
  const auto& pool = Pool(kind, static_cast<Band>(state.range(0)));
  size_t i = 0;
  for (auto _ : state) {
    const auto& [a, b] = pool[i];
    benchmark::DoNotOptimize(IsCloserThan(a, b, kThreshold_m));
    i = (i + 1) % pool.size();
  }
}

// Arg: 0 separated, 1 near, 2 overlapping.
void Bands(benchmark::internal::Benchmark* b) {
  b->ArgName("band(0sep,1near,2overlap)")->Arg(0)->Arg(1)->Arg(2);
}
BENCHMARK_TEMPLATE(BM_Distance, Kind::kCapsuleCapsule)->Apply(Bands);
BENCHMARK_TEMPLATE(BM_Distance, Kind::kCapsuleBox)->Apply(Bands);
BENCHMARK_TEMPLATE(BM_Distance, Kind::kBoxBox)->Apply(Bands);
BENCHMARK_TEMPLATE(BM_IsCloserThan, Kind::kCapsuleCapsule)->Apply(Bands);
BENCHMARK_TEMPLATE(BM_IsCloserThan, Kind::kCapsuleBox)->Apply(Bands);
BENCHMARK_TEMPLATE(BM_IsCloserThan, Kind::kBoxBox)->Apply(Bands);

std::string CpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown";
}

}  // namespace
}  // namespace arm_collision_monitor

int main(int argc, char** argv) {
  benchmark::AddCustomContext("cpu_model", arm_collision_monitor::CpuModel());
  benchmark::AddCustomContext("compiler", __VERSION__);
  benchmark::AddCustomContext("seed", std::to_string(arm_collision_monitor::kSeed));
#if defined(__FMA__)
  benchmark::AddCustomContext("fma", "compiled in");
#else
  benchmark::AddCustomContext("fma", "not compiled in (Veltkamp split products)");
#endif
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
