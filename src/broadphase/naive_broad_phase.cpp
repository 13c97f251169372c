#include "arm_collision_monitor/broadphase/naive_broad_phase.h"

#include <algorithm>

#include "arm_collision_monitor/broadphase/broad_phase_util.h"

namespace arm_collision_monitor {

void NaiveBroadPhase::Reserve(std::uint32_t max_primitives) {
  if (entries_.size() < max_primitives) {
    entries_.resize(max_primitives);
    slot_.resize(max_primitives, 0);
    moving_slot_.resize(max_primitives, 0);
  }
  boxes_.Reserve(max_primitives);
  present_ids_.reserve(max_primitives);
  moving_ids_.reserve(max_primitives);
}

void NaiveBroadPhase::Add(PrimitiveId id, const Aabb& box_W, double tolerance_m,
                          Motion motion) {
  if (id >= entries_.size()) Reserve(id + 1);
  Entry& e = entries_[id];
  if (e.present) return;  // precondition violated: keep the first registration
  e.tolerance_m = tolerance_m;
  e.motion = motion;
  e.present = true;
  slot_[id] = static_cast<std::uint32_t>(present_ids_.size());
  present_ids_.push_back(id);
  boxes_.PushBack(box_W.Inflated(tolerance_m));
  if (motion == Motion::kMoving) {
    moving_slot_[id] = static_cast<std::uint32_t>(moving_ids_.size());
    moving_ids_.push_back(id);
  }
}

void NaiveBroadPhase::Remove(PrimitiveId id) {
  if (id >= entries_.size() || !entries_[id].present) return;
  Entry& e = entries_[id];
  boxes_.SwapRemove(slot_[id]);
  SwapRemove(&present_ids_, &slot_, slot_[id]);
  if (e.motion == Motion::kMoving) SwapRemove(&moving_ids_, &moving_slot_, moving_slot_[id]);
  e.present = false;
}

void NaiveBroadPhase::Move(PrimitiveId id, const Aabb& box_W) {
  if (id >= entries_.size() || !entries_[id].present) return;
  boxes_.Set(slot_[id], box_W.Inflated(entries_[id].tolerance_m));
}

void NaiveBroadPhase::FindPairs(const CompatibilityMatrix& compatible,
                                std::vector<CandidatePair>* pairs) {
  pairs->clear();
  for (const PrimitiveId a : moving_ids_) {
    counters_.object_object_tests += boxes_.MarkOverlaps(boxes_.Get(slot_[a]));
    boxes_.ForEachHit([&](std::uint32_t s) {
      const PrimitiveId b = present_ids_[s];
      // A moving-moving pair is met twice; keep it from the smaller id's side only.
      if (b == a || (entries_[b].motion == Motion::kMoving && b < a)) return;
      if (IsCompatiblePair(compatible, a, b)) return;
      pairs->push_back(MakeOrderedPair(a, b));
    });
  }
  std::sort(pairs->begin(), pairs->end());
}

void NaiveBroadPhase::FindPairsOf(PrimitiveId id, const CompatibilityMatrix& compatible,
                                  std::vector<CandidatePair>* pairs) {
  pairs->clear();
  if (id >= entries_.size() || !entries_[id].present) return;
  const bool is_static = entries_[id].motion == Motion::kStatic;
  counters_.object_object_tests += boxes_.MarkOverlaps(boxes_.Get(slot_[id]));
  boxes_.ForEachHit([&](std::uint32_t s) {
    const PrimitiveId b = present_ids_[s];
    if (b == id || (is_static && entries_[b].motion == Motion::kStatic)) return;
    if (IsCompatiblePair(compatible, id, b)) return;
    pairs->push_back(MakeOrderedPair(id, b));
  });
  std::sort(pairs->begin(), pairs->end());
}

}  // namespace arm_collision_monitor
