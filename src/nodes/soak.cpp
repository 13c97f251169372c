// Soak test of the Monitor (offline, ROS-free): many cycles of random smooth joint motion with
// occasional jumps on a workcell, the octree broad phase against the all-pairs reference every
// k cycles, and the process's memory at the start and the end. Exits 1 on any divergence.
// Two comparisons: (1) a Monitor with the octree against a Monitor with the naive broad phase
// (reports); (2) since the Monitor owns its broad phase, the wrap-around of the octree's 32-bit
// stamps is soaked on a second octree that follows the first Monitor's shapes every cycle,
// rebuilt every few thousand cycles with its stamps set a few steps before the wrap (the hook
// must be used before any Add), against an all-pairs index fed the same (candidate pairs, plus
// the octree's Validate() after each wrap).
//
//   soak --urdf <file> --scene <file> --config <file> [--cycles N] [--every k] [--seed s]
//
// scripts/soak runs it on the bundled workcell.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/broadphase/cell_broad_phase.h"
#include "arm_collision_monitor/broadphase/naive_broad_phase.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {
namespace {

struct SoakOptions {
  std::string urdf_path;
  std::string scene_path;
  std::string config_path;
  std::uint64_t cycles = 100000000;  // 10^8
  std::uint64_t compare_every = 64;
  std::uint64_t seed = 1;
};

// Mean cycles between jumps (a new random configuration: a teleport, like a restarted publisher
// or a bag loop). Dimensionless.
constexpr double kMeanCyclesBetweenJumps = 5000.0;
// Each joint's speed is at most this fraction of its URDF velocity limit (dimensionless): about
// the end-effector speed the octree's minimum cell size is designed for, so that the
// incremental update, not the re-insert fallback, is what gets soaked.
constexpr double kJointSpeedFraction = 0.15;
// Joint speed used when the URDF gives no limit, rad/s or m/s.
constexpr double kDefaultJointSpeed = 1.0;
// Every this many cycles the stamp soak's octree is rebuilt with its stamps set r steps before
// the 32-bit wrap, r cycling through 0 .. kStampMaxStepsBeforeWrap - 1 so that the wrap falls
// in the Adds, the Moves, the pair scan or a merge check; its Validate() runs
// kValidateDelayCycles later.
constexpr std::uint64_t kStampForceEveryCycles = 4096;
constexpr std::uint32_t kStampMaxStepsBeforeWrap = 64;
constexpr std::uint64_t kValidateDelayCycles = 2 * 64;

// One joint's motion: q(t) = centre + amplitude sin(omega t + phase), inside the limits.
struct JointMotion {
  double centre = 0.0;
  double amplitude = 0.0;
  double omega_rad_per_s = 0.0;
  double phase_rad = 0.0;
};

// Peak and current resident set size of this process, kB (/proc/self/status VmHWM, VmRSS).
void ReadMemory(long* vm_hwm_kb, long* vm_rss_kb) {
  *vm_hwm_kb = -1;
  *vm_rss_kb = -1;
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") status >> *vm_hwm_kb;
    if (key == "VmRSS:") status >> *vm_rss_kb;
    status.ignore(1 << 20, '\n');
  }
}

bool ParseArguments(int argc, char** argv, SoakOptions* options) {
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const std::string value = argv[i + 1];
    if (key == "--urdf") {
      options->urdf_path = value;
    } else if (key == "--scene") {
      options->scene_path = value;
    } else if (key == "--config") {
      options->config_path = value;
    } else if (key == "--cycles") {
      options->cycles = std::stoull(value);
    } else if (key == "--every") {
      options->compare_every = std::stoull(value);
    } else if (key == "--seed") {
      options->seed = std::stoull(value);
    } else {
      return false;
    }
  }
  return argc % 2 == 1 && !options->urdf_path.empty() && !options->scene_path.empty() &&
         !options->config_path.empty() && options->compare_every > 0;
}

