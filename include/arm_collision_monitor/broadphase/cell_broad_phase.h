// What the octree and the uniform grid share: the primitive table, the location links between
// primitives and cells (the seed's Figure 4), the list of primitives outside the world cube,
// the unlinked list of boxes too large for the cells or jumping across them, the visit and
// pair stamps, and the per-cycle pair scan (cell_broad_phase.cpp; the self-checks in
// cell_broad_phase_validate.cpp).
// The cell structure itself (which cells exist, where a box goes, how cells split and merge) is
// left to the derived class.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/box_array.h"
#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/broadphase/broad_phase_factory.h"

namespace arm_collision_monitor {

/// How a cell structure follows a moving primitive.
enum class CellUpdateStrategy : std::uint8_t {
  kIncremental,  ///< the seed's update: neighbours of the old cells only, split/merge on demand
  kReinsert,     ///< delete and re-insert every moved primitive (the seed's second approach)
  kRebuild,      ///< clear and rebuild the whole structure once per cycle (its first approach)
};

/// Base of the cell-based broad phases. Not for direct use: see OctreeBroadPhase and
/// GridBroadPhase.
class CellBroadPhase : public BroadPhase {
 public:
  void Add(PrimitiveId id, const Aabb& box_W, double tolerance_m, Motion motion) override;
  void Remove(PrimitiveId id) override;
  void Move(PrimitiveId id, const Aabb& box_W) override;
  void FindPairs(const CompatibilityMatrix& compatible,
                 std::vector<CandidatePair>* pairs) override;
  void FindPairsOf(PrimitiveId id, const CompatibilityMatrix& compatible,
                   std::vector<CandidatePair>* pairs) override;

  /// True iff every invariant holds (location links equal exactly the cells each primitive's
  /// inflated box overlaps, counts, lists, stamps, plus the derived structure's own rules);
  /// otherwise false with the first violation described in `why`. Slow: for tests.
  bool Validate(std::string* why) const override;

  /// Test hook for the wrap-around of the 32-bit stamps, valid at any time between calls: does
  /// what the wrap handling does (every stored cell visit, pair and union stamp back to 0),
  /// then sets the visit (per update), pair scan (per moving primitive per FindPairs) and
  /// distinct-count (per merge check) counters to max - `steps_before_wrap`, so that each wraps
  /// after that many more stamps.
  void ForceStampsNearWrap(std::uint32_t steps_before_wrap) override;

  /// Number of present primitives whose inflated box is not inside the world cube (unlinked
  /// ones not counted).
  std::size_t outside_count() const { return outside_ids_.size(); }
  /// Number of present primitives kept in the unlinked list instead of the cells: an oversize
  /// box (IsOversize), or one whose last move was a jump (Record::jumped).
  std::size_t unlinked_count() const { return unlinked_ids_.size(); }

 protected:
  static constexpr std::uint32_t kNone = 0xffffffffu;

  struct Record {
    Aabb box_W;  // inflated by the tolerance: what cells and pairs are decided on
    double tolerance_m = 0.0;
    Motion motion = Motion::kStatic;
    bool present = false;
    bool outside = false;   // box not inside the world cube: also kept in outside_ids_
    bool jumped = false;    // its last move was IsJump (incremental strategy only)
    bool unlinked = false;  // IsOversize(box) or jumped: in unlinked_ids_ only, in no cell
    std::uint32_t first_link = kNone;
    std::uint32_t link_count = 0;
    std::uint32_t pair_stamp = 0;   // scan stamp of the last pair test in this cycle
    std::uint32_t union_stamp = 0;  // distinct-primitive counting (merges, splits' bookkeeping)
    std::uint32_t present_slot = 0, moving_slot = 0, outside_slot = 0, unlinked_slot = 0;
  };
  // A location link: primitive `prim` lies in cell `cell`. Each link is on two doubly linked
  // lists, the cell's and the primitive's, so it is added and removed in O(1).
  struct Link {
    PrimitiveId prim = 0;
    std::uint32_t cell = 0;
    std::uint32_t next_in_cell = kNone, prev_in_cell = kNone;
    std::uint32_t next_of_prim = kNone, prev_of_prim = kNone;
  };

