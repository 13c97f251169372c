// The Monitor's index slack and its cache of candidate pairs (MonitorOptions::index_slack_m).
// Each moving primitive is indexed by its shape as of its last re-index (its "indexed copy"),
// grown by the slack, and re-indexed by a kinematics cycle once a point of it has moved
// farther than the cycle asks (FollowMoved): at most the slack, and half of it
// (kReindexSlackFraction) when the Monitor's steps are small enough for bounded cycles, which
// need every primitive's displacement plus its motion since the kinematics within the slack.
// Re-indexed together at half, the primitives leave runs of bounded cycles; each re-indexed
// only at the slack itself, some primitive is near it in nearly every cycle (the sphere robot
// of bench_tasks_experiments' workloads: 1,148 instead of 370 of 1,572 cycles bounded, 42 %
// fewer instructions).
// The broad phase's candidate pairs are kept between cycles, each with a lower bound on the
// distance of the two indexed copies; by the triangle inequality a pair is at least that far
// apart less both primitives' motion since, so the narrow phase runs only on the pairs whose
// bound no longer clears their threshold. The set is rebuilt after any change of the index or
// of the compatibility (stale), and otherwise updated per re-indexed primitive.
//
// The narrow phase is batched (TestPairs): the pairs whose bound does not clear their threshold
// get a single-precision certified lower bound first (geometry/clearance_batch.h, on float copies
// of the shapes, made when a batch first needs them), and only those it cannot clear get the
// exact double distance and its witness points. New pairs' bounds on their indexed copies come
// from the same batch.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/clearance_batch.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/monitor/motion_bounds.h"

namespace arm_collision_monitor {

/// A candidate pair kept between cycles with bounds on its distance (m).
struct KeptPair {
  CandidatePair pair;
  double lower_bound_m = 0.0;       ///< <= distance of the indexed copies; NaN: not yet known
  double kinematics_bound_m = 0.0;  ///< <= distance of the shapes at the last kinematics; NaN
  /// kinematics_bound_m is that distance itself (the exact narrow phase ran on the pair this
  /// cycle); false after a float clearance bound settled it (then it is that bound).
  bool is_exact = false;
};

/// The index slack and the kept candidate pairs (see the file comment). Preallocated at
/// construction: nothing in it allocates afterwards.
class PairCache {
 public:
  PairCache() = default;
  /// `max_pairs`: the most pairs the broad phase can report at once (MonitorModel::
  /// max_tested_pairs); `slack_m`: MonitorOptions::index_slack_m; `world_edge_m`: the longest
  /// edge of the world box, the length scale of the rounding margin (BoundMargin_m).
  PairCache(std::uint32_t primitive_count, std::size_t max_pairs, double slack_m,
            double world_edge_m);

  // --- the index slack, per primitive ----------------------------------------------------
  /// Primitive `id` was (re-)added to the index at `shape_W`: its indexed copy; the pair set is
  /// stale.
  void SetIndexed(PrimitiveId id, const Shape& shape_W);
  /// The index or the compatibility changed: the next Update rebuilds the pair set.
  void MarkStale() { is_stale_ = true; }
  bool is_stale() const { return is_stale_; }
  /// Starts a cycle's re-indexing: clears reindexed().
  void BeginReindex() {
    for (const PrimitiveId id : reindexed_) is_reindexed_[id] = 0;
    reindexed_.clear();
  }
  /// The part of the slack a kinematics cycle with small steps re-indexes beyond (FollowMoved).
  static constexpr double kReindexSlackFraction = 0.5;
  /// Indexed primitive `id` moved to `shape_W`: true when it moved farther than `reindex_at_m`
  /// (at most the slack) from its indexed copy, then `shape_W` is
  /// its new indexed copy and the caller moves it in the index (listed in reindexed()). Every
  /// change of an indexed primitive's shape comes through here or SetIndexed (TestPairs' float
  /// copies of the shapes follow these calls).
  bool FollowMoved(PrimitiveId id, const Shape& shape_W, double reindex_at_m) {
    // Every point of the shape lies within this of its indexed copy (the displacement of a
    // point of a capsule or box is a convex combination of its defining points').
    return FollowMovedBy(id, MaxPointDisplacement_m(indexed_W_[id], shape_W), shape_W,
                         reindex_at_m);
  }
  /// FollowMoved when the caller has MaxPointDisplacement_m(indexed_shape_W(id), shape_W) at
  /// hand: `d_m`.
  bool FollowMovedBy(PrimitiveId id, double d_m, const Shape& shape_W, double reindex_at_m) {
    is_now_f_made_[id] = 0;
    if (d_m <= std::min(reindex_at_m, slack_m_)) {
      disp_m_[id] = d_m;
      is_now_indexed_[id] = 0;
      return false;
    }
    Reindex(id, shape_W);
    return true;
  }
  /// Makes `shape_W`, where indexed primitive `id` is now, its indexed copy before it leaves its
  /// slack (the caller moves it in the index; listed in reindexed()).
  void Reindex(PrimitiveId id, const Shape& shape_W);
  /// The primitives re-indexed since BeginReindex, in call order.
  const std::vector<PrimitiveId>& reindexed() const { return reindexed_; }
  /// Whether `id` is in reindexed().
  bool is_reindexed(PrimitiveId id) const { return is_reindexed_[id] != 0; }
  /// How far (m) a point of `id` has moved from its indexed copy, as of the last FollowMoved.
  double displacement_m(PrimitiveId id) const { return disp_m_[id]; }
  const Shape& indexed_shape_W(PrimitiveId id) const { return indexed_W_[id]; }

