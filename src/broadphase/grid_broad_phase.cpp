#include "arm_collision_monitor/broadphase/grid_broad_phase.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "arm_collision_monitor/broadphase/broad_phase_util.h"
#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

int CellsPerAxis(const BroadPhaseOptions& options) {
  return std::clamp(options.grid_cells_per_axis, 1, 1 << 10);
}

double CellSize(const BroadPhaseOptions& options) {
  return WorldCubeEdge(options.world_W) / CellsPerAxis(options);
}

Aabb GridCube(const BroadPhaseOptions& options) {
  Aabb cube_W;
  cube_W.min_W = options.world_W.min_W;
  for (int a = 0; a < 3; ++a) {
    cube_W.max_W[a] = LatticeCoordinate(cube_W.min_W[a],
                                        static_cast<std::uint32_t>(CellsPerAxis(options)),
                                        CellSize(options));
  }
  return cube_W;
}

}  // namespace

GridBroadPhase::GridBroadPhase(const BroadPhaseOptions& options)
    // Range differences are exact for steps of any size: no jump limit (an infinite spacing).
    : CellBroadPhase(GridCube(options), options.techniques, CellUpdateStrategy::kIncremental,
                     std::numeric_limits<double>::infinity(), CellSize(options)),
      g_(CellsPerAxis(options)),
      cell_m_(CellSize(options)) {
  ResizeCells(static_cast<std::size_t>(g_) * g_ * g_);
}

void GridBroadPhase::Reserve(std::uint32_t max_primitives) {
  ReserveShared(max_primitives,
                max_primitives * static_cast<std::uint32_t>(kReservedLinksPerPrimitive),
                static_cast<std::uint32_t>(cell_head_.size()));
  if (ranges_.size() < max_primitives) ranges_.resize(max_primitives);
}

Aabb GridBroadPhase::CellBox(int i, int j, int k) const {
  const int u[3] = {i, j, k};
  Aabb box_W;
  for (int a = 0; a < 3; ++a) {
    box_W.min_W[a] =
        LatticeCoordinate(world_W_.min_W[a], static_cast<std::uint32_t>(u[a]), cell_m_);
    box_W.max_W[a] =
        LatticeCoordinate(world_W_.min_W[a], static_cast<std::uint32_t>(u[a] + 1), cell_m_);
  }
  return box_W;
}

void GridBroadPhase::CellCoordinates(std::uint32_t cell, int u[3]) const {
  u[0] = static_cast<int>(cell / (g_ * g_));
  u[1] = static_cast<int>((cell / g_) % g_);
  u[2] = static_cast<int>(cell % g_);
}

Aabb GridBroadPhase::CellBox(std::uint32_t cell) const {
  int u[3];
  CellCoordinates(cell, u);
  return CellBox(u[0], u[1], u[2]);
}

void GridBroadPhase::CandidateRange(const Aabb& box_W, int lo[3], int hi[3]) const {
  // Clamped as doubles first: a box reaching far beyond the cube must not overflow the cast.
  const double last = g_ - 1;
  for (int a = 0; a < 3; ++a) {
    lo[a] = static_cast<int>(
        std::clamp(std::floor((box_W.min_W[a] - world_W_.min_W[a]) / cell_m_) - 1, 0.0, last));
    hi[a] = static_cast<int>(
        std::clamp(std::floor((box_W.max_W[a] - world_W_.min_W[a]) / cell_m_) + 1, 0.0, last));
  }
}

void GridBroadPhase::OverlapRange(const Aabb& box_W, int lo[3], int hi[3]) const {
  CandidateRange(box_W, lo, hi);
  for (int a = 0; a < 3; ++a) {
    const double origin_m = world_W_.min_W[a];
    // Cell i spans [L(i), L(i + 1)] and overlaps the closed box on axis a iff
    // L(i) <= max and min <= L(i + 1); the cells that do are contiguous.
    while (lo[a] < g_ - 1 &&
           LatticeCoordinate(origin_m, static_cast<std::uint32_t>(lo[a] + 1), cell_m_) <
               box_W.min_W[a]) {
      ++lo[a];
    }
    while (hi[a] > 0 &&
           LatticeCoordinate(origin_m, static_cast<std::uint32_t>(hi[a]), cell_m_) >
               box_W.max_W[a]) {
      --hi[a];
    }
  }
}

void GridBroadPhase::InsertIntoCells(PrimitiveId id) {
  if (id >= ranges_.size()) ranges_.resize(records_.size());
  int* lo = ranges_[id].lo;
  int* hi = ranges_[id].hi;
  OverlapRange(records_[id].box_W, lo, hi);
  for (int i = lo[0]; i <= hi[0]; ++i) {
    for (int j = lo[1]; j <= hi[1]; ++j) {
      for (int k = lo[2]; k <= hi[2]; ++k) AddLink(id, Index(i, j, k));
    }
  }
  counters_.object_node_tests += 6;  // the range's faces
}

