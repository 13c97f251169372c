// Soak test of the Monitor (offline, ROS-free): many cycles of random smooth joint motion with
// occasional jumps on a workcell, on one Monitor with its octree, and the process's memory at
// the start and the end. Exits 1 on any divergence or Validate() / ValidateIndex() failure.
// - Brute force: every k cycles (and on every jump) the report of Monitor::Update(q) is compared
//   with Monitor::Check(q) computed just before it. Check() tests every active, non-compatible
//   pair on a copy of the model without the broad phase, so it is the all-pairs reference: no
//   second Monitor with the naive broad phase is needed.
// - Stamp wrap-around: every kStampForceEveryCycles cycles the 32-bit visit, pair-scan and
//   distinct-count stamps of the Monitor's own octree are forced r steps before the wrap
//   (Monitor::ForceIndexStampsNearWrap), r cycling through 0 .. kStampMaxStepsBeforeWrap - 1, so
//   that the wrap falls in a Move, the pair scan or a merge check of the live index; the next
//   cycles are all compared with Check() and Monitor::Validate() and ValidateIndex() run
//   kValidateDelayCycles later.
//
//   soak --urdf <file> --scene <file> --config <file> [--cycles N] [--every k] [--seed s]
//
// scripts/soak runs it on the bundled workcell.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
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
// Every this many cycles the Monitor's octree has its stamps forced r steps before the 32-bit
// wrap, r cycling through 0 .. kStampMaxStepsBeforeWrap - 1 so that the wrap falls in a Move,
// the pair scan or a merge check. Each kind of stamp is drawn at least once per cycle with
// motion (the merge counter only when a primitive leaves a cell), so the wrap falls within
// kValidateDelayCycles cycles after forcing: every one of them is compared with Check(), and
// Validate() runs at the last.
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
      if (joint.max_velocity > 0.0)
        speed_[joint.q_index] = joint.max_velocity * kJointSpeedFraction;
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

// Equal reports: same input status, stop flag and warnings (pairs, distances, thresholds and
// closest points exactly: Update() and Check() run the same narrow phase on the same shapes).
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
        u.threshold_m != v.threshold_m || u.p_WA != v.p_WA || u.p_WB != v.p_WB) {
      *difference = "warning " + std::to_string(k) + ": (" + std::to_string(u.a) + ", " +
                    std::to_string(u.b) + ") vs (" + std::to_string(v.a) + ", " +
                    std::to_string(v.b) + ")";
      return false;
    }
  }
  return true;
}

// What the soak counts over the run.
struct SoakCounts {
  std::uint64_t divergences = 0, comparisons = 0, jumps = 0, warning_cycles = 0,
                refused_cycles = 0, forced_wraps = 0, validations = 0;
};

void PrintStart(const SoakOptions& soak, const Monitor& monitor) {
  long hwm_start_kb = 0, rss_start_kb = 0;
  ReadMemory(&hwm_start_kb, &rss_start_kb);
  std::printf("soak: seed %llu, %llu cycles, %s broad phase, Update vs Check (brute force) "
              "every %llu cycles, stamps forced near the wrap every %llu cycles, %u primitives\n",
              static_cast<unsigned long long>(soak.seed),
              static_cast<unsigned long long>(soak.cycles), monitor.broad_phase_name().c_str(),
              static_cast<unsigned long long>(soak.compare_every),
              static_cast<unsigned long long>(kStampForceEveryCycles), monitor.primitive_count());
  std::printf("soak: start: VmHWM %ld kB, VmRSS %ld kB\n", hwm_start_kb, rss_start_kb);
  std::fflush(stdout);
}

// Monitor::Validate() and ValidateIndex(); false with the failure, named, otherwise.
bool MonitorValid(const Monitor& monitor, std::string* difference) {
  if (!monitor.Validate(difference)) {
    *difference = "Monitor::Validate(): " + *difference;
    return false;
  }
  if (!monitor.ValidateIndex(difference)) {
    *difference = "Monitor::ValidateIndex(): " + *difference;
    return false;
  }
  return true;
}