class MotionGenerator {
 public:
  MotionGenerator(const Workcell& workcell, double period_s, std::uint64_t seed)
      : period_s_(period_s), rng_(seed), motion_(workcell.joint_names.size()),
        q_(static_cast<Eigen::Index>(workcell.joint_names.size())) {
    const KinematicModel& model = workcell.kinematics;
    lower_.assign(motion_.size(), -EIGEN_PI);
    upper_.assign(motion_.size(), EIGEN_PI);
    speed_.assign(motion_.size(), kDefaultJointSpeed * kJointSpeedFraction);
    for (int link = 1; link < model.link_count(); ++link) {
      const JointSpec& joint = model.joint(link);
      if (joint.q_index < 0 || joint.q_index >= static_cast<int>(motion_.size())) continue;
      if (std::isfinite(joint.lower) && std::isfinite(joint.upper)) {
        lower_[joint.q_index] = joint.lower;
        upper_[joint.q_index] = joint.upper;
      }
      if (joint.max_velocity > 0.0) speed_[joint.q_index] = joint.max_velocity * kJointSpeedFraction;
    }
    for (std::size_t i = 0; i < motion_.size(); ++i) Randomise(i, /*keep_position=*/false);
  }

  // The next cycle's q: smooth motion, or with probability 1/kMeanCyclesBetweenJumps a jump.
  const Eigen::VectorXd& Next(bool* jumped) {
    *jumped = unit_(rng_) < 1.0 / kMeanCyclesBetweenJumps;
    t_s_ += period_s_;
    for (std::size_t i = 0; i < motion_.size(); ++i) {
      if (*jumped) Randomise(i, false);
      const JointMotion& m = motion_[i];
      q_[static_cast<Eigen::Index>(i)] =
          m.centre + m.amplitude * std::sin(m.omega_rad_per_s * t_s_ + m.phase_rad);
    }
    // Now and then one joint changes course (new amplitude and speed, same position): the
    // motion stays continuous but does not settle into a periodic orbit.
    if (unit_(rng_) < 0.01) {
      Randomise(static_cast<std::size_t>(unit_(rng_) * motion_.size()) % motion_.size(), true);
    }
    return q_;
  }

 private:
  void Randomise(std::size_t i, bool keep_position) {
    JointMotion& m = motion_[i];
    const double half_range = 0.5 * (upper_[i] - lower_[i]);
    const double q_now = m.centre + m.amplitude * std::sin(m.omega_rad_per_s * t_s_ + m.phase_rad);
    m.centre = 0.5 * (upper_[i] + lower_[i]);
    m.amplitude = half_range * (0.2 + 0.8 * unit_(rng_));
    // Continuing from q_now needs an amplitude that reaches it (it is within the half range).
    if (keep_position) m.amplitude = std::max(m.amplitude, std::abs(q_now - m.centre));
    m.omega_rad_per_s = speed_[i] * (0.1 + 0.9 * unit_(rng_)) / std::max(m.amplitude, 1e-9);
    if (keep_position) {
      // Continue from q_now: the phase that puts the new sinusoid there now.
      const double s = std::max(-1.0, std::min(1.0, (q_now - m.centre) / m.amplitude));
      m.phase_rad = std::asin(s) - m.omega_rad_per_s * t_s_;
    } else {
      m.phase_rad = 2.0 * EIGEN_PI * unit_(rng_);
    }
  }

  double period_s_;
  double t_s_ = 0.0;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
  std::vector<JointMotion> motion_;
  std::vector<double> lower_, upper_, speed_;
  Eigen::VectorXd q_;
};

// Equal reports: same input status, stop flag and warnings (pairs and distances exactly: both
// monitors run the same narrow phase on the same shapes).
bool SameReports(const CycleReport& a, const CycleReport& b, std::string* difference) {
  if (a.input != b.input || a.stop != b.stop || a.warnings.size() != b.warnings.size()) {
    *difference = "status/stop/warning count " + std::to_string(a.warnings.size()) + " vs " +
                  std::to_string(b.warnings.size());
    return false;
  }
  for (std::size_t k = 0; k < a.warnings.size(); ++k) {
    const Warning& u = a.warnings[k];
    const Warning& v = b.warnings[k];
    if (u.a != v.a || u.b != v.b || u.distance_m != v.distance_m ||
        u.threshold_m != v.threshold_m) {
      *difference = "warning " + std::to_string(k) + ": (" + std::to_string(u.a) + ", " +
                    std::to_string(u.b) + ") vs (" + std::to_string(v.a) + ", " +
                    std::to_string(v.b) + ")";
      return false;
    }
  }
  return true;
}

