// Chooses and configures a broad phase by name, so the Monitor, the replay tool and the
// benchmarks can swap implementations by a parameter.
#pragma once

#include <memory>
#include <string>

#include "arm_collision_monitor/broadphase/broad_phase.h"

namespace arm_collision_monitor {

/// Which broad phase MakeBroadPhase builds (names as in ParseBroadPhaseMethod). kAuto: one of
/// naive, grid and octree, chosen from the scene by ChooseBroadPhaseMethod.
enum class BroadPhaseMethod { kAuto, kOctree, kNaive, kGrid, kRebuild, kReinsert };

/// Parses "auto", "octree", "naive", "grid", "rebuild", "reinsert". False if unknown.
bool ParseBroadPhaseMethod(const std::string& name, BroadPhaseMethod* method);
/// The name ParseBroadPhaseMethod accepts for `method`.
std::string BroadPhaseMethodName(BroadPhaseMethod method);

/// The seed's performance techniques; each can be switched off for the ablation benchmark.
/// Switching one off changes the work done, never the pairs returned.
struct BroadPhaseTechniques {
  bool directional_neighbours = true;  ///< only neighbours in the direction of motion
  bool inside_node_exit = true;        ///< skip neighbours when the box stays inside its leaf
  bool pair_deduplication = true;      ///< test each pair once per cycle
  /// Box tests before object-node / object-object work. In the octree: one test against a
  /// split neighbour before descending into its children (the grid has none to skip); the
  /// Monitor's narrow phase may read it for its own box pretests.
  bool bounding_box_pretests = true;
};

/// auto's rule: the fastest of naive, grid and octree per cycle for `moving` moving and
/// `statics` static primitives in the broad phase, by the crossovers that
/// bench_broadphase_workloads measures (its sweep prints the method this picks per point);
/// naive or the grid, as the octree was best at no point of the sweep (core/constants.h).
BroadPhaseMethod ChooseBroadPhaseMethod(std::uint32_t moving, std::uint32_t statics);

/// auto's grid resolution: the `configured` cells per axis, made coarser where the boxes are
/// larger than such cells: min(configured, cells of edge about `box_edge_m` across a world
/// cube of edge `world_edge_m`, kept within [kAutoGridMinCellsPerAxis,
/// kAutoGridMaxCellsPerAxis]); `configured` when either length is not positive and finite.
/// (Finer cells than configured measured no faster: 13 against 16 with 3,000 small statics.)
int GridCellsFor(double world_edge_m, double box_edge_m, int configured);

struct BroadPhaseOptions {
  BroadPhaseMethod method = BroadPhaseMethod::kAuto;
  /// For kAuto: the moving and static primitives the structure will hold (a caller that knows
  /// its scene sets them; the Monitor counts its active primitives at start-up; a static wholly
  /// outside the world cube is not counted: it is only in the all-pairs outside list), and the
  /// mean longest edge (m) of the moving primitives' inflated boxes (0: unknown). When auto picks
  /// the grid and knows that edge, cells smaller than it are coarsened to about it
  /// (GridCellsFor): boxes much larger than cells cost links and scans in every cell.
  std::uint32_t auto_moving = 0, auto_statics = 0;
  double auto_moving_box_edge_m = 0.0;
  Aabb world_W;                   ///< the world cube (octree root, grid extent)
  int max_objects_per_leaf = 10;  ///< the seed's decomposition rule N
  /// No cell is split below this edge length: the maximum speed times the cycle period (the
  /// farthest any primitive moves in one cycle). The octree rounds it up to root / 2^k.
  double min_cell_size_m = 0.61 * 0.05;  // the seed's 0.61 m/s (24 in/s) times 0.05 s (20 Hz)
  int grid_cells_per_axis = 16;   ///< G for the uniform grid
  /// Pools (node, location link, per-primitive arrays) are reserved at construction for this
  /// many primitive ids, so the cycle does not allocate; more still work (the pools grow once).
  std::uint32_t reserve_primitives = 256;
  BroadPhaseTechniques techniques;
};

/// The broad phase `options.method` names (kAuto: ChooseBroadPhaseMethod(options.auto_moving,
/// options.auto_statics)), configured by `options`, its pools reserved for
/// options.reserve_primitives ids.
std::unique_ptr<BroadPhase> MakeBroadPhase(const BroadPhaseOptions& options);

}  // namespace arm_collision_monitor
