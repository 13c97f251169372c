// The reference broad phase: every moving primitive against every present primitive. No
// spatial structure, so nothing to get wrong; every other broad phase is tested against it.
// The boxes are a BoxArray whose slot is the primitive id (an absent id's box is NaN, which
// overlaps nothing), scanned without branches per query; the scan's hit words are then masked
// a word at a time by the compatibility matrix's row, which is in id order too, so no hit is
// looked at only to be dropped as compatible, static-static or the query itself.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/box_array.h"
#include "arm_collision_monitor/broadphase/broad_phase.h"

namespace arm_collision_monitor {

/// All pairs (Jolt keeps a brute-force broad phase as its reference the same way). Work per
/// cycle is (moving primitives) x (highest present id + 1): linear in the scene size.
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
  /// One scan for the hull of the group's boxes; each member then decides only the hull's hits.
  bool FindPairsOfGroup(const PrimitiveId* ids, std::uint32_t count,
                        const CompatibilityMatrix& compatible,
                        std::vector<CandidatePair>* pairs) override;
  /// The flag words and the present count agree with the entries, every absent id's slot below
  /// the scan's end is NaN, and the scan ends just past the highest present id.
  bool Validate(std::string* why) const override;

  /// Sizes the per-id arrays for ids < max_primitives so that Add() does not allocate.
  void Reserve(std::uint32_t max_primitives);

 private:
  struct Entry {
    double tolerance_m = 0.0;
    Motion motion = Motion::kStatic;
    bool present = false;
  };
  // Appends the pairs of `id` (its box marked in boxes_ last) whose bits survive
  // keep(word index) (and `compatible`'s row of id), for b ascending.
  template <typename Keep>
  void TakeHits(PrimitiveId id, const CompatibilityMatrix& compatible, Keep&& keep,
                std::vector<CandidatePair>* pairs) const;

  std::vector<Entry> entries_;              // indexed by id
  // Slot = id, the tight box grown by the tolerance (what pairs are decided on); NaN for an
  // absent id. size(): the highest present id + 1, so the scan ends there.
  BoxArray boxes_;
  // Bit id % 64 of word id / 64: present and static; present and moving.
  std::vector<std::uint64_t> static_bits_, moving_bits_;
  // FindPairsOfGroup's scratch, the same layout: the group's members.
  std::vector<std::uint64_t> group_bits_;
  std::uint32_t present_count_ = 0;
};

}  // namespace arm_collision_monitor