// One soak cycle: the next q, a forced stamp wrap when due, Update, and on compare cycles the
// comparison with Check (and Validate at the end of a forced wrap's window).
void RunCycle(std::uint64_t cycle, const SoakOptions& soak, Monitor* monitor,
              MotionGenerator* motion, std::uint64_t* compare_all_until, SoakCounts* counts) {
  bool jumped = false;
  const Eigen::VectorXd& q = motion->Next(&jumped);
  counts->jumps += jumped;
  if (cycle % kStampForceEveryCycles == 0) {
    monitor->ForceIndexStampsNearWrap(
        static_cast<std::uint32_t>(counts->forced_wraps % kStampMaxStepsBeforeWrap));
    ++counts->forced_wraps;
    *compare_all_until = cycle + kValidateDelayCycles;
  }
  const bool is_compare_cycle =
      cycle % soak.compare_every == 0 || jumped || cycle <= *compare_all_until;
  CycleReport expected;  // allocates only when filled
  if (is_compare_cycle) expected = monitor->Check(q);  // before Update: the same model state
  const CycleReport& report = monitor->Update(q);
  counts->warning_cycles += !report.warnings.empty();
  counts->refused_cycles += report.input != InputStatus::kOk;
  if (!is_compare_cycle) return;
  ++counts->comparisons;
  std::string difference;
  bool same = SameReports(report, expected, &difference);
  if (same && cycle == *compare_all_until) {
    ++counts->validations;
    same = MonitorValid(*monitor, &difference);
  }
  if (!same && ++counts->divergences <= 10) {
    std::printf("soak: DIVERGENCE at cycle %llu: %s\n", static_cast<unsigned long long>(cycle),
                difference.c_str());
  }
}

void PrintEnd(const SoakOptions& soak, const Monitor& monitor, const SoakCounts& counts,
              double elapsed_s) {
  long hwm_end_kb = 0, rss_end_kb = 0;
  ReadMemory(&hwm_end_kb, &rss_end_kb);
  const BroadPhaseCounters& totals = monitor.total_counters();
  std::printf("soak: end: VmHWM %ld kB, VmRSS %ld kB\n", hwm_end_kb, rss_end_kb);
  std::printf("soak: %llu cycles in %.1f s (%.0f cycles/s): %llu with warnings, %llu refused, "
              "%llu jumps, %llu re-insert fallbacks, %llu outside the world\n",
              static_cast<unsigned long long>(soak.cycles), elapsed_s, soak.cycles / elapsed_s,
              static_cast<unsigned long long>(counts.warning_cycles),
              static_cast<unsigned long long>(counts.refused_cycles),
              static_cast<unsigned long long>(counts.jumps),
              static_cast<unsigned long long>(totals.reinsert_fallbacks),
              static_cast<unsigned long long>(totals.outside_world));
  std::printf("soak: %llu comparisons with Check (brute force), %llu forced stamp wraps, "
              "%llu Validate() calls, %llu divergences\n",
              static_cast<unsigned long long>(counts.comparisons),
              static_cast<unsigned long long>(counts.forced_wraps),
              static_cast<unsigned long long>(counts.validations),
              static_cast<unsigned long long>(counts.divergences));
}

int RunSoak(const SoakOptions& soak) {
  MonitorOptions options = LoadMonitorOptions(soak.config_path);
  const auto workcell = std::make_shared<const Workcell>(
      LoadWorkcell(soak.urdf_path, soak.scene_path, options.tolerance_m));
  options.broad_phase.method = BroadPhaseMethod::kOctree;
  Monitor monitor(workcell, options);
  MotionGenerator motion(*workcell, options.cycle_period_s, soak.seed);
  PrintStart(soak, monitor);

  SoakCounts counts;
  // The last cycle in which every report is compared after a forced wrap (the wrap happens
  // before it: at most kStampMaxStepsBeforeWrap stamps of each kind away).
  std::uint64_t compare_all_until = 0;
  const std::uint64_t progress_every = std::max<std::uint64_t>(soak.cycles / 10, 1);
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t cycle = 1; cycle <= soak.cycles; ++cycle) {
    RunCycle(cycle, soak, &monitor, &motion, &compare_all_until, &counts);
    if (cycle % progress_every == 0) {
      const double elapsed_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("soak: %llu cycles, %.0f cycles/s, %llu divergences\n",
                  static_cast<unsigned long long>(cycle), cycle / elapsed_s,
                  static_cast<unsigned long long>(counts.divergences));
      std::fflush(stdout);
    }
  }
  PrintEnd(soak, monitor, counts,
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return counts.divergences == 0 ? 0 : 1;
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
