#include "arm_collision_monitor/broadphase/cell_broad_phase.h"

#include <algorithm>
#include <limits>

#include "arm_collision_monitor/broadphase/broad_phase_util.h"
#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

// True when every face of the box moved by less than `limit_m` (false for a NaN bound).
bool FacesMovedLess(const Aabb& old_box_W, const Aabb& new_box_W, double limit_m) {
  return ((new_box_W.min_W - old_box_W.min_W).array().abs() < limit_m).all() &&
         ((new_box_W.max_W - old_box_W.max_W).array().abs() < limit_m).all();
}

}  // namespace

// Why the neighbour search of the incremental update is exact (the seed's "an object cannot
// move through a node", made precise). Every cell boundary lies on the lattice
// origin + i * s, s = the minimum cell edge (octree: root / 2^depth; grid: the cell edge),
// and cells are closed boxes. Let the inflated box move from B0 to B1 with every face moving
// by less than s. Take a cell X that B1 overlaps, at a point p. Clamp p into B0 axis by axis to
// get q; on each axis |p - q| < s, because the face of B0 that q lies on is within s of the
// matching face of B1, which lies beyond p. q lies in some cell Y that B0 overlaps. On each
// axis the intervals of X and Y meet: were they disjoint, a gap between two lattice points
// would separate them, at least s wide, yet p and q are less than s apart. So the closed
// cells X and Y share a point: X is Y, or a face, edge or corner neighbour of Y (or a
// descendant of one lying on the common face, edge or corner). Searching the 26 neighbour
// directions of every old cell therefore finds every new cell. Moves of s or more (jumps), and
// boxes leaving or re-entering the world cube, take the full remove-and-insert path instead.
// Floating point: boundaries are spaced s within rounding, hence the margin in jump_limit_m_.

CellBroadPhase::CellBroadPhase(const Aabb& world_W, const BroadPhaseTechniques& techniques,
                               CellUpdateStrategy strategy, double cell_spacing_m,
                               double oversize_spacing_m)
    : world_W_(world_W),
      techniques_(techniques),
      strategy_(strategy),
      jump_limit_m_(cell_spacing_m * (1.0 - kCellSpacingMarginRel)),
      inv_oversize_spacing_(1.0 / oversize_spacing_m),
      jump_step_m_(kJumpSpacingFraction * oversize_spacing_m) {}

void CellBroadPhase::ResizeCells(std::size_t cell_count) {
  cell_head_.resize(cell_count, kNone);
  cell_count_.resize(cell_count, 0);
  cell_visit_.resize(cell_count, 0);
}

void CellBroadPhase::ReserveShared(std::uint32_t max_primitives, std::uint32_t max_links,
                                   std::uint32_t max_cells) {
  cell_head_.reserve(max_cells);
  cell_count_.reserve(max_cells);
  cell_visit_.reserve(max_cells);
  if (records_.size() < max_primitives) records_.resize(max_primitives);
  present_ids_.reserve(max_primitives);
  present_boxes_.Reserve(max_primitives);
  moving_ids_.reserve(max_primitives);
  outside_ids_.reserve(max_primitives);
  outside_boxes_.Reserve(max_primitives);
  unlinked_ids_.reserve(max_primitives);
  unlinked_boxes_.Reserve(max_primitives);
  links_.reserve(max_links);
  scratch_cells_.reserve(max_links);
}

void CellBroadPhase::AddLink(PrimitiveId prim, std::uint32_t cell) {
  std::uint32_t l;
  if (free_link_ != kNone) {
    l = free_link_;
    free_link_ = links_[l].next_in_cell;
  } else {
    l = static_cast<std::uint32_t>(links_.size());
    links_.emplace_back();
  }
  Record& r = records_[prim];
  Link& link = links_[l];
  link.prim = prim;
  link.cell = cell;
  link.prev_in_cell = kNone;
  link.next_in_cell = cell_head_[cell];
  if (link.next_in_cell != kNone) links_[link.next_in_cell].prev_in_cell = l;
  cell_head_[cell] = l;
  ++cell_count_[cell];
  link.prev_of_prim = kNone;
  link.next_of_prim = r.first_link;
  if (link.next_of_prim != kNone) links_[link.next_of_prim].prev_of_prim = l;
  r.first_link = l;
  ++r.link_count;
  ++live_links_;
}

