#include "arm_collision_monitor/broadphase/octree_broad_phase.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "arm_collision_monitor/broadphase/broad_phase_util.h"
#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

// The seed's minimum cell: the deepest level whose cells are still at least min_cell_size_m
// (250 in / 2^7 = 1.95 in for 1.2 in of motion per cycle).
// The octree counts a box's cells for the unlinked list (kOversizeCells) in cells of this many
// minimum leaves per edge: leaves are split only where more than N boxes crowd, so a box meets
// far fewer leaves than minimum cells; an arm link's box (under a metre long) stays indexed,
// while a box grown by a large tolerance (over about 1.2 m at the default's leaves of 2 in)
// goes to the list.
constexpr double kOversizeLeaves = 8.0;

int DepthFor(double edge_m, double min_cell_size_m) {
  int depth = 0;
  while (depth < kOctreeMaxDepth &&
         edge_m / static_cast<double>(1u << (depth + 1)) >= min_cell_size_m) {
    ++depth;
  }
  return depth;
}

double LeafSize(const BroadPhaseOptions& options) {
  const double edge_m = WorldCubeEdge(options.world_W);
  return edge_m / static_cast<double>(1u << DepthFor(edge_m, options.min_cell_size_m));
}

// The root cube, with its upper corner computed exactly as every other lattice point.
Aabb RootCube(const BroadPhaseOptions& options) {
  const double edge_m = WorldCubeEdge(options.world_W);
  const int depth = DepthFor(edge_m, options.min_cell_size_m);
  const double leaf_m = edge_m / static_cast<double>(1u << depth);
  Aabb root_W;
  root_W.min_W = options.world_W.min_W;
  for (int a = 0; a < 3; ++a) {
    root_W.max_W[a] = LatticeCoordinate(root_W.min_W[a], 1u << depth, leaf_m);
  }
  return root_W;
}

}  // namespace

OctreeBroadPhase::OctreeBroadPhase(const BroadPhaseOptions& options, CellUpdateStrategy strategy)
    : CellBroadPhase(RootCube(options), options.techniques, strategy, LeafSize(options),
                     kOversizeLeaves * LeafSize(options)),
      min_leaf_m_(LeafSize(options)),
      max_depth_(DepthFor(WorldCubeEdge(options.world_W), options.min_cell_size_m)),
      max_objects_per_leaf_(static_cast<std::uint32_t>(std::max(1, options.max_objects_per_leaf))) {
  nodes_.resize(1);  // the root, an empty leaf
  ResizeCells(1);
}

std::string OctreeBroadPhase::name() const {
  switch (strategy_) {
    case CellUpdateStrategy::kIncremental:
      return "octree";
    case CellUpdateStrategy::kReinsert:
      return "reinsert";
    case CellUpdateStrategy::kRebuild:
      return "rebuild";
  }
  return "octree";
}

void OctreeBroadPhase::Reserve(std::uint32_t max_primitives, std::uint32_t max_nodes) {
  ReserveShared(max_primitives,
                max_primitives * static_cast<std::uint32_t>(kReservedLinksPerPrimitive) + max_nodes,
                max_nodes);
  nodes_.reserve(max_nodes);
}

Aabb OctreeBroadPhase::CellBox(std::uint32_t node) const {
  const Node& n = nodes_[node];
  const std::uint32_t size = SizeUnits(node);
  const std::uint32_t u[3] = {n.x, n.y, n.z};
  Aabb box_W;
  for (int a = 0; a < 3; ++a) {
    box_W.min_W[a] = LatticeCoordinate(world_W_.min_W[a], u[a], min_leaf_m_);
    box_W.max_W[a] = LatticeCoordinate(world_W_.min_W[a], u[a] + size, min_leaf_m_);
  }
  return box_W;
}

std::uint32_t OctreeBroadPhase::AllocateBlock() {
  std::uint32_t first;
  if (free_block_ != kNone) {
    first = free_block_;
    free_block_ = nodes_[first].next_free;
  } else {
    first = static_cast<std::uint32_t>(nodes_.size());
    nodes_.resize(nodes_.size() + 8);
    ResizeCells(nodes_.size());
  }
  return first;
}