  /// `cell_spacing_m`: the jump limit of UpdateCells (see there); `oversize_spacing_m`: the
  /// lattice spacing IsOversize counts cells in (and IsJump's step, a fraction of it).
  CellBroadPhase(const Aabb& world_W, const BroadPhaseTechniques& techniques,
                 CellUpdateStrategy strategy, double cell_spacing_m, double oversize_spacing_m);

  // --- Hooks of the cell structure (one virtual call per primitive update, none per cell) ---
  /// Links `id` (its box meets the world cube) into every cell its box overlaps, splitting as
  /// needed.
  virtual void InsertIntoCells(PrimitiveId id) = 0;
  /// Brings the links of `id` from `old_box_W` to its current box. Preconditions: every face
  /// moved by less than the cell spacing given at construction (see ShortMove; infinite for a
  /// structure whose update is exact for any step); both boxes meet the world cube.
  virtual void UpdateCells(PrimitiveId id, const Aabb& old_box_W) = 0;
  /// Unlinks `id` from all its cells (merging where the structure allows).
  virtual void RemoveFromCells(PrimitiveId id) = 0;
  /// Empties the structure: every cell and link gone (rebuild strategy).
  virtual void ClearCells() = 0;
  /// The structure's own invariants, including that the links of each primitive are exactly
  /// the cells its box overlaps.
  virtual bool ValidateCells(std::string* why) const = 0;

  // --- Shared machinery ---
  void ResizeCells(std::size_t cell_count);
  void ReserveShared(std::uint32_t max_primitives, std::uint32_t max_links,
                     std::uint32_t max_cells);
  void AddLink(PrimitiveId prim, std::uint32_t cell);
  void RemoveLink(std::uint32_t link);
  void ClearLinks();
  /// A fresh visit stamp for one primitive update; on wrap-around every cell's stamp is reset
  /// (the seed's ThisCheckNo / lastCheckNo).
  std::uint32_t NextVisitStamp();
  /// A fresh stamp for counting distinct primitives (Record::union_stamp), wrap handled.
  std::uint32_t NextUnionStamp();
  /// True when no face of the box moved by the cell spacing (with margin) or more: then the
  /// neighbour search from the old cells is exact (argument in cell_broad_phase.cpp).
  bool ShortMove(const Aabb& old_box_W, const Aabb& new_box_W) const;
  /// Stamps every cell `id` is linked to as visited by `stamp`: its old cells need no test.
  void StampLinkedCells(PrimitiveId id, std::uint32_t stamp);
  /// Unlinks `id`, following its links from `first_link` on, from each cell its box no longer
  /// overlaps; `cell_box_W(cell)` gives a cell's box, `on_exit(cell)` hears of each removal.
  template <typename CellBoxFn, typename OnExitFn>
  void RemoveExitedLinks(PrimitiveId id, std::uint32_t first_link, CellBoxFn cell_box_W,
                         OnExitFn on_exit) {
    for (std::uint32_t l = first_link; l != kNone;) {
      const std::uint32_t next = links_[l].next_of_prim;
      const std::uint32_t cell = links_[l].cell;
      ++counters_.object_node_tests;
      if (!records_[id].box_W.Overlaps(cell_box_W(cell))) {
        RemoveLink(l);
        on_exit(cell);
      }
      l = next;
    }
  }
  /// The cell `cell` with box `cell_W`, as reported by CollectCells.
  IndexCell MakeIndexCell(std::uint32_t cell, const Aabb& cell_W) const;
  /// True when the cells `id` is linked to are exactly `expected` (sorted ascending);
  /// otherwise false with the two counts in `why`. `actual` is scratch space.
  bool LinkedCellsEqual(PrimitiveId id, const std::vector<std::uint32_t>& expected,
                        std::vector<std::uint32_t>* actual, std::string* why) const;

