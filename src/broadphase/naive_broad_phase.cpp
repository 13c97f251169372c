#include "arm_collision_monitor/broadphase/naive_broad_phase.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "arm_collision_monitor/broadphase/broad_phase_util.h"

namespace arm_collision_monitor {
namespace {

const Aabb kAbsentBox = Aabb::Nowhere();

/// The bits of word `w` for ids at most `id`.
std::uint64_t UpToMask(PrimitiveId id, std::uint32_t w) {
  if (w < id / 64) return ~std::uint64_t{0};
  if (w > id / 64) return 0;
  return ~std::uint64_t{0} >> (63 - id % 64);
}

void SetBit(std::vector<std::uint64_t>* words, PrimitiveId id, bool value) {
  const std::uint64_t bit = std::uint64_t{1} << (id % 64);
  std::uint64_t& word = (*words)[id / 64];
  word = value ? word | bit : word & ~bit;
}

}  // namespace

void NaiveBroadPhase::Reserve(std::uint32_t max_primitives) {
  if (entries_.size() < max_primitives) entries_.resize(max_primitives);
  const std::size_t words = (entries_.size() + 63) / 64;
  static_bits_.resize(words, 0);
  moving_bits_.resize(words, 0);
  group_bits_.resize(words, 0);
  boxes_.Reserve(entries_.size());
}

void NaiveBroadPhase::Add(PrimitiveId id, const Aabb& box_W, double tolerance_m,
                          Motion motion) {
  if (id >= entries_.size()) Reserve(id + 1);
  Entry& e = entries_[id];
  if (e.present) return;  // precondition violated: keep the first registration
  e.tolerance_m = tolerance_m;
  e.motion = motion;
  e.present = true;
  ++present_count_;
  while (boxes_.size() <= id) boxes_.PushBack(kAbsentBox);
  boxes_.Set(id, box_W.Inflated(tolerance_m));
  SetBit(motion == Motion::kMoving ? &moving_bits_ : &static_bits_, id, true);
}

void NaiveBroadPhase::Remove(PrimitiveId id) {
  if (id >= entries_.size() || !entries_[id].present) return;
  entries_[id].present = false;
  --present_count_;
  SetBit(&moving_bits_, id, false);
  SetBit(&static_bits_, id, false);
  boxes_.Set(id, kAbsentBox);
  // The scan ends past the highest present id.
  while (boxes_.size() > 0 && !entries_[boxes_.size() - 1].present) boxes_.PopBack();
}

void NaiveBroadPhase::Move(PrimitiveId id, const Aabb& box_W) {
  if (id >= entries_.size() || !entries_[id].present) return;
  boxes_.Set(id, box_W.Inflated(entries_[id].tolerance_m));
}

template <typename Keep>
void NaiveBroadPhase::TakeHits(PrimitiveId id, const CompatibilityMatrix& compatible,
                               Keep&& keep, std::vector<CandidatePair>* pairs) const {
  const std::uint64_t* compatible_row = compatible.RowWords(id);
  const std::uint32_t row_words = compatible_row != nullptr ? compatible.words_per_row() : 0;
  boxes_.ForEachHit(
      [&](std::uint32_t w) {
        return keep(w) & ~(w < row_words ? compatible_row[w] : std::uint64_t{0});
      },
      [&](std::uint32_t b) { pairs->push_back(MakeOrderedPair(id, b)); });
}

void NaiveBroadPhase::FindPairs(const CompatibilityMatrix& compatible,
                                std::vector<CandidatePair>* pairs) {
  pairs->clear();
  for (std::uint32_t word = 0; word < moving_bits_.size(); ++word) {
    for (std::uint64_t bits = moving_bits_[word]; bits != 0; bits &= bits - 1) {
      const PrimitiveId a = 64 * word + static_cast<PrimitiveId>(__builtin_ctzll(bits));
      counters_.object_object_tests += present_count_;
      boxes_.MarkOverlaps(boxes_.Get(a));
      // A moving-moving pair is met twice: kept from the smaller id's side only (which also
      // leaves out a itself).
      TakeHits(a, compatible,
               [&](std::uint32_t w) { return ~(moving_bits_[w] & UpToMask(a, w)); }, pairs);
    }
  }
  std::sort(pairs->begin(), pairs->end());
}

void NaiveBroadPhase::FindPairsOf(PrimitiveId id, const CompatibilityMatrix& compatible,
                                  std::vector<CandidatePair>* pairs) {
  pairs->clear();
  if (id >= entries_.size() || !entries_[id].present) return;
  counters_.object_object_tests += present_count_;
  boxes_.MarkOverlaps(boxes_.Get(id));
  // Ascending b: the pairs (b, id) with b < id, then (id, b), already sorted.
  if (entries_[id].motion == Motion::kStatic) {
    // Static-static pairs are never reported (id is among the static ones).
    TakeHits(id, compatible, [&](std::uint32_t w) { return ~static_bits_[w]; }, pairs);
  } else {
    const std::uint32_t self_word = id / 64;
    const std::uint64_t not_self = ~(std::uint64_t{1} << (id % 64));
    TakeHits(id, compatible,
             [&](std::uint32_t w) { return w == self_word ? not_self : ~std::uint64_t{0}; },
             pairs);
  }
}

bool NaiveBroadPhase::FindPairsOfGroup(const PrimitiveId* ids, std::uint32_t count,
                                       const CompatibilityMatrix& compatible,
                                       std::vector<CandidatePair>* pairs) {
  pairs->clear();
  Aabb hull_W = kAbsentBox;
  bool is_any_present = false;
  for (std::uint32_t k = 0; k < count; ++k) {
    const PrimitiveId id = ids[k];
    if (id >= entries_.size() || !entries_[id].present) continue;
    SetBit(&group_bits_, id, true);
    // Every box that meets a member's meets the hull; a member with a NaN bound meets nothing
    // and is left out of it (it would void the hull for the others).
    const Aabb box_W = boxes_.Get(id);
    if (box_W.min_W.hasNaN() || box_W.max_W.hasNaN()) continue;
    if (is_any_present) {
      hull_W.Enclose(box_W);
    } else {
      hull_W = box_W;
    }
    is_any_present = true;
  }
  counters_.object_object_tests += present_count_;
  // One scan for the hull; each member then decides its flags against its own box.
  boxes_.MarkOverlaps(hull_W);
  for (std::uint32_t k = 0; k < count; ++k) {
    const PrimitiveId id = ids[k];
    if (id >= entries_.size() || !entries_[id].present) continue;
    const std::uint64_t* compatible_row = compatible.RowWords(id);
    const std::uint32_t row_words = compatible_row != nullptr ? compatible.words_per_row() : 0;
    const bool is_static = entries_[id].motion == Motion::kStatic;
    // Each kept flag is one exact test.
    counters_.object_object_tests += boxes_.ForEachHitOf(
        boxes_.Get(id),
        [&](std::uint32_t w) {
          // Not compatible, not static-static, and not a member up to id (the smaller member's
          // side takes a pair of two members; itself is one of them).
          return ~(w < row_words ? compatible_row[w] : std::uint64_t{0}) &
                 ~(is_static ? static_bits_[w] : std::uint64_t{0}) &
                 ~(group_bits_[w] & UpToMask(id, w));
        },
        [&](std::uint32_t b) { pairs->push_back(MakeOrderedPair(id, b)); });
  }
  for (std::uint32_t k = 0; k < count; ++k) {
    if (ids[k] < entries_.size()) SetBit(&group_bits_, ids[k], false);
  }
  return true;
}

bool NaiveBroadPhase::Validate(std::string* why) const {
  std::uint32_t present = 0;
  std::uint32_t end = 0;
  for (PrimitiveId id = 0; id < entries_.size(); ++id) {
    const Entry& e = entries_[id];
    const bool is_moving = (moving_bits_[id / 64] >> (id % 64)) & 1;
    const bool is_static = (static_bits_[id / 64] >> (id % 64)) & 1;
    if (is_moving != (e.present && e.motion == Motion::kMoving) ||
        is_static != (e.present && e.motion == Motion::kStatic)) {
      return FailValidation(why, "naive: the flag words of id " + std::to_string(id) +
                                     " disagree with its entry");
    }
    if (!e.present) continue;
    ++present;
    end = id + 1;
  }
  if (present != present_count_ || end != boxes_.size()) {
    return FailValidation(why, "naive: " + std::to_string(present_count_) + " counted present, " +
                                   std::to_string(present) + " found; scan end " +
                                   std::to_string(boxes_.size()) + ", expected " +
                                   std::to_string(end));
  }
  for (PrimitiveId id = 0; id < end; ++id) {
    if (!entries_[id].present && !std::isnan(boxes_.Get(id).min_W.x())) {
      return FailValidation(why, "naive: absent id " + std::to_string(id) + " has a box");
    }
  }
  return true;
}

}  // namespace arm_collision_monitor
