// The swept check's per-cycle scratch (Monitor::Impl::swept; the algorithm is in
// swept_check.cpp). Private to the monitor module; preallocated at start-up.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "arm_collision_monitor/broadphase/box_array.h"
#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/primitives.h"
#include "arm_collision_monitor/monitor/motion_bounds.h"

namespace arm_collision_monitor {

/// A pair the swept check looks at, with a lower bound on its distance at the step's end (m;
/// NaN when unknown).
struct SweptPair {
  CandidatePair pair;
  double end_bound_m = 0.0;
  bool is_exact = false;  ///< end_bound_m is the distance itself
};

/// A sub-interval [s0, s1] of the step (fractions) with the pair's exact distances at its ends.
struct SweptInterval {
  double s0 = 0.0, s1 = 1.0;
  double d0_m = 0.0, d1_m = 0.0;
  int depth = 0;
};

/// How many samples of a step keep their link poses for the other pairs (SweepPair).
inline constexpr int kSweptPoseCacheSize = 32;

struct SweptScratch {
  Eigen::VectorXd q_start;                 // the step's start: the last accepted q
  Eigen::VectorXd q_s;                     // a sample along the step
  // Link poses at q_start (has_start), when is_behind (else Impl::X_WL_before holds them).
  std::vector<Eigen::Isometry3d> X_WL_start;
  std::vector<Eigen::Isometry3d> X_WL_s;      // link poses at q_s
  bool has_start = false;
  // Link poses at the first pose_count samples of this cycle's step, fraction pose_s[i] in
  // X_WL_at[i]: every pair bisects the same dyadic fractions, so most samples are shared.
  std::array<double, kSweptPoseCacheSize> pose_s{};
  std::vector<std::vector<Eigen::Isometry3d>> X_WL_at;  // kSweptPoseCacheSize slots
  int pose_count = 0;
  // The step's motion bounds when the step starts behind the last kinematics (after bounded
  // cycles; else Impl::motion holds them: the step is then the motion since the kinematics,
  // which the bounded-cycle test needs anyway). Same levers as Impl::motion.
  MotionBounds step;
  bool is_behind = false;            // kinematics_behind at the step's start: step is used
  std::vector<std::uint8_t> is_step_bound_known;  // per primitive: computed this cycle
  double largest_step_m = 0.0;  // the largest step bound (CycleWork::step_m)
  // Per primitive, at q (CollectSweptPairs): its box, and that grown by its reach in the step.
  // Those without levers keep theirs until a scene change (are_fixed_boxes_current).
  std::vector<Aabb> box_W;
  std::vector<Aabb> grown_W;
  bool are_fixed_boxes_current = false;
  std::vector<std::uint8_t> leaves_slack;  // per primitive: may leave its slack in the step
  std::vector<PrimitiveId> leavers;        // those that may, in order
  std::vector<PrimitiveId> near;           // the indexed ones whose boxes meet the leavers' hull
  BoxArray grown_by_id_W;  // per id: grown_W, NaN if not indexed (ScanSweptPairs)
  std::vector<std::uint64_t> leaver_words;  // bit id % 64 of word id / 64: leaves_slack
  // At the step's start, when has_start_displacement (the index unchanged since the last
  // kinematics): the last kinematics' q. A bound on a primitive's displacement at q_start adds
  // its motion since to its displacement then (Impl::StartDisplacement_m, only for the few
  // primitives that need it).
  Eigen::VectorXd q_kinematics;
  bool has_start_displacement = false;
  bool is_since_kinematics_set = false;  // Impl::motion holds q_kinematics -> q_start
  std::vector<SweptPair> pairs;            // pairs of those besides the kept ones, in order
  // Per primitive: its box at q_start, made on first use in a step (IsClearFromBothEnds) when
  // its start_box_step is not this step's step_count (64 bits: never wraps).
  std::vector<Aabb> start_box_W;
  std::vector<std::uint64_t> start_box_step;
  std::uint64_t step_count = 0;
  // Depth-first bisection: at most one pending sibling per level, plus the current interval.
  std::array<SweptInterval, kMaxSweptBisections + 2> stack;
};

}  // namespace arm_collision_monitor
