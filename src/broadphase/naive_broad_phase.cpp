#include "arm_collision_monitor/broadphase/naive_broad_phase.h"

#include <algorithm>
#include <cstdint>

#include "arm_collision_monitor/broadphase/broad_phase_util.h"

namespace arm_collision_monitor {
namespace {

// Hit flags come in blocks of this many (ForEachHit).
constexpr std::size_t kHitBlock = 8;
std::size_t RoundUpToBlock(std::size_t count) {
  return (count + kHitBlock - 1) / kHitBlock * kHitBlock;
}

// An AVX2 copy of a function beside the portable one, picked at load time by the CPU (GCC and
// clang function multi-versioning); elsewhere than x86-64 only the portable one.
#if defined(__x86_64__) && defined(__GNUC__)
#define ACM_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define ACM_AVX2_CLONE
#endif

// hits[s] = 1 when box s (bounds lo_*[s], hi_*[s]) and `box_W` overlap as closed boxes, as
// Aabb::Overlaps (NaN: 0). One 64-bit flag per box and no branch: with AVX2 the compiler runs
// the loop on four boxes at a time (SSE2 alone has no 64-bit integer compare results to pack).
ACM_AVX2_CLONE void MarkOverlapsOf(
    const double* __restrict lo_x, const double* __restrict hi_x, const double* __restrict lo_y,
    const double* __restrict hi_y, const double* __restrict lo_z, const double* __restrict hi_z,
    const Aabb& box_W, std::size_t count, std::int64_t* __restrict hits) {
  const double x0 = box_W.min_W.x(), y0 = box_W.min_W.y(), z0 = box_W.min_W.z();
  const double x1 = box_W.max_W.x(), y1 = box_W.max_W.y(), z1 = box_W.max_W.z();
  for (std::size_t s = 0; s < count; ++s) {
    const std::int64_t in_x = (lo_x[s] <= x1) & (x0 <= hi_x[s]);
    const std::int64_t in_y = (lo_y[s] <= y1) & (y0 <= hi_y[s]);
    const std::int64_t in_z = (lo_z[s] <= z1) & (z0 <= hi_z[s]);
    hits[s] = in_x & in_y & in_z;
  }
}

// Calls f(s) for every slot s < count with hits[s] set, in order; hits is zero from count up to
// the next multiple of kHitBlock, so whole blocks without a hit are skipped at once.
template <typename F>
void ForEachHit(const std::int64_t* hits, std::size_t count, F&& f) {
  for (std::size_t block = 0; block < count; block += kHitBlock) {
    std::int64_t any = 0;
    for (std::size_t s = block; s < block + kHitBlock; ++s) any |= hits[s];
    if (any == 0) continue;
    for (std::size_t s = block; s < block + kHitBlock; ++s) {
      if (hits[s] != 0) f(static_cast<std::uint32_t>(s));
    }
  }
}

}  // namespace

void NaiveBroadPhase::Reserve(std::uint32_t max_primitives) {
  if (entries_.size() < max_primitives) {
    entries_.resize(max_primitives);
    slot_.resize(max_primitives, 0);
    moving_slot_.resize(max_primitives, 0);
    for (int axis = 0; axis < 3; ++axis) {
      lo_W_[axis].resize(max_primitives, 0.0);
      hi_W_[axis].resize(max_primitives, 0.0);
    }
    hits_.resize(RoundUpToBlock(max_primitives), 0);
  }
  present_ids_.reserve(max_primitives);
  moving_ids_.reserve(max_primitives);
}

void NaiveBroadPhase::SetSlotBox(std::uint32_t slot, const Aabb& inflated_W) {
  for (int axis = 0; axis < 3; ++axis) {
    lo_W_[axis][slot] = inflated_W.min_W[axis];
    hi_W_[axis][slot] = inflated_W.max_W[axis];
  }
}

Aabb NaiveBroadPhase::SlotBox(std::uint32_t slot) const {
  Aabb box;
  for (int axis = 0; axis < 3; ++axis) {
    box.min_W[axis] = lo_W_[axis][slot];
    box.max_W[axis] = hi_W_[axis][slot];
  }
  return box;
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
  SetSlotBox(slot_[id], box_W.Inflated(tolerance_m));
  if (motion == Motion::kMoving) {
    moving_slot_[id] = static_cast<std::uint32_t>(moving_ids_.size());
    moving_ids_.push_back(id);
  }
}

void NaiveBroadPhase::Remove(PrimitiveId id) {
  if (id >= entries_.size() || !entries_[id].present) return;
  Entry& e = entries_[id];
  // The last slot's box moves with its id into the freed slot.
  const std::uint32_t last = static_cast<std::uint32_t>(present_ids_.size() - 1);
  SetSlotBox(slot_[id], SlotBox(last));
  SwapRemove(&present_ids_, &slot_, slot_[id]);
  if (e.motion == Motion::kMoving) SwapRemove(&moving_ids_, &moving_slot_, moving_slot_[id]);
  e.present = false;
}

void NaiveBroadPhase::Move(PrimitiveId id, const Aabb& box_W) {
  if (id >= entries_.size() || !entries_[id].present) return;
  SetSlotBox(slot_[id], box_W.Inflated(entries_[id].tolerance_m));
}

void NaiveBroadPhase::MarkOverlaps(const Aabb& box_W) {
  const std::size_t count = present_ids_.size();
  MarkOverlapsOf(lo_W_[0].data(), hi_W_[0].data(), lo_W_[1].data(), hi_W_[1].data(),
                 lo_W_[2].data(), hi_W_[2].data(), box_W, count, hits_.data());
  std::fill(hits_.begin() + count, hits_.begin() + RoundUpToBlock(count), 0);
  counters_.object_object_tests += count;
}

void NaiveBroadPhase::FindPairs(const CompatibilityMatrix& compatible,
                                std::vector<CandidatePair>* pairs) {
  pairs->clear();
  for (const PrimitiveId a : moving_ids_) {
    MarkOverlaps(SlotBox(slot_[a]));
    ForEachHit(hits_.data(), present_ids_.size(), [&](std::uint32_t s) {
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
  MarkOverlaps(SlotBox(slot_[id]));
  ForEachHit(hits_.data(), present_ids_.size(), [&](std::uint32_t s) {
    const PrimitiveId b = present_ids_[s];
    if (b == id || (is_static && entries_[b].motion == Motion::kStatic)) return;
    if (IsCompatiblePair(compatible, id, b)) return;
    pairs->push_back(MakeOrderedPair(id, b));
  });
  std::sort(pairs->begin(), pairs->end());
}

}  // namespace arm_collision_monitor
