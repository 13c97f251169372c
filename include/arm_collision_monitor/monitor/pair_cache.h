// The Monitor's index slack and its cache of candidate pairs (MonitorOptions::index_slack_m).
// Each moving primitive is indexed by its shape as of its last re-index (its "indexed copy"),
// grown by the slack, and re-indexed only once a point of it has moved farther than the slack.
// The broad phase's candidate pairs are kept between cycles, each with a lower bound on the
// distance of the two indexed copies; by the triangle inequality a pair is at least that far
// apart less both primitives' motion since, so the narrow phase runs only on the pairs whose
// bound no longer clears their threshold. The set is rebuilt after any change of the index or
// of the compatibility (stale), and otherwise updated per re-indexed primitive.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"

namespace arm_collision_monitor {

/// A candidate pair kept between cycles with bounds on its distance (m).
struct KeptPair {
  CandidatePair pair;
  double lower_bound_m = 0.0;       ///< <= distance of the indexed copies; NaN: not yet known
  double kinematics_bound_m = 0.0;  ///< <= distance of the shapes at the last kinematics; NaN
  /// kinematics_bound_m is that distance itself (the narrow phase ran on the pair this cycle).
  bool is_exact = false;
};

/// The index slack and the kept candidate pairs (see the file comment). Preallocated at
/// construction: nothing in it allocates afterwards.
class PairCache {
 public:
  PairCache() = default;
  /// `slack_m`: MonitorOptions::index_slack_m; `world_edge_m`: the longest edge of the world box,
  /// the length scale of the rounding margin (BoundMargin_m).
  PairCache(std::uint32_t primitive_count, double slack_m, double world_edge_m);

  // --- the index slack, per primitive ----------------------------------------------------
  /// Primitive `id` was (re-)added to the index at `shape_W`: its indexed copy; the pair set is
  /// stale.
  void SetIndexed(PrimitiveId id, const Shape& shape_W);
  /// The index or the compatibility changed: the next Update rebuilds the pair set.
  void MarkStale() { is_stale_ = true; }
  bool is_stale() const { return is_stale_; }
  /// Starts a cycle's re-indexing: clears reindexed().
  void BeginReindex() { reindexed_.clear(); }
  /// Indexed primitive `id` moved to `shape_W`: true when it left its slack, then `shape_W` is
  /// its new indexed copy and the caller moves it in the index (listed in reindexed()).
  bool FollowMoved(PrimitiveId id, const Shape& shape_W);
  /// Makes `shape_W`, where indexed primitive `id` is now, its indexed copy before it leaves its
  /// slack (the caller moves it in the index; listed in reindexed()).
  void Reindex(PrimitiveId id, const Shape& shape_W);
  /// The primitives re-indexed since BeginReindex, in call order.
  const std::vector<PrimitiveId>& reindexed() const { return reindexed_; }
  /// How far (m) a point of `id` has moved from its indexed copy, as of the last FollowMoved.
  double displacement_m(PrimitiveId id) const { return disp_m_[id]; }
  const Shape& indexed_shape_W(PrimitiveId id) const { return indexed_W_[id]; }

  // --- the kept pairs -----------------------------------------------------------------------
  /// After the kinematics and the re-indexing: brings the kept pairs up to date with
  /// `broad_phase` (all found anew when stale, else the pairs of the re-indexed primitives
  /// replaced, their bounds unknown until TestPairs), and each pair's kinematics bound: its
  /// distance now is at least its indexed distance less both primitives' displacement.
  void Update(BroadPhase* broad_phase, const CompatibilityMatrix& compatible);
  /// The narrow phase over the kept pairs: `narrow_phase(a, b)` (returning the distance of the
  /// current shapes, m) is called on each pair whose lower bound does not clear its threshold
  /// tol_m[a] + tol_m[b], in pair order. Returns the exact distance computations done (those of
  /// new pairs' bounds included).
  template <typename NarrowPhase>
  std::uint32_t TestPairs(const std::vector<double>& tol_m, NarrowPhase&& narrow_phase);
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
  /// FollowMoved) and the slack; and, unless stale, that the kept pairs are exactly `expected`
  /// (sorted: the pairs whose indexed boxes overlap, by brute force), that each lower bound
  /// under-estimates its indexed copies' distance and each kinematics bound the distance of
  /// `shapes_W`. False with the first violation in `why`.
  bool ValidatePrimitive(PrimitiveId id, const Shape& shape_W, std::string* why) const;
  bool ValidatePairs(const std::vector<CandidatePair>& expected,
                     const std::vector<Shape>& shapes_W, std::string* why) const;

 private:
  // The pair set of Update.
  void UpdatePairs(BroadPhase* broad_phase, const CompatibilityMatrix& compatible);
  double KinematicsBound_m(const KeptPair& kept) const {
    return kept.lower_bound_m - disp_m_[kept.pair.a] - disp_m_[kept.pair.b];
  }

  double slack_m_ = 0.0;
  double world_edge_m_ = 0.0;
  std::vector<Shape> indexed_W_;     // per primitive: as last indexed
  std::vector<double> disp_m_;       // per primitive: farthest point motion since then
  std::vector<KeptPair> pairs_;      // the broad phase's candidate pairs, sorted
  std::vector<KeptPair> scratch_;
  std::vector<CandidatePair> found_, new_pairs_;  // scratch for FindPairs / FindPairsOf
  std::vector<PrimitiveId> reindexed_;
  std::vector<std::uint8_t> is_reindexed_;
  bool is_stale_ = true;
};

template <typename NarrowPhase>
std::uint32_t PairCache::TestPairs(const std::vector<double>& tol_m, NarrowPhase&& narrow_phase) {
  std::uint32_t tests = 0;
  for (KeptPair& kept : pairs_) {
    const PrimitiveId a = kept.pair.a;
    const PrimitiveId b = kept.pair.b;
    // A new pair: the distance of the indexed copies, exact until either is re-indexed.
    if (std::isnan(kept.lower_bound_m)) {
      ++tests;
      kept.lower_bound_m = ShapeDistance(indexed_W_[a], indexed_W_[b]).distance_m;
      kept.kinematics_bound_m = KinematicsBound_m(kept);
    }
    // Triangle inequality: dist(now) >= dist(indexed) - motion of a - motion of b.
    const double motion_m = disp_m_[a] + disp_m_[b];
    if (IsClear(kept.lower_bound_m, motion_m, tol_m[a] + tol_m[b])) continue;
    ++tests;
    const double distance_m = narrow_phase(a, b);
    kept.lower_bound_m = std::max(kept.lower_bound_m, distance_m - motion_m);
    kept.kinematics_bound_m = distance_m;
    kept.is_exact = true;
  }
  return tests;
}

}  // namespace arm_collision_monitor
