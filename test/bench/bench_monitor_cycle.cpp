// Per-cycle Monitor time on the bundled workcell with every joint of both arms moving smoothly
// (seeded sinusoids at up to 80 % of each joint's velocity limit, 50 ms cycles), and the idle
// cycle. Prints median / p99 / p99.9 of individually timed cycles (steady clock, preallocated
// samples), first the every-cycle figures (issue 15 goal b: every Update a full kinematics
// cycle), then per broad phase, then Google Benchmark's means, among them the narrow phase alone
// on a sphere-robot-like scene (exact distances against the float batch, BM_NarrowPhase*). Run:
//   build/ws_<name>/devel/lib/arm_collision_monitor/bench_monitor_cycle
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>

#include "arm_collision_monitor/core/timing_summary.h"
#include "arm_collision_monitor/geometry/clearance_batch.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint64_t kSeed = 1990;    // printed with the figures
constexpr int kTrajectoryCycles = 20000;  // 1000 s of motion at 20 Hz
constexpr double kSpeedFraction = 0.8;    // of each joint's velocity limit

std::shared_ptr<const Workcell> BundledWorkcell() {
  static const auto workcell = std::make_shared<const Workcell>(
      LoadWorkcell(ACM_SOURCE_DIR "/urdf/workcell.urdf", ACM_SOURCE_DIR "/config/scene.yaml"));
  return workcell;
}

/// Every joint a sinusoid inside its limits; returns the q of every cycle.
std::vector<Eigen::VectorXd> SmoothTrajectory(const Workcell& wc, double period_s) {
  std::mt19937_64 rng(kSeed);
  const KinematicModel& model = wc.kinematics;
  const int n = model.q_size();
  Eigen::VectorXd centre(n), amplitude(n), omega(n), phase(n);
  for (int link = 1; link < model.link_count(); ++link) {
    const JointSpec& joint = model.joint(link);
    const int i = joint.q_index;
    if (i < 0) continue;
    const double lower = std::isfinite(joint.lower) ? joint.lower : -M_PI;
    const double upper = std::isfinite(joint.upper) ? joint.upper : M_PI;
    amplitude[i] = std::uniform_real_distribution<double>(0.1, 0.45)(rng) * (upper - lower);
    centre[i] = std::uniform_real_distribution<double>(lower + amplitude[i],
                                                       upper - amplitude[i])(rng);
    omega[i] = kSpeedFraction * joint.max_velocity / amplitude[i] *
               std::uniform_real_distribution<double>(0.5, 1.0)(rng);
    phase[i] = std::uniform_real_distribution<double>(0.0, 2.0 * M_PI)(rng);
  }
  std::vector<Eigen::VectorXd> qs(kTrajectoryCycles);
  for (int k = 0; k < kTrajectoryCycles; ++k) {
    qs[k] = centre + amplitude.cwiseProduct(
                         (omega * (k * period_s) + phase).array().sin().matrix());
  }
  return qs;
}

MonitorOptions Options(BroadPhaseMethod method, bool speed_scaled) {
  MonitorOptions options;
  options.broad_phase.method = method;
  options.speed_scaled_tolerance = speed_scaled;
  return options;
}

// Each Update over `qs` timed on its own (ns), after a first pass that warms caches and pools
// and is not recorded; `on_report` sees each timed report.
template <typename OnReport>
std::vector<double> TimeUpdates(Monitor* monitor, const std::vector<Eigen::VectorXd>& qs,
                                OnReport&& on_report) {
  for (const auto& q : qs) monitor->Update(q);
  std::vector<double> ns(qs.size());
  for (std::size_t k = 0; k < qs.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    const CycleReport& report = monitor->Update(qs[k]);
    const auto stop = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(report);
    ns[k] = std::chrono::duration<double, std::nano>(stop - start).count();
    on_report(report);
  }
  return ns;
}

