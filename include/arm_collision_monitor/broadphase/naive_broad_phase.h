// The reference broad phase: every moving primitive against every present primitive. No
// spatial structure, so nothing to get wrong; every other broad phase is tested against it.
// The present boxes are a BoxArray, scanned without branches per query.
#pragma once

#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/box_array.h"
#include "arm_collision_monitor/broadphase/broad_phase.h"

namespace arm_collision_monitor {

/// All pairs (Jolt keeps a brute-force broad phase as its reference the same way). Work per
/// cycle is (moving primitives) x (present primitives): linear in the scene size.
class NaiveBroadPhase final : public BroadPhase {
 public:
  NaiveBroadPhase() = default;

  std::string name() const override { return "naive"; }
  void Add(PrimitiveId id, const Aabb& box_W, double tolerance_m, Motion motion) override;
  void Remove(PrimitiveId id) override;
  void Move(PrimitiveId id, const Aabb& box_W) override;
  void FindPairs(const CompatibilityMatrix& compatible,
                 std::vector<CandidatePair>* pairs) override;
  void FindPairsOf(PrimitiveId id, const CompatibilityMatrix& compatible,
                   std::vector<CandidatePair>* pairs) override;

  /// Sizes the per-id arrays for ids < max_primitives so that Add() does not allocate.
  void Reserve(std::uint32_t max_primitives);

 private:
  struct Entry {
    double tolerance_m = 0.0;
    Motion motion = Motion::kStatic;
    bool present = false;
  };
  std::vector<Entry> entries_;             // indexed by id
  std::vector<PrimitiveId> present_ids_;   // dense list of present ids (order irrelevant)
  std::vector<std::uint32_t> slot_;        // id -> index in present_ids_
  // Per slot of present_ids_: the tight box grown by the tolerance (what pairs are decided on).
  BoxArray boxes_;
  std::vector<PrimitiveId> moving_ids_;    // dense list of present moving ids
  std::vector<std::uint32_t> moving_slot_; // id -> index in moving_ids_
};

}  // namespace arm_collision_monitor
