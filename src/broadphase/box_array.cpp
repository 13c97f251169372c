// Boxes as arrays of bounds, scanned without branches (see box_array.h).
#include "arm_collision_monitor/broadphase/box_array.h"

#include <algorithm>

namespace arm_collision_monitor {
namespace {

// An AVX2 copy of a function beside the portable one, picked at load time by the CPU (GCC and
// clang function multi-versioning); elsewhere than x86-64 only the portable one.
#if defined(__x86_64__) && defined(__GNUC__)
#define ACM_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define ACM_AVX2_CLONE
#endif

// Bit k of hit_words[w] set when box 64 w + k (bounds lo_*[s], hi_*[s]) and `box_W` overlap as
// closed boxes, as Aabb::Overlaps (NaN: clear), for the `count` boxes; the bits past `count`
// clear. With AVX2 the compiler runs the compares and the packing four boxes at a time (SSE2
// alone cannot pack double compares into 64-bit lanes, and leaves the loop scalar).
ACM_AVX2_CLONE void MarkOverlapsOf(
    const double* __restrict lo_x, const double* __restrict hi_x, const double* __restrict lo_y,
    const double* __restrict hi_y, const double* __restrict lo_z, const double* __restrict hi_z,
    const Aabb& box_W, std::size_t count, std::uint64_t* __restrict hit_words) {
  const double x0 = box_W.min_W.x(), y0 = box_W.min_W.y(), z0 = box_W.min_W.z();
  const double x1 = box_W.max_W.x(), y1 = box_W.max_W.y(), z1 = box_W.max_W.z();
  for (std::size_t first = 0; first < count; first += 64) {
    const std::size_t n = std::min<std::size_t>(64, count - first);
    std::uint64_t word = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t s = first + k;
      const std::uint64_t in_x = (lo_x[s] <= x1) & (x0 <= hi_x[s]);
      const std::uint64_t in_y = (lo_y[s] <= y1) & (y0 <= hi_y[s]);
      const std::uint64_t in_z = (lo_z[s] <= z1) & (z0 <= hi_z[s]);
      word |= (in_x & in_y & in_z) << k;
    }
    hit_words[first / 64] = word;
  }
}

}  // namespace

void BoxArray::Reserve(std::size_t capacity) {
  if (lo_W_[0].size() >= capacity) return;
  for (int axis = 0; axis < 3; ++axis) {
    lo_W_[axis].resize(capacity, 0.0);
    hi_W_[axis].resize(capacity, 0.0);
  }
  hit_words_.resize((capacity + 63) / 64, 0);
}

void BoxArray::PushBack(const Aabb& box_W) {
  // Grows by half when full (only beyond Reserve's capacity).
  if (size_ >= lo_W_[0].size()) Reserve(size_ + size_ / 2 + 1);
  Set(size_++, box_W);
}

void BoxArray::Set(std::uint32_t slot, const Aabb& box_W) {
  for (int axis = 0; axis < 3; ++axis) {
    lo_W_[axis][slot] = box_W.min_W[axis];
    hi_W_[axis][slot] = box_W.max_W[axis];
  }
}

Aabb BoxArray::Get(std::uint32_t slot) const {
  Aabb box_W;
  for (int axis = 0; axis < 3; ++axis) {
    box_W.min_W[axis] = lo_W_[axis][slot];
    box_W.max_W[axis] = hi_W_[axis][slot];
  }
  return box_W;
}

void BoxArray::SwapRemove(std::uint32_t slot) {
  Set(slot, Get(size_ - 1));
  --size_;
}

std::uint32_t BoxArray::MarkOverlaps(const Aabb& box_W) {
  MarkOverlapsOf(lo_W_[0].data(), hi_W_[0].data(), lo_W_[1].data(), hi_W_[1].data(),
                 lo_W_[2].data(), hi_W_[2].data(), box_W, size_, hit_words_.data());
  return size_;
}

}  // namespace arm_collision_monitor
