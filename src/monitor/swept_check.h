// The swept check's per-cycle scratch (Monitor::Impl::swept; the algorithm is in
// swept_check.cpp). Private to the monitor module; preallocated at start-up.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/primitives.h"

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

struct SweptScratch {
  Eigen::VectorXd q_start;                 // the step's start: the last accepted q
  Eigen::VectorXd q_s;                     // a sample along the step
  std::vector<Eigen::Isometry3d> X_WL_start;  // link poses at q_start (has_start)
  std::vector<Eigen::Isometry3d> X_WL_s;      // link poses at q_s
  bool has_start = false;
  // Per primitive, at q (CollectSweptPairs): its box, and that grown by its reach in the step.
  std::vector<Aabb> box_W;
  std::vector<Aabb> grown_W;
  std::vector<std::uint8_t> leaves_slack;  // per primitive: may leave its slack in the step
  std::vector<PrimitiveId> leavers;        // those that may, in order
  std::vector<PrimitiveId> near;           // those whose grown box meets the leavers', in order
  // Per primitive: a bound on its displacement from its indexed copy at q_start (m), when
  // has_start_displacement (the index unchanged since the last kinematics).
  std::vector<double> start_displacement_m;
  bool has_start_displacement = false;
  std::vector<std::uint8_t> is_reindexed;  // per primitive, this cycle (scratch)
  std::vector<SweptPair> pairs;            // pairs of those besides the kept ones, in order
  // Depth-first bisection: at most one pending sibling per level, plus the current interval.
  std::array<SweptInterval, kMaxSweptBisections + 2> stack;
};

}  // namespace arm_collision_monitor
