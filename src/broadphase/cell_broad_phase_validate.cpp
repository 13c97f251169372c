// CellBroadPhase's self-checks (Validate and the helpers the grid's and the octree's own checks
// share): slow, for tests and soaks; nothing on a cycle's path calls them.
#include "arm_collision_monitor/broadphase/cell_broad_phase.h"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>

#include "arm_collision_monitor/broadphase/broad_phase_util.h"

namespace arm_collision_monitor {

bool CellBroadPhase::LinkedCellsEqual(PrimitiveId id, const std::vector<std::uint32_t>& expected,
                                      std::vector<std::uint32_t>* actual,
                                      std::string* why) const {
  actual->clear();
  for (std::uint32_t l = records_[id].first_link; l != kNone; l = links_[l].next_of_prim) {
    actual->push_back(links_[l].cell);
  }
  std::sort(actual->begin(), actual->end());
  if (*actual == expected) return true;
  if (why != nullptr) {
    std::ostringstream msg;
    msg << "primitive " << id << " is linked to " << actual->size() << " cells but overlaps "
        << expected.size();
    *why = msg.str();
  }
  return false;
}

bool CellBroadPhase::Validate(std::string* why) const {
  if (!ValidateShared(why)) return false;
  if (needs_rebuild_) return true;  // rebuild strategy between Move and FindPairs: stale cells
  return ValidateCells(why);
}

bool CellBroadPhase::ValidateListed(PrimitiveId id, const char* list,
                                    const std::vector<PrimitiveId>& ids, const BoxArray& boxes,
                                    std::uint32_t slot, std::string* why) const {
  if (ids.size() > slot && ids[slot] == id) {
    const Aabb listed_W = boxes.Get(slot);
    const Aabb& box_W = records_[id].box_W;
    if (std::memcmp(listed_W.min_W.data(), box_W.min_W.data(), 3 * sizeof(double)) == 0 &&
        std::memcmp(listed_W.max_W.data(), box_W.max_W.data(), 3 * sizeof(double)) == 0) {
      return true;
    }
  }
  return FailValidation(why, "primitive " + std::to_string(id) + " not at its slot of the " +
                                 list + " list with its box");
}

bool CellBroadPhase::ValidateRecord(PrimitiveId id, ListCounts* counts, std::string* why) const {
  std::ostringstream msg;
  const Record& r = records_[id];
  if (r.pair_stamp > scan_stamp_ || r.union_stamp > union_stamp_) {
    msg << "primitive " << id << " has a stamp from the future";
    return FailValidation(why, msg.str());
  }
  if (!r.present) {
    if (r.link_count != 0 || r.first_link != kNone) {
      msg << "absent primitive " << id << " still has links";
      return FailValidation(why, msg.str());
    }
    return true;
  }
  ++counts->present;
  if (!ValidateListed(id, "present", present_ids_, present_boxes_, r.present_slot, why)) {
    return false;
  }
  if (r.motion == Motion::kMoving) {
    ++counts->moving;
    if (moving_ids_.size() <= r.moving_slot || moving_ids_[r.moving_slot] != id) {
      msg << "primitive " << id << " not at its slot of the moving list";
      return FailValidation(why, msg.str());
    }
  }
  if (r.outside) {
    ++counts->outside;
    if (!ValidateListed(id, "outside", outside_ids_, outside_boxes_, r.outside_slot, why)) {
      return false;
    }
  }
  if (r.jumped && strategy_ != CellUpdateStrategy::kIncremental) {
    msg << "primitive " << id << " jumped under a reference strategy";
    return FailValidation(why, msg.str());
  }
  if (r.unlinked != (r.jumped || IsOversize(r.box_W))) {
    msg << "primitive " << id << " unlinked flag " << r.unlinked
        << " disagrees with its box and its last move";
    return FailValidation(why, msg.str());
  }
  if (r.unlinked) {
    ++counts->unlinked;
    if (!ValidateListed(id, "unlinked", unlinked_ids_, unlinked_boxes_, r.unlinked_slot, why)) {
      return false;
    }
    if (r.outside || r.link_count != 0) {
      msg << "unlinked primitive " << id << " is on the outside list or has links";
      return FailValidation(why, msg.str());
    }
    return true;
  }
  if (!needs_rebuild_) {
    if (r.outside == world_W_.Contains(r.box_W)) {
      msg << "primitive " << id << " outside flag " << r.outside << " disagrees with its box";
      return FailValidation(why, msg.str());
    }
    if (!world_W_.Overlaps(r.box_W) && r.link_count != 0) {
      msg << "primitive " << id << " is wholly outside the world but has links";
      return FailValidation(why, msg.str());
    }
  }
  return true;
}

bool CellBroadPhase::ValidateRecords(std::uint64_t* prim_links, std::string* why) const {
  std::ostringstream msg;
  ListCounts counts;
  *prim_links = 0;
  for (PrimitiveId id = 0; id < records_.size(); ++id) {
    if (!ValidateRecord(id, &counts, why)) return false;
    const Record& r = records_[id];
    if (!r.present) continue;
    std::uint32_t count = 0;
    std::uint32_t prev = kNone;
    for (std::uint32_t l = r.first_link; l != kNone; l = links_[l].next_of_prim) {
      if (l >= links_.size() || links_[l].prim != id || links_[l].prev_of_prim != prev ||
          count > live_links_) {
        msg << "broken location list of primitive " << id;
        return FailValidation(why, msg.str());
      }
      prev = l;
      ++count;
    }
    if (count != r.link_count) {
      msg << "primitive " << id << " link count " << r.link_count << " but list has " << count;
      return FailValidation(why, msg.str());
    }
    *prim_links += count;
  }
  if (counts.present != present_ids_.size() || counts.moving != moving_ids_.size() ||
      counts.outside != outside_ids_.size() || outside_boxes_.size() != outside_ids_.size() ||
      counts.unlinked != unlinked_ids_.size() || unlinked_boxes_.size() != unlinked_ids_.size() ||
      present_boxes_.size() != present_ids_.size()) {
    return FailValidation(why,
                          "present/moving/outside/unlinked list sizes disagree with the records");
  }
  return true;
}

bool CellBroadPhase::ValidateCellLists(std::uint64_t* cell_links, std::string* why) const {
  std::ostringstream msg;
  *cell_links = 0;
  for (std::uint32_t c = 0; c < cell_head_.size(); ++c) {
    if (cell_visit_[c] > visit_stamp_) {
      msg << "cell " << c << " visit stamp " << cell_visit_[c] << " > current " << visit_stamp_;
      return FailValidation(why, msg.str());
    }
    std::uint32_t count = 0;
    std::uint32_t prev = kNone;
    for (std::uint32_t l = cell_head_[c]; l != kNone; l = links_[l].next_in_cell) {
      if (l >= links_.size() || links_[l].cell != c || links_[l].prev_in_cell != prev ||
          count > live_links_ || !records_[links_[l].prim].present) {
        msg << "broken member list of cell " << c;
        return FailValidation(why, msg.str());
      }
      prev = l;
      ++count;
    }
    if (count != cell_count_[c]) {
      msg << "cell " << c << " count " << cell_count_[c] << " but list has " << count;
      return FailValidation(why, msg.str());
    }
    *cell_links += count;
  }
  return true;
}

bool CellBroadPhase::ValidateShared(std::string* why) const {
  std::uint64_t prim_links = 0, cell_links = 0;
  if (!ValidateRecords(&prim_links, why) || !ValidateCellLists(&cell_links, why)) return false;
  if (cell_links != live_links_ || prim_links != live_links_) {
    std::ostringstream msg;
    msg << "link totals disagree: cells " << cell_links << ", primitives " << prim_links
        << ", live " << live_links_;
    return FailValidation(why, msg.str());
  }
  std::uint64_t free_links = 0;
  for (std::uint32_t l = free_link_; l != kNone; l = links_[l].next_in_cell) {
    if (++free_links > links_.size()) return FailValidation(why, "cycle in the free link list");
  }
  if (free_links + live_links_ != links_.size()) {
    return FailValidation(why, "free + live links != link pool size");
  }
  return true;
}

}  // namespace arm_collision_monitor