// The second octree (see the top of the file) and its all-pairs reference.
class StampSoak {
 public:
  StampSoak(const Monitor& monitor, const MonitorOptions& options)
      : compatible_(monitor.workcell().compatible), octree_options_(options.broad_phase) {
    octree_options_.method = BroadPhaseMethod::kOctree;
    // As the Monitor configures its own broad phase (monitor/monitor.h, MonitorOptions).
    octree_options_.world_W = monitor.workcell().world_W;
    octree_options_.min_cell_size_m = options.max_speed_mps * options.cycle_period_s;
    naive_.Reserve(monitor.primitive_count());
    for (PrimitiveId id = 0; id < monitor.primitive_count(); ++id) {
      if (!monitor.is_active(id)) continue;
      active_.push_back(id);
      const bool is_static = monitor.workcell().primitives[id].is_static;
      naive_.Add(id, ComputeAabb(monitor.shape_W(id)), monitor.tolerance_m(id),
                 is_static ? Motion::kStatic : Motion::kMoving);
      if (!is_static) moving_.push_back(id);
    }
    RestartNearWrap(monitor);
  }

  bool is_cell_structure() const { return cells_ != nullptr; }

  /// A new octree holding the primitives at their current shapes in `monitor`, its stamps set
  /// a few steps before the wrap (the hook's precondition: before any Add).
  void RestartNearWrap(const Monitor& monitor) {
    octree_ = MakeBroadPhase(octree_options_);
    cells_ = dynamic_cast<CellBroadPhase*>(octree_.get());
    if (cells_ == nullptr) return;
    const std::uint32_t steps = static_cast<std::uint32_t>(forced_wraps_ % kStampMaxStepsBeforeWrap);
    cells_->SetStampsForTest(std::numeric_limits<std::uint32_t>::max() - steps);
    ++forced_wraps_;
    for (const PrimitiveId id : active_) {
      const bool is_static = monitor.workcell().primitives[id].is_static;
      octree_->Add(id, ComputeAabb(monitor.shape_W(id)), monitor.tolerance_m(id),
                   is_static ? Motion::kStatic : Motion::kMoving);
    }
  }

  /// Moves every moving primitive to its current shape in `monitor`.
  void Follow(const Monitor& monitor) {
    for (const PrimitiveId id : moving_) {
      const Aabb box_W = ComputeAabb(monitor.shape_W(id));
      octree_->Move(id, box_W);
      naive_.Move(id, box_W);
    }
  }

  bool SamePairs(std::string* difference) {
    octree_->FindPairs(compatible_, &octree_pairs_);
    naive_.FindPairs(compatible_, &naive_pairs_);
    std::sort(octree_pairs_.begin(), octree_pairs_.end());
    std::sort(naive_pairs_.begin(), naive_pairs_.end());
    if (octree_pairs_ == naive_pairs_) return true;
    *difference = "stamp soak: " + std::to_string(octree_pairs_.size()) + " octree pairs, " +
                  std::to_string(naive_pairs_.size()) + " all-pairs pairs";
    return false;
  }

  bool Validate(std::string* difference) const {
    if (cells_->Validate(difference)) return true;
    *difference = "stamp soak: octree Validate(): " + *difference;
    return false;
  }

  std::uint64_t forced_wraps() const { return forced_wraps_; }

 private:
  const CompatibilityMatrix& compatible_;
  BroadPhaseOptions octree_options_;
  std::unique_ptr<BroadPhase> octree_;
  CellBroadPhase* cells_ = nullptr;  // octree_ seen through the class with the stamp hooks
  NaiveBroadPhase naive_;
  std::vector<PrimitiveId> active_, moving_;
  std::vector<CandidatePair> octree_pairs_, naive_pairs_;
  std::uint64_t forced_wraps_ = 0;
};