  // --- the kept pairs -----------------------------------------------------------------------
  /// After the kinematics and the re-indexing: brings the kept pairs up to date with
  /// `broad_phase` (all found anew when stale, else the pairs of the re-indexed primitives
  /// replaced, their bounds unknown until TestPairs), and each pair's kinematics bound: its
  /// distance now is at least its indexed distance less both primitives' displacement.
  /// `group_of` (per primitive; may be null): re-indexed primitives in a row with the same
  /// group >= 0 (the Monitor's: their carrier link) are queried together (FindPairsOfGroup).
  void Update(BroadPhase* broad_phase, const CompatibilityMatrix& compatible,
              const std::vector<int>* group_of = nullptr);
  /// The narrow phase over the kept pairs: `narrow_phase(a, b)` (returning the exact distance of
  /// the current shapes, m) is called, in pair order, on each pair that neither its lower bound
  /// nor the float clearance bound of its current shapes `shapes_W` (as last given to
  /// FollowMoved or SetIndexed) clears of its threshold tol_m[a] + tol_m[b]; a batch of fewer
  /// than kClearanceBatchMinPairs pairs skips the float bound. Returns the exact distance
  /// computations done (narrow_phase's calls and new pairs' exact bounds).
  template <typename NarrowPhase>
  std::uint32_t TestPairs(const std::vector<Shape>& shapes_W, const std::vector<double>& tol_m,
                          NarrowPhase&& narrow_phase);
  /// The kept pairs, sorted.
  const std::vector<KeptPair>& pairs() const { return pairs_; }

  /// The skip test: a distance of at least bound_m - motion_m is clear of threshold_m with a
  /// margin against rounding (false for NaN).
  bool IsClear(double bound_m, double motion_m, double threshold_m) const {
    return bound_m - motion_m - BoundMargin_m(bound_m) > threshold_m;
  }
  /// What a distance bound keeps in hand against rounding (m): far above the rounding of the
  /// terms compared with it (lengths up to the world's edge; kLowerBoundMarginPerMetre).
  double BoundMargin_m(double bound_m) const {
    return kLowerBoundMarginPerMetre * (world_edge_m_ + std::abs(bound_m));
  }

  /// Checks `id`'s recorded displacement against its shape `shape_W` (as of its last
  /// FollowMoved) and the slack, and its float copies (when made) against it and its indexed
  /// copy; and, unless stale, that the kept pairs are exactly `expected`
  /// (sorted: the pairs whose indexed boxes overlap, by brute force), that each lower bound
  /// under-estimates its indexed copies' distance and each kinematics bound the distance of
  /// `shapes_W` (but where `moved` flags either primitive: moved since the bound was taken).
  /// False with the first violation in `why`.
  bool ValidatePrimitive(PrimitiveId id, const Shape& shape_W, std::string* why) const;
  bool ValidatePairs(const std::vector<CandidatePair>& expected,
                     const std::vector<Shape>& shapes_W, const std::vector<std::uint8_t>& moved,
                     std::string* why) const;