void CellBroadPhase::RemoveLink(std::uint32_t l) {
  Link& link = links_[l];
  if (link.prev_in_cell != kNone) {
    links_[link.prev_in_cell].next_in_cell = link.next_in_cell;
  } else {
    cell_head_[link.cell] = link.next_in_cell;
  }
  if (link.next_in_cell != kNone) links_[link.next_in_cell].prev_in_cell = link.prev_in_cell;
  --cell_count_[link.cell];
  Record& r = records_[link.prim];
  if (link.prev_of_prim != kNone) {
    links_[link.prev_of_prim].next_of_prim = link.next_of_prim;
  } else {
    r.first_link = link.next_of_prim;
  }
  if (link.next_of_prim != kNone) links_[link.next_of_prim].prev_of_prim = link.prev_of_prim;
  --r.link_count;
  --live_links_;
  link.next_in_cell = free_link_;  // the free list reuses next_in_cell
  free_link_ = l;
}

void CellBroadPhase::ClearLinks() {
  links_.clear();  // keeps the capacity
  free_link_ = kNone;
  live_links_ = 0;
  for (Record& r : records_) {
    r.first_link = kNone;
    r.link_count = 0;
  }
  std::fill(cell_head_.begin(), cell_head_.end(), kNone);
  std::fill(cell_count_.begin(), cell_count_.end(), 0u);
}

void CellBroadPhase::ResetVisitStamps() {
  // The seed: "the tree should be traversed and every node's lastCheckNo reset".
  std::fill(cell_visit_.begin(), cell_visit_.end(), 0u);
  visit_stamp_ = 0;
}

void CellBroadPhase::ResetScanStamps() {
  for (Record& r : records_) r.pair_stamp = 0;
  scan_stamp_ = 0;
}

void CellBroadPhase::ResetUnionStamps() {
  for (Record& r : records_) r.union_stamp = 0;
  union_stamp_ = 0;
}

void CellBroadPhase::ForceStampsNearWrap(std::uint32_t steps_before_wrap) {
  ResetVisitStamps();
  ResetScanStamps();
  ResetUnionStamps();
  const std::uint32_t near_wrap = std::numeric_limits<std::uint32_t>::max() - steps_before_wrap;
  visit_stamp_ = near_wrap;
  scan_stamp_ = near_wrap;
  union_stamp_ = near_wrap;
}

std::uint32_t CellBroadPhase::NextVisitStamp() {
  if (visit_stamp_ == std::numeric_limits<std::uint32_t>::max()) ResetVisitStamps();
  return ++visit_stamp_;
}

std::uint32_t CellBroadPhase::NextUnionStamp() {
  if (union_stamp_ == std::numeric_limits<std::uint32_t>::max()) ResetUnionStamps();
  return ++union_stamp_;
}

bool CellBroadPhase::ShortMove(const Aabb& old_box_W, const Aabb& new_box_W) const {
  return FacesMovedLess(old_box_W, new_box_W, jump_limit_m_);
}

void CellBroadPhase::StampLinkedCells(PrimitiveId id, std::uint32_t stamp) {
  for (std::uint32_t l = records_[id].first_link; l != kNone; l = links_[l].next_of_prim) {
    cell_visit_[links_[l].cell] = stamp;
  }
}

IndexCell CellBroadPhase::MakeIndexCell(std::uint32_t cell, const Aabb& cell_W) const {
  IndexCell out;
  out.box_W = cell_W;
  out.primitive_count = cell_count_[cell];
  for (std::uint32_t l = cell_head_[cell]; l != kNone; l = links_[l].next_in_cell) {
    if (records_[links_[l].prim].motion == Motion::kMoving) out.holds_moving = true;
  }
  return out;
}

unsigned CellBroadPhase::ReachMask(const Aabb& box_W, const Aabb& cell_W) {
  unsigned mask = 0;
  for (int a = 0; a < 3; ++a) {
    if (box_W.max_W[a] >= cell_W.max_W[a]) mask |= 1u << a;
    if (box_W.min_W[a] <= cell_W.min_W[a]) mask |= 1u << (3 + a);
  }
  return mask;
}

