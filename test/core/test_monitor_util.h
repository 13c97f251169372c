// Shared by the Monitor tests: the bundled workcell, joint helpers, seeded smooth trajectories
// and an independent brute-force reference (all pairs, ShapeDistance, compatibility) that knows
// nothing of the Monitor's broad phase, culling or caches.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {
namespace test {

inline std::shared_ptr<const Workcell> LoadBundledWorkcell() {
  static const std::shared_ptr<const Workcell> workcell = std::make_shared<const Workcell>(
      LoadWorkcell(ACM_SOURCE_DIR "/urdf/workcell.urdf", ACM_SOURCE_DIR "/config/scene.yaml"));
  return workcell;
}

/// The URDF `urdf_path` with the bundled scene file's text after `edit` (written as
/// `name`.yaml in the test's temporary directory): scenes that differ from the bundled one in a
/// few lines.
template <typename Edit>
std::shared_ptr<const Workcell> LoadSceneEdited(const std::string& urdf_path,
                                                const std::string& name, Edit&& edit) {
  std::ifstream in(ACM_SOURCE_DIR "/config/scene.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  edit(&scene);
  const std::string path = ::testing::TempDir() + "/" + name + ".yaml";
  std::ofstream(path) << scene;
  return std::make_shared<const Workcell>(LoadWorkcell(urdf_path, path));
}

/// LoadSceneEdited with the bundled URDF.
template <typename Edit>
std::shared_ptr<const Workcell> LoadBundledSceneEdited(const std::string& name, Edit&& edit) {
  return LoadSceneEdited(ACM_SOURCE_DIR "/urdf/workcell.urdf", name, std::forward<Edit>(edit));
}

inline MonitorOptions OptionsFor(BroadPhaseMethod method) {
  MonitorOptions options;
  options.broad_phase.method = method;
  return options;
}

inline const std::vector<BroadPhaseMethod>& AllMethods() {
  static const std::vector<BroadPhaseMethod> methods = {
      BroadPhaseMethod::kOctree, BroadPhaseMethod::kNaive, BroadPhaseMethod::kGrid,
      BroadPhaseMethod::kRebuild, BroadPhaseMethod::kReinsert};
  return methods;
}

/// Joint limits by q index.
struct JointLimits {
  Eigen::VectorXd lower, upper, max_velocity;
};
inline JointLimits LimitsOf(const Workcell& workcell) {
  const KinematicModel& model = workcell.kinematics;
  JointLimits limits;
  limits.lower.resize(model.q_size());
  limits.upper.resize(model.q_size());
  limits.max_velocity.resize(model.q_size());
  for (int link = 1; link < model.link_count(); ++link) {
    const JointSpec& joint = model.joint(link);
    if (joint.q_index < 0) continue;
    limits.lower[joint.q_index] = std::isfinite(joint.lower) ? joint.lower : -M_PI;
    limits.upper[joint.q_index] = std::isfinite(joint.upper) ? joint.upper : M_PI;
    limits.max_velocity[joint.q_index] = joint.max_velocity;
  }
  return limits;
}

inline int JointIndex(const Workcell& workcell, const std::string& name) {
  const auto it = std::find(workcell.joint_names.begin(), workcell.joint_names.end(), name);
  EXPECT_NE(it, workcell.joint_names.end()) << "no joint " << name;
  return static_cast<int>(it - workcell.joint_names.begin());
}

/// q with every joint at 0 (the home pose: every link straight up) but the named ones.
inline Eigen::VectorXd MakeQ(const Workcell& workcell,
                             const std::vector<std::pair<std::string, double>>& set) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(static_cast<int>(workcell.joint_names.size()));
  for (const auto& [name, value] : set) q[JointIndex(workcell, name)] = value;
  return q;
}

/// Planar inverse kinematics of one arm of the bundled workcell (joints alternate roll and pitch;
/// 0.3 m from flange to shoulder, 0.65 m shoulder to elbow (links 2+3), 0.65 m elbow to wrist
/// (links 4+5), 0.305 m wrist to tool tip): puts the tool tip, pointing straight down, at
/// (x, y, tip_z). Returns {q1, q2, q4, q6}.
inline std::array<double, 4> ReachDown(const Eigen::Vector3d& p_W_flange, double x, double y,
                                double tip_z) {
  const double a = 0.65, b = 0.65, w = 0.305;
  const double dx = x - p_W_flange.x(), dy = y - p_W_flange.y();
  const double r = std::hypot(dx, dy);
  const double dz = tip_z + w - (p_W_flange.z() + 0.3);
  const double d2 = r * r + dz * dz;
  const double q4 = std::acos((d2 - a * a - b * b) / (2 * a * b));
  const double q2 = std::atan2(r, dz) - std::atan2(b * std::sin(q4), a + b * std::cos(q4));
  return {std::atan2(dy, dx), q2, q4, M_PI - q2 - q4};
}

inline Eigen::VectorXd ArmReachDown(const Workcell& wc, const std::string& arm, double x, double y,
                             double tip_z) {
  const Eigen::Vector3d flange(0.0, arm == "left" ? 0.55 : -0.55, 0.8);
  const auto q = ReachDown(flange, x, y, tip_z);
  return MakeQ(wc, {{arm + "_joint1", q[0]},
                    {arm + "_joint2", q[1]},
                    {arm + "_joint4", q[2]},
                    {arm + "_joint6", q[3]}});
}

inline Eigen::VectorXd RandomQ(const JointLimits& limits, std::mt19937_64* rng) {
  Eigen::VectorXd q(limits.lower.size());
  for (int i = 0; i < q.size(); ++i) {
    q[i] = std::uniform_real_distribution<double>(limits.lower[i], limits.upper[i])(*rng);
  }
  return q;
}

/// A seeded smooth trajectory: every joint a sinusoid inside its limits whose peak speed is
/// `speed_fraction` of the joint's velocity limit.
struct SmoothTrajectory {
  Eigen::VectorXd centre, amplitude, omega, phase;
  SmoothTrajectory(const JointLimits& limits, double speed_fraction, std::mt19937_64* rng) {
    const int n = static_cast<int>(limits.lower.size());
    centre.resize(n);
    amplitude.resize(n);
    omega.resize(n);
    phase.resize(n);
    for (int i = 0; i < n; ++i) {
      const double span = limits.upper[i] - limits.lower[i];
      amplitude[i] = std::uniform_real_distribution<double>(0.1, 0.45)(*rng) * span;
      centre[i] = std::uniform_real_distribution<double>(limits.lower[i] + amplitude[i],
                                                         limits.upper[i] - amplitude[i])(*rng);
      omega[i] = speed_fraction * limits.max_velocity[i] / amplitude[i] *
                 std::uniform_real_distribution<double>(0.5, 1.0)(*rng);
      phase[i] = std::uniform_real_distribution<double>(0.0, 2.0 * M_PI)(*rng);
    }
  }
  void At(double t_s, Eigen::VectorXd* q) const {
    *q = centre + amplitude.cwiseProduct((omega * t_s + phase).array().sin().matrix());
  }
};

/// The arms in turns, as from one joint-state topic per arm: step k's arm (the left on even k,
/// the right on odd; its joints named "left_..." or "right_...") takes its joints of q_path.
inline void TakeArmsTurn(const Workcell& wc, int k, const Eigen::VectorXd& q_path,
                         Eigen::VectorXd* q) {
  const std::vector<std::string> names = wc.kinematics.ActuatedJointNames();
  const std::string arm = k % 2 == 0 ? "left_" : "right_";
  for (int i = 0; i < q_path.size(); ++i) {
    if (names[i].rfind(arm, 0) == 0) (*q)[i] = q_path[i];
  }
}

/// The scene state the reference needs to know besides q.
struct ReferenceScene {
  std::map<int, std::string> variant_of_link;  ///< link index -> active variant ("" default)
  struct Held {
    int link = -1;
    Shape shape_L;  ///< the object's primitive in the holding link's frame
  };
  std::map<PrimitiveId, Held> held;               ///< object primitive -> holder
  std::set<std::pair<int, int>> grasp;            ///< (link index, object index) excused
  std::map<PrimitiveId, Shape> moved_objects_W;   ///< frame-bound objects moved away
};

struct ReferenceWarning {
  PrimitiveId a, b;
  double distance_m, threshold_m;
  bool operator<(const ReferenceWarning& o) const { return a < o.a || (a == o.a && b < o.b); }
};

/// Brute force over all pairs: the warnings the Monitor must report for `q`.
inline std::vector<ReferenceWarning> ReferenceWarnings(const Workcell& wc,
                                                       const Eigen::VectorXd& q,
                                                       const ReferenceScene& scene = {}) {
  const KinematicModel& model = wc.kinematics;
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  model.ComputeLinkPoses(q, &X_WL);
  const std::size_t n = wc.primitives.size();
  std::vector<Shape> shape(n);
  std::vector<bool> present(n, true), is_static(n, false);
  std::vector<double> tol(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PrimitiveSpec& p = wc.primitives[i];
    tol[i] = p.tolerance_m;
    if (p.link_index >= 0) {
      const auto v = scene.variant_of_link.find(p.link_index);
      present[i] = p.variant == (v == scene.variant_of_link.end() ? "" : v->second);
      shape[i] = TransformShape(X_WL[p.link_index], p.shape_L);
      is_static[i] = p.is_static;
      continue;
    }
    const ObjectSpec& object = wc.objects[p.object_index];
    const auto held = scene.held.find(static_cast<PrimitiveId>(i));
    if (held != scene.held.end()) {
      shape[i] = TransformShape(X_WL[held->second.link], held->second.shape_L);
      // The tolerance of the holder's, or of its nearest ancestor's with geometry (a tool frame
      // has none).
      auto has_geometry = [&](int link) {
        return std::any_of(wc.primitives.begin(), wc.primitives.end(),
                           [&](const PrimitiveSpec& l) { return l.link_index == link; });
      };
      int holder = held->second.link;
      while (holder > 0 && !has_geometry(holder)) holder = wc.kinematics.parent_link(holder);
      for (const PrimitiveSpec& l : wc.primitives) {
        if (l.link_index == holder) tol[i] = std::max(tol[i], l.tolerance_m);
      }
    } else {
      const auto moved = scene.moved_objects_W.find(static_cast<PrimitiveId>(i));
      shape[i] = moved != scene.moved_objects_W.end() ? moved->second : p.shape_L;
      is_static[i] = object.frame.empty();
    }
  }
  auto excused = [&](std::size_t a, std::size_t b) {
    if (wc.compatible.AreCompatible(a, b)) return true;
    for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}}) {
      const PrimitiveSpec& px = wc.primitives[x];
      const PrimitiveSpec& py = wc.primitives[y];
      if (px.link_index < 0 || py.object_index < 0) continue;
      const auto held = scene.held.find(static_cast<PrimitiveId>(y));
      if (held != scene.held.end() && held->second.link == px.link_index) return true;
      if (scene.grasp.count({px.link_index, py.object_index})) return true;
    }
    return false;
  };
  std::vector<ReferenceWarning> warnings;
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      if (!present[a] || !present[b] || (is_static[a] && is_static[b]) || excused(a, b)) continue;
      const double d = ShapeDistance(shape[a], shape[b]).distance_m;
      if (d < tol[a] + tol[b] || d == 0.0) {  // touching or overlapping always warns
        warnings.push_back({static_cast<PrimitiveId>(a), static_cast<PrimitiveId>(b), d,
                            tol[a] + tol[b]});
      }
    }
  }
  return warnings;
}

