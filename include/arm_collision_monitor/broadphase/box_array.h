// Boxes kept as six arrays of their bounds (structure of arrays), scanned against one query box
// without branches: one 64-bit overlap flag per box, then only the few boxes that meet it are
// looked at. The brute-force lists of the broad phases use it: NaiveBroadPhase's every present
// primitive, CellBroadPhase's primitives outside the world cube.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// A dense list of boxes, slot 0 .. size() - 1, in step with a caller's list of ids.
/// Nothing allocates while size() stays within Reserve's capacity.
class BoxArray {
 public:
  void Reserve(std::size_t capacity);
  std::uint32_t size() const { return size_; }
  void PushBack(const Aabb& box_W);
  void Set(std::uint32_t slot, const Aabb& box_W);
  Aabb Get(std::uint32_t slot) const;
  /// Moves the last box into `slot` and drops the last (as SwapRemove on the ids' list).
  void SwapRemove(std::uint32_t slot);

  /// Flags every box that overlaps `box_W` as closed boxes (Aabb::Overlaps: a NaN bound on
  /// either side overlaps nothing), for ForEachHit; returns the boxes tested (size()).
  std::uint32_t MarkOverlaps(const Aabb& box_W);
  /// Calls f(slot) for every box flagged by the last MarkOverlaps, in slot order (the boxes
  /// must not change in between).
  template <typename F>
  void ForEachHit(F&& f) const;

 private:
  // Flags come in blocks of this many: a block without a hit is skipped at once.
  static constexpr std::uint32_t kHitBlock = 8;
  static std::size_t RoundUpToBlock(std::size_t count) {
    return (count + kHitBlock - 1) / kHitBlock * kHitBlock;
  }

  std::array<std::vector<double>, 3> lo_W_, hi_W_;  // per slot and axis: min, max
  std::vector<std::int64_t> hits_;  // per slot, zero from size_ to the next block boundary
  std::uint32_t size_ = 0;
};

template <typename F>
void BoxArray::ForEachHit(F&& f) const {
  const std::int64_t* hits = hits_.data();
  for (std::uint32_t block = 0; block < size_; block += kHitBlock) {
    std::int64_t any = 0;
    for (std::uint32_t s = block; s < block + kHitBlock; ++s) any |= hits[s];
    if (any == 0) continue;
    for (std::uint32_t s = block; s < block + kHitBlock; ++s) {
      if (hits[s] != 0) f(s);
    }
  }
}

}  // namespace arm_collision_monitor
