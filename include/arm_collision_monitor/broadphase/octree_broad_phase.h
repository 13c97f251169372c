// The seed's N-objects octree (Shaffer & Herb, TR 90-28, section 3): a leaf splits when more
// than N primitives lie in it and more than N of them fit in a child (boxes larger than the
// children would not be separated), never below the minimum cell size (the farthest any primitive
// moves in one cycle); moving primitives are followed by visiting only the face, edge and
// corner neighbours of the leaves they were in, toward where they now reach, and siblings merge
// when the primitives leave. The same class also runs the two update schemes the seed rejects
// (rebuild every cycle, delete and re-insert), for comparison.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/cell_broad_phase.h"

namespace arm_collision_monitor {

/// Shape of the tree, for the benchmark report (the seed's section 5 figures).
struct OctreeStatistics {
  std::uint32_t nodes = 0;
  std::uint32_t leaves = 0;
  std::uint32_t empty_leaves = 0;
  double mean_primitives_per_nonempty_leaf = 0.0;
  double mean_leaves_per_primitive = 0.0;  ///< over primitives with at least one leaf
  int depth = 0;                           ///< deepest leaf level (root = 0)
};

class OctreeBroadPhase final : public CellBroadPhase {
 public:
  /// Uses options.world_W (made a cube on its min corner with the largest edge),
  /// max_objects_per_leaf, min_cell_size_m, techniques.
  OctreeBroadPhase(const BroadPhaseOptions& options, CellUpdateStrategy strategy);

  std::string name() const override;
  void CollectCells(std::vector<IndexCell>* cells) const override;

  /// Preallocates for up to `max_primitives` ids and `max_nodes` nodes so that the steady
  /// state allocates nothing (it would not anyway once the pools reach their high-water mark).
  void Reserve(std::uint32_t max_primitives, std::uint32_t max_nodes);

  OctreeStatistics ComputeStatistics() const;
  /// Edge of the smallest leaf allowed (m): root / 2^max_depth, the smallest such value that is
  /// at least options.min_cell_size_m.
  double min_leaf_size_m() const { return min_leaf_m_; }
  int max_depth() const { return max_depth_; }
  const Aabb& root_W() const { return world_W_; }

 private:
  struct Node {
    std::uint32_t x = 0, y = 0, z = 0;  // min corner in units of min_leaf_m_ from the origin
    std::uint32_t parent = kNone;
    std::uint32_t first_child = kNone;  // children are 8 consecutive nodes (a block)
    std::uint8_t level = 0;             // root = 0
    bool is_split = false;
    bool is_free = false;  // in the free block list (its index may still sit in a queue)
    std::uint32_t next_free = kNone;
  };

  void InsertIntoCells(PrimitiveId id) override;
  void UpdateCells(PrimitiveId id, const Aabb& old_box_W) override;
  void RemoveFromCells(PrimitiveId id) override;
  void ClearCells() override;
  bool ValidateCells(std::string* why) const override;

  Aabb CellBox(std::uint32_t node) const;
  std::uint32_t SizeUnits(std::uint32_t node) const {
    return 1u << (max_depth_ - nodes_[node].level);
  }
  /// The seed's InsertObject below `node`, whose cell `id`'s box overlaps: a child is entered
  /// where the box reaches its side of the node's split planes.
  void InsertFrom(PrimitiveId id, std::uint32_t node);
  void InsertIntoLeaf(PrimitiveId id, std::uint32_t leaf);
  bool SplitSeparates(std::uint32_t leaf, PrimitiveId id) const;
  void SplitLeaf(std::uint32_t leaf);
  std::uint32_t AllocateBlock();
  void FreeBlock(std::uint32_t first);
  /// Samet's neighbour finding: the node of at least the leaf's size adjacent to it on side d.
  std::uint32_t FindNeighbour(std::uint32_t leaf, const int d[3]) const;
  void UpdateNeighbour(PrimitiveId id, std::uint32_t node, std::uint32_t from_leaf,
                       std::uint32_t stamp);
  bool Touches(std::uint32_t a, std::uint32_t b) const;
  void TryMergeUpward(std::uint32_t node);
  void MergeQueuedParents();

  /// Calls visit(n) on `top` and every node below it, parents before their children.
  template <typename Fn>
  void ForEachNodeBelow(std::uint32_t top, Fn visit) const {
    std::vector<std::uint32_t> stack = {top};
    while (!stack.empty()) {
      const std::uint32_t n = stack.back();
      stack.pop_back();
      visit(n);
      if (nodes_[n].is_split) {
        for (std::uint32_t c = 0; c < 8; ++c) stack.push_back(nodes_[n].first_child + c);
      }
    }
  }
  void CollectOverlappedLeaves(const Aabb& box_W, std::uint32_t node,
                               std::vector<std::uint32_t>* leaves) const;
  // The parts of ValidateCells. ValidateSplitNode: the children's parent, level and corner,
  // and the canonical shape (more than N distinct primitives below; `region_stamp` marks the
  // primitives seen in `region`, a number new for each call). ValidateReachableNodes: every
  // node reachable from the root once, split nodes valid. ValidateFreeBlocks: the free list,
  // which with the reachable nodes makes the pool.
  bool ValidateSplitNode(std::uint32_t n, std::vector<std::uint32_t>* region_stamp,
                         std::uint32_t region, std::string* why) const;
  bool ValidateReachableNodes(std::vector<char>* reached, std::size_t* reached_count,
                              std::string* why) const;
  bool ValidateFreeBlocks(const std::vector<char>& reached, std::size_t reached_count,
                          std::string* why) const;

  std::vector<Node> nodes_;  // node 0 is the root; blocks of 8 from index 1
  std::uint32_t free_block_ = kNone;
  double min_leaf_m_ = 0.0;
  int max_depth_ = 0;
  std::uint32_t max_objects_per_leaf_ = 10;
};

}  // namespace arm_collision_monitor