inline std::string Describe(const Workcell& wc, PrimitiveId a, PrimitiveId b) {
  return wc.primitives[a].name + "--" + wc.primitives[b].name;
}

/// The warnings at the cycle's q: the swept check's between-samples ones left out (those are
/// tested against a dense sampler in test_monitor_swept.cpp).
inline std::vector<Warning> AtSampleWarnings(const std::vector<Warning>& warnings) {
  std::vector<Warning> at_sample;
  for (const Warning& w : warnings) {
    if (!w.between_samples) at_sample.push_back(w);
  }
  return at_sample;
}

/// The stop a report must request when `has_expected` warnings are due at its q: those, a
/// contact between samples, or a jump.
inline bool ExpectedStop(const CycleReport& report, bool has_expected) {
  return has_expected || report.input_jumped || report.input != InputStatus::kOk ||
         std::any_of(report.warnings.begin(), report.warnings.end(),
                     [](const Warning& w) { return w.between_samples; });
}

/// Asserts the Monitor's warnings at q equal the reference pair for pair (ids, distances,
/// thresholds); between-samples warnings are left out (AtSampleWarnings).
inline void ExpectSameWarnings(const Workcell& wc, const std::vector<ReferenceWarning>& expected,
                               const std::vector<Warning>& all, const std::string& context) {
  const std::vector<Warning> actual = AtSampleWarnings(all);
  std::vector<std::string> missing, extra;
  std::size_t i = 0, j = 0;
  while (i < expected.size() || j < actual.size()) {
    if (j == actual.size() ||
        (i < expected.size() && (expected[i].a < actual[j].a ||
                                 (expected[i].a == actual[j].a && expected[i].b < actual[j].b)))) {
      missing.push_back(Describe(wc, expected[i].a, expected[i].b));
      ++i;
    } else if (i == expected.size() || expected[i].a != actual[j].a ||
               expected[i].b != actual[j].b) {
      extra.push_back(Describe(wc, actual[j].a, actual[j].b));
      ++j;
    } else {
      EXPECT_DOUBLE_EQ(expected[i].distance_m, actual[j].distance_m) << context;
      EXPECT_DOUBLE_EQ(expected[i].threshold_m, actual[j].threshold_m) << context;
      ++i;
      ++j;
    }
  }
  auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += x + " ";
    return s;
  };
  EXPECT_TRUE(missing.empty()) << context << ": missing " << join(missing);
  EXPECT_TRUE(extra.empty()) << context << ": extra " << join(extra);
}

inline bool HasWarning(const std::vector<Warning>& warnings, PrimitiveId a, PrimitiveId b) {
  if (a > b) std::swap(a, b);
  return std::any_of(warnings.begin(), warnings.end(),
                     [&](const Warning& w) { return w.a == a && w.b == b; });
}

inline PrimitiveId Prim(const Workcell& wc, const std::string& name) {
  const int id = wc.FindPrimitive(name);
  EXPECT_GE(id, 0) << "no primitive " << name;
  return static_cast<PrimitiveId>(id);
}

inline std::uint64_t PrintSeed(std::uint64_t seed) {
  std::printf("seed = %llu\n", static_cast<unsigned long long>(seed));
  return seed;
}

}  // namespace test
}  // namespace arm_collision_monitor
