// The index slack and the kept candidate pairs (see pair_cache.h).
#include "arm_collision_monitor/monitor/pair_cache.h"

#include <algorithm>
#include <cstring>
#include <sstream>


namespace arm_collision_monitor {

PairCache::PairCache(std::uint32_t primitive_count, std::size_t max_pairs, double slack_m,
                     double world_edge_m)
    : slack_m_(slack_m), world_edge_m_(world_edge_m) {
  const std::size_t n = primitive_count;
  indexed_W_.resize(n);
  disp_m_.assign(n, 0.0);
  indexed_f_.resize(n);
  now_f_.resize(n);
  is_indexed_f_made_.assign(n, 0);
  is_now_f_made_.assign(n, 0);
  is_now_indexed_.assign(n, 1);
  test_pairs_.resize(max_pairs);
  batch_pairs_.resize(max_pairs);
  batch_a_.resize(max_pairs);
  batch_b_.resize(max_pairs);
  batch_bound_m_.resize(max_pairs);
  pairs_.reserve(max_pairs);
  scratch_.reserve(max_pairs);
  found_.reserve(max_pairs);
  new_pairs_.reserve(max_pairs);
  reindexed_.reserve(n);
  is_reindexed_.assign(n, 0);
}

void PairCache::SetIndexed(PrimitiveId id, const Shape& shape_W) {
  indexed_W_[id] = shape_W;
  disp_m_[id] = 0.0;
  is_indexed_f_made_[id] = 0;
  is_now_f_made_[id] = 0;
  is_now_indexed_[id] = 1;
  is_stale_ = true;
}

void PairCache::Reindex(PrimitiveId id, const Shape& shape_W) {
  indexed_W_[id] = shape_W;
  is_indexed_f_made_[id] = 0;
  is_now_indexed_[id] = 1;
  disp_m_[id] = 0.0;
  reindexed_.push_back(id);
  is_reindexed_[id] = 1;
}

void PairCache::Update(BroadPhase* broad_phase, const CompatibilityMatrix& compatible,
                       const std::vector<int>* group_of) {
  UpdatePairs(broad_phase, compatible, group_of);
  for (KeptPair& kept : pairs_) {
    kept.kinematics_bound_m = KinematicsBound_m(kept);
    kept.is_exact = false;
  }
}

void PairCache::UpdatePairs(BroadPhase* broad_phase, const CompatibilityMatrix& compatible,
                            const std::vector<int>* group_of) {
  constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  if (is_stale_) {
    broad_phase->FindPairs(compatible, &found_);
    pairs_.clear();
    for (const CandidatePair& p : found_) pairs_.push_back({p, kUnknown, kUnknown, false});
    is_stale_ = false;
    return;
  }
  if (reindexed_.empty()) return;
  // The pairs of primitives that stayed within their slack keep their bounds ...
  pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(),
                              [&](const KeptPair& k) {
                                return is_reindexed_[k.pair.a] || is_reindexed_[k.pair.b];
                              }),
               pairs_.end());
  // ... and the re-indexed ones get theirs anew; a pair of two re-indexed primitives is taken
  // from the query of the smaller id (a group query has each pair within the group once).
  new_pairs_.clear();
  const std::size_t count = reindexed_.size();
  for (std::size_t first = 0; first < count;) {
    std::size_t end = first + 1;
    const int group = group_of != nullptr ? (*group_of)[reindexed_[first]] : -1;
    while (group >= 0 && end < count && (*group_of)[reindexed_[end]] == group) ++end;
    const PrimitiveId* ids = &reindexed_[first];
    const auto size = static_cast<std::uint32_t>(end - first);
    if (size > 1 && broad_phase->FindPairsOfGroup(ids, size, compatible, &found_)) {
      for (std::uint32_t k = 0; k < size; ++k) is_reindexed_[ids[k]] = kInGroup;
      for (const CandidatePair& p : found_) {
        // Either member, when both are in the group.
        const PrimitiveId member = is_reindexed_[p.a] == kInGroup ? p.a : p.b;
        const PrimitiveId other = member == p.a ? p.b : p.a;
        if (is_reindexed_[other] == 1 && other < member) continue;
        new_pairs_.push_back(p);
      }
      for (std::uint32_t k = 0; k < size; ++k) is_reindexed_[ids[k]] = 1;
    } else {
      for (std::uint32_t k = 0; k < size; ++k) {
        broad_phase->FindPairsOf(ids[k], compatible, &found_);
        for (const CandidatePair& p : found_) {
          const PrimitiveId other = p.a == ids[k] ? p.b : p.a;
          if (is_reindexed_[other] && other < ids[k]) continue;
          new_pairs_.push_back(p);
        }
      }
    }
    first = end;
  }
  std::sort(new_pairs_.begin(), new_pairs_.end());
  scratch_.clear();
  auto old_it = pairs_.begin();
  for (const CandidatePair& p : new_pairs_) {
    while (old_it != pairs_.end() && old_it->pair < p) scratch_.push_back(*old_it++);
    scratch_.push_back({p, kUnknown, kUnknown, false});
  }
  scratch_.insert(scratch_.end(), old_it, pairs_.end());
  pairs_.swap(scratch_);
}

