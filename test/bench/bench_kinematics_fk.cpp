// Forward kinematics of the bundled workcell (two 7-DOF arms, 21 links): ComputeLinkPoses
// (/moving_only:0) and ComputeLinkPosesOf every moving link (/moving_only:1) per call, over a ring of seeded
// random configurations within the joint limits (the seed spent 28% of its cycle here). The
// machine is printed by Google Benchmark's context.
//
//   $ACM_WS/devel/lib/arm_collision_monitor/bench_kinematics_fk
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "arm_collision_monitor/kinematics/kinematic_model.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint64_t kSeed = 424242;
constexpr int kConfigurations = 1024;
const std::string kUrdf = std::string(ACM_SOURCE_DIR) + "/urdf/workcell.urdf";

// ComputeLinkPoses (all links) or, with range(0) = 1, ComputeLinkPosesOf the moving links.
void BM_ComputeLinkPoses(benchmark::State& state) {
  const bool moving_links_only = state.range(0) == 1;
  const KinematicModel model = KinematicModel::FromUrdfFile(kUrdf);
  std::mt19937_64 rng(kSeed);
  std::vector<Eigen::VectorXd> qs(kConfigurations, Eigen::VectorXd(model.q_size()));
  for (Eigen::VectorXd& q : qs) {
    for (int link = 1; link < model.link_count(); ++link) {
      const JointSpec& joint = model.joint(link);
      if (joint.q_index < 0) continue;
      q[joint.q_index] = std::uniform_real_distribution<double>(joint.lower, joint.upper)(rng);
    }
  }
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  model.ComputeLinkPoses(qs.back(), &X_WL);  // ComputeLinkPosesOf's precondition
  std::vector<std::uint8_t> all(model.link_count(), 1);
  std::vector<int> moving;
  model.MovingLinksTo(&all, &moving);
  std::size_t i = 0;
  for (auto _ : state) {
    if (moving_links_only) {
      model.ComputeLinkPosesOf(qs[i], moving, &X_WL);
    } else {
      model.ComputeLinkPoses(qs[i], &X_WL);
    }
    benchmark::DoNotOptimize(X_WL.data());
    benchmark::ClobberMemory();
    i = (i + 1) % qs.size();
  }
  state.counters["links"] = model.link_count();
  state.counters["joints"] = model.q_size();
  state.SetLabel(std::string(moving_links_only ? "moving links only, " : "all links, ") +
                 "seed " + std::to_string(kSeed));
}
BENCHMARK(BM_ComputeLinkPoses)->ArgName("moving_only")->Arg(0)->Arg(1);

}  // namespace
}  // namespace arm_collision_monitor

BENCHMARK_MAIN();
