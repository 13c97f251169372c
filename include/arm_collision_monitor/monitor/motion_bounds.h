// Joint-space motion bounds for the Monitor's bounded cycles: how far a primitive carried by a
// link can have moved between two joint vectors, from the joint deltas alone (no kinematics).
// Per joint j above the link, a point moves by at most |delta q_j| times its lever arm about
// j's axis (1 for a prismatic joint, |multiplier| times that for a mimic joint); summed over the
// chain by the triangle inequality. The levers are fixed per (primitive, carrier link): they
// change only when Attach / Detach change an object's carrier.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/geometry/primitives.h"
#include "arm_collision_monitor/kinematics/kinematic_model.h"

namespace arm_collision_monitor {

/// Largest displacement (m) of a defining point between two poses of the same primitive: the
/// endpoints of a capsule, the vertices of a box. The displacement of a rigid motion is affine
/// in the point, so this bounds the displacement of every point of the shape. Capsules (every
/// moving link's, every kinematics cycle) inline.
double MaxBoxVertexDisplacement_m(const Box& before, const Box& after);
inline double MaxPointDisplacement_m(const Shape& before, const Shape& after) {
  const auto* c0 = std::get_if<Capsule>(&before);
  if (c0 == nullptr) return MaxBoxVertexDisplacement_m(std::get<Box>(before), std::get<Box>(after));
  const Capsule& c1 = std::get<Capsule>(after);
  return std::sqrt(
      std::max((c1.p0_W - c0->p0_W).squaredNorm(), (c1.p1_W - c0->p1_W).squaredNorm()));
}

/// Over a stretch of motion along which a pair's distance (or a point's displacement) changes
/// by at most `motion_m` in all -- it is 1-Lipschitz in the motion -- and which starts at d0_m
/// and ends at d1_m: after motion m it is within [d0 - m, d0 + m] and [d1 - (P - m), d1 + (P -
/// m)]. The smallest value it can take is then (d0 + d1 - P) / 2, the largest (d0 + d1 + P) / 2
/// (conservative advancement's bounds on an interval; still bounds when d0 and d1 are only a
/// lower, resp. upper, bound). NaN stays NaN.
inline double SmallestOverStretch_m(double d0_m, double d1_m, double motion_m) {
  return 0.5 * (d0_m + d1_m - motion_m);
}
inline double LargestOverStretch_m(double d0_m, double d1_m, double motion_m) {
  return 0.5 * (d0_m + d1_m + motion_m);
}

/// The index into q that drives `joint` (its own, or the one it mimics); -1 if it does not move.
int DrivingQIndex(const JointSpec& joint);

/// Per-primitive levers over a kinematic chain, and the motion bounds they give for a joint
/// motion (see the file comment). Built once per model; SetCarrier allocates nothing.
class MotionBounds {
 public:
  /// One moving joint above a primitive: its points move by at most |delta q[q_index]| times
  /// m_per_unit (m per rad for a revolute joint, per m for a prismatic one).
  struct Lever {
    int q_index = 0;
    double m_per_unit = 0.0;
  };

  MotionBounds() = default;
  /// Start-up: the chain structure of `model` (which must outlive this) for `primitive_count`
  /// primitives, none carried yet.
  MotionBounds(const KinematicModel& model, std::uint32_t primitive_count);

  /// Primitive `id` is carried by `link` (-1: by none) with shape `shape_L` in the link frame;
  /// it gets levers only when `is_moving` (a primitive on a link fixed to the root has none).
  void SetCarrier(PrimitiveId id, int link, bool is_moving, const Shape& shape_L);

  /// The levers of `id` from its link upward; lever_count(id) of them.
  int lever_count(PrimitiveId id) const { return lever_count_[id]; }
  const Lever* levers(PrimitiveId id) const {
    return &levers_[static_cast<std::size_t>(id) * max_levers_];
  }