// Range difference: unlink the old cells outside the new range, link the new cells outside the
// old range. Exact for any step, as both ranges are exact (the links of a box are always its
// OverlapRange). The octree's neighbour techniques have nothing to skip here.
void GridBroadPhase::UpdateCells(PrimitiveId id, const Aabb& /*old_box_W*/) {
  // The old box's range is the one its links were made from.
  const CellRange old = ranges_[id];
  const int* old_lo = old.lo;
  const int* old_hi = old.hi;
  int* lo = ranges_[id].lo;
  int* hi = ranges_[id].hi;
  OverlapRange(records_[id].box_W, lo, hi);
  counters_.object_node_tests += 6;
  auto inside = [](const int u[3], const int l[3], const int h[3]) {
    return l[0] <= u[0] && u[0] <= h[0] && l[1] <= u[1] && u[1] <= h[1] && l[2] <= u[2] &&
           u[2] <= h[2];
  };
  for (std::uint32_t l = records_[id].first_link; l != kNone;) {
    const std::uint32_t next = links_[l].next_of_prim;
    int u[3];
    CellCoordinates(links_[l].cell, u);
    if (!inside(u, lo, hi)) RemoveLink(l);
    l = next;
  }
  for (int i = lo[0]; i <= hi[0]; ++i) {
    for (int j = lo[1]; j <= hi[1]; ++j) {
      for (int k = lo[2]; k <= hi[2]; ++k) {
        const int u[3] = {i, j, k};
        ++counters_.neighbours_visited;
        if (!inside(u, old_lo, old_hi)) AddLink(id, Index(i, j, k));
      }
    }
  }
}

void GridBroadPhase::RemoveFromCells(PrimitiveId id) {
  while (records_[id].first_link != kNone) RemoveLink(records_[id].first_link);
}

void GridBroadPhase::ClearCells() { ClearLinks(); }

bool GridBroadPhase::ValidateCells(std::string* why) const {
  if (cell_head_.size() != static_cast<std::size_t>(g_) * g_ * g_) {
    if (why != nullptr) *why = "grid cell arrays have the wrong size";
    return false;
  }
  std::vector<std::uint32_t> expected, actual;
  for (PrimitiveId id = 0; id < records_.size(); ++id) {
    const Record& r = records_[id];
    if (!r.present || r.unlinked) continue;  // an unlinked one has no links (ValidateShared)
    expected.clear();
    // Cells two or more away from the box's cell quotient cannot touch it (a wider window
    // than CandidateRange's, computed independently of it).
    if (!r.box_W.Overlaps(world_W_)) {
      if (r.link_count != 0) {
        if (why != nullptr) *why = "a box wholly outside the grid has cells";
        return false;
      }
      continue;
    }
    int lo[3], hi[3];
    const double last = g_ - 1;
    for (int a = 0; a < 3; ++a) {
      lo[a] = static_cast<int>(
          std::clamp((r.box_W.min_W[a] - world_W_.min_W[a]) / cell_m_ - 2, 0.0, last));
      hi[a] = static_cast<int>(
          std::clamp((r.box_W.max_W[a] - world_W_.min_W[a]) / cell_m_ + 2, 0.0, last));
    }
    for (int i = lo[0]; i <= hi[0]; ++i) {
      for (int j = lo[1]; j <= hi[1]; ++j) {
        for (int k = lo[2]; k <= hi[2]; ++k) {
          if (r.box_W.Overlaps(CellBox(i, j, k))) expected.push_back(Index(i, j, k));
        }
      }
    }
    if (!LinkedCellsEqual(id, expected, &actual, why)) return false;
    // The kept range is the box's (UpdateCells' old range).
    OverlapRange(r.box_W, lo, hi);
    for (int a = 0; a < 3; ++a) {
      if (ranges_[id].lo[a] != lo[a] || ranges_[id].hi[a] != hi[a]) {
        if (why != nullptr) *why = "a primitive's kept cell range is not its box's";
        return false;
      }
    }
  }
  return true;
}

void GridBroadPhase::CollectCells(std::vector<IndexCell>* cells) const {
  cells->clear();
  for (int i = 0; i < g_; ++i) {
    for (int j = 0; j < g_; ++j) {
      for (int k = 0; k < g_; ++k) {
        const std::uint32_t c = Index(i, j, k);
        if (cell_count_[c] != 0) cells->push_back(MakeIndexCell(c, CellBox(i, j, k)));
      }
    }
  }
}

}  // namespace arm_collision_monitor