void OctreeBroadPhase::FreeBlock(std::uint32_t first) {
  for (std::uint32_t c = 0; c < 8; ++c) {
    nodes_[first + c].is_free = true;
    nodes_[first + c].is_split = false;
  }
  nodes_[first].next_free = free_block_;
  free_block_ = first;
}

// The seed's SplitNode plus the redistribution loop of SplitInsert / UpdateSplitInsert: the
// children are stamped as visited by the current update (they are decided here, exactly).
void OctreeBroadPhase::SplitLeaf(std::uint32_t leaf) {
  const std::uint32_t first = AllocateBlock();  // may reallocate nodes_: index from here on
  const std::uint32_t half = SizeUnits(leaf) / 2;
  for (std::uint32_t c = 0; c < 8; ++c) {
    Node& child = nodes_[first + c];
    const Node& parent = nodes_[leaf];
    child.x = parent.x + ((c & 1u) ? half : 0u);
    child.y = parent.y + ((c & 2u) ? half : 0u);
    child.z = parent.z + ((c & 4u) ? half : 0u);
    child.level = static_cast<std::uint8_t>(parent.level + 1);
    child.parent = leaf;
    child.first_child = kNone;
    child.is_split = false;
    child.is_free = false;
    child.next_free = kNone;
    cell_visit_[first + c] = visit_stamp_;
  }
  nodes_[leaf].is_split = true;
  nodes_[leaf].first_child = first;
  Aabb child_W[8];
  for (std::uint32_t c = 0; c < 8; ++c) child_W[c] = CellBox(first + c);
  while (cell_head_[leaf] != kNone) {
    const std::uint32_t l = cell_head_[leaf];
    const PrimitiveId q = links_[l].prim;
    for (std::uint32_t c = 0; c < 8; ++c) {
      ++counters_.object_node_tests;
      if (records_[q].box_W.Overlaps(child_W[c])) AddLink(q, first + c);
    }
    RemoveLink(l);
  }
  ++counters_.splits;
}

// A split separates only boxes that fit in a child: boxes larger than a child land in several
// children (a crowd of mutually overlapping inflated boxes in all eight), so splitting a leaf
// whose members are mostly such boxes multiplies links and neighbour walks without separating
// anything (the pathology of boxes larger than cells: 10^4 leaves per box at the minimum size).
// True when more than N of the leaf's members, with `id`, have every edge within a child's.
bool OctreeBroadPhase::SplitSeparates(std::uint32_t leaf, PrimitiveId id) const {
  const double child_m = static_cast<double>(SizeUnits(leaf) / 2) * min_leaf_m_;
  auto fits = [&](PrimitiveId q) {
    const Aabb& box_W = records_[q].box_W;
    return ((box_W.max_W - box_W.min_W).array() <= child_m).all();
  };
  std::uint32_t fitting = fits(id) ? 1 : 0;
  for (std::uint32_t l = cell_head_[leaf]; l != kNone; l = links_[l].next_in_cell) {
    if (fits(links_[l].prim) && ++fitting > max_objects_per_leaf_) return true;
  }
  return fitting > max_objects_per_leaf_;
}

// The seed's AddObjectToNode / SplitInsert: at most N per leaf, except at the minimum size and
// where a split would separate nothing (SplitSeparates).
void OctreeBroadPhase::InsertIntoLeaf(PrimitiveId id, std::uint32_t leaf) {
  if (cell_count_[leaf] < max_objects_per_leaf_ || nodes_[leaf].level == max_depth_ ||
      !SplitSeparates(leaf, id)) {
    AddLink(id, leaf);
    return;
  }
  SplitLeaf(leaf);
  const std::uint32_t first = nodes_[leaf].first_child;
  for (std::uint32_t c = 0; c < 8; ++c) {
    ++counters_.object_node_tests;
    if (records_[id].box_W.Overlaps(CellBox(first + c))) InsertIntoLeaf(id, first + c);
  }
}

