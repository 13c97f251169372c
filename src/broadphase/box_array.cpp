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

// hits[s] = 1 when box s (bounds lo_*[s], hi_*[s]) and `box_W` overlap as closed boxes, as
// Aabb::Overlaps (NaN: 0), else 0. With AVX2 the compiler runs the loop on four boxes at a time
// (SSE2 alone cannot pack double compares into 64-bit flags, and leaves it scalar).
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

}  // namespace

void BoxArray::Reserve(std::size_t capacity) {
  if (lo_W_[0].size() >= capacity) return;
  for (int axis = 0; axis < 3; ++axis) {
    lo_W_[axis].resize(capacity, 0.0);
    hi_W_[axis].resize(capacity, 0.0);
  }
  hits_.resize(RoundUpToBlock(capacity), 0);
}

void BoxArray::PushBack(const Aabb& box_W) {
  // Grows by half when full (only beyond Reserve's capacity).
  if (size_ >= lo_W_[0].size()) Reserve(size_ + size_ / 2 + 1);
  Set(size_++, box_W);  // its flag is 0: it was past the last slot
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
  hits_[size_] = 0;
}

std::uint32_t BoxArray::MarkOverlaps(const Aabb& box_W) {
  MarkOverlapsOf(lo_W_[0].data(), hi_W_[0].data(), lo_W_[1].data(), hi_W_[1].data(),
                 lo_W_[2].data(), hi_W_[2].data(), box_W, size_, hits_.data());
  return size_;
}

}  // namespace arm_collision_monitor