 private:
  // The pair set of Update.
  void UpdatePairs(BroadPhase* broad_phase, const CompatibilityMatrix& compatible,
                   const std::vector<int>* group_of);
  double KinematicsBound_m(const KeptPair& kept) const {
    return kept.lower_bound_m - disp_m_[kept.pair.a] - disp_m_[kept.pair.b];
  }
  // Pair pairs_[i] as batched pair k.
  void AddToBatch(std::uint32_t i, std::size_t k) {
    batch_pairs_[k] = i;
    batch_a_[k] = pairs_[i].pair.a;
    batch_b_[k] = pairs_[i].pair.b;
  }
  // The float copies, made when first needed after a change: of the indexed copy; of the
  // current shape `shape_W`.
  void MakeIndexedFloat(PrimitiveId id) {
    if (!is_indexed_f_made_[id]) ToFloatPrimitive(indexed_W_[id], &indexed_f_[id]);
    is_indexed_f_made_[id] = 1;
  }
  void MakeNowFloat(PrimitiveId id, const Shape& shape_W) {
    if (!is_now_f_made_[id]) ToFloatPrimitive(shape_W, &now_f_[id]);
    is_now_f_made_[id] = 1;
  }
  // TestPairs without the float bound: one pass, the exact distance for every pair not cleared
  // by its bound (new pairs: of their indexed copies first).
  template <typename NarrowPhase>
  std::uint32_t TestPairsExactly(const std::vector<double>& tol_m, NarrowPhase&& narrow_phase);
  // The narrow phase's exact distance of `kept` now, its primitives `motion_m` from their indexed
  // copies: the distance itself for the kinematics, less that motion for the indexed copies.
  static void RecordExact(KeptPair* kept, double distance_m, double motion_m) {
    kept->lower_bound_m = std::max(kept->lower_bound_m, distance_m - motion_m);
    kept->kinematics_bound_m = distance_m;
    kept->is_exact = true;
  }
  // The float clearance bounds of the first `count` batched pairs on `primitives` into
  // batch_bound_m_.
  void BoundBatch(const std::vector<FloatPrimitive>& primitives, std::size_t count) {
    ComputeClearanceLowerBounds(primitives.data(), batch_a_.data(), batch_b_.data(), count,
                                batch_bound_m_.data());
  }