// Which sides of an old cell Y need a neighbour search (NeedsDirection). A cell X on side d of
// Y that the new box B1 overlaps (at a point of the cube) has to be visited only if the old box
// B0 did not overlap it, since B0's cells are all linked already. Side d can be skipped when
//  (a) on every axis with d[a] != 0, B0 already reached Y's face on that side: X's extent on
//      that axis starts at the face, which B0 covers (B0 also overlaps Y); and
//  (b) on every axis with d[a] == 0, B1 covers no coordinate of Y's extent that B0 did not:
//      X's extent there contains Y's (then B0, overlapping Y, meets it) or lies inside Y's
//      (then B1's part of it, non-empty, lies in B0).
// Then B0 overlaps X on every axis: X is an old cell. Condition (a) fails exactly when the box
// newly reaches a face, (b) when it grew sideways: the directions of motion.
CellBroadPhase::CellReach CellBroadPhase::ComputeCellReach(const Aabb& old_box_W,
                                                           const Aabb& new_box_W,
                                                           const Aabb& cell_W) {
  CellReach r;
  r.reach_new = ReachMask(new_box_W, cell_W);
  r.reach_old = ReachMask(old_box_W, cell_W);
  for (int a = 0; a < 3; ++a) {
    const double lo = std::max(new_box_W.min_W[a], cell_W.min_W[a]);
    const double hi = std::min(new_box_W.max_W[a], cell_W.max_W[a]);
    if (lo <= hi && (lo < old_box_W.min_W[a] || hi > old_box_W.max_W[a])) r.grew_axes |= 1u << a;
  }
  return r;
}

const std::array<CellBroadPhase::Direction, 26>& CellBroadPhase::Directions() {
  static const std::array<Direction, 26> kDirections = [] {
    std::array<Direction, 26> out{};
    int n = 0;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          Direction& dir = out[n++];
          dir.d[0] = dx;
          dir.d[1] = dy;
          dir.d[2] = dz;
          dir.needed_mask = 0;
          dir.zero_axes = 0;
          for (int a = 0; a < 3; ++a) {
            if (dir.d[a] > 0) dir.needed_mask |= 1u << a;
            if (dir.d[a] < 0) dir.needed_mask |= 1u << (3 + a);
            if (dir.d[a] == 0) dir.zero_axes |= 1u << a;
          }
        }
      }
    }
    return out;
  }();
  return kDirections;
}

void CellBroadPhase::AddToList(std::vector<PrimitiveId>* list, std::uint32_t Record::*slot,
                               PrimitiveId id) {
  records_[id].*slot = static_cast<std::uint32_t>(list->size());
  list->push_back(id);
}

void CellBroadPhase::RemoveFromList(std::vector<PrimitiveId>* list,
                                    std::uint32_t Record::*slot, PrimitiveId id) {
  const std::uint32_t index = records_[id].*slot;
  const PrimitiveId last = list->back();
  (*list)[index] = last;
  records_[last].*slot = index;
  list->pop_back();
}

bool CellBroadPhase::SetListed(PrimitiveId id, bool on, bool Record::*flag,
                               std::uint32_t Record::*slot, std::vector<PrimitiveId>* ids,
                               BoxArray* boxes) {
  Record& r = records_[id];
  if (r.*flag == on) {
    if (on) boxes->Set(r.*slot, r.box_W);  // its box may have moved
    return false;
  }
  r.*flag = on;
  if (on) {
    AddToList(ids, slot, id);
    boxes->PushBack(r.box_W);
  } else {
    boxes->SwapRemove(r.*slot);
    RemoveFromList(ids, slot, id);
  }
  return true;
}

void CellBroadPhase::SetOutside(PrimitiveId id, bool outside) {
  SetListed(id, outside, &Record::outside, &Record::outside_slot, &outside_ids_, &outside_boxes_);
}

bool CellBroadPhase::IsOversize(const Aabb& box_W) const {
  double cells = 1.0;
  for (int a = 0; a < 3; ++a) {
    cells *= (box_W.max_W[a] - box_W.min_W[a]) * inv_oversize_spacing_ + 1.0;
  }
  return cells > kOversizeCells;
}

bool CellBroadPhase::IsJump(const Aabb& old_box_W, const Aabb& new_box_W) const {
  return !FacesMovedLess(old_box_W, new_box_W, jump_step_m_);
}

void CellBroadPhase::SetUnlinked(PrimitiveId id, bool unlinked) {
  if (SetListed(id, unlinked, &Record::unlinked, &Record::unlinked_slot, &unlinked_ids_,
                &unlinked_boxes_)) {
    ++counters_.unlinked_changes;
  }
}

void CellBroadPhase::Place(PrimitiveId id) {
  const Record& r = records_[id];
  const bool unlinked = r.jumped || IsOversize(r.box_W);
  SetUnlinked(id, unlinked);
  SetOutside(id, !unlinked && !world_W_.Contains(r.box_W));
  if (unlinked) return;
  if (strategy_ == CellUpdateStrategy::kRebuild) {
    needs_rebuild_ = true;
  } else if (world_W_.Overlaps(r.box_W)) {
    InsertIntoCells(id);
  }
}

