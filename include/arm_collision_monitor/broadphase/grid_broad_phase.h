// The uniform grid the seed compares the octree with (section 5): a G x G x G array of cells
// over the world cube that never split or merge. A moved box's cells are a range of cell
// indices on each axis, so its update is the difference of its old and new ranges: cost in
// proportion to the cells it leaves and enters, whatever the size of the step or of the box.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/cell_broad_phase.h"

namespace arm_collision_monitor {

class GridBroadPhase final : public CellBroadPhase {
 public:
  /// Uses options.world_W (made a cube on its min corner with the largest edge),
  /// grid_cells_per_axis (G), techniques.
  explicit GridBroadPhase(const BroadPhaseOptions& options);

  std::string name() const override { return "grid"; }
  /// The non-empty cells (an empty grid cell carries no information).
  void CollectCells(std::vector<IndexCell>* cells) const override;

  /// Preallocates for up to `max_primitives` ids so that the steady state allocates nothing.
  void Reserve(std::uint32_t max_primitives);

  double cell_size_m() const { return cell_m_; }

 private:
  void InsertIntoCells(PrimitiveId id) override;
  void UpdateCells(PrimitiveId id, const Aabb& old_box_W) override;
  void RemoveFromCells(PrimitiveId id) override;
  void ClearCells() override;
  bool ValidateCells(std::string* why) const override;

  std::uint32_t Index(int i, int j, int k) const {
    return (static_cast<std::uint32_t>(i) * g_ + j) * g_ + k;
  }
  Aabb CellBox(int i, int j, int k) const;
  Aabb CellBox(std::uint32_t cell) const;
  /// Inverse of Index().
  void CellCoordinates(std::uint32_t cell, int u[3]) const;
  /// Cell index range on each axis that can overlap the box (one cell of slack each side
  /// against rounding; the exact test decides).
  void CandidateRange(const Aabb& box_W, int lo[3], int hi[3]) const;
  /// The cells the closed box overlaps: lo[a]..hi[a] on each axis (the same closed test as
  /// Aabb::Overlaps against CellBox, done per axis). Precondition: the box meets the grid cube.
  void OverlapRange(const Aabb& box_W, int lo[3], int hi[3]) const;

  // Per primitive: the OverlapRange of its box as last linked (InsertIntoCells, UpdateCells),
  // the old range of its next UpdateCells.
  struct CellRange {
    int lo[3] = {0, 0, 0};
    int hi[3] = {-1, -1, -1};
  };
  std::vector<CellRange> ranges_;
  int g_;
  double cell_m_;
};

}  // namespace arm_collision_monitor