// The default trajectory's moving and idle cycles, with percentiles.
void PrintPercentiles(BroadPhaseMethod method, bool speed_scaled) {
  const auto wc = BundledWorkcell();
  Monitor monitor(wc, Options(method, speed_scaled));
  const auto qs = SmoothTrajectory(*wc, monitor.options().cycle_period_s);
  std::uint64_t warnings = 0, moved = 0, object_tests = 0;
  std::vector<double> ns = TimeUpdates(&monitor, qs, [&](const CycleReport& report) {
    warnings += report.warnings.size();
    moved += report.moved_primitives;
    object_tests += report.counters.object_object_tests;
  });
  // Idle: the same q again (each call returns the previous report).
  std::vector<double> idle_ns(qs.size());
  const Eigen::VectorXd& last = qs.back();
  for (std::size_t k = 0; k < idle_ns.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(monitor.Update(last));
    const auto stop = std::chrono::steady_clock::now();
    idle_ns[k] = std::chrono::duration<double, std::nano>(stop - start).count();
  }
  // The cost of the two clock reads themselves, included in every sample above.
  std::vector<double> clock_ns(qs.size());
  for (std::size_t k = 0; k < clock_ns.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    const auto stop = std::chrono::steady_clock::now();
    clock_ns[k] = std::chrono::duration<double, std::nano>(stop - start).count();
  }
  std::sort(ns.begin(), ns.end());
  const TimingSummary moving = SummarizeTimings(ns);
  const TimingSummary idle = SummarizeTimings(std::move(idle_ns));
  const TimingSummary clock_pair = SummarizeTimings(std::move(clock_ns));
  std::printf(
      "%-8s %-12s moving: median %7.0f ns  p99 %7.0f ns  p99.9 %7.0f ns  max %8.0f ns | idle "
      "median %4.0f ns (clock pair alone %2.0f ns) | per cycle: %.1f moved, %.2f warnings, %.1f "
      "box tests\n",
      monitor.broad_phase_name().c_str(), speed_scaled ? "speed-scaled" : "fixed-tol",
      moving.median, moving.p99, NearestRankPercentile(ns, 0.999), moving.max, idle.median,
      clock_pair.median, static_cast<double>(moved) / qs.size(),
      static_cast<double>(warnings) / qs.size(), static_cast<double>(object_tests) / qs.size());
}

// Issue 15 goal (b): every Update a full kinematics cycle (forward kinematics, re-index, pair
// upkeep, narrow phase, swept check). index_slack_m = 0 forces it: a moving primitive is then
// re-indexed whenever it moves, and IsProvablyClear needs every motion bound within the slack,
// so no cycle is bounded (the figures print how many were, to show it). The default options
// (slack 0.1 m) run beside it for reference. Also printed: the exact double distances the
// narrow phase computed per cycle (CycleReport::narrow_phase_tests).
void PrintEveryCycle(const char* label, double index_slack_m) {
  const auto wc = BundledWorkcell();
  MonitorOptions options;
  options.index_slack_m = index_slack_m;
  Monitor monitor(wc, options);
  const auto qs = SmoothTrajectory(*wc, monitor.options().cycle_period_s);
  std::uint64_t bounded = 0, exact_tests = 0, candidates = 0, warnings = 0;
  std::vector<double> ns = TimeUpdates(&monitor, qs, [&](const CycleReport& report) {
    bounded += report.bounded;
    exact_tests += report.narrow_phase_tests;
    candidates += report.candidate_pairs;
    warnings += report.warnings.size();
  });
  const double n = static_cast<double>(qs.size());
  std::sort(ns.begin(), ns.end());
  const TimingSummary all = SummarizeTimings(ns);
  std::printf(
      "every-cycle %-22s %s: median %6.0f ns  p99 %6.0f ns  p99.9 %6.0f ns  max %7.0f ns | "
      "%.0f%% bounded cycles, per cycle %.1f candidate pairs, %.2f exact distances, %.2f "
      "warnings\n",
      label, monitor.broad_phase_name().c_str(), all.median, all.p99,
      NearestRankPercentile(ns, 0.999), all.max, 100.0 * bounded / n, candidates / n,
      exact_tests / n, warnings / n);
}

void BM_MonitorCycle(benchmark::State& state) {
  const auto wc = BundledWorkcell();
  Monitor monitor(wc, Options(static_cast<BroadPhaseMethod>(state.range(0)), state.range(1)));
  const auto qs = SmoothTrajectory(*wc, monitor.options().cycle_period_s);
  for (const auto& q : qs) monitor.Update(q);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(monitor.Update(qs[k]));
    k = k + 1 == qs.size() ? 0 : k + 1;
  }
  state.SetLabel(monitor.broad_phase_name() + (state.range(1) ? " speed-scaled" : ""));
}
BENCHMARK(BM_MonitorCycle)
    ->ArgsProduct({{static_cast<int>(BroadPhaseMethod::kOctree),
                    static_cast<int>(BroadPhaseMethod::kNaive),
                    static_cast<int>(BroadPhaseMethod::kGrid)},
                   {0, 1}});

void BM_MonitorIdleCycle(benchmark::State& state) {
  const auto wc = BundledWorkcell();
  Monitor monitor(wc, Options(BroadPhaseMethod::kOctree, false));
  const auto qs = SmoothTrajectory(*wc, monitor.options().cycle_period_s);
  monitor.Update(qs[123]);
  for (auto _ : state) benchmark::DoNotOptimize(monitor.Update(qs[123]));
}
BENCHMARK(BM_MonitorIdleCycle);