void CellBroadPhase::Add(PrimitiveId id, const Aabb& box_W, double tolerance_m, Motion motion) {
  if (id >= records_.size()) records_.resize(static_cast<std::size_t>(id) + 1);
  if (records_[id].present) return;  // precondition violated: keep the first registration
  Record& r = records_[id];
  r.box_W = box_W.Inflated(tolerance_m);
  r.tolerance_m = tolerance_m;
  r.motion = motion;
  r.present = true;
  r.outside = false;
  r.jumped = false;
  r.unlinked = false;
  AddToList(&present_ids_, &Record::present_slot, id);
  present_boxes_.PushBack(r.box_W);
  if (motion == Motion::kMoving) AddToList(&moving_ids_, &Record::moving_slot, id);
  if (!world_W_.Contains(r.box_W)) ++counters_.outside_world;
  Place(id);
}

void CellBroadPhase::Remove(PrimitiveId id) {
  if (id >= records_.size() || !records_[id].present) return;
  Record& r = records_[id];
  if (r.link_count > 0) RemoveFromCells(id);
  if (r.outside) SetOutside(id, false);
  if (r.unlinked) SetUnlinked(id, false);
  present_boxes_.SwapRemove(r.present_slot);
  RemoveFromList(&present_ids_, &Record::present_slot, id);
  if (r.motion == Motion::kMoving) RemoveFromList(&moving_ids_, &Record::moving_slot, id);
  r.present = false;
  if (strategy_ == CellUpdateStrategy::kRebuild) needs_rebuild_ = true;
}

void CellBroadPhase::Move(PrimitiveId id, const Aabb& box_W) {
  if (id >= records_.size() || !records_[id].present) return;  // refused: unknown primitive
  Record& r = records_[id];
  const Aabb old_box_W = r.box_W;
  r.box_W = box_W.Inflated(r.tolerance_m);
  present_boxes_.Set(r.present_slot, r.box_W);
  // A box not inside the world cube joins the outside list (pairs between two such boxes are
  // found by brute force); whatever part of it overlaps the cube stays indexed in the cells, so
  // pairs with primitives inside are found there. Contains() and Overlaps() are false for NaN
  // coordinates: a corrupt box overlaps nothing and is linked to no cell; no crash.
  const bool inside = world_W_.Contains(r.box_W);
  if (!inside) ++counters_.outside_world;
  // A jump (a step of kJumpSpacingFraction oversize spacings or more) leaves and enters more
  // cells than testing the box against every box costs: the box waits in the unlinked list,
  // scanned as the all-pairs broad phase does, until a shorter step (the reference strategies
  // keep the seed's updates). A NaN bound counts as a jump: the corrupt box is unlinked,
  // overlapping nothing, until a valid box follows it.
  r.jumped = strategy_ == CellUpdateStrategy::kIncremental && IsJump(old_box_W, r.box_W);
  if (r.unlinked || r.jumped || IsOversize(r.box_W)) {
    // Into, within or out of the unlinked list: Place decides anew from no cells.
    if (r.link_count > 0) RemoveFromCells(id);
    Place(id);
    return;
  }
  SetOutside(id, !inside);
  if (strategy_ == CellUpdateStrategy::kRebuild) {
    needs_rebuild_ = true;
    return;
  }
  const bool was_indexed = world_W_.Overlaps(old_box_W);
  const bool is_indexed = world_W_.Overlaps(r.box_W);
  if (strategy_ == CellUpdateStrategy::kIncremental && was_indexed && is_indexed &&
      ShortMove(old_box_W, r.box_W)) {
    // Both boxes meet the cube: the exactness argument above holds within it.
    UpdateCells(id, old_box_W);
    return;
  }
  if (strategy_ == CellUpdateStrategy::kIncremental && is_indexed) {
    ++counters_.reinsert_fallbacks;  // a jump, or re-entering the cube from wholly outside
  }
  if (was_indexed) RemoveFromCells(id);
  if (is_indexed) InsertIntoCells(id);
}

void CellBroadPhase::Rebuild() {
  ClearCells();
  for (const PrimitiveId id : present_ids_) {
    if (!records_[id].unlinked && world_W_.Overlaps(records_[id].box_W)) InsertIntoCells(id);
  }
}

void CellBroadPhase::ScanAll(PrimitiveId m, bool from_smaller_only,
                             const CompatibilityMatrix& compatible,
                             std::vector<CandidatePair>* pairs) {
  counters_.object_object_tests += present_boxes_.MarkOverlaps(records_[m].box_W);
  present_boxes_.ForEachHit([&](std::uint32_t slot) {
    TakeListed(m, present_ids_[slot], from_smaller_only, compatible, pairs);
  });
}