// A child's cell is its parent's with one bound per axis moved to the split plane
// (LatticeCoordinate, bit for bit as CellBox(child)); with the parent's cell overlapped, the
// child's is overlapped iff on each axis the box reaches the split plane from the child's side.
void OctreeBroadPhase::InsertFrom(PrimitiveId id, std::uint32_t node) {
  if (!nodes_[node].is_split) {
    InsertIntoLeaf(id, node);
    return;
  }
  // Splits below may reallocate nodes_: what the loop needs is copied first.
  const Node& n = nodes_[node];
  const std::uint32_t first_child = n.first_child;
  const std::uint32_t half = SizeUnits(node) / 2;
  const std::uint32_t u[3] = {n.x + half, n.y + half, n.z + half};
  const Aabb& box_W = records_[id].box_W;
  bool reaches_low[3], reaches_high[3];  // per axis: the box meets the lower / upper child
  for (int a = 0; a < 3; ++a) {
    const double mid_m = LatticeCoordinate(world_W_.min_W[a], u[a], min_leaf_m_);
    reaches_low[a] = box_W.min_W[a] <= mid_m;
    reaches_high[a] = box_W.max_W[a] >= mid_m;
  }
  for (std::uint32_t c = 0; c < 8; ++c) {
    ++counters_.object_node_tests;
    if ((c & 1u ? reaches_high[0] : reaches_low[0]) &&
        (c & 2u ? reaches_high[1] : reaches_low[1]) &&
        (c & 4u ? reaches_high[2] : reaches_low[2])) {
      InsertFrom(id, first_child + c);
    }
  }
}

// The seed's InsertObject from the root.
void OctreeBroadPhase::InsertIntoCells(PrimitiveId id) {
  ++counters_.object_node_tests;
  if (records_[id].box_W.Overlaps(CellBox(0))) InsertFrom(id, 0);
}

// Samet, "Neighbor finding in images represented by octrees" (CVGIP 46, 1989): ascend to the
// nearest ancestor containing the adjacent cell, then descend toward it, stopping at a leaf or
// at the leaf's own level. Done on integer lattice coordinates instead of child-number tables.
std::uint32_t OctreeBroadPhase::FindNeighbour(std::uint32_t leaf, const int d[3]) const {
  const Node& y = nodes_[leaf];
  const std::int64_t size = SizeUnits(leaf);
  const std::int64_t extent = std::int64_t{1} << max_depth_;
  const std::int64_t u[3] = {y.x, y.y, y.z};
  std::int64_t t[3];
  for (int a = 0; a < 3; ++a) {
    t[a] = u[a] + d[a] * size;
    if (t[a] < 0 || t[a] >= extent) return kNone;  // beyond the world cube
  }
  std::uint32_t n = leaf;
  for (;;) {
    const Node& cand = nodes_[n];
    const std::int64_t s = SizeUnits(n);
    if (cand.x <= t[0] && t[0] < cand.x + s && cand.y <= t[1] && t[1] < cand.y + s &&
        cand.z <= t[2] && t[2] < cand.z + s) {
      break;
    }
    n = cand.parent;  // the root contains every in-range target, so this ends
  }
  while (nodes_[n].is_split && nodes_[n].level < y.level) {
    const Node& cand = nodes_[n];
    const std::int64_t half = SizeUnits(n) / 2;
    const std::uint32_t c = (t[0] >= cand.x + half ? 1u : 0u) | (t[1] >= cand.y + half ? 2u : 0u) |
                            (t[2] >= cand.z + half ? 4u : 0u);
    n = cand.first_child + c;
  }
  return n;
}

bool OctreeBroadPhase::Touches(std::uint32_t a, std::uint32_t b) const {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  const std::uint32_t sa = SizeUnits(a), sb = SizeUnits(b);
  return na.x <= nb.x + sb && nb.x <= na.x + sa && na.y <= nb.y + sb && nb.y <= na.y + sa &&
         na.z <= nb.z + sb && nb.z <= na.z + sa;
}

