// Boxes kept as arrays of their bounds (structure of arrays), scanned against one query box
// without branches: one overlap bit per box, 64 boxes to a word, then only the few boxes whose
// bits are set are looked at (one count-trailing-zeros each). The scan runs on float copies of
// the bounds, four or eight boxes per instruction: rounding to nearest is monotone (x <= y gives
// float(x) <= float(y)), so it flags every box the exact test would, and a few more; each
// flagged box is then decided by the exact double test before it is handed out. The brute-force
// lists of the broad phases use it: NaiveBroadPhase's every present primitive, CellBroadPhase's
// primitives outside the world cube and unlinked from its cells; so does the Monitor's swept
// check, for the grown boxes of a step with many primitives leaving their slack.
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
  /// Whether the box in `slot` overlaps `box_W` (Aabb::Overlaps, exactly: NaN meets nothing).
  bool Overlaps(std::uint32_t slot, const Aabb& box_W) const {
    return lo_W_[0][slot] <= box_W.max_W.x() && box_W.min_W.x() <= hi_W_[0][slot] &&
           lo_W_[1][slot] <= box_W.max_W.y() && box_W.min_W.y() <= hi_W_[1][slot] &&
           lo_W_[2][slot] <= box_W.max_W.z() && box_W.min_W.z() <= hi_W_[2][slot];
  }
  /// Moves the last box into `slot` and drops the last (as SwapRemove on the ids' list).
  void SwapRemove(std::uint32_t slot);
  /// Drops the last box.
  void PopBack() { --size_; }
  /// Drops every box (the capacity stays).
  void Clear() { size_ = 0; }

  /// The scan's code: the best the CPU has (the default: AVX2, else SSE2 on x86-64; elsewhere
  /// the portable one), or one forced for every BoxArray (tests; kAvx2 only where the CPU has
  /// it, as kBest).
  enum class ScanPath : std::uint8_t { kBest, kPortable, kSse2, kAvx2 };
  static void ForceScanPath(ScanPath path);

  /// Flags every box that may overlap `box_W`, for ForEachHit (which decides them exactly, as
  /// Aabb::Overlaps on closed boxes: a NaN bound on either side overlaps nothing); returns the
  /// boxes tested (size()).
  std::uint32_t MarkOverlaps(const Aabb& box_W);
  /// The last MarkOverlaps' flags, bit slot % 64 of word slot / 64 (size() + 63) / 64 words:
  /// every box that overlaps its box and a few more (float bounds), each still to be decided
  /// exactly (Overlaps).
  const std::uint64_t* hit_words() const { return hit_words_.data(); }
  /// Calls f(slot) for every box that overlaps the last MarkOverlaps' box, in slot order (the
  /// boxes must not change in between). Returns the flagged boxes decided exactly.
  template <typename F>
  std::uint32_t ForEachHit(F&& f) const {
    return ForEachHit([](std::uint32_t) { return ~std::uint64_t{0}; }, f);
  }
  /// The same for the boxes whose bits survive `keep(w)`, a mask for word w (slots 64 w ..
  /// 64 w + 63): only those are decided exactly.
  template <typename Keep, typename F>
  std::uint32_t ForEachHit(Keep&& keep, F&& f) const {
    return ForEachHitOf(query_W_, keep, f);
  }
  /// ForEachHit for a box `box_W` inside the last MarkOverlaps' box (one of several whose hull
  /// it scanned: every box meeting box_W is flagged): f(slot) for each flagged box whose bit
  /// survives keep(w) and that overlaps box_W exactly, in slot order.
  template <typename Keep, typename F>
  std::uint32_t ForEachHitOf(const Aabb& box_W, Keep&& keep, F&& f) const;

 private:
  std::array<std::vector<double>, 3> lo_W_, hi_W_;  // per slot and axis: min, max
  // The same rounded to float (NaN stays NaN), padded to a multiple of 8 slots.
  std::array<std::vector<float>, 3> lo_f_, hi_f_;
  std::vector<std::uint64_t> hit_words_;  // MarkOverlaps' flags: bit k of word w for slot 64 w + k
  Aabb query_W_;                          // MarkOverlaps' box
  std::uint32_t size_ = 0;
};

template <typename Keep, typename F>
std::uint32_t BoxArray::ForEachHitOf(const Aabb& box_W, Keep&& keep, F&& f) const {
  const std::uint32_t word_count = (size_ + 63) / 64;
  std::uint32_t decided = 0;
  for (std::uint32_t w = 0; w < word_count; ++w) {
    const std::uint64_t hits = hit_words_[w];
    if (hits == 0) continue;
    for (std::uint64_t bits = hits & keep(w); bits != 0; bits &= bits - 1) {
      const std::uint32_t slot = 64 * w + static_cast<std::uint32_t>(__builtin_ctzll(bits));
      ++decided;
      if (Overlaps(slot, box_W)) f(slot);
    }
  }
  return decided;
}

}  // namespace arm_collision_monitor
