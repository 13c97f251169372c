// Boxes as arrays of bounds, scanned without branches (see box_array.h).
#include "arm_collision_monitor/broadphase/box_array.h"

#include <algorithm>
#include <limits>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace arm_collision_monitor {
namespace {

/// The float bounds of the scan: per axis the slots' min and max, and the query's.
struct FloatScan {
  const float* lo[3];
  const float* hi[3];
  float q_lo[3], q_hi[3];
};

// Bits of `count` slots into hit_words, one slot at a time: any CPU.
void ScanPortable(const FloatScan& s, std::size_t count, std::uint64_t* hit_words) {
  for (std::size_t first = 0; first < count; first += 64) {
    const std::size_t end = std::min(first + 64, count);
    std::uint64_t word = 0;
    for (std::size_t k = first; k < end; ++k) {
      bool in = true;
      for (int a = 0; a < 3; ++a) in = in && s.lo[a][k] <= s.q_hi[a] && s.q_lo[a] <= s.hi[a][k];
      word |= static_cast<std::uint64_t>(in) << (k - first);
    }
    hit_words[first / 64] = word;
  }
}

BoxArray::ScanPath forced_scan_path = BoxArray::ScanPath::kBest;  // ForceScanPath's

#if defined(__x86_64__) && defined(__GNUC__)
// Bits of `count` slots (a multiple of 8 is read) into hit_words, x86-64: four slots per SSE2
// compare, or eight per AVX2 compare on a CPU that has it (picked once at load time).
void ScanSse2(const FloatScan& s, std::size_t count, std::uint64_t* hit_words) {
  __m128 q_lo[3], q_hi[3];
  for (int a = 0; a < 3; ++a) {
    q_lo[a] = _mm_set1_ps(s.q_lo[a]);
    q_hi[a] = _mm_set1_ps(s.q_hi[a]);
  }
  for (std::size_t first = 0; first < count; first += 64) {
    const std::size_t end = std::min(first + 64, count);
    std::uint64_t word = 0;
    for (std::size_t k = first; k < end; k += 4) {
      __m128 in = _mm_and_ps(_mm_cmple_ps(_mm_loadu_ps(s.lo[0] + k), q_hi[0]),
                             _mm_cmple_ps(q_lo[0], _mm_loadu_ps(s.hi[0] + k)));
      for (int a = 1; a < 3; ++a) {
        in = _mm_and_ps(in, _mm_and_ps(_mm_cmple_ps(_mm_loadu_ps(s.lo[a] + k), q_hi[a]),
                                       _mm_cmple_ps(q_lo[a], _mm_loadu_ps(s.hi[a] + k))));
      }
      word |= static_cast<std::uint64_t>(_mm_movemask_ps(in)) << (k - first);
    }
    hit_words[first / 64] = word;
  }
}

__attribute__((target("avx2"))) void ScanAvx2(const FloatScan& s, std::size_t count,
                                              std::uint64_t* hit_words) {
  __m256 q_lo[3], q_hi[3];
  for (int a = 0; a < 3; ++a) {
    q_lo[a] = _mm256_set1_ps(s.q_lo[a]);
    q_hi[a] = _mm256_set1_ps(s.q_hi[a]);
  }
  for (std::size_t first = 0; first < count; first += 64) {
    const std::size_t end = std::min(first + 64, count);
    std::uint64_t word = 0;
    for (std::size_t k = first; k < end; k += 8) {
      __m256 in = _mm256_and_ps(_mm256_cmp_ps(_mm256_loadu_ps(s.lo[0] + k), q_hi[0], _CMP_LE_OQ),
                                _mm256_cmp_ps(q_lo[0], _mm256_loadu_ps(s.hi[0] + k), _CMP_LE_OQ));
      for (int a = 1; a < 3; ++a) {
        in = _mm256_and_ps(
            in, _mm256_and_ps(_mm256_cmp_ps(_mm256_loadu_ps(s.lo[a] + k), q_hi[a], _CMP_LE_OQ),
                              _mm256_cmp_ps(q_lo[a], _mm256_loadu_ps(s.hi[a] + k), _CMP_LE_OQ)));
      }
      word |= static_cast<std::uint64_t>(_mm256_movemask_ps(in)) << (k - first);
    }
    hit_words[first / 64] = word;
  }
}

void Scan(const FloatScan& s, std::size_t count, std::uint64_t* hit_words) {
  static const bool kHasAvx2 = __builtin_cpu_supports("avx2");
  switch (forced_scan_path) {
    case BoxArray::ScanPath::kPortable:
      return ScanPortable(s, count, hit_words);
    case BoxArray::ScanPath::kSse2:
      return ScanSse2(s, count, hit_words);
    case BoxArray::ScanPath::kBest:
    case BoxArray::ScanPath::kAvx2:
      break;
  }
  if (kHasAvx2) return ScanAvx2(s, count, hit_words);
  ScanSse2(s, count, hit_words);
}
#else
void Scan(const FloatScan& s, std::size_t count, std::uint64_t* hit_words) {
  ScanPortable(s, count, hit_words);
}
#endif

}  // namespace

void BoxArray::Reserve(std::size_t capacity) {
  if (lo_W_[0].size() >= capacity) return;
  // The scan reads whole groups of 8 float slots (MarkOverlaps clears the bits past size_).
  const std::size_t padded = (capacity + 7) / 8 * 8;
  const float nan_f = std::numeric_limits<float>::quiet_NaN();
  for (int axis = 0; axis < 3; ++axis) {
    lo_W_[axis].resize(capacity, 0.0);
    hi_W_[axis].resize(capacity, 0.0);
    lo_f_[axis].resize(padded, nan_f);
    hi_f_[axis].resize(padded, nan_f);
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
    lo_f_[axis][slot] = static_cast<float>(box_W.min_W[axis]);
    hi_f_[axis][slot] = static_cast<float>(box_W.max_W[axis]);
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
  PopBack();
}

void BoxArray::ForceScanPath(ScanPath path) { forced_scan_path = path; }

std::uint32_t BoxArray::MarkOverlaps(const Aabb& box_W) {
  query_W_ = box_W;
  FloatScan s;
  for (int axis = 0; axis < 3; ++axis) {
    s.lo[axis] = lo_f_[axis].data();
    s.hi[axis] = hi_f_[axis].data();
    s.q_lo[axis] = static_cast<float>(box_W.min_W[axis]);
    s.q_hi[axis] = static_cast<float>(box_W.max_W[axis]);
  }
  Scan(s, size_, hit_words_.data());
  // The scan's last group reads past size_: those slots are no boxes.
  if (size_ % 64 != 0) hit_words_[size_ / 64] &= (std::uint64_t{1} << (size_ % 64)) - 1;
  return size_;
}

}  // namespace arm_collision_monitor