// The seed's UpdateNeighbor: a split neighbour is entered only through its children on the
// face, edge or corner shared with the leaf the primitive came from.
void OctreeBroadPhase::UpdateNeighbour(PrimitiveId id, std::uint32_t node, std::uint32_t from_leaf,
                                       std::uint32_t stamp) {
  ++counters_.neighbours_visited;
  if (nodes_[node].is_split) {
    if (techniques_.bounding_box_pretests) {
      // One box test can rule out a whole subtree before its leaves are visited.
      ++counters_.object_node_tests;
      if (!records_[id].box_W.Overlaps(CellBox(node))) return;
    }
    const std::uint32_t first = nodes_[node].first_child;
    for (std::uint32_t c = 0; c < 8; ++c) {
      if (Touches(first + c, from_leaf)) UpdateNeighbour(id, first + c, from_leaf, stamp);
    }
    return;
  }
  if (cell_visit_[node] == stamp) return;
  cell_visit_[node] = stamp;
  ++counters_.object_node_tests;
  if (!records_[id].box_W.Overlaps(CellBox(node))) return;
  InsertIntoLeaf(id, node);
}

// The seed's UpdateObject, collision checks left to FindPairs. Exactness: see the argument at
// the top of cell_broad_phase.cpp (every new leaf touches an old one).
void OctreeBroadPhase::UpdateCells(PrimitiveId id, const Aabb& old_box_W) {
  const std::uint32_t stamp = NextVisitStamp();
  const std::uint32_t old_head = records_[id].first_link;
  StampLinkedCells(id, stamp);
  // New links go to the front of the primitive's list, so the old ones stay from old_head on.
  for (std::uint32_t l = old_head; l != kNone; l = links_[l].next_of_prim) {
    const std::uint32_t leaf = links_[l].cell;
    const CellReach reach = ComputeCellReach(old_box_W, records_[id].box_W, CellBox(leaf));
    // BoundingBoxInsideNode: strictly inside its leaf, the box touches no neighbour.
    if (techniques_.inside_node_exit && reach.reach_new == 0) continue;
    for (const Direction& dir : Directions()) {
      if (!NeedsDirection(reach, dir)) continue;  // NeighborInDirection
      const std::uint32_t neighbour = FindNeighbour(leaf, dir.d);
      if (neighbour != kNone) UpdateNeighbour(id, neighbour, leaf, stamp);
    }
  }
  // Exits: old leaves the box no longer overlaps; then merge where the rule allows.
  scratch_cells_.clear();
  RemoveExitedLinks(
      id, old_head, [this](std::uint32_t leaf) { return CellBox(leaf); },
      [this](std::uint32_t leaf) {
        if (leaf != 0) scratch_cells_.push_back(nodes_[leaf].parent);
      });
  MergeQueuedParents();
}

void OctreeBroadPhase::RemoveFromCells(PrimitiveId id) {
  scratch_cells_.clear();
  while (records_[id].first_link != kNone) {
    const std::uint32_t l = records_[id].first_link;
    const std::uint32_t leaf = links_[l].cell;
    RemoveLink(l);
    if (leaf != 0) scratch_cells_.push_back(nodes_[leaf].parent);
  }
  MergeQueuedParents();
}

void OctreeBroadPhase::MergeQueuedParents() {
  // A primitive's links to sibling leaves lie next to each other (inserted depth first): their
  // parent, queued once per link, is tried once per run (a second try would find what the
  // first left).
  for (std::size_t i = 0; i < scratch_cells_.size(); ++i) {
    if (i == 0 || scratch_cells_[i] != scratch_cells_[i - 1]) TryMergeUpward(scratch_cells_[i]);
  }
  scratch_cells_.clear();
}

// Merge eight leaf siblings into their parent when together they hold at most N distinct
// primitives (the inverse of the decomposition rule), and repeat one level up.
void OctreeBroadPhase::TryMergeUpward(std::uint32_t node) {
  while (node != kNone) {
    if (nodes_[node].is_free || !nodes_[node].is_split) return;
    const std::uint32_t first = nodes_[node].first_child;
    for (std::uint32_t c = 0; c < 8; ++c) {
      if (nodes_[first + c].is_split) return;
    }
    const std::uint32_t count_stamp = NextUnionStamp();
    std::uint32_t distinct = 0;
    for (std::uint32_t c = 0; c < 8; ++c) {
      for (std::uint32_t l = cell_head_[first + c]; l != kNone; l = links_[l].next_in_cell) {
        Record& r = records_[links_[l].prim];
        if (r.union_stamp == count_stamp) continue;
        r.union_stamp = count_stamp;
        if (++distinct > max_objects_per_leaf_) return;
      }
    }
    const std::uint32_t merge_stamp = NextUnionStamp();
    for (std::uint32_t c = 0; c < 8; ++c) {
      while (cell_head_[first + c] != kNone) {
        const std::uint32_t l = cell_head_[first + c];
        const PrimitiveId q = links_[l].prim;
        if (records_[q].union_stamp != merge_stamp) {
          records_[q].union_stamp = merge_stamp;
          AddLink(q, node);
        }
        RemoveLink(l);
      }
    }
    nodes_[node].is_split = false;
    nodes_[node].first_child = kNone;
    FreeBlock(first);
    ++counters_.merges;
    node = nodes_[node].parent;
  }
}