// The narrow phase alone on a sphere-robot-like scene: 75 spheres (zero-length capsules) and 15
// boxes in a 1.5 m cube, the pairs whose boxes grown by 5 cm overlap (what a broad phase would
// hand over), threshold 5 cm. Exact: ShapeDistance on every pair (the narrow phase before the
// batch). Batch: float copies of all 90 shapes (all move in a sphere robot), the float bounds of
// all pairs, then ShapeDistance on those they do not clear (counter settled_fraction).
constexpr double kSphereRobotThreshold_m = 0.05;
struct SphereRobotPairs {
  std::vector<Shape> shapes;
  std::vector<PrimitiveId> a, b;
};
const SphereRobotPairs& SphereRobotScene() {
  static const SphereRobotPairs scene = [] {
    SphereRobotPairs s;
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> coordinate(-0.75, 0.75);
    auto point = [&] { return Eigen::Vector3d(coordinate(rng), coordinate(rng), coordinate(rng)); };
    for (int i = 0; i < 75; ++i) {
      Capsule sphere;
      sphere.p0_W = sphere.p1_W = point();
      sphere.radius_m = std::uniform_real_distribution<double>(0.04, 0.10)(rng);
      s.shapes.push_back(sphere);
    }
    for (int i = 0; i < 15; ++i) {
      Box box;
      box.X_WB.translation() = point();
      std::normal_distribution<double> normal;
      box.X_WB.linear() =
          Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized()
              .matrix();
      std::uniform_real_distribution<double> half_m(0.02, 0.32);
      box.half_extents_m = Eigen::Vector3d(half_m(rng), half_m(rng), half_m(rng));
      s.shapes.push_back(box);
    }
    for (PrimitiveId i = 0; i < s.shapes.size(); ++i) {
      for (PrimitiveId j = i + 1; j < s.shapes.size(); ++j) {
        if (ComputeAabb(s.shapes[i]).Inflated(kSphereRobotThreshold_m)
                .Overlaps(ComputeAabb(s.shapes[j]))) {
          s.a.push_back(i);
          s.b.push_back(j);
        }
      }
    }
    return s;
  }();
  return scene;
}

void BM_NarrowPhaseExact(benchmark::State& state) {
  const SphereRobotPairs& s = SphereRobotScene();
  std::size_t close = 0;
  for (auto _ : state) {
    close = 0;
    for (std::size_t k = 0; k < s.a.size(); ++k) {
      close += ShapeDistance(s.shapes[s.a[k]], s.shapes[s.b[k]]).distance_m <
               kSphereRobotThreshold_m;
    }
    benchmark::DoNotOptimize(close);
  }
  state.counters["pairs"] = static_cast<double>(s.a.size());
  state.counters["close"] = static_cast<double>(close);
}
BENCHMARK(BM_NarrowPhaseExact);

void BM_NarrowPhaseBatch(benchmark::State& state) {
  const SphereRobotPairs& s = SphereRobotScene();
  std::vector<double> bound_m(s.a.size());
  std::vector<FloatPrimitive> floats(s.shapes.size());
  std::size_t close = 0, exact = 0;
  for (auto _ : state) {
    close = exact = 0;
    for (std::size_t i = 0; i < s.shapes.size(); ++i) ToFloatPrimitive(s.shapes[i], &floats[i]);
    ComputeClearanceLowerBounds(floats.data(), s.a.data(), s.b.data(), s.a.size(),
                                bound_m.data());
    for (std::size_t k = 0; k < s.a.size(); ++k) {
      if (bound_m[k] > kSphereRobotThreshold_m) continue;
      ++exact;
      close += ShapeDistance(s.shapes[s.a[k]], s.shapes[s.b[k]]).distance_m <
               kSphereRobotThreshold_m;
    }
    benchmark::DoNotOptimize(close);
  }
  state.counters["pairs"] = static_cast<double>(s.a.size());
  state.counters["close"] = static_cast<double>(close);
  state.counters["settled_fraction"] = 1.0 - static_cast<double>(exact) / s.a.size();
}
BENCHMARK(BM_NarrowPhaseBatch);

}  // namespace
}  // namespace arm_collision_monitor

int main(int argc, char** argv) {
  using arm_collision_monitor::BroadPhaseMethod;
  // Wall-clock percentiles mean little on a loaded machine: say how loaded it was.
  std::string load;
  std::getline(std::ifstream("/proc/loadavg"), load);
  std::printf("load average at start: %s\n", load.c_str());
  std::printf("bench_monitor_cycle: seed %llu, %d cycles of 50 ms, joints at up to %.0f%% of "
              "their velocity limits; %u hardware threads\n",
              static_cast<unsigned long long>(arm_collision_monitor::kSeed),
              arm_collision_monitor::kTrajectoryCycles, 100 * arm_collision_monitor::kSpeedFraction,
              std::thread::hardware_concurrency());
  arm_collision_monitor::PrintEveryCycle("(index_slack_m 0)", 0.0);
  arm_collision_monitor::PrintEveryCycle("(default options)",
                                         arm_collision_monitor::kDefaultIndexSlack_m);
  for (const auto method : {BroadPhaseMethod::kOctree, BroadPhaseMethod::kNaive,
                            BroadPhaseMethod::kGrid}) {
    for (const bool speed_scaled : {false, true}) {
      arm_collision_monitor::PrintPercentiles(method, speed_scaled);
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
