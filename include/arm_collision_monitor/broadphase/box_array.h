// Boxes kept as six arrays of their bounds (structure of arrays), scanned against one query box
// without branches: one overlap bit per box, 64 boxes to a word, then only the few boxes whose
// bits are set are looked at (one count-trailing-zeros each). The brute-force lists of the
// broad phases use it: NaiveBroadPhase's every present primitive, CellBroadPhase's primitives
// outside the world cube.
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
  std::array<std::vector<double>, 3> lo_W_, hi_W_;  // per slot and axis: min, max
  std::vector<std::uint64_t> hit_words_;  // MarkOverlaps' flags: bit k of word w for slot 64 w + k
  std::uint32_t size_ = 0;
};

template <typename F>
void BoxArray::ForEachHit(F&& f) const {
  const std::uint32_t word_count = (size_ + 63) / 64;
  for (std::uint32_t w = 0; w < word_count; ++w) {
    for (std::uint64_t bits = hit_words_[w]; bits != 0; bits &= bits - 1) {
      f(64 * w + static_cast<std::uint32_t>(__builtin_ctzll(bits)));
    }
  }
}

}  // namespace arm_collision_monitor