void OctreeBroadPhase::ClearCells() {
  ClearLinks();
  nodes_.resize(1);
  nodes_[0] = Node{};
  free_block_ = kNone;
  ResizeCells(1);
}

void OctreeBroadPhase::CollectOverlappedLeaves(const Aabb& box_W, std::uint32_t node,
                                               std::vector<std::uint32_t>* leaves) const {
  if (!box_W.Overlaps(CellBox(node))) return;
  if (!nodes_[node].is_split) {
    leaves->push_back(node);
    return;
  }
  for (std::uint32_t c = 0; c < 8; ++c) {
    CollectOverlappedLeaves(box_W, nodes_[node].first_child + c, leaves);
  }
}

bool OctreeBroadPhase::ValidateSplitNode(std::uint32_t n, std::vector<std::uint32_t>* region_stamp,
                                         std::uint32_t region, std::string* why) const {
  std::ostringstream msg;
  const Node& node = nodes_[n];
  if (cell_head_[n] != kNone || cell_count_[n] != 0 || node.level >= max_depth_ ||
      node.first_child == kNone || node.first_child + 8 > nodes_.size()) {
    msg << "internal node " << n << " holds primitives, is too deep or has no children";
    return FailValidation(why, msg.str());
  }
  const std::uint32_t half = SizeUnits(n) / 2;
  for (std::uint32_t c = 0; c < 8; ++c) {
    const Node& child = nodes_[node.first_child + c];
    if (child.parent != n || child.level != node.level + 1 ||
        child.x != node.x + ((c & 1u) ? half : 0u) ||
        child.y != node.y + ((c & 2u) ? half : 0u) ||
        child.z != node.z + ((c & 4u) ? half : 0u)) {
      msg << "child " << c << " of node " << n << " has a wrong parent, level or corner";
      return FailValidation(why, msg.str());
    }
  }
  // Canonical shape: a split node holds more than N distinct primitives in its region, else
  // its children should have merged (and it should never have split).
  std::uint32_t distinct = 0;
  ForEachNodeBelow(n, [&](std::uint32_t s) {
    if (nodes_[s].is_split) return;
    for (std::uint32_t l = cell_head_[s]; l != kNone; l = links_[l].next_in_cell) {
      if ((*region_stamp)[links_[l].prim] != region) {
        (*region_stamp)[links_[l].prim] = region;
        ++distinct;
      }
    }
  });
  if (distinct <= max_objects_per_leaf_) {
    msg << "split node " << n << " holds only " << distinct << " <= N distinct primitives";
    return FailValidation(why, msg.str());
  }
  return true;
}

bool OctreeBroadPhase::ValidateReachableNodes(std::vector<char>* reached,
                                              std::size_t* reached_count,
                                              std::string* why) const {
  std::ostringstream msg;
  reached->assign(nodes_.size(), 0);
  *reached_count = 0;
  std::vector<std::uint32_t> stack = {0};
  std::vector<std::uint32_t> region_stamp(records_.size(), 0);
  std::uint32_t region = 0;
  while (!stack.empty()) {
    const std::uint32_t n = stack.back();
    stack.pop_back();
    const Node& node = nodes_[n];
    if ((*reached)[n] || node.is_free) {
      msg << "node " << n << " reached twice or free";
      return FailValidation(why, msg.str());
    }
    (*reached)[n] = 1;
    ++*reached_count;
    // A leaf may hold more than N: a split is decided when a primitive enters (SplitSeparates),
    // and boxes change size in place afterwards (a turning capsule), so no capacity rule on
    // leaves holds at all times; the canonical-shape rule of split nodes below does.
    if (!node.is_split) continue;
    if (!ValidateSplitNode(n, &region_stamp, ++region, why)) return false;
    for (std::uint32_t c = 0; c < 8; ++c) stack.push_back(node.first_child + c);
  }
  return true;
}