int RunSoak(const SoakOptions& soak) {
  MonitorOptions options = LoadMonitorOptions(soak.config_path);
  const auto workcell = std::make_shared<const Workcell>(
      LoadWorkcell(soak.urdf_path, soak.scene_path, options.tolerance_m));
  if (options.speed_scaled_tolerance) {
    // The reference only sees every k-th cycle, so it cannot know the speeds.
    std::cerr << "soak: speed_scaled_tolerance must be off in " << soak.config_path << "\n";
    return 2;
  }
  options.auto_broad_phase = false;
  options.broad_phase.method = BroadPhaseMethod::kOctree;
  MonitorOptions reference_options = options;
  reference_options.broad_phase.method = BroadPhaseMethod::kNaive;
  Monitor monitor(workcell, options);
  Monitor reference(workcell, reference_options);
  MotionGenerator motion(*workcell, options.cycle_period_s, soak.seed);
  StampSoak stamp_soak(monitor, options);
  if (!stamp_soak.is_cell_structure()) {
    std::cerr << "soak: the octree has no stamps to force (not a CellBroadPhase)\n";
    return 2;
  }

  long hwm_start_kb = 0, rss_start_kb = 0;
  ReadMemory(&hwm_start_kb, &rss_start_kb);
  std::printf("soak: seed %llu, %llu cycles, octree vs naive every %llu cycles, %u primitives\n",
              static_cast<unsigned long long>(soak.seed),
              static_cast<unsigned long long>(soak.cycles),
              static_cast<unsigned long long>(soak.compare_every), monitor.primitive_count());
  std::printf("soak: start: VmHWM %ld kB, VmRSS %ld kB\n", hwm_start_kb, rss_start_kb);
  std::fflush(stdout);

  std::uint64_t divergences = 0, comparisons = 0, jumps = 0, warning_cycles = 0,
                refused_cycles = 0;
  const std::uint64_t progress_every = std::max<std::uint64_t>(soak.cycles / 10, 1);
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t cycle = 1; cycle <= soak.cycles; ++cycle) {
    bool jumped = false;
    const Eigen::VectorXd& q = motion.Next(&jumped);
    jumps += jumped;
    const CycleReport& report = monitor.Update(q);
    warning_cycles += !report.warnings.empty();
    refused_cycles += report.input != InputStatus::kOk;
    stamp_soak.Follow(monitor);
    if (cycle % kStampForceEveryCycles == 0) stamp_soak.RestartNearWrap(monitor);
    const bool is_validate_cycle = cycle % kStampForceEveryCycles == kValidateDelayCycles;
    if (cycle % soak.compare_every == 0 || jumped || is_validate_cycle) {
      ++comparisons;
      std::string difference;
      const CycleReport& expected = reference.Update(q);
      bool same = SameReports(report, expected, &difference) &&
                  stamp_soak.SamePairs(&difference);
      if (same && is_validate_cycle) {
        same = monitor.Validate(&difference) && stamp_soak.Validate(&difference);
      }
      if (!same) {
        if (++divergences <= 10) {
          std::printf("soak: DIVERGENCE at cycle %llu: %s\n",
                      static_cast<unsigned long long>(cycle), difference.c_str());
        }
      }
    }
    if (cycle % progress_every == 0) {
      const double elapsed_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("soak: %llu cycles, %.0f cycles/s, %llu divergences\n",
                  static_cast<unsigned long long>(cycle), cycle / elapsed_s,
                  static_cast<unsigned long long>(divergences));
      std::fflush(stdout);
    }
  }
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  long hwm_end_kb = 0, rss_end_kb = 0;
  ReadMemory(&hwm_end_kb, &rss_end_kb);
  const BroadPhaseCounters& totals = monitor.total_counters();
  std::printf("soak: end: VmHWM %ld kB, VmRSS %ld kB\n", hwm_end_kb, rss_end_kb);
  std::printf("soak: %llu cycles in %.1f s (%.0f cycles/s): %llu with warnings, %llu refused, "
              "%llu jumps, %llu re-insert fallbacks, %llu outside the world\n",
              static_cast<unsigned long long>(soak.cycles), elapsed_s, soak.cycles / elapsed_s,
              static_cast<unsigned long long>(warning_cycles),
              static_cast<unsigned long long>(refused_cycles),
              static_cast<unsigned long long>(jumps),
              static_cast<unsigned long long>(totals.reinsert_fallbacks),
              static_cast<unsigned long long>(totals.outside_world));
  std::printf("soak: %llu comparisons with the naive broad phase, %llu forced stamp wraps, "
              "%llu divergences\n",
              static_cast<unsigned long long>(comparisons),
              static_cast<unsigned long long>(stamp_soak.forced_wraps()),
              static_cast<unsigned long long>(divergences));
  return divergences == 0 ? 0 : 1;
}

}  // namespace
}  // namespace arm_collision_monitor

int main(int argc, char** argv) {
  arm_collision_monitor::SoakOptions options;
  bool is_valid = false;
  try {
    is_valid = arm_collision_monitor::ParseArguments(argc, argv, &options);
  } catch (const std::logic_error&) {  // std::stoull: not a number, or out of range
  }
  if (!is_valid) {
    std::cerr << "usage: soak --urdf <file> --scene <file> --config <file> [--cycles N] "
                 "[--every k] [--seed s]\n";
    return 2;
  }
  try {
    return arm_collision_monitor::RunSoak(options);
  } catch (const arm_collision_monitor::LoadError& e) {
    std::cerr << "soak: " << e.what() << "\n";
    return 2;
  }
}
