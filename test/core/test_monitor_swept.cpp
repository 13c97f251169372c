// The swept check (MonitorOptions::swept_check): thin plates and rods crossed within one step,
// arms crossing, a wrist flip, and random fast trajectories, each step against an independent
// dense sampler (>= 1,000 sub-samples of the same straight joint-space path, brute force over
// all pairs): no contact the sampler finds is missed, and every between-samples warning is
// checked at its own fraction to lie within threshold + resolution. Also: jumps beyond
// max_step_m, a long step far from everything at both ends (no pair bisected), the start-up
// tolerance check, and how rarely the path is needed.
#include <array>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "load_error_expect.h"
#include "test_monitor_util.h"

namespace arm_collision_monitor {
namespace {

using test::JointIndex;
using test::MakeQ;

constexpr int kDenseSamples = 1000;

/// The default options, without a step limit (the steps here are meant to be swept).
MonitorOptions Unlimited() {
  MonitorOptions options;
  options.max_step_m = std::numeric_limits<double>::infinity();
  return options;
}

/// `object_line` (one YAML list entry) added to the objects of the bundled scene's `scene`.
void AddObjectLine(const std::string& object_line, std::string* scene) {
  const std::size_t at = scene->find("\nobjects:\n");
  ASSERT_NE(at, std::string::npos);
  scene->insert(at + 10, "  " + object_line + "\n");
}

/// The bundled scene with `object_line` added to its objects.
std::shared_ptr<const Workcell> LoadSceneWith(const std::string& name,
                                              const std::string& object_line) {
  return test::LoadBundledSceneEdited(
      "swept_" + name, [&](std::string* scene) { AddObjectLine(object_line, scene); });
}

/// YAML list entries (for LoadSceneWith) of 3 cm cubes on a grid: count[a] along axis a from
/// `first_m`, `spacing_m` apart.
std::string CubeGrid(const std::array<int, 3>& count, const Eigen::Vector3d& first_m,
                     const Eigen::Vector3d& spacing_m) {
  std::ostringstream cubes;
  for (int i = 0; i < count[0]; ++i) {
    for (int j = 0; j < count[1]; ++j) {
      for (int k = 0; k < count[2]; ++k) {
        const Eigen::Vector3d centre_m =
            first_m + spacing_m.cwiseProduct(Eigen::Vector3d(i, j, k));
        cubes << (i + j + k == 0 ? "" : "\n  ") << "- {name: cube_" << i << "_" << j << "_" << k
              << ", size_m: [0.03, 0.03, 0.03], pose: {xyz_m: [" << centre_m.x() << ", "
              << centre_m.y() << ", " << centre_m.z() << "]}}";
      }
    }
  }
  return cubes.str();
}

/// The straight joint-space path of a step.
Eigen::VectorXd Along(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1, double s) {
  return q0 + s * (q1 - q0);
}

/// Per non-excused pair (default variants, no scene change): the smallest distance over the
/// samples s = k / N, k = 1..N, and its threshold. Independent of the Monitor: all pairs, AABB
/// pre-test only to skip pairs far beyond any threshold.
struct DensePair {
  double min_m = std::numeric_limits<double>::infinity();
  double threshold_m = 0.0;
  bool warns = false;  ///< some sample within the threshold (or touching)
};
using DenseResult = std::map<std::pair<PrimitiveId, PrimitiveId>, DensePair>;

DenseResult DenseStep(const Workcell& wc, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                      int samples) {
  const KinematicModel& model = wc.kinematics;
  const std::size_t n = wc.primitives.size();
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  std::vector<Shape> shape(n);
  std::vector<Aabb> box(n);
  // The far cut: 0.1 m beyond any threshold; nearer pairs get exact distances.
  constexpr double kFar_m = 0.1;
  std::vector<std::uint8_t> is_static(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PrimitiveSpec& p = wc.primitives[i];
    is_static[i] = p.link_index >= 0 ? p.is_static : wc.objects[p.object_index].frame.empty();
  }
  DenseResult result;
  for (int k = 1; k <= samples; ++k) {
    model.ComputeLinkPoses(Along(q0, q1, static_cast<double>(k) / samples), &X_WL);
    for (std::size_t i = 0; i < n; ++i) {
      const PrimitiveSpec& p = wc.primitives[i];
      shape[i] = p.link_index >= 0 ? TransformShape(X_WL[p.link_index], p.shape_L) : p.shape_L;
      box[i] = ComputeAabb(shape[i]).Inflated(p.tolerance_m + kFar_m);
    }
    // Each pair with a moving primitive (two static ones are never checked), from the moving
    // one, or from the smaller id when both move.
    for (std::size_t m = 0; m < n; ++m) {
      if (!wc.primitives[m].variant.empty() || is_static[m]) continue;
      for (std::size_t o = 0; o < n; ++o) {
        if (o == m || !wc.primitives[o].variant.empty() || (!is_static[o] && o < m)) continue;
        const std::size_t a = std::min(m, o), b = std::max(m, o);
        const PrimitiveSpec& pa = wc.primitives[a];
        const PrimitiveSpec& pb = wc.primitives[b];
        if (wc.compatible.AreCompatible(a, b) || !box[a].Overlaps(box[b])) continue;
        DensePair& pair = result[{static_cast<PrimitiveId>(a), static_cast<PrimitiveId>(b)}];
        pair.threshold_m = pa.tolerance_m + pb.tolerance_m;
        const double d = ShapeDistance(shape[a], shape[b]).distance_m;
        pair.min_m = std::min(pair.min_m, d);
        pair.warns = pair.warns || d < pair.threshold_m || d <= 0.0;
      }
    }
  }
  return result;
}

/// What a step's report did against the dense sampler.
struct StepTally {
  int steps = 0, dense_contacts = 0, missed = 0, between = 0, false_warnings = 0;
  int swept_cycles = 0;
};

/// Checks one step's report against the dense sampler: every pair the sampler finds within its
/// threshold is warned (at q or between samples); every between-samples warning is re-measured
/// independently at its own fraction and lies within threshold + resolution.
void CheckStep(const Workcell& wc, const MonitorOptions& options, const Eigen::VectorXd& q0,
               const Eigen::VectorXd& q1, const CycleReport& report, const std::string& context,
               StepTally* tally) {
  const DenseResult dense = DenseStep(wc, q0, q1, kDenseSamples);
  ++tally->steps;
  if (report.swept_pairs > 0) ++tally->swept_cycles;
  for (const auto& [pair, d] : dense) {
    if (!d.warns) continue;
    ++tally->dense_contacts;
    if (!test::HasWarning(report.warnings, pair.first, pair.second)) {
      ++tally->missed;
      ADD_FAILURE() << context << ": missed " << test::Describe(wc, pair.first, pair.second)
                    << ", dense minimum " << d.min_m << " m, threshold " << d.threshold_m;
    }
  }
  std::vector<Eigen::Isometry3d> X_WL(wc.kinematics.link_count());
  for (const Warning& w : report.warnings) {
    if (!w.between_samples) continue;
    ++tally->between;
    ASSERT_GE(w.step_fraction, 0.0) << context;
    ASSERT_LE(w.step_fraction, 1.0) << context;
    wc.kinematics.ComputeLinkPoses(Along(q0, q1, w.step_fraction), &X_WL);
    auto shape_at = [&](PrimitiveId id) {
      const PrimitiveSpec& p = wc.primitives[id];
      return p.link_index >= 0 ? TransformShape(X_WL[p.link_index], p.shape_L) : p.shape_L;
    };
    const double d = ShapeDistance(shape_at(w.a), shape_at(w.b)).distance_m;
    EXPECT_NEAR(d, w.distance_m, 1e-9) << context << " " << test::Describe(wc, w.a, w.b);
    EXPECT_LE(w.distance_m, w.threshold_m + options.swept_resolution_m + 1e-9)
        << context << " " << test::Describe(wc, w.a, w.b) << " at " << w.step_fraction;
    const auto it = dense.find({w.a, w.b});
    if (it == dense.end() || !it->second.warns) ++tally->false_warnings;
  }
}

/// The step from q0 to q1: the Monitor first accepts q0; returns the step's report (a copy).
CycleReport RunStep(Monitor* monitor, const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  monitor->Update(q0);
  return monitor->Update(q1);
}

/// The pair warned between samples whose owners are `owner_a` and `owner_b` (either order).
bool HasBetweenSamples(const Workcell& wc, const CycleReport& report, const std::string& owner_a,
                       const std::string& owner_b) {
  for (const Warning& w : report.warnings) {
    const std::string& x = wc.primitives[w.a].owner;
    const std::string& y = wc.primitives[w.b].owner;
    if (w.between_samples && ((x == owner_a && y == owner_b) || (x == owner_b && y == owner_a))) {
      return true;
    }
  }
  return false;
}

// A 2 mm plate in the gripper's path: the left arm's base joint swings the tool across it in
// one step; neither end is near it.
TEST(MonitorSwept, ThinPlateCrossedInOneStep) {
  const auto wc = LoadSceneWith(
      "plate", "- {name: plate, size_m: [0.3, 0.002, 0.3], pose: {xyz_m: [0.7, 0.55, 0.95]}}");
  const Eigen::VectorXd mid = test::ArmReachDown(*wc, "left", 0.7, 0.55, 0.9);
  const int j1 = JointIndex(*wc, "left_joint1");
  Eigen::VectorXd q0 = mid, q1 = mid;
  q0[j1] -= 0.4;
  q1[j1] += 0.4;
  MonitorOptions options = Unlimited();
  Monitor monitor(wc, options);
  ASSERT_TRUE(monitor.Check(q0).warnings.empty());
  ASSERT_TRUE(monitor.Check(q1).warnings.empty());
  const CycleReport report = RunStep(&monitor, q0, q1);
  EXPECT_TRUE(report.stop);
  EXPECT_FALSE(report.input_jumped);
  EXPECT_TRUE(HasBetweenSamples(*wc, report, "left_link7", "plate"));
  EXPECT_GT(report.swept_pairs, 0u);
  StepTally tally;
  CheckStep(*wc, options, q0, q1, report, "plate", &tally);
  EXPECT_GT(tally.dense_contacts, 0);
  // The same step with the swept check off: both ends are clear, the plate is missed; but the
  // step moves the gripper farther than its tolerance, beyond what the samples cover (the
  // start-up check assumed steps of cycle_period_s): a jump, and a stop.
  options.swept_check = false;
  options.cycle_period_s = 0.001;  // (a tolerance above the per-cycle motion, as required)
  Monitor discrete(wc, options);
  const CycleReport samples_only = RunStep(&discrete, q0, q1);
  EXPECT_FALSE(HasBetweenSamples(*wc, samples_only, "left_link7", "plate"));
  EXPECT_TRUE(samples_only.warnings.empty());
  EXPECT_TRUE(samples_only.input_jumped);
  EXPECT_TRUE(samples_only.stop);
  // It says which primitive the samples leave uncovered: one of the swinging arm's, whose step
  // bound is over its tolerance (the gripper's swing is about 0.5 m; the swept Monitor's is no
  // such step).
  const StepBeyondSamples& beyond = samples_only.beyond_samples;
  ASSERT_TRUE(beyond.is_beyond);
  EXPECT_EQ(wc->primitives[beyond.primitive].name.rfind("left_", 0), 0u)
      << wc->primitives[beyond.primitive].name;
  EXPECT_EQ(beyond.tolerance_m, discrete.tolerance_m(beyond.primitive));
  EXPECT_GT(beyond.motion_m, beyond.tolerance_m);
  EXPECT_LE(beyond.motion_m, samples_only.step_motion_m);
  EXPECT_FALSE(report.beyond_samples.is_beyond);
  // Steps within the tolerances (a cycle's at most) are covered: no stop.
  Eigen::VectorXd q = q0;
  discrete.Update(q);
  for (int k = 0; k < 20; ++k) {
    q[j1] += 0.001;
    const CycleReport& small = discrete.Update(q);
    EXPECT_FALSE(small.input_jumped) << k << ": " << small.step_motion_m;
    EXPECT_FALSE(small.beyond_samples.is_beyond) << k;
    EXPECT_FALSE(small.stop) << k;
  }
}

// With the swept check off, a step is beyond the samples when some primitive's bound exceeds
// its own tolerance, also when every other primitive's tolerance would cover the whole step:
// right_link7 (its fingers too) with a 4 mm zone, the others 30.5 mm; a wrist pitch of either
// arm moving its tool by 10 mm, and the right one's by 3 mm (within every tolerance: no
// primitive's own bound is needed). With speed-scaled tolerance the same: the zones grown by
// the speed (each wrist primitive moved in the cycle before) do not cover what the samples
// leave out.
TEST(MonitorSwept, AStepBeyondTheSmallestToleranceIsBeyondTheSamples) {
  const auto wc = test::LoadBundledSceneEdited("small_zone", [](std::string* scene) {
    const std::string at = "  right_base_link: {ignore: true}\n";
    const std::size_t k = scene->find(at);
    ASSERT_NE(k, std::string::npos);
    scene->insert(k + at.size(), "  right_link7: {tolerance_m: 0.004}\n");
  });
  MonitorOptions options = Unlimited();
  options.swept_check = false;
  options.cycle_period_s = 0.0002;  // within the 4 mm at the URDF's velocity limits
  const Eigen::VectorXd home = MakeQ(*wc, {});
  // The step of `arm`'s wrist pitch that moves its tool by `step_m`.
  auto pitch = [&](const MonitorOptions& o, const std::string& arm, double step_m) {
    Monitor monitor(wc, o);
    const int j6 = JointIndex(*wc, arm + "_joint6");
    Eigen::VectorXd q = home;
    q[j6] += 0.1;
    // The step's bound is linear in the pitch.
    const double per_rad_m = RunStep(&monitor, home, q).step_motion_m / 0.1;
    EXPECT_GT(per_rad_m, 0.0) << arm;
    q = home;
    q[j6] += step_m / per_rad_m;
    const CycleReport report = RunStep(&monitor, home, q);
    EXPECT_NEAR(report.step_motion_m, step_m, 1e-9) << arm;
    return report;
  };
  for (const bool is_speed_scaled : {false, true}) {
    options.speed_scaled_tolerance = is_speed_scaled;
    for (const auto& [arm, step_m] : {std::pair{"left", 0.01}, std::pair{"right", 0.003}}) {
      const CycleReport report = pitch(options, arm, step_m);
      EXPECT_FALSE(report.beyond_samples.is_beyond)
          << arm << " " << wc->primitives[report.beyond_samples.primitive].name;
      EXPECT_FALSE(report.input_jumped) << arm;
      // (Grown by the speed, the zones of link5 and link7, 0.13 m apart, meet: a warning.)
      if (!is_speed_scaled) EXPECT_FALSE(report.stop) << arm;
    }
    const CycleReport report = pitch(options, "right", 0.01);
    const StepBeyondSamples& beyond = report.beyond_samples;
    ASSERT_TRUE(beyond.is_beyond) << is_speed_scaled;
    EXPECT_EQ(wc->primitives[beyond.primitive].owner, "right_link7");
    EXPECT_EQ(beyond.tolerance_m, 0.004);
    EXPECT_GT(beyond.motion_m, 0.004);
    EXPECT_TRUE(report.input_jumped);
    EXPECT_TRUE(report.stop);
  }
}

// The same swing past a live plate that a scene change moves into the path after a swept step
// found it far: the swept check's kept boxes of primitives without levers (cached until a scene
// change) must follow it.
TEST(MonitorSwept, PlateMovedIntoPathAfterSweptStep) {
  const auto wc = test::LoadBundledWorkcell();
  const Eigen::VectorXd mid = test::ArmReachDown(*wc, "left", 0.7, 0.55, 0.9);
  const int j1 = JointIndex(*wc, "left_joint1");
  Eigen::VectorXd q0 = mid, q1 = mid;
  q0[j1] -= 0.4;
  q1[j1] += 0.4;
  Monitor monitor(wc, Unlimited());
  const std::vector<Shape> plate_O = {Box{Eigen::Isometry3d::Identity(), {0.15, 0.001, 0.15}}};
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() = Eigen::Vector3d(2.5, 2.5, 0.5);
  std::string error;
  ASSERT_TRUE(monitor.AddObject("plate", plate_O, X_WO, 0.0, false, &error)) << error;
  // Whether the report warns about the plate (`between`: between samples, with the left arm's
  // tool).
  auto plate_warned = [&](const CycleReport& report, bool between) {
    for (const Warning& w : report.warnings) {
      const std::string& x = monitor.primitive(w.a).owner;
      const std::string& y = monitor.primitive(w.b).owner;
      const bool is_plate = x == "plate" || y == "plate";
      const bool is_tool = x == "left_link7" || y == "left_link7";
      if (is_plate && (!between || (w.between_samples && is_tool))) return true;
    }
    return false;
  };
  // Far from the path: both ways swept (pairs beyond the slack looked at), nothing met.
  monitor.Update(q0);
  CycleReport report = monitor.Update(q1);
  EXPECT_FALSE(plate_warned(report, false));
  report = monitor.Update(q0);
  EXPECT_FALSE(plate_warned(report, false));
  // Into the path, where the swing crosses it; both ends stay clear of it.
  X_WO.translation() = Eigen::Vector3d(0.7, 0.55, 0.95);
  ASSERT_TRUE(monitor.MoveObject("plate", X_WO, &error)) << error;
  ASSERT_FALSE(plate_warned(monitor.Check(q0), false));
  ASSERT_FALSE(plate_warned(monitor.Check(q1), false));
  report = monitor.Update(q1);
  EXPECT_TRUE(report.stop);
  EXPECT_TRUE(plate_warned(report, true));
  EXPECT_GT(report.swept_pairs, 0u);
}

/// A plate across the left tool's way at `mid` (the left arm reaching down at x 0.7) as left
/// joint `j1` grows: its pose `X_WO` at (0.7, y, 0.95) on the side the tool moves to, with its gap
/// to the left arm at `mid`, less the arm's tolerances (the plate's own is 0), `gap_m`;
/// `achieved_m` the gap measured there.
struct PlateInTheWay {
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  double achieved_m = 0.0;
};

PlateInTheWay PlaceInTheWay(const Workcell& wc, const Eigen::VectorXd& mid, int j1,
                            const Box& plate_O, double gap_m) {
  std::vector<Eigen::Isometry3d> X_WL(wc.kinematics.link_count());
  const int link7 = wc.kinematics.FindLink("left_link7");
  Eigen::VectorXd ahead = mid;
  ahead[j1] += 0.01;
  wc.kinematics.ComputeLinkPoses(ahead, &X_WL);
  const double y_ahead = X_WL[link7].translation().y();
  wc.kinematics.ComputeLinkPoses(mid, &X_WL);
  const double way = y_ahead > X_WL[link7].translation().y() ? 1.0 : -1.0;  // +y or -y
  auto gap_at = [&](double y) {
    Box box = plate_O;
    box.X_WB.translation() = Eigen::Vector3d(0.7, y, 0.95);
    double gap = std::numeric_limits<double>::infinity();
    for (const PrimitiveSpec& p : wc.primitives) {
      if (p.group != "left" || !p.variant.empty()) continue;
      const double d = ShapeDistance(TransformShape(X_WL[p.link_index], p.shape_L), box)
                           .distance_m;
      gap = std::min(gap, d - p.tolerance_m);
    }
    return gap;
  };
  const double y_far = 0.55 + way * 0.2;
  const double y = y_far - way * (gap_at(y_far) - gap_m);
  PlateInTheWay plate;
  plate.X_WO.translation() = Eigen::Vector3d(0.7, y, 0.95);
  plate.achieved_m = gap_at(y);
  return plate;
}

// A contact just past a sample a hair above the threshold: the swing's midpoint passes a live
// plate 0.3 mm beyond the tool's threshold, and the tool goes on into it. The bisection meets
// the plate first in intervals ending at the midpoint, which resolve there (within threshold +
// resolution); the pair's warning must still report a sample inside the threshold, where it
// reported the midpoint (a dual Kinova Gen3 plan: "0.0612 m (threshold 0.0610 m)" for a
// contact 5 mm deep).
TEST(MonitorSwept, ContactJustPastANearMissSampleIsReportedInside) {
  const auto wc = test::LoadBundledWorkcell();
  const Eigen::VectorXd mid = test::ArmReachDown(*wc, "left", 0.7, 0.55, 0.9);
  const int j1 = JointIndex(*wc, "left_joint1");
  Monitor monitor(wc, Unlimited());
  const Box plate_O{Eigen::Isometry3d::Identity(), {0.15, 0.001, 0.15}};
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() = Eigen::Vector3d(2.5, 2.5, 0.5);
  std::string error;
  ASSERT_TRUE(monitor.AddObject("plate", {plate_O}, X_WO, 0.0, false, &error)) << error;
  PrimitiveId plate = 0;
  while (plate < monitor.primitive_count() && monitor.primitive(plate).owner != "plate") ++plate;
  ASSERT_LT(plate, monitor.primitive_count());
  // The plate across the tool's way, 0.3 mm beyond the tool's threshold at the midpoint.
  const PlateInTheWay in_the_way = PlaceInTheWay(*wc, mid, j1, plate_O, 0.0003);
  ASSERT_NEAR(in_the_way.achieved_m, 0.0003, 1e-9);
  X_WO = in_the_way.X_WO;
  ASSERT_TRUE(monitor.MoveObject("plate", X_WO, &error)) << error;
  Eigen::VectorXd q0 = mid, q1 = mid;
  q0[j1] -= 0.4;
  q1[j1] += 0.4;
  ASSERT_TRUE(monitor.Check(q0).warnings.empty());
  ASSERT_TRUE(monitor.Check(q1).warnings.empty());
  const CycleReport report = RunStep(&monitor, q0, q1);
  EXPECT_TRUE(report.stop);
  int plate_warnings = 0;
  for (const Warning& w : report.warnings) {
    if (w.b != plate) continue;
    ++plate_warnings;
    EXPECT_TRUE(w.between_samples);
    EXPECT_LT(w.distance_m, w.threshold_m)
        << monitor.primitive(w.a).name << " at " << w.step_fraction << " of the step";
    EXPECT_GT(w.step_fraction, 0.5) << monitor.primitive(w.a).name;
  }
  EXPECT_GT(plate_warnings, 0);
}

// Fast input near a threshold: the tool 0.3 mm beyond its threshold from a live plate at one end
// of a 1 ms step (left_joint1 by 1 mrad, a motion bound of about 1 mm), moving away from it, then
// towards it. The bound alone does not certify such a step (its ends' mean less half the bound
// is below the threshold), and it was not bisected (its motion is within twice the resolution):
// it warned 'not certified clear' at the near end, fraction 0 or 1 (three new users' 1 kHz
// bags). Bisected a few levels more, it is certified; the plate 0.3 mm inside the threshold
// still warns, at that sample.
TEST(MonitorSwept, FastStepsNearTheThresholdAreCertifiedClear) {
  const auto wc = test::LoadBundledWorkcell();
  const Eigen::VectorXd mid = test::ArmReachDown(*wc, "left", 0.7, 0.55, 0.9);
  const int j1 = JointIndex(*wc, "left_joint1");
  const MonitorOptions options = Unlimited();
  const Box plate_O{Eigen::Isometry3d::Identity(), {0.15, 0.001, 0.15}};
  Eigen::VectorXd away = mid;
  away[j1] -= 0.001;
  for (const double gap_at_mid_m : {0.0003, -0.0003}) {
    const PlateInTheWay in_the_way = PlaceInTheWay(*wc, mid, j1, plate_O, gap_at_mid_m);
    ASSERT_NEAR(in_the_way.achieved_m, gap_at_mid_m, 1e-9);
    const Eigen::Isometry3d& X_WO = in_the_way.X_WO;
    for (const bool is_moving_away : {true, false}) {
      const std::string context = std::string(is_moving_away ? "away from" : "towards") +
                                  " the plate, " + std::to_string(gap_at_mid_m) + " m at mid";
      Monitor monitor(wc, options);
      std::string error;
      ASSERT_TRUE(monitor.AddObject("plate", {plate_O}, X_WO, 0.0, false, &error)) << error;
      const Eigen::VectorXd& q0 = is_moving_away ? mid : away;
      const Eigen::VectorXd& q1 = is_moving_away ? away : mid;
      const CycleReport report = RunStep(&monitor, q0, q1);
      ASSERT_LE(report.step_motion_m, 2.0 * options.swept_resolution_m) << context;
      ASSERT_GT(report.step_motion_m, 0.5 * options.swept_resolution_m) << context;
      int plate_warnings = 0;
      for (const Warning& w : report.warnings) {
        if (monitor.primitive(w.b).owner != "plate") continue;
        ++plate_warnings;
        EXPECT_LT(w.distance_m, w.threshold_m) << context << ": " << monitor.primitive(w.a).name
                                               << " at " << w.step_fraction << " of the step";
      }
      // Inside: the step's start warns at q0 (between samples) or its end at q1 (at q).
      EXPECT_EQ(plate_warnings > 0, gap_at_mid_m < 0.0) << context;
    }
  }
}

// The left arm, stretched out, swings its base joint through the right arm (straight up) in
// one step; the ends are found by scanning for clear poses either side of the contact.
TEST(MonitorSwept, ArmsCrossInOneStep) {
  // The bundled scene, and the same with 336 small cubes low between the pedestals, under the
  // arms and inside the hull of the leavers' grown boxes: with those near, the leavers' pairs are
  // found by CollectSweptPairs' scan (kSweptScanMinTests). The left-right pairs are pairs of two
  // leavers (slack 0, the right arm turning slightly too).
  const std::string cubes = CubeGrid({8, 14, 3}, {-0.5, -1.7, 0.55}, {0.13, 0.2, 0.05});
  for (const auto& wc : {test::LoadBundledWorkcell(), LoadSceneWith("cubes_above", cubes)}) {
    const int j1 = JointIndex(*wc, "left_joint1");
    const Eigen::VectorXd base = MakeQ(*wc, {{"left_joint2", 1.3}});
    MonitorOptions options = Unlimited();
    options.index_slack_m = 0.0;
    Monitor monitor(wc, options);
    // Scan the base joint for the left-right contact and clear poses either side of it.
    double contact = std::nan(""), before = std::nan(""), after = std::nan("");
    for (double t = -2.9; t <= 2.9; t += 0.01) {
      Eigen::VectorXd q = base;
      q[j1] = t;
      const CycleReport r = monitor.Check(q);
      const bool arms_near =
          std::any_of(r.warnings.begin(), r.warnings.end(), [&](const Warning& w) {
            return wc->primitives[w.a].owner.rfind("left", 0) == 0 &&
                   wc->primitives[w.b].owner.rfind("right", 0) == 0;
          });
      if (arms_near && std::isnan(contact)) contact = t;
      if (r.warnings.empty() && std::isnan(contact)) before = t;
      if (r.warnings.empty() && !std::isnan(contact) && std::isnan(after)) after = t;
    }
    ASSERT_FALSE(std::isnan(contact) || std::isnan(before) || std::isnan(after));
    Eigen::VectorXd q0 = base, q1 = base;
    q0[j1] = before;
    q1[j1] = after;
    q1[JointIndex(*wc, "right_joint1")] += 0.01;
    const CycleReport report = RunStep(&monitor, q0, q1);
    EXPECT_TRUE(report.stop);
    bool arm_arm = false;
    for (const Warning& w : report.warnings) {
      arm_arm = arm_arm || (w.between_samples && wc->primitives[w.a].owner.rfind("left", 0) == 0 &&
                            wc->primitives[w.b].owner.rfind("right", 0) == 0);
    }
    const std::string context = std::to_string(wc->primitives.size()) + " primitives";
    EXPECT_TRUE(arm_arm) << context << ", step " << before << " -> " << after << " rad";
    StepTally tally;
    CheckStep(*wc, options, q0, q1, report, "arms cross, " + context, &tally);
    EXPECT_GT(tally.dense_contacts, 0) << context;
  }
}

// A wrist flip, dominated by rotation: joint 6 swings the gripper through a 3 mm rod laid along
// the joint's axis across the gripper's path at mid-swing.
TEST(MonitorSwept, WristFlipPastThinRod) {
  const auto bundled = test::LoadBundledWorkcell();
  const KinematicModel& model = bundled->kinematics;
  const int j6 = JointIndex(*bundled, "left_joint6");
  const int link7 = model.FindLink("left_link7");
  ASSERT_GE(link7, 0);
  std::vector<Eigen::Isometry3d> X(model.link_count());
  Eigen::VectorXd q = MakeQ(*bundled, {});
  model.ComputeLinkPoses(q, &X);
  const Eigen::Vector3d p_tip0 = X[link7] * Eigen::Vector3d(0, 0, 0.15);
  const Eigen::Vector3d p_wrist = X[link7].translation();
  q[j6] = 0.01;
  model.ComputeLinkPoses(q, &X);
  const Eigen::Vector3d p_tip1 = X[link7] * Eigen::Vector3d(0, 0, 0.15);
  const Eigen::Vector3d axis = (p_tip1 - p_tip0).cross(p_tip0 - p_wrist).normalized();
  const Eigen::Matrix3d R =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix();
  // URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll).
  const double pitch = std::asin(-R(2, 0));
  const double roll = std::atan2(R(2, 1), R(2, 2));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  std::ostringstream rod;
  rod << "- {name: rod, type: capsule, radius_m: 0.0015, length_m: 0.12, pose: {xyz_m: ["
      << p_tip0.x() << ", " << p_tip0.y() << ", " << p_tip0.z() << "], rpy: [" << roll << ", "
      << pitch << ", " << yaw << "]}}";
  const auto wc = LoadSceneWith("rod", rod.str());
  Eigen::VectorXd q0 = MakeQ(*wc, {}), q1 = q0;
  q0[j6] = -1.6;
  q1[j6] = 1.6;
  const MonitorOptions options = Unlimited();
  Monitor monitor(wc, options);
  ASSERT_TRUE(monitor.Check(q0).warnings.empty());
  ASSERT_TRUE(monitor.Check(q1).warnings.empty());
  const CycleReport report = RunStep(&monitor, q0, q1);
  EXPECT_TRUE(report.stop);
  EXPECT_TRUE(HasBetweenSamples(*wc, report, "left_link7", "rod"));
  StepTally tally;
  CheckStep(*wc, options, q0, q1, report, "wrist flip", &tally);
  EXPECT_GT(tally.dense_contacts, 0);
}

void PrintTally(const char* what, const StepTally& t) {
  std::printf("%s: %d steps, %d dense contacts (pairs), %d missed, %d between-samples warnings, "
              "%d false (%.2f %% of steps), swept path needed in %d steps\n",
              what, t.steps, t.dense_contacts, t.missed, t.between, t.false_warnings,
              t.steps > 0 ? 100.0 * t.false_warnings / t.steps : 0.0, t.swept_cycles);
}

// Random fast trajectories (peak joint speeds at the velocity limits) sampled at 5 and 10 Hz,
// each step against the dense sampler: 0 missed.
TEST(MonitorSwept, RandomFastTrajectoriesMissNothing) {
  const auto wc = test::LoadBundledWorkcell();
  const test::JointLimits limits = test::LimitsOf(*wc);
  std::mt19937_64 rng(test::PrintSeed(1414));
  for (const BroadPhaseMethod method : {BroadPhaseMethod::kOctree, BroadPhaseMethod::kNaive}) {
    for (const double period_s : {0.2, 0.1}) {
      StepTally tally;
      for (int trajectory = 0; trajectory < 6; ++trajectory) {
        const test::SmoothTrajectory path(limits, 1.0, &rng);
        MonitorOptions options = test::OptionsFor(method);
        options.max_step_m = Unlimited().max_step_m;
        Monitor monitor(wc, options);
        Eigen::VectorXd q_prev, q;
        path.At(0.0, &q_prev);
        monitor.Update(q_prev);
        for (int k = 1; k <= 40; ++k) {
          path.At(k * period_s, &q);
          const CycleReport& report = monitor.Update(q);
          CheckStep(*wc, options, q_prev, q, report,
                    BroadPhaseMethodName(method) + " trajectory " + std::to_string(trajectory) +
                        " step " + std::to_string(k),
                    &tally);
          std::string error;
          ASSERT_TRUE(monitor.Validate(&error)) << error;
          q_prev = q;
        }
      }
      const std::string what = BroadPhaseMethodName(method) + " at " +
                               std::to_string(static_cast<int>(1.0 / period_s)) + " Hz";
      PrintTally(what.c_str(), tally);
      EXPECT_EQ(tally.missed, 0);
      EXPECT_GT(tally.dense_contacts, 0) << "the trajectories must pass near things";
    }
  }
}

// As above with the arms in turns, as from one joint-state topic per arm: each step moves one
// arm along its path while the other holds. The kinematics then recomputes only the moved
// arm's links, and the swept check's start poses (the kinematics before) mix the two.
TEST(MonitorSwept, ArmsMovingInTurnsMissNothing) {
  const auto wc = test::LoadBundledWorkcell();
  const test::JointLimits limits = test::LimitsOf(*wc);
  std::mt19937_64 rng(test::PrintSeed(1616));
  for (const double period_s : {0.2, 0.1}) {
    StepTally tally;
    for (int trajectory = 0; trajectory < 6; ++trajectory) {
      const test::SmoothTrajectory path(limits, 1.0, &rng);
      MonitorOptions options = Unlimited();
      Monitor monitor(wc, options);
      Eigen::VectorXd q_prev, q, q_path;
      path.At(0.0, &q_prev);
      monitor.Update(q_prev);
      for (int k = 1; k <= 40; ++k) {
        path.At(k * period_s, &q_path);
        q = q_prev;
        test::TakeArmsTurn(*wc, k, q_path, &q);
        const CycleReport& report = monitor.Update(q);
        CheckStep(*wc, options, q_prev, q, report,
                  "trajectory " + std::to_string(trajectory) + " step " + std::to_string(k),
                  &tally);
        q_prev = q;
      }
    }
    const std::string what =
        "arms in turns at " + std::to_string(static_cast<int>(1.0 / period_s)) + " Hz";
    PrintTally(what.c_str(), tally);
    EXPECT_EQ(tally.missed, 0);
    EXPECT_GT(tally.between, 0) << "the trajectories must pass near things between samples";
  }
}

// Many small boxes around the arms, index slack 0 (every moving primitive may leave its slack in
// every step) and fast steps: some 20 leavers by a few hundred near boxes, so CollectSweptPairs
// scans the boxes as arrays (kSweptScanMinTests) rather than one by one. Each step against the
// dense sampler: 0 missed.
void RunCrowdedSteps(const std::shared_ptr<const Workcell>& wc) {
  std::size_t moving = 0;
  for (const PrimitiveSpec& p : wc->primitives) moving += p.link_index >= 0 && !p.is_static;
  ASSERT_GE(moving * wc->primitives.size(), 2 * kSweptScanMinTests) << "too few to scan";
  const test::JointLimits limits = test::LimitsOf(*wc);
  std::mt19937_64 rng(test::PrintSeed(2718));
  // Slack 0, where the nearby pairs are kept pairs too, and the default slack, which steps of
  // 0.2 s at full speed leave.
  for (const double slack_m : {0.0, MonitorOptions().index_slack_m}) {
    StepTally tally;
    for (int trajectory = 0; trajectory < 2; ++trajectory) {
      const test::SmoothTrajectory path(limits, 1.0, &rng);
      MonitorOptions options = Unlimited();
      options.index_slack_m = slack_m;
      Monitor monitor(wc, options);
      Eigen::VectorXd q_prev, q;
      path.At(0.0, &q_prev);
      monitor.Update(q_prev);
      for (int k = 1; k <= 12; ++k) {
        path.At(k * 0.2, &q);
        const CycleReport& report = monitor.Update(q);
        CheckStep(*wc, options, q_prev, q, report,
                  "slack " + std::to_string(slack_m) + " trajectory " +
                      std::to_string(trajectory) + " step " + std::to_string(k),
                  &tally);
        q_prev = q;
      }
    }
    PrintTally(("crowded, slack " + std::to_string(slack_m) + " m").c_str(), tally);
    EXPECT_EQ(tally.missed, 0);
    EXPECT_GT(tally.dense_contacts, 0) << "the trajectories must pass near things";
    EXPECT_GT(tally.swept_cycles, 0);
  }
}

/// CrowdedStepsScannedAsArraysMissNothing's boxes around the arms, in the bundled scene.
std::string CrowdedCubes() { return CubeGrid({8, 8, 6}, {-0.8, -1.4, 0.7}, {0.3, 0.4, 0.3}); }

TEST(MonitorSwept, CrowdedStepsScannedAsArraysMissNothing) {
  RunCrowdedSteps(LoadSceneWith("cubes", CrowdedCubes()));
}

// The same with every <collision> of the bundled URDF given twice, the copy 8 cm further along
// its link's z: each link's primitives leave their slack together, and CollectSweptPairs' scan
// takes them as one (one scan for the hull of their boxes); a pair missed there, or a hull short
// of a box, leaves a contact unwarned.
TEST(MonitorSwept, CrowdedStepsOfLinksWithSeveralPrimitivesMissNothing) {
  std::ifstream in(ACM_SOURCE_DIR "/urdf/workcell.urdf");
  std::stringstream text;
  text << in.rdbuf();
  std::string urdf = text.str();
  std::string doubled;
  std::size_t copied = 0, twice = 0;
  for (std::size_t at = urdf.find("<collision>"); at != std::string::npos;
       at = urdf.find("<collision>", copied)) {
    const std::size_t end = urdf.find("</collision>", at) + std::string("</collision>").size();
    const std::string block = urdf.substr(at, end - at);
    std::smatch xyz;
    const std::regex origin("xyz=\"(\\S+) (\\S+) ([^\"]+)\"");
    ASSERT_TRUE(std::regex_search(block, xyz, origin)) << block;
    const std::string moved = "xyz=\"" + xyz[1].str() + " " + xyz[2].str() + " " +
                              std::to_string(std::stod(xyz[3].str()) + 0.08) + "\"";
    doubled += urdf.substr(copied, end - copied) + xyz.prefix().str() + moved + xyz.suffix().str();
    copied = end;
    ++twice;
  }
  doubled += urdf.substr(copied);
  const std::string urdf_path = ::testing::TempDir() + "/swept_doubled.urdf";
  std::ofstream(urdf_path) << doubled;
  LoadSceneWith("doubled_cubes", CrowdedCubes());  // writes the scene file
  const auto wc = std::make_shared<const Workcell>(
      LoadWorkcell(urdf_path, ::testing::TempDir() + "/swept_doubled_cubes.yaml"));
  ASSERT_GT(twice, 0u);
  std::map<int, int> per_link;
  for (const PrimitiveSpec& p : wc->primitives) per_link[p.link_index] += !p.is_static;
  for (const auto& [link, count] : per_link) {
    if (link >= 0 && count > 0) {
      EXPECT_GE(count, 2) << "link " << link;
    }
  }
  RunCrowdedSteps(wc);
}

// Differential against the dense sampler on random steps from random configurations, up to
// max_step_m: large steps take the swept check's all-pairs path (beyond the index slack).
TEST(MonitorSwept, RandomStepsMatchDenseSampler) {
  const auto wc = test::LoadBundledWorkcell();
  const test::JointLimits limits = test::LimitsOf(*wc);
  std::mt19937_64 rng(test::PrintSeed(1515));
  const MonitorOptions options = Unlimited();
  Monitor monitor(wc, options);
  StepTally tally;
  for (int k = 0; k < 150; ++k) {
    const Eigen::VectorXd q0 = test::RandomQ(limits, &rng);
    Eigen::VectorXd q1 = q0;
    const double size_rad = std::uniform_real_distribution<double>(0.02, 0.6)(rng);
    for (int i = 0; i < q1.size(); ++i) {
      q1[i] = std::clamp(q0[i] + std::uniform_real_distribution<double>(-size_rad, size_rad)(rng),
                         limits.lower[i], limits.upper[i]);
    }
    const CycleReport report = RunStep(&monitor, q0, q1);
    CheckStep(*wc, options, q0, q1, report, "random step " + std::to_string(k), &tally);
    if (::testing::Test::HasFailure()) break;
  }
  PrintTally("random steps", tally);
  EXPECT_EQ(tally.missed, 0);
  EXPECT_GT(tally.between, 0);
}

// A metre-long step (the 1 m jump between two messages): swept (the path, through the other
// arm, warns between samples), and beyond max_step_m a stop "input jumped" that a normal step
// clears.
TEST(MonitorSwept, MetreJumpIsSweptOrStopped) {
  const auto wc = test::LoadBundledWorkcell();
  const Eigen::VectorXd home = MakeQ(*wc, {});
  // Left arm swung from pointing away to pointing at the right arm and past it.
  const Eigen::VectorXd q0 = MakeQ(*wc, {{"left_joint1", -2.4}, {"left_joint2", 1.3}});
  const Eigen::VectorXd q1 = MakeQ(*wc, {{"left_joint1", -0.8}, {"left_joint2", 1.3}});
  const MonitorOptions options = Unlimited();
  Monitor swept(wc, options);
  const CycleReport report = RunStep(&swept, q0, q1);
  EXPECT_GT(report.step_motion_m, 1.0);
  EXPECT_FALSE(report.input_jumped);
  EXPECT_TRUE(report.stop);
  StepTally tally;
  CheckStep(*wc, options, q0, q1, report, "1 m step", &tally);
  EXPECT_GT(tally.dense_contacts, 0);
  EXPECT_GT(tally.between, 0);
  // A check of the reading just taken repeats the report but for the step's between-samples
  // warnings: the pairs Update gives at q1 again (a step of zero).
  const std::vector<Warning> at_sample = test::AtSampleWarnings(report.warnings);
  EXPECT_LT(at_sample.size(), report.warnings.size());
  const CycleReport checked = swept.Check(q1);
  const CycleReport again = swept.Update(q1);
  const auto pairs = [](const std::vector<Warning>& warnings) {
    std::vector<std::pair<PrimitiveId, PrimitiveId>> ab;
    for (const Warning& w : warnings) ab.emplace_back(w.a, w.b);
    return ab;
  };
  EXPECT_EQ(pairs(checked.warnings), pairs(at_sample));
  EXPECT_EQ(pairs(again.warnings), pairs(at_sample));
  EXPECT_EQ(checked.stop, !at_sample.empty());
  EXPECT_EQ(again.stop, checked.stop);

  Monitor jumped(wc, MonitorOptions{});
  ASSERT_FALSE(jumped.Update(home).stop);
  const CycleReport& jump = jumped.Update(q0);
  EXPECT_TRUE(jump.input_jumped);
  EXPECT_TRUE(jump.stop);
  EXPECT_GT(jump.step_motion_m, jumped.options().max_step_m);
  CheckStep(*wc, jumped.options(), home, q0, jump, "jump", &tally);  // swept all the same
  // Idle (a step of zero) and normal steps: no longer jumped.
  const CycleReport& idle = jumped.Update(q0);
  EXPECT_FALSE(idle.input_jumped);
  EXPECT_EQ(idle.stop, !idle.warnings.empty());
  for (const Warning& w : idle.warnings) EXPECT_FALSE(w.between_samples);
  Eigen::VectorXd q_next = q0;
  q_next[JointIndex(*wc, "left_joint3")] += 0.01;
  const CycleReport& normal = jumped.Update(q_next);
  EXPECT_FALSE(normal.input_jumped);
  EXPECT_EQ(normal.stop, !normal.warnings.empty());
}

// With sample times, the same step beyond max_step_m is a sparse path's step when every joint
// stays within kJumpVelocityFactor times its URDF velocity limit over the time between the
// samples (left_joint1 moves 2.4 rad, left_joint2 1.3 rad, both limited to 1 rad/s), and a jump
// when it does not; an idle cycle re-dates the last accepted sample.
TEST(MonitorSwept, TimedStepsBeyondMaxStepAreJumpsOnlyAboveTheVelocityLimits) {
  const auto wc = test::LoadBundledWorkcell();
  const Eigen::VectorXd home = MakeQ(*wc, {});
  const Eigen::VectorXd q0 = MakeQ(*wc, {{"left_joint1", -2.4}, {"left_joint2", 1.3}});
  for (const std::string joint : {"left_joint1", "left_joint2"}) {
    ASSERT_EQ(wc->kinematics.joint(wc->kinematics.FindJointChildLink(joint)).max_velocity, 1.0);
  }
  const double at_limit_s = 2.4 / (kJumpVelocityFactor * 1.0);
  for (const auto& [idle_until_s, step_s, is_jump] :
       {std::tuple{0.0, 1.01 * at_limit_s, false}, std::tuple{0.0, 0.99 * at_limit_s, true},
        std::tuple{5.0, 5.0 + 1.01 * at_limit_s, false},
        std::tuple{5.0, 5.0 + 0.99 * at_limit_s, true}}) {
    Monitor monitor(wc, MonitorOptions{});
    ASSERT_FALSE(monitor.Update(home, 0.0).stop);
    if (idle_until_s > 0.0) {
      ASSERT_FALSE(monitor.Update(home, idle_until_s).stop);
    }
    const CycleReport& report = monitor.Update(q0, step_s);
    const std::string context = "home at 0 s and " + std::to_string(idle_until_s) +
                                " s, then q0 at " + std::to_string(step_s) + " s";
    EXPECT_GT(report.step_motion_m, monitor.options().max_step_m) << context;
    EXPECT_EQ(report.input_jumped, is_jump) << context;
    EXPECT_EQ(report.stop, is_jump || !report.warnings.empty()) << context;
  }
}

// One topic per arm (a driver each), both silent for 6 s and then back with the arms far from
// where they were, the left arm's message first: with each joint dated by its own sample the
// right arm's move, 1 ms after the left one's, is timed from its own last sample, 6 s before,
// and neither is a jump; dated by the newest message alone it would be (a 1 ms step).
TEST(MonitorSwept, JointsDatedApartAreTimedFromTheirOwnSamples) {
  const auto wc = test::LoadBundledWorkcell();
  const Eigen::VectorXd home = MakeQ(*wc, {});
  const Eigen::VectorXd left_moved = MakeQ(*wc, {{"left_joint1", -2.4}, {"left_joint2", 1.3}});
  const Eigen::VectorXd both_moved = MakeQ(
      *wc, {{"left_joint1", -2.4}, {"left_joint2", 1.3}, {"right_joint1", 2.4},
            {"right_joint2", 1.3}});
  Eigen::VectorXd joint_time_s = Eigen::VectorXd::Zero(home.size());
  Monitor monitor(wc, MonitorOptions{});
  ASSERT_FALSE(monitor.Update(home, joint_time_s).stop);
  for (const std::string& joint : wc->joint_names) {
    if (joint.rfind("left_", 0) == 0) joint_time_s[JointIndex(*wc, joint)] = 6.0;
  }
  const CycleReport& left = monitor.Update(left_moved, joint_time_s);
  EXPECT_GT(left.step_motion_m, monitor.options().max_step_m);
  EXPECT_FALSE(left.input_jumped);
  for (const std::string& joint : wc->joint_names) {
    if (joint.rfind("right_", 0) == 0) joint_time_s[JointIndex(*wc, joint)] = 6.001;
  }
  const CycleReport& right = monitor.Update(both_moved, joint_time_s);
  EXPECT_GT(right.step_motion_m, monitor.options().max_step_m);
  EXPECT_FALSE(right.input_jumped);
  // The same messages dated by the newest alone.
  Monitor newest(wc, MonitorOptions{});
  ASSERT_FALSE(newest.Update(home, 0.0).stop);
  EXPECT_FALSE(newest.Update(left_moved, 6.0).input_jumped);
  EXPECT_TRUE(newest.Update(both_moved, 6.001).input_jumped);
  // Times of another size than q count as unknown: a jump.
  Monitor unsized(wc, MonitorOptions{});
  ASSERT_FALSE(unsized.Update(home, Eigen::VectorXd::Zero(3)).stop);
  EXPECT_TRUE(unsized.Update(left_moved, Eigen::VectorXd::Constant(3, 6.0)).input_jumped);
}

/// The bundled workcell with left_joint1 continuous (no position limits, `velocity` rad/s),
/// `more_urdf` before the URDF's end and `object_line` among the scene's objects.
std::shared_ptr<const Workcell> LoadWithContinuousJoint1(const std::string& name,
                                                         const std::string& velocity,
                                                         const std::string& more_urdf,
                                                         const std::string& object_line) {
  const std::string urdf_path = WriteEditedFile(
      ACM_SOURCE_DIR "/urdf/workcell.urdf", name + ".urdf",
      {{"<joint name=\"left_joint1\" type=\"revolute\">",
        "<joint name=\"left_joint1\" type=\"continuous\">"},
       {"<limit lower=\"-2.967060\" upper=\"2.967060\" velocity=\"1.0\"",
        "<limit velocity=\"" + velocity + "\""},
       {"</robot>", more_urdf + "</robot>"}});
  return test::LoadSceneEdited(urdf_path, name, [&](std::string* scene) {
    AddObjectLine(object_line, scene);
  });
}

/// Whether `warnings` hold a pair of `object`'s.
bool WarnsWith(const Workcell& wc, const std::vector<Warning>& warnings,
               const std::string& object) {
  for (const Warning& w : warnings) {
    if (wc.primitives[w.a].name == object || wc.primitives[w.b].name == object) return true;
  }
  return false;
}

/// The wrapped-reading cases: left_joint1 continuous, the left arm leaning out (joint 2 at 1
/// rad), and a block where its wrist is with joint 1 at 0, which it meets only on the long way
/// round from near pi.
class WrappedReadings : public ::testing::Test {
 protected:
  /// The workcell of `velocity` and `more_urdf` (LoadWithContinuousJoint1) with the block.
  static std::shared_ptr<const Workcell> Load(const std::string& name,
                                              const std::string& velocity = "1.0",
                                              const std::string& more_urdf = "") {
    const auto plain = LoadWithContinuousJoint1(
        name + "_plain", velocity, more_urdf,
        "- {name: spare, size_m: [0.1, 0.1, 0.1], pose: {xyz_m: [0.0, 0.0, 5.5]}}");
    std::vector<Eigen::Isometry3d> X_WL(plain->kinematics.link_count());
    plain->kinematics.ComputeLinkPoses(Pose(*plain, 0.0), &X_WL);
    const Eigen::Vector3d p_W = X_WL[plain->kinematics.FindLink("left_link6")].translation();
    std::ostringstream block;
    block << "- {name: block, size_m: [0.1, 0.1, 0.1], pose: {xyz_m: [" << p_W.x() << ", "
          << p_W.y() << ", " << p_W.z() << "]}}";
    const auto wc = LoadWithContinuousJoint1(name, velocity, more_urdf, block.str());
    EXPECT_TRUE(WarnsWith(*wc, Monitor(wc, Unlimited()).Update(Pose(*wc, 0.0), 0.0).warnings,
                          "block"));
    return wc;
  }
  static Eigen::VectorXd Pose(const Workcell& wc, double q1) {
    return MakeQ(wc, {{"left_joint1", q1}, {"left_joint2", 1.0}});
  }
  /// q1 as a driver that wraps into [-pi, pi] reports it.
  static double Wrapped(double q1) { return std::atan2(std::sin(q1), std::cos(q1)); }
  /// Joint 1 turning at 1 rad/s from 3.131 to 3.151 rad across pi, reported wrapped at 1 kHz
  /// from `t0_s` (without times when `is_timed` is false): the largest step motion, and
  /// whether any cycle jumped or warned against the block.
  struct Crossing {
    double largest_step_m = 0.0;
    bool is_jumped = false;
    bool warns = false;
  };
  static Crossing CrossPi(const Workcell& wc, Monitor* monitor, bool is_timed = true,
                          double t0_s = 0.0) {
    Crossing crossing;
    for (int k = 0; k <= 20; ++k) {
      const Eigen::VectorXd q = Pose(wc, Wrapped(3.131 + 0.001 * k));
      const CycleReport& report =
          is_timed ? monitor->Update(q, t0_s + 0.001 * k) : monitor->Update(q);
      crossing.largest_step_m = std::max(crossing.largest_step_m, report.step_motion_m);
      crossing.is_jumped |= report.input_jumped;
      crossing.warns |= WarnsWith(wc, report.warnings, "block");
    }
    return crossing;
  }
  static void ExpectValid(const Monitor& monitor) {
    std::string why;
    EXPECT_TRUE(monitor.Validate(&why)) << why;
  }
};

// A continuous joint without limits that a driver reports wrapped into [-pi, pi] (Kinova's
// kortex driver): at 1 kHz, turning at 1 rad/s across pi, its reading goes from 3.141 to
// -3.141. That step is the short one: no jump (the long way round was a 2 pi turn in 1 ms, far
// beyond the velocity limit) and no warning against the block that only the long way meets.
// The same reading after a pause of 10 s is no move at all (an idle cycle), and the turn back
// across pi the short way again. Where the velocity limit allows either way -- 0.3 rad from 3.0
// across pi after 10 s, as after a pause, the same after 3.2 s of refused cycles, or jitter
// back across pi after a pause at rest -- the step takes the short way too (the long way meets
// the block: a reviewer's full turn swept after a pause) and is an 'input jumped' stop, as
// nothing tells which way the joint turned; 0.2 s after, it is a plain step.
TEST_F(WrappedReadings, TakeTheShortWay) {
  const auto wc = Load("continuous_joint1");
  {
    Monitor monitor(wc, MonitorOptions{});
    const Crossing crossing = CrossPi(*wc, &monitor);
    EXPECT_FALSE(crossing.is_jumped);
    EXPECT_LT(crossing.largest_step_m, 0.01);
    EXPECT_FALSE(crossing.warns);
    ASSERT_LT(Wrapped(3.151), 0.0);
    const CycleReport& later = monitor.Update(Pose(*wc, Wrapped(3.151)), 10.0);
    EXPECT_EQ(later.step_motion_m, 0.0);
    EXPECT_FALSE(WarnsWith(*wc, later.warnings, "block"));
    const CycleReport& back = monitor.Update(Pose(*wc, 3.141), 10.01);
    EXPECT_FALSE(back.input_jumped);
    EXPECT_LT(back.step_motion_m, 0.02);
    EXPECT_FALSE(WarnsWith(*wc, back.warnings, "block"));
    // Parked just past pi, then after a pause a reading a hair back across it.
    ASSERT_FALSE(monitor.Update(Pose(*wc, -kPi + 1e-4), 10.02).input_jumped);
    const CycleReport& jitter = monitor.Update(Pose(*wc, kPi - 1e-4), 20.0);
    EXPECT_TRUE(jitter.input_jumped);
    EXPECT_LT(jitter.step_motion_m, 0.01);
    EXPECT_FALSE(WarnsWith(*wc, jitter.warnings, "block"));
    ExpectValid(monitor);
  }
  const double end = Wrapped(3.3);  // -2.98: 5.98 rad the long way from 3.0
  for (const auto& [elapsed_s, is_ambiguous] : {std::pair{10.0, true}, std::pair{0.2, false}}) {
    Monitor monitor(wc, MonitorOptions{});
    ASSERT_FALSE(WarnsWith(*wc, monitor.Update(Pose(*wc, 3.0), 0.0).warnings, "block"));
    const CycleReport& report = monitor.Update(Pose(*wc, end), elapsed_s);
    const std::string context = "3.0 to " + std::to_string(end) + " rad in " +
                                std::to_string(elapsed_s) + " s";
    EXPECT_EQ(report.input_jumped, is_ambiguous) << context;
    EXPECT_LT(report.step_motion_m, 1.0) << context;
    EXPECT_FALSE(WarnsWith(*wc, report.warnings, "block")) << context;
    EXPECT_EQ(report.stop, is_ambiguous || !report.warnings.empty()) << context;
    ExpectValid(monitor);
  }
  {
    // Refused cycles (a NaN of another joint) for 3.2 s while joint 1 turns 0.1 rad across pi.
    Monitor monitor(wc, MonitorOptions{});
    ASSERT_FALSE(monitor.Update(Pose(*wc, 3.1), 0.0).stop);
    Eigen::VectorXd bad = Pose(*wc, 3.15);
    bad[JointIndex(*wc, "right_joint2")] = std::numeric_limits<double>::quiet_NaN();
    for (int k = 1; k < 32; ++k) ASSERT_TRUE(monitor.Update(bad, 0.1 * k).stop);
    const CycleReport& resumed = monitor.Update(Pose(*wc, Wrapped(3.2)), 3.2);
    EXPECT_TRUE(resumed.input_jumped);
    EXPECT_LT(resumed.step_motion_m, 1.0);
    EXPECT_FALSE(WarnsWith(*wc, resumed.warnings, "block"));
    ExpectValid(monitor);
  }
}

// Without a velocity limit (0 in the URDF) or without sample times nothing tells a wrapped
// reading from a turn the long way: the reading is taken as given (its 2 pi step meets the
// block, and stops), as before the unwinding.
TEST_F(WrappedReadings, WithoutAVelocityLimitOrTimesAreTakenAsGiven) {
  const auto unlimited = Load("continuous_joint1_no_velocity", "0");
  const auto limited = Load("continuous_joint1_untimed");
  for (const auto& [wc, is_timed] : {std::pair{unlimited, true}, std::pair{limited, false}}) {
    Monitor monitor(wc, Unlimited());
    const Crossing crossing = CrossPi(*wc, &monitor, is_timed);
    const std::string context = is_timed ? "velocity 0" : "no times";
    EXPECT_GT(crossing.largest_step_m, 1.0) << context;
    EXPECT_TRUE(crossing.warns) << context;
    ExpectValid(monitor);
  }
}

/// URDF text of a link on left_link1 whose joint mimics left_joint1 by `multiplier`.
std::string SpinnerMimic(const std::string& multiplier) {
  return "  <link name=\"left_spinner\"/>\n"
         "  <joint name=\"left_spinner_joint\" type=\"revolute\">\n"
         "    <parent link=\"left_link1\"/><child link=\"left_spinner\"/>\n"
         "    <axis xyz=\"0 0 1\"/>\n"
         "    <limit lower=\"-100\" upper=\"100\" velocity=\"1.0\" effort=\"1\"/>\n"
         "    <mimic joint=\"left_joint1\" multiplier=\"" +
         multiplier + "\"/>\n  </joint>\n";
}

// A mimic joint that follows the continuous joint by half its angle would not come back to its
// pose after a whole turn of its leader: the leader's readings are then never unwound (the
// 2 pi step across the wrap is swept as given); by twice the angle it would, and they are.
TEST_F(WrappedReadings, NotUnwoundWhereAMimicJointFollowsByOtherThanWholeTurns) {
  for (const auto& [multiplier, is_unwound] : {std::pair{"0.5", false}, std::pair{"2", true}}) {
    const auto wc = Load(std::string("continuous_joint1_mimic_") + (is_unwound ? "2" : "half"),
                         "1.0", SpinnerMimic(multiplier));
    Monitor monitor(wc, Unlimited());
    const Crossing crossing = CrossPi(*wc, &monitor);
    EXPECT_EQ(crossing.largest_step_m < 0.01, is_unwound) << "multiplier " << multiplier;
    EXPECT_EQ(crossing.warns, !is_unwound) << "multiplier " << multiplier;
    ExpectValid(monitor);
  }
}

// A reading beyond kMaxUnlimitedPosition_rad (a corrupt message: 1e308 is finite) is refused,
// named, and takes no turns: the reading a whole turn off the last good one is unwound to it
// after them, and warns of the block again. (A red team's 1e308 then 1.7e308 were accepted: the
// turns kept from them, or with a x2 mimic the NaN poses of 2e308 rad, left every later cycle
// clear.)
TEST_F(WrappedReadings, AbsurdReadingsAreRefusedAndTakeNoTurns) {
  for (const std::string& more_urdf : {std::string(), SpinnerMimic("2")}) {
    const auto wc = Load(more_urdf.empty() ? "continuous_joint1_absurd"
                                           : "continuous_joint1_absurd_mimic",
                         "1.0", more_urdf);
    Monitor monitor(wc, MonitorOptions{});
    ASSERT_TRUE(WarnsWith(*wc, monitor.Update(Pose(*wc, 0.0), 0.0).warnings, "block"));
    double t_s = 0.0;
    for (const double absurd : {1e308, 1.7e308, -1e308, 2e9}) {
      const Eigen::VectorXd q = Pose(*wc, absurd);
      const CycleReport& refused = monitor.Update(q, t_s += 0.05);
      EXPECT_EQ(refused.input, InputStatus::kOutOfLimits) << absurd;
      EXPECT_TRUE(refused.stop);
      const std::string why = monitor.DescribeRefusal(q);
      EXPECT_NE(why.find("joint 'left_joint1' at "), std::string::npos) << why;
      EXPECT_NE(why.find(", beyond the +/-1e+09 rad a joint may take on a side without a limit"),
                std::string::npos)
          << why;
    }
    const CycleReport& back = monitor.Update(Pose(*wc, kTurn), t_s += 0.05);
    EXPECT_EQ(back.input, InputStatus::kOk);
    EXPECT_LT(back.step_motion_m, 1e-9);
    EXPECT_TRUE(WarnsWith(*wc, back.warnings, "block"));
    ExpectValid(monitor);
  }
}

// With turns kept (a wrap crossed), a reading just beyond the bound is refused all the same,
// as ~check refuses it, and names the joint: the kept turns do not shift it back within. (A
// review found -1e9 - 1 rad accepted after one wrap, +2 pi kept; it then carried 1.6e8 turns to
// the true readings after it.)
TEST_F(WrappedReadings, AReadingBeyondTheBoundIsRefusedWithTurnsKept) {
  const auto wc = Load("continuous_joint1_beyond_turns");
  Monitor monitor(wc, MonitorOptions{});
  const Crossing crossing = CrossPi(*wc, &monitor);
  ASSERT_LT(crossing.largest_step_m, 0.01);  // unwound: a turn is kept
  const Eigen::VectorXd q = Pose(*wc, -kMaxUnlimitedPosition_rad - 1.0);
  EXPECT_EQ(monitor.Check(q).input, InputStatus::kOutOfLimits);
  const CycleReport& refused = monitor.Update(q, 0.05);
  EXPECT_EQ(refused.input, InputStatus::kOutOfLimits);
  EXPECT_TRUE(refused.stop);
  const std::string why = monitor.DescribeRefusal(q);
  EXPECT_NE(why.find("joint 'left_joint1' at -1e+09"), std::string::npos) << why;
  // A reading within the bound that the kept turn takes beyond it is refused, named unwound.
  const Eigen::VectorXd edge = Pose(*wc, kMaxUnlimitedPosition_rad - 1.0);
  EXPECT_EQ(monitor.Update(edge, 0.055).input, InputStatus::kOutOfLimits);
  const std::string unwound = monitor.DescribeRefusal(edge);
  EXPECT_NE(unwound.find("with the whole turns unwound so far), beyond the +/-1e+09 rad"),
            std::string::npos)
      << unwound;
  // The turn is still kept: the next reading of the crossing is unwound, no step, no warning.
  const CycleReport& next = monitor.Update(Pose(*wc, Wrapped(3.152)), 0.06);
  EXPECT_EQ(next.input, InputStatus::kOk);
  EXPECT_LT(next.step_motion_m, 0.01);
  EXPECT_FALSE(WarnsWith(*wc, next.warnings, "block"));
  ExpectValid(monitor);
}

// A continuous joint's reading 1e6 rad from the last (within the +/-1e9 rad accepted; a corrupt
// driver), 1 ms later: the step is swept within the test budget, and what it leaves is warned
// as not certified clear, with a stop. (A review's: this cycle took 27 s, 1e9 rad hours, with
// the node's thread held; the bisection's depth was bounded, its sample count not.)
TEST_F(WrappedReadings, AStepOfAbsurdLengthIsSweptWithinTheTestBudget) {
  const auto wc = Load("continuous_joint1_absurd_step");
  Monitor monitor(wc, MonitorOptions{});
  monitor.Update(Pose(*wc, 0.0), 0.0);
  const CycleReport& far = monitor.Update(Pose(*wc, 1e6), 0.001);
  EXPECT_EQ(far.input, InputStatus::kOk);
  EXPECT_GT(far.step_motion_m, 1e4);
  EXPECT_GE(far.swept_distance_tests, kMaxSweptTests);
  // Past the budget, two tests a pair at most (its distances at the step's ends).
  const std::size_t pairs = wc->primitives.size() * wc->primitives.size();
  EXPECT_LE(far.swept_distance_tests,
            kMaxSweptTests + kSweptTestsPerPair * far.swept_pairs + 2 * pairs);
  EXPECT_TRUE(far.stop);
  const auto uncertified = std::count_if(far.warnings.begin(), far.warnings.end(),
                                         [](const Warning& w) {
                                           return w.between_samples &&
                                                  !IsWarningDistance(w.distance_m, w.threshold_m);
                                         });
  EXPECT_GT(uncertified, 0);
  ExpectValid(monitor);
}

// A crowded scene (3 cm cubes 10 cm apart over the arms' workspace, 5,417 primitives) sampled
// once a second at the velocity limits: real steps, which no test budget may cut short (a
// review's: with one budget for the step whatever its pairs, 22 of these 48 steps warned some
// 7,000 pairs each as not certified clear, at any distance).
TEST(MonitorSwept, CrowdedSceneAtOneHertzStaysWithinTheTestBudget) {
  const auto wc =
      LoadSceneWith("dense_grid", CubeGrid({16, 24, 14}, {-0.8, -1.4, 0.3}, {0.1, 0.1, 0.1}));
  const test::JointLimits limits = test::LimitsOf(*wc);
  std::mt19937_64 rng(4242);
  const MonitorOptions options = Unlimited();
  std::uint32_t most = 0;
  for (int trajectory = 0; trajectory < 4; ++trajectory) {
    const test::SmoothTrajectory path(limits, 1.0, &rng);
    Monitor monitor(wc, options);
    Eigen::VectorXd q;
    path.At(0.0, &q);
    monitor.Update(q);
    for (int k = 1; k <= 12; ++k) {
      path.At(k * 1.0, &q);
      const CycleReport& report = monitor.Update(q);
      most = std::max(most, report.swept_distance_tests);
      EXPECT_LT(report.swept_distance_tests,
                kMaxSweptTests + kSweptTestsPerPair * report.swept_pairs)
          << "trajectory " << trajectory << " step " << k;
      for (const Warning& w : report.warnings) {
        EXPECT_FALSE(w.between_samples &&
                     w.distance_m > w.threshold_m + options.swept_resolution_m)
            << "trajectory " << trajectory << " step " << k << ": " << w.distance_m;
      }
    }
  }
  EXPECT_GT(most, kMaxSweptTests);  // the scene is crowded enough to need the pairs' share
}

// A long step far from everything at both ends: each pair's distances at the two ends, less its
// motion bound, leave twice the threshold, so no pair is bisected, though for many pairs the
// motion bound exceeds the distance at the end (a test of the end alone would bisect them).
TEST(MonitorSwept, LongStepFarAtBothEndsBisectsNoPair) {
  const auto wc = test::LoadBundledWorkcell();
  // The left arm, tilted forward, turned 0.45 rad about its base joint, pointing away from the
  // right arm, the tables and the shelves.
  const Eigen::VectorXd q0 = MakeQ(*wc, {{"left_joint1", -2.6}, {"left_joint2", 1.1}});
  const Eigen::VectorXd q1 = MakeQ(*wc, {{"left_joint1", -2.15}, {"left_joint2", 1.1}});
  const MonitorOptions options = Unlimited();
  Monitor monitor(wc, options);
  const CycleReport report = RunStep(&monitor, q0, q1);
  EXPECT_GT(report.step_motion_m, 0.7);
  EXPECT_EQ(report.swept_pairs, 0u);
  EXPECT_EQ(report.swept_distance_tests, 0u);
  EXPECT_TRUE(report.warnings.empty());
  StepTally tally;
  CheckStep(*wc, options, q0, q1, report, "long step far at both ends", &tally);
  EXPECT_EQ(tally.dense_contacts, 0);
}

// Start-up: a tolerance below the per-cycle motion is a notice with the swept check on, an
// error with it off; a short enough cycle needs neither, nor do the joints' real top speeds
// given in the scene file (joint_limits: velocity) where the URDF's allow more.
TEST(MonitorSwept, StartupToleranceCheck) {
  const auto wc = test::LoadBundledWorkcell();
  MonitorOptions options;
  {
    Monitor monitor(wc, options);
    ASSERT_EQ(monitor.startup_notices().size(), 1u);
    EXPECT_NE(monitor.startup_notices()[0].find("swept check covers"), std::string::npos)
        << monitor.startup_notices()[0];
    // The notice counts the primitives in the same case: some of both arms' (each arm
    // primitive's 0.0305 m tolerance equals max_speed_mps * cycle_period_s, and the URDF
    // velocity limits allow more to those far from the base).
    int arm_primitives = 0;
    for (const PrimitiveSpec& p : wc->primitives) arm_primitives += !p.group.empty();
    const std::string& notice = monitor.startup_notices()[0];
    const std::string count_at = "(of the ";
    const std::size_t at = notice.find(count_at);
    ASSERT_NE(at, std::string::npos) << notice;
    const int below = std::atoi(notice.c_str() + at + count_at.size());
    EXPECT_GE(below, 2) << notice;
    EXPECT_LE(below, arm_primitives) << notice;
    EXPECT_NE(notice.find(std::to_string(below) + " moving primitives whose tolerance is below "
                                                  "their motion, the one furthest below)"),
              std::string::npos)
        << notice;
    // The motion named first is the larger of its two sources, each given.
    EXPECT_NE(notice.find("is below its motion in one cycle, "), std::string::npos) << notice;
    const double motion_m =
        std::atof(notice.c_str() + notice.find("one cycle, ") + std::strlen("one cycle, "));
    const double speed_m = std::atof(notice.c_str() + notice.find("cycle_period_s (") +
                                     std::strlen("cycle_period_s ("));
    const double urdf_m = std::atof(notice.c_str() + notice.find("allow in a cycle (") +
                                    std::strlen("allow in a cycle ("));
    EXPECT_DOUBLE_EQ(speed_m, options.max_speed_mps * options.cycle_period_s) << notice;
    EXPECT_GT(urdf_m, speed_m) << notice;
    EXPECT_NEAR(motion_m, urdf_m, 1e-5 * urdf_m) << notice;
    // Faster input than the default 20 Hz is set where the period comes from.
    EXPECT_NE(notice.find("the monitor options' cycle_period_s, to be set to the period of "
                          "faster input"),
              std::string::npos)
        << notice;
  }
  options.swept_check = false;
  try {
    Monitor monitor(wc, options);
    ADD_FAILURE() << "no LoadError";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("swept_check"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("tolerance of primitive"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("joint_limits: {<joint>: {velocity: v}}"),
              std::string::npos)
        << e.what();
  }
  // 0.05 rad/s a joint: under 0.0305 m a cycle for every primitive (lever arms under 2 m).
  const auto slow = test::LoadBundledSceneEdited("slow_joints", [](std::string* scene) {
    *scene += "\njoint_limits:\n";
    for (const char* arm : {"left", "right"}) {
      for (int k = 1; k <= 7; ++k) {
        *scene += "  " + std::string(arm) + "_joint" + std::to_string(k) + ": {velocity: 0.05}\n";
      }
    }
  });
  Monitor slow_monitor(slow, options);
  EXPECT_TRUE(slow_monitor.startup_notices().empty());
  options.swept_check = true;
  EXPECT_TRUE(Monitor(slow, options).startup_notices().empty());
  options.swept_check = false;
  options.cycle_period_s = 0.002;
  Monitor fast(wc, options);
  EXPECT_TRUE(fast.startup_notices().empty());
}

// Cheap when nothing is near: on smooth trajectories at 100 Hz the path is needed only in the
// few cycles where some pair's margin is below the step's motion bound (under 10 %); bounded
// cycles never need it.
TEST(MonitorSwept, PathRarelyNeededAtHighRate) {
  const auto wc = test::LoadBundledWorkcell();
  const test::JointLimits limits = test::LimitsOf(*wc);
  std::mt19937_64 rng(test::PrintSeed(1616));
  std::uint64_t cycles = 0, needed = 0, bounded = 0, tests = 0;
  for (int trajectory = 0; trajectory < 5; ++trajectory) {
    Monitor monitor(wc, MonitorOptions{});
    const test::SmoothTrajectory path(limits, 0.5, &rng);
    std::uint64_t needed_here = 0;
    Eigen::VectorXd q;
    for (int k = 0; k < 2000; ++k) {
      path.At(k * 0.01, &q);
      const CycleReport& report = monitor.Update(q);
      ++cycles;
      if (report.bounded) {
        ++bounded;
        EXPECT_EQ(report.swept_distance_tests, 0u);
      }
      needed_here += report.swept_pairs > 0 ? 1 : 0;
      tests += report.swept_distance_tests;
    }
    EXPECT_EQ(monitor.swept_cycles(), needed_here);
    needed += needed_here;
  }
  std::printf("%llu cycles at 100 Hz: %llu bounded, swept path needed in %llu (%.2f %%), %.3f "
              "swept distance tests per cycle\n",
              static_cast<unsigned long long>(cycles), static_cast<unsigned long long>(bounded),
              static_cast<unsigned long long>(needed), 100.0 * needed / cycles,
              static_cast<double>(tests) / cycles);
  EXPECT_LT(needed, cycles / 10);
}

}  // namespace
}  // namespace arm_collision_monitor