  /// Bit a (0..2) set: the box reaches the upper face of `cell_W` on axis a (box max >= face);
  /// bit 3 + a: it reaches the lower face. A neighbour on side d can hold the box only if every
  /// non-zero component of d has its bit set.
  static unsigned ReachMask(const Aabb& box_W, const Aabb& cell_W);
  /// The 26 directions to face, edge and corner neighbours, the ReachMask bits each needs, and
  /// its zero axes (bit a set when d[a] == 0).
  struct Direction {
    int d[3];
    unsigned needed_mask;
    unsigned zero_axes;
  };
  static const std::array<Direction, 26>& Directions();
  /// How a moved box relates to one of its old cells, for choosing the neighbours to visit.
  struct CellReach {
    unsigned reach_new = 0;  // ReachMask of the new box
    unsigned reach_old = 0;  // ReachMask of the old box
    unsigned grew_axes = 0;  // bit a: within the cell's extent on axis a the new box covers
                             // coordinates the old one did not
  };
  static CellReach ComputeCellReach(const Aabb& old_box_W, const Aabb& new_box_W,
                                    const Aabb& cell_W);
  /// Whether the neighbours of a cell on side `dir` may hold cells the moved box newly
  /// overlaps (the seed's NeighborInDirection, made exact; argument in the .cpp). Always true
  /// with the directional technique off.
  bool NeedsDirection(const CellReach& reach, const Direction& dir) const {
    if (!techniques_.directional_neighbours) return true;
    if ((dir.needed_mask & ~reach.reach_new) != 0) return false;
    return (dir.needed_mask & ~reach.reach_old) != 0 || (dir.zero_axes & reach.grew_axes) != 0;
  }

  std::vector<Record> records_;  // by id
  std::vector<Link> links_;
  std::uint32_t free_link_ = kNone;
  std::uint32_t live_links_ = 0;
  // Per cell (cell ids are the derived structure's: node indices, grid indices).
  std::vector<std::uint32_t> cell_head_;
  std::vector<std::uint32_t> cell_count_;
  std::vector<std::uint32_t> cell_visit_;  // lastCheckNo

  std::vector<PrimitiveId> present_ids_;
  BoxArray present_boxes_;  // per slot of present_ids_: its record's box (ScanAll)
  std::vector<PrimitiveId> moving_ids_;
  std::vector<PrimitiveId> outside_ids_;
  BoxArray outside_boxes_;  // per slot of outside_ids_: its record's box, for the brute force
  std::vector<PrimitiveId> unlinked_ids_;
  BoxArray unlinked_boxes_;  // per slot of unlinked_ids_: its record's box
  std::vector<std::uint32_t> scratch_cells_;  // merge candidates, reserved at start-up

  Aabb world_W_;  // the cube the cells span: octree root, whole grid; lattice origin at min_W
  BroadPhaseTechniques techniques_;
  CellUpdateStrategy strategy_;
  double jump_limit_m_;  // cell spacing * (1 - margin)
  double inv_oversize_spacing_;  // 1 / the spacing IsOversize counts cells in
  double jump_step_m_;  // IsJump's step: that spacing * kJumpSpacingFraction
  std::uint32_t visit_stamp_ = 0;
  std::uint32_t scan_stamp_ = 0;
  std::uint32_t union_stamp_ = 0;
  bool needs_rebuild_ = false;