bool PairCache::ValidatePrimitive(PrimitiveId id, const Shape& shape_W, std::string* why) const {
  const double d_m = MaxPointDisplacement_m(indexed_W_[id], shape_W);
  FloatPrimitive now_f, indexed_f;
  ToFloatPrimitive(shape_W, &now_f);
  ToFloatPrimitive(indexed_W_[id], &indexed_f);
  if ((is_now_f_made_[id] && std::memcmp(&now_f, &now_f_[id], sizeof now_f) != 0) ||
      (is_indexed_f_made_[id] && std::memcmp(&indexed_f, &indexed_f_[id], sizeof now_f) != 0)) {
    *why = "primitive " + std::to_string(id) + ": its float copy is not its shape's";
    return false;
  }
  if (d_m == disp_m_[id] && d_m <= slack_m_) return true;
  std::ostringstream msg;
  msg << "primitive " << id << " moved " << d_m << " m from its indexed copy, recorded "
      << disp_m_[id] << " m, slack " << slack_m_ << " m";
  *why = msg.str();
  return false;
}

bool PairCache::ValidatePairs(const std::vector<CandidatePair>& expected,
                              const std::vector<Shape>& shapes_W,
                              const std::vector<std::uint8_t>& moved, std::string* why) const {
  if (is_stale_) return true;  // a scene change since the last cycle: rebuilt in the next one
  std::ostringstream msg;
  // TestPairs writes its batches by index, sized for the most pairs the index can report.
  if (pairs_.size() > test_pairs_.size()) {
    msg << pairs_.size() << " kept candidate pairs, room for " << test_pairs_.size();
    *why = msg.str();
    return false;
  }
  if (expected.size() != pairs_.size()) {
    msg << pairs_.size() << " kept candidate pairs, " << expected.size()
        << " indexed boxes overlapping";
    *why = msg.str();
    return false;
  }
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const KeptPair& kept = pairs_[i];
    const PrimitiveId a = kept.pair.a, b = kept.pair.b;
    if (!(kept.pair == expected[i])) {
      msg << "kept candidate pair " << i << " is (" << a << "," << b << "), expected ("
          << expected[i].a << "," << expected[i].b << ")";
      break;
    }
    const double d_m = ShapeDistance(indexed_W_[a], indexed_W_[b]).distance_m;
    if (kept.lower_bound_m > d_m + BoundMargin_m(d_m)) {
      msg << "pair (" << a << "," << b << ") lower bound " << kept.lower_bound_m
          << " m exceeds the indexed shapes' distance " << d_m << " m";
      break;
    }
    if (moved[a] || moved[b]) continue;
    const double now_m = ShapeDistance(shapes_W[a], shapes_W[b]).distance_m;
    if (kept.kinematics_bound_m > now_m + BoundMargin_m(now_m)) {
      msg << "pair (" << a << "," << b << ") bound " << kept.kinematics_bound_m
          << " m exceeds its distance " << now_m << " m at the last kinematics";
      break;
    }
  }
  if (msg.tellp() == 0) return true;
  *why = msg.str();
  return false;
}

}  // namespace arm_collision_monitor