  /// Per cycle: the joint motion |q - q_from| that the following bounds are for.
  void SetJointMotion(const Eigen::Ref<const Eigen::VectorXd>& q,
                      const Eigen::Ref<const Eigen::VectorXd>& q_from) {
    dq_abs_.head(q.size()) = (q - q_from).cwiseAbs();
  }
  /// Per cycle, for a whole step: a joint motion that bounds |q - q_from| for every q on the
  /// straight path from q0 to q1, joint by joint the larger of its two ends' (|.| of an affine
  /// function is convex, so its largest value on a segment is at an end).
  void SetSegmentMotion(const Eigen::Ref<const Eigen::VectorXd>& q0,
                        const Eigen::Ref<const Eigen::VectorXd>& q1,
                        const Eigen::Ref<const Eigen::VectorXd>& q_from) {
    dq_abs_.head(q0.size()) = (q0 - q_from).cwiseAbs().cwiseMax((q1 - q_from).cwiseAbs());
  }
  /// Bound (m) on the motion of every point of `id` for the joint motion set last (0 without
  /// levers); keeps its partial sums for PairBound_m. NaN when a delta is NaN.
  double ComputeBound_m(PrimitiveId id) {
    const int count = lever_count_[id];
    const Lever* l = levers(id);
    double* sums = LeverSums(id);
    for (int k = 0; k < count; ++k) sums[k + 1] = sums[k] + dq_abs_[l[k].q_index] * l[k].m_per_unit;
    return sums[count];
  }
  /// After SetCarrier calls: finds the undominated primitives now (a scene change), not in the
  /// cycle whose ComputeLargestBound_m would otherwise (O(moving x all) Covers tests).
  void PrepareLargestBound() {
    if (is_undominated_stale_) FindUndominated();
  }
  /// The largest ComputeBound_m over all primitives for the joint motion set last (m; 0 when
  /// none has levers), computed over the undominated ones only: a primitive each of whose
  /// levers another matches on the same joint with one no smaller never has the larger bound.
  /// The set is rebuilt after SetCarrier (no allocation). Their sums are taken kLanes at a time
  /// (independent chains of additions, in each primitive's lever order: bit for bit its
  /// ComputeBound_m), leaving the lever sums of PairBound_m as they were.
  double ComputeLargestBound_m();
  /// The most primitives with levers among which the undominated ones are searched; with more,
  /// all are kept.
  static constexpr std::size_t kMaxDominanceSearch = 256;
  /// The bound ComputeBound_m(id) returned last (m).
  double bound_m(PrimitiveId id) const { return LeverSums(id)[lever_count_[id]]; }
  /// After ComputeBound_m of both (of those with levers): how far a and b can have moved
  /// relative to each other (m). The joints above both carriers' lowest common ancestor move
  /// both alike and leave their distance unchanged, so they are left out.
  double PairBound_m(PrimitiveId a, PrimitiveId b) const {
    const int la = carrier_[a], lb = carrier_[b];
    // Slot 0 (0 m) for one without levers: its link is -1 or fixed to the root, which shares
    // no moving joint with any other.
    const int shared =
        la >= 0 && lb >= 0 ? shared_levers_[static_cast<std::size_t>(la) * link_count_ + lb] : 0;
    return LeverSums(a)[lever_count_[a] - shared] + LeverSums(b)[lever_count_[b] - shared];
  }

  /// Checks the invariants: every carrier is a link or -1; a primitive has either no levers or
  /// one per moving joint above its link, each driven by a valid q index with a lever >= 0
  /// (+inf for unlimited prismatic travel; NaN would void the sums). False with the first
  /// violation in `why`.
  bool Validate(std::string* why) const;

 private:
  // Whether every lever of p is matched by one of r on the same joint, no smaller.
  bool Covers(PrimitiveId r, PrimitiveId p) const;
  void FindUndominated();
  // Slot k: the motion bound from primitive id's k lowest levers (slot 0 is 0).
  double* LeverSums(PrimitiveId id) {
    return &lever_sums_m_[static_cast<std::size_t>(id) * (max_levers_ + 1)];
  }
  const double* LeverSums(PrimitiveId id) const {
    return &lever_sums_m_[static_cast<std::size_t>(id) * (max_levers_ + 1)];
  }

  const KinematicModel* model_ = nullptr;
  int link_count_ = 0;
  int max_levers_ = 0;                        // moving joints above the deepest link
  std::vector<int> link_depth_;               // per link: moving joints from it up to the root
  std::vector<std::uint8_t> shared_levers_;   // link x link: link_depth_ of their lowest
                                              // common ancestor
  std::vector<int> carrier_;                  // per primitive, -1 for none or when not moving
  std::vector<Lever> levers_;                 // per primitive, max_levers_ slots
  std::vector<int> lever_count_;              // per primitive
  std::vector<double> lever_sums_m_;          // per primitive, max_levers_ + 1 slots
  std::vector<PrimitiveId> undominated_;      // ComputeLargestBound_m's primitives
  // ComputeLargestBound_m's levers: undominated_ in groups of kLanes, per group max_levers_
  // slots, slot k holding each lane's k-th lever; slots past a primitive's levers, and lanes
  // past the last primitive, hold a 0 m lever on the extra joint motion slot (always 0).
  static constexpr int kLanes = 4;
  struct LeverLanes {
    int q_index[kLanes];
    double m_per_unit[kLanes];
  };
  std::vector<LeverLanes> lever_lanes_;
  bool is_undominated_stale_ = true;          // SetCarrier since they were found
  Eigen::VectorXd dq_abs_;                    // |q - q_from| of the last SetJointMotion,
                                              // then one 0 (the padding levers' joint)
};

}  // namespace arm_collision_monitor