void CellBroadPhase::TakeListed(PrimitiveId m, PrimitiveId x, bool from_smaller_only,
                                const CompatibilityMatrix& compatible,
                                std::vector<CandidatePair>* pairs) const {
  if (x == m) return;
  if (records_[x].motion == Motion::kMoving ? from_smaller_only && x < m
                                            : records_[m].motion == Motion::kStatic) {
    return;
  }
  if (IsCompatiblePair(compatible, m, x)) return;
  pairs->push_back(MakeOrderedPair(m, x));
}

void CellBroadPhase::ScanPartners(PrimitiveId m, bool from_smaller_only,
                                  const CompatibilityMatrix& compatible,
                                  std::vector<CandidatePair>* pairs) {
  const Record& rm = records_[m];
  if (rm.unlinked) {
    ScanAll(m, from_smaller_only, compatible, pairs);
    return;
  }
  const bool dedup = techniques_.pair_deduplication;
  // Every partner with an overlap inside the world cube shares a cell with m (the two closed
  // boxes share a point of the cube, and it lies in some closed cell). An overlap can lie wholly
  // outside the cube only if both boxes are outside it: brute force over the outside list.
  if (rm.first_link != kNone) {
    if (scan_stamp_ == std::numeric_limits<std::uint32_t>::max()) ResetScanStamps();
    const std::uint32_t stamp = ++scan_stamp_;
    for (std::uint32_t l = rm.first_link; l != kNone; l = links_[l].next_of_prim) {
      for (std::uint32_t k = cell_head_[links_[l].cell]; k != kNone;
           k = links_[k].next_in_cell) {
        const PrimitiveId q = links_[k].prim;
        if (q == m) continue;
        Record& rq = records_[q];
        if (rq.motion == Motion::kMoving ? from_smaller_only && q < m
                                         : rm.motion == Motion::kStatic) {
          continue;
        }
        if (rm.outside && rq.outside) continue;  // the brute force below takes this pair
        if (dedup) {
          // One test per pair per scan even when the two share several cells.
          if (rq.pair_stamp == stamp) continue;
          rq.pair_stamp = stamp;
        }
        ++counters_.object_object_tests;
        if (!rm.box_W.Overlaps(rq.box_W)) continue;
        if (IsCompatiblePair(compatible, m, q)) continue;
        pairs->push_back(MakeOrderedPair(m, q));
      }
    }
  }
  // A partner from a brute-force list (never m's cells' members): the same rules as above.
  // The unlinked primitives are in no cell (an unlinked m scans everything: ScanAll).
  if (unlinked_boxes_.size() > 0) {
    counters_.object_object_tests += unlinked_boxes_.MarkOverlaps(rm.box_W);
    unlinked_boxes_.ForEachHit([&](std::uint32_t slot) {
      TakeListed(m, unlinked_ids_[slot], from_smaller_only, compatible, pairs);
    });
  }
  if (!rm.outside) return;
  counters_.object_object_tests += outside_boxes_.MarkOverlaps(rm.box_W);
  outside_boxes_.ForEachHit([&](std::uint32_t slot) {
    TakeListed(m, outside_ids_[slot], from_smaller_only, compatible, pairs);
  });
}

void CellBroadPhase::FindPairs(const CompatibilityMatrix& compatible,
                               std::vector<CandidatePair>* pairs) {
  // A pair of two moving primitives is met from both; it is taken from the smaller id.
  CollectPairs(moving_ids_.data(), moving_ids_.size(), true, compatible, pairs);
}

void CellBroadPhase::FindPairsOf(PrimitiveId id, const CompatibilityMatrix& compatible,
                                 std::vector<CandidatePair>* pairs) {
  const bool is_present = id < records_.size() && records_[id].present;
  CollectPairs(&id, is_present ? 1 : 0, false, compatible, pairs);
}

void CellBroadPhase::CollectPairs(const PrimitiveId* ids, std::size_t count,
                                  bool from_smaller_only, const CompatibilityMatrix& compatible,
                                  std::vector<CandidatePair>* pairs) {
  if (needs_rebuild_) {
    Rebuild();
    needs_rebuild_ = false;
  }
  pairs->clear();
  for (std::size_t i = 0; i < count; ++i) {
    ScanPartners(ids[i], from_smaller_only, compatible, pairs);
  }
  std::sort(pairs->begin(), pairs->end());
  if (!techniques_.pair_deduplication) {
    pairs->erase(std::unique(pairs->begin(), pairs->end()), pairs->end());
  }
}

}  // namespace arm_collision_monitor