bool OctreeBroadPhase::ValidateFreeBlocks(const std::vector<char>& reached,
                                          std::size_t reached_count, std::string* why) const {
  std::ostringstream msg;
  std::size_t free_count = 0;
  for (std::uint32_t b = free_block_; b != kNone; b = nodes_[b].next_free) {
    for (std::uint32_t c = 0; c < 8; ++c) {
      if (b + c >= nodes_.size() || !nodes_[b + c].is_free || reached[b + c] ||
          cell_count_[b + c] != 0) {
        msg << "free block " << b << " is in use or holds primitives";
        return FailValidation(why, msg.str());
      }
    }
    free_count += 8;
    if (free_count > nodes_.size()) {
      msg << "cycle in the free block list";
      return FailValidation(why, msg.str());
    }
  }
  if (reached_count + free_count != nodes_.size()) {
    msg << "node pool " << nodes_.size() << " != reachable " << reached_count << " + free "
        << free_count;
    return FailValidation(why, msg.str());
  }
  return true;
}

bool OctreeBroadPhase::ValidateCells(std::string* why) const {
  if (nodes_.empty() || nodes_[0].is_free || nodes_[0].parent != kNone || nodes_[0].level != 0 ||
      (nodes_.size() - 1) % 8 != 0 || cell_head_.size() != nodes_.size()) {
    std::ostringstream msg;
    msg << "bad root or node pool size " << nodes_.size();
    return FailValidation(why, msg.str());
  }
  // Structure: reachable nodes, then the free blocks, must account for the whole pool.
  std::vector<char> reached;
  std::size_t reached_count = 0;
  if (!ValidateReachableNodes(&reached, &reached_count, why) ||
      !ValidateFreeBlocks(reached, reached_count, why)) {
    return false;
  }
  // Location links: exactly the leaves each inflated box overlaps (closed boxes).
  std::vector<std::uint32_t> expected, actual;
  for (PrimitiveId id = 0; id < records_.size(); ++id) {
    const Record& r = records_[id];
    if (!r.present || r.unlinked) continue;  // an unlinked one has no links (ValidateShared)
    expected.clear();
    CollectOverlappedLeaves(r.box_W, 0, &expected);
    std::sort(expected.begin(), expected.end());
    if (!LinkedCellsEqual(id, expected, &actual, why)) return false;
  }
  return true;
}

OctreeStatistics OctreeBroadPhase::ComputeStatistics() const {
  OctreeStatistics stats;
  std::uint64_t nonempty_links = 0;
  std::uint32_t nonempty = 0;
  ForEachNodeBelow(0, [&](std::uint32_t n) {
    ++stats.nodes;
    if (nodes_[n].is_split) return;
    ++stats.leaves;
    stats.depth = std::max(stats.depth, static_cast<int>(nodes_[n].level));
    if (cell_count_[n] == 0) {
      ++stats.empty_leaves;
    } else {
      ++nonempty;
      nonempty_links += cell_count_[n];
    }
  });
  std::size_t indexed = 0;
  for (const PrimitiveId id : present_ids_) indexed += records_[id].link_count > 0 ? 1 : 0;
  stats.mean_primitives_per_nonempty_leaf =
      nonempty > 0 ? static_cast<double>(nonempty_links) / nonempty : 0.0;
  stats.mean_leaves_per_primitive =
      indexed > 0 ? static_cast<double>(live_links_) / static_cast<double>(indexed) : 0.0;
  return stats;
}

void OctreeBroadPhase::CollectCells(std::vector<IndexCell>* cells) const {
  cells->clear();
  ForEachNodeBelow(0, [&](std::uint32_t n) {
    if (!nodes_[n].is_split) cells->push_back(MakeIndexCell(n, CellBox(n)));
  });
}

}  // namespace arm_collision_monitor