 private:
  void AddToList(std::vector<PrimitiveId>* list, std::uint32_t Record::*slot, PrimitiveId id);
  void RemoveFromList(std::vector<PrimitiveId>* list, std::uint32_t Record::*slot,
                      PrimitiveId id);
  // Puts `id` on or off a brute-force list (`flag`: its membership, `slot`: its place there);
  // on it, its listed box is its record's. True when the membership changed.
  bool SetListed(PrimitiveId id, bool on, bool Record::*flag, std::uint32_t Record::*slot,
                 std::vector<PrimitiveId>* ids, BoxArray* boxes);
  // Puts `id` on or off the outside list by `outside` (SetListed).
  void SetOutside(PrimitiveId id, bool outside);
  // True when the box spans more than kOversizeCells lattice cells (false for NaN bounds).
  bool IsOversize(const Aabb& box_W) const;
  // True when a face of the box moved by jump_step_m_ or more (or a bound is NaN): the cells
  // left and entered would cost more than testing the box against every box.
  bool IsJump(const Aabb& old_box_W, const Aabb& new_box_W) const;
  // Puts `id` (linked to no cell, on no outside list) on or off the unlinked list.
  void SetUnlinked(PrimitiveId id, bool unlinked);
  // Links `id` into the cells of its box, or lists it as unlinked (oversize or jumped: its
  // record's flag), and sets its outside flag (it is linked to no cell and on neither list).
  void Place(PrimitiveId id);
  // Appends the pairs of an unlinked primitive `m`: every present primitive's box tested (the
  // present list's structure of arrays, as the all-pairs broad phase).
  void ScanAll(PrimitiveId m, bool from_smaller_only, const CompatibilityMatrix& compatible,
               std::vector<CandidatePair>* pairs);
  // Appends the pair of `m` and `x`, whose boxes overlap (a brute-force list's hit), unless it
  // is m with itself, left to x's own scan (from_smaller_only, x < m, both moving), of two
  // statics, or compatible.
  void TakeListed(PrimitiveId m, PrimitiveId x, bool from_smaller_only,
                  const CompatibilityMatrix& compatible, std::vector<CandidatePair>* pairs) const;
  // The wrap handling of each kind of stamp (the seed's lastCheckNo reset): every stored stamp
  // of that kind and its counter back to 0.
  void ResetVisitStamps();
  void ResetScanStamps();
  void ResetUnionStamps();
  void Rebuild();
  /// Appends the candidate pairs of `m` found through its cells, the unlinked list and, when
  /// its box is outside the world cube, the outside list (ScanAll for an unlinked `m`); moving
  /// partners with a smaller id are left to
  /// their own scan when `from_smaller_only` (FindPairs meets such a pair from both sides).
  void ScanPartners(PrimitiveId m, bool from_smaller_only, const CompatibilityMatrix& compatible,
                    std::vector<CandidatePair>* pairs);
  /// Rebuilds first if the strategy left the cells stale, then sets `pairs` to the sorted,
  /// distinct pairs that ScanPartners finds from each of ids[0..count).
  void CollectPairs(const PrimitiveId* ids, std::size_t count, bool from_smaller_only,
                    const CompatibilityMatrix& compatible, std::vector<CandidatePair>* pairs);
  // The parts of ValidateShared: ValidateRecord checks one record against the id lists and
  // its box (counting it in `counts`); ValidateRecords adds each record's location list (their
  // links summed in prim_links) and the list sizes; ValidateCellLists checks the cells' member
  // lists (their links summed in cell_links). ValidateShared then checks the totals and the
  // free link list.
  struct ListCounts {
    std::size_t present = 0, moving = 0, outside = 0, unlinked = 0;
  };
  // Whether `id` is at `slot` of `ids` and `boxes` holds its box there, bit for bit; false with
  // the violation, naming the `list`, in `why`.
  bool ValidateListed(PrimitiveId id, const char* list, const std::vector<PrimitiveId>& ids,
                      const BoxArray& boxes, std::uint32_t slot, std::string* why) const;
  bool ValidateRecord(PrimitiveId id, ListCounts* counts, std::string* why) const;
  bool ValidateRecords(std::uint64_t* prim_links, std::string* why) const;
  bool ValidateCellLists(std::uint64_t* cell_links, std::string* why) const;
  bool ValidateShared(std::string* why) const;
};

}  // namespace arm_collision_monitor
