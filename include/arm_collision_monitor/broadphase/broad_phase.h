// One interface for every broad phase: the N-objects octree (the seed's index), and the
// references it is measured against (all pairs, uniform grid, rebuild-every-cycle,
// delete-and-reinsert). Any of them can be swapped in by configuration and tested against the
// others: they must return exactly the same candidate pairs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/compatibility_matrix.h"
#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// A candidate pair, a < b.
struct CandidatePair {
  PrimitiveId a = 0;
  PrimitiveId b = 0;
  bool operator==(const CandidatePair& o) const { return a == o.a && b == o.b; }
  bool operator<(const CandidatePair& o) const { return a < o.a || (a == o.a && b < o.b); }
};

/// Work done, accumulated since the last ResetCounters(): for benchmarks and diagnostics.
struct BroadPhaseCounters {
  std::uint64_t object_node_tests = 0;    ///< box-vs-cell tests
  std::uint64_t object_object_tests = 0;  ///< box-vs-box tests between primitives
  std::uint64_t neighbours_visited = 0;   ///< neighbour cells examined during updates
  std::uint64_t splits = 0;
  std::uint64_t merges = 0;
  std::uint64_t reinsert_fallbacks = 0;   ///< moves too large for the incremental update
  std::uint64_t outside_world = 0;        ///< moves that left (part of) the box outside the world
  std::uint64_t unlinked_changes = 0;     ///< boxes into or out of a cell index's unlinked list
  BroadPhaseCounters& operator+=(const BroadPhaseCounters& o) {
    object_node_tests += o.object_node_tests;
    object_object_tests += o.object_object_tests;
    neighbours_visited += o.neighbours_visited;
    splits += o.splits;
    merges += o.merges;
    reinsert_fallbacks += o.reinsert_fallbacks;
    outside_world += o.outside_world;
    unlinked_changes += o.unlinked_changes;
    return *this;
  }
};

/// Whether a primitive may move after Add(). Pairs of two static primitives are never reported.
enum class Motion : std::uint8_t { kStatic, kMoving };

/// A leaf cell of a spatial index, for visualisation and statistics.
struct IndexCell {
  Aabb box_W;
  std::uint32_t primitive_count = 0;
  bool holds_moving = false;
};

/// The broad-phase interface: keeps the inflated boxes of the primitives and returns the pairs
/// whose boxes overlap. Boxes in W, metres.
class BroadPhase {
 public:
  virtual ~BroadPhase() = default;

  /// Short name ("octree", "naive", "grid", "rebuild", "reinsert").
  virtual std::string name() const = 0;

  /// Start-up: adds primitive `id` with tight box `box_W`; it is indexed by
  /// box_W.Inflated(tolerance_m). `id` must not be present already.
  virtual void Add(PrimitiveId id, const Aabb& box_W, double tolerance_m, Motion motion) = 0;
  /// Removes primitive `id` (model switching, detaching). No-op if absent.
  virtual void Remove(PrimitiveId id) = 0;
  /// Primitive `id` now has tight box `box_W` (same tolerance as when added).
  virtual void Move(PrimitiveId id, const Aabb& box_W) = 0;

  /// The candidate pairs now: every pair of present primitives whose inflated boxes overlap
  /// (Aabb::Overlaps), each once with a < b, leaving out pairs marked in `compatible` and pairs
  /// of two static primitives. Replaces the contents of `pairs` (its capacity is reused); every
  /// implementation returns them sorted (CandidatePair::operator<), so results compare directly.
  virtual void FindPairs(const CompatibilityMatrix& compatible,
                         std::vector<CandidatePair>* pairs) = 0;
  /// The candidate pairs of one primitive: exactly the pairs of FindPairs() that contain `id`
  /// (same rules, sorted), for callers that keep the pair set and update it as primitives move.
  /// Empty when `id` is not present. Replaces the contents of `pairs`.
  virtual void FindPairsOf(PrimitiveId id, const CompatibilityMatrix& compatible,
                           std::vector<CandidatePair>* pairs) = 0;
  /// The candidate pairs of several primitives at once (distinct ids, such as one link's, which
  /// lie close together): exactly the pairs of FindPairs() that contain any of ids[0, count),
  /// each once, in any order; replaces the contents of `pairs`. False, with `pairs` untouched,
  /// where the structure answers one primitive at a time (the callers use FindPairsOf then).
  virtual bool FindPairsOfGroup(const PrimitiveId* /*ids*/, std::uint32_t /*count*/,
                                const CompatibilityMatrix& /*compatible*/,
                                std::vector<CandidatePair>* /*pairs*/) {
    return false;
  }

  /// The leaf cells (left empty by structures without cells, e.g. all pairs).
  virtual void CollectCells(std::vector<IndexCell>* cells) const { cells->clear(); }
  /// Test hook: brings every visit stamp the structure keeps to `steps_before_wrap` steps short
  /// of its 32-bit wrap-around (see CellBroadPhase). Valid at any time between calls; no-op for
  /// structures without stamps.
  virtual void ForceStampsNearWrap(std::uint32_t /*steps_before_wrap*/) {}
  /// True iff the structure's invariants hold (false with the first violation in `why`). Slow:
  /// for tests and soaks. Structures without invariants beyond their lists return true.
  virtual bool Validate(std::string* /*why*/) const { return true; }

  const BroadPhaseCounters& counters() const { return counters_; }
  void ResetCounters() { counters_ = BroadPhaseCounters{}; }

 protected:
  BroadPhaseCounters counters_;
};

}  // namespace arm_collision_monitor