  double slack_m_ = 0.0;
  double world_edge_m_ = 0.0;
  std::vector<Shape> indexed_W_;     // per primitive: as last indexed
  std::vector<double> disp_m_;       // per primitive: farthest point motion since then
  // Per primitive: float copies of the indexed copy and of the current shape, whether each is
  // up to date, and whether the current shape is the indexed copy.
  std::vector<FloatPrimitive> indexed_f_, now_f_;
  std::vector<std::uint8_t> is_indexed_f_made_, is_now_f_made_, is_now_indexed_;
  // TestPairs' scratch: the pairs to test (index into pairs_, in pair order); the batched pairs:
  // index into pairs_, primitives, float bound (m).
  std::vector<std::uint32_t> test_pairs_, batch_pairs_;
  std::vector<PrimitiveId> batch_a_, batch_b_;
  std::vector<double> batch_bound_m_;
  std::vector<KeptPair> pairs_;      // the broad phase's candidate pairs, sorted
  std::vector<KeptPair> scratch_;
  std::vector<CandidatePair> found_, new_pairs_;  // scratch for FindPairs / FindPairsOf
  std::vector<PrimitiveId> reindexed_;
  std::vector<std::uint8_t> is_reindexed_;  // per primitive: in reindexed_ (1, or kInGroup)
  // is_reindexed_ of the members of the group UpdatePairs is taking the pairs of.
  static constexpr std::uint8_t kInGroup = 2;
  bool is_stale_ = true;
};

template <typename NarrowPhase>
std::uint32_t PairCache::TestPairsExactly(const std::vector<double>& tol_m,
                                          NarrowPhase&& narrow_phase) {
  std::uint32_t tests = 0;
  for (KeptPair& kept : pairs_) {
    const PrimitiveId a = kept.pair.a;
    const PrimitiveId b = kept.pair.b;
    if (std::isnan(kept.lower_bound_m)) {
      ++tests;
      kept.lower_bound_m = ShapeDistance(indexed_W_[a], indexed_W_[b]).distance_m;
      kept.kinematics_bound_m = KinematicsBound_m(kept);
    }
    const double motion_m = disp_m_[a] + disp_m_[b];
    if (IsClear(kept.lower_bound_m, motion_m, tol_m[a] + tol_m[b])) continue;
    ++tests;
    RecordExact(&kept, narrow_phase(a, b), motion_m);
  }
  return tests;
}

template <typename NarrowPhase>
std::uint32_t PairCache::TestPairs(const std::vector<Shape>& shapes_W,
                                   const std::vector<double>& tol_m, NarrowPhase&& narrow_phase) {
  // Too few pairs for any batch: the passes that pick the batches would cost more than nothing.
  if (pairs_.size() < kClearanceBatchMinPairs) return TestPairsExactly(tol_m, narrow_phase);
  // New pairs: a lower bound on the distance of their indexed copies, kept until either is
  // re-indexed (a few new pairs take the exact distance directly: kClearanceBatchMinPairs).
  std::uint32_t tests = 0;
  std::size_t count = 0;
  for (std::uint32_t i = 0; i < pairs_.size(); ++i) {
    if (std::isnan(pairs_[i].lower_bound_m)) AddToBatch(i, count++);
  }
  if (count >= kClearanceBatchMinPairs) {
    for (std::size_t k = 0; k < count; ++k) {
      MakeIndexedFloat(batch_a_[k]);
      MakeIndexedFloat(batch_b_[k]);
    }
    BoundBatch(indexed_f_, count);
  } else {
    for (std::size_t k = 0; k < count; ++k) {
      batch_bound_m_[k] =
          ShapeDistance(indexed_W_[batch_a_[k]], indexed_W_[batch_b_[k]]).distance_m;
    }
    tests += static_cast<std::uint32_t>(count);
  }
  for (std::size_t k = 0; k < count; ++k) {
    KeptPair& kept = pairs_[batch_pairs_[k]];
    kept.lower_bound_m = batch_bound_m_[k];
    kept.kinematics_bound_m = KinematicsBound_m(kept);
  }
  // Triangle inequality: dist(now) >= dist(indexed) - motion of a - motion of b. The pairs that
  // bound does not clear get the float bound of their current shapes (unless both are their
  // indexed copies: it was just computed), and those it does not clear either the exact distance.
  std::size_t test_count = 0;
  count = 0;
  for (std::uint32_t i = 0; i < pairs_.size(); ++i) {
    const KeptPair& kept = pairs_[i];
    const PrimitiveId a = kept.pair.a;
    const PrimitiveId b = kept.pair.b;
    if (IsClear(kept.lower_bound_m, disp_m_[a] + disp_m_[b], tol_m[a] + tol_m[b])) continue;
    test_pairs_[test_count++] = i;
    if (!(is_now_indexed_[a] && is_now_indexed_[b])) AddToBatch(i, count++);
  }
  if (count < kClearanceBatchMinPairs) count = 0;
  for (std::size_t k = 0; k < count; ++k) {
    MakeNowFloat(batch_a_[k], shapes_W[batch_a_[k]]);
    MakeNowFloat(batch_b_[k], shapes_W[batch_b_[k]]);
  }
  BoundBatch(now_f_, count);
  std::size_t k = 0;  // the next batched pair
  for (std::size_t t = 0; t < test_count; ++t) {
    const std::uint32_t i = test_pairs_[t];
    KeptPair& kept = pairs_[i];
    const PrimitiveId a = kept.pair.a;
    const PrimitiveId b = kept.pair.b;
    const double motion_m = disp_m_[a] + disp_m_[b];
    if (k < count && batch_pairs_[k] == i) {
      const double now_bound_m = batch_bound_m_[k++];
      if (IsClear(now_bound_m, 0.0, tol_m[a] + tol_m[b])) {
        kept.lower_bound_m = std::max(kept.lower_bound_m, now_bound_m - motion_m);
        kept.kinematics_bound_m = std::max(kept.kinematics_bound_m, now_bound_m);
        continue;
      }
    }
    ++tests;
    RecordExact(&kept, narrow_phase(a, b), motion_m);
  }
  return tests;
}

}  // namespace arm_collision_monitor
