#include "arm_collision_monitor/broadphase/broad_phase_factory.h"

#include <algorithm>
#include <cmath>

#include "arm_collision_monitor/broadphase/broad_phase_util.h"
#include "arm_collision_monitor/broadphase/grid_broad_phase.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/broadphase/naive_broad_phase.h"
#include "arm_collision_monitor/broadphase/octree_broad_phase.h"

namespace arm_collision_monitor {

bool ParseBroadPhaseMethod(const std::string& name, BroadPhaseMethod* method) {
  static constexpr BroadPhaseMethod kAll[] = {BroadPhaseMethod::kAuto,
                                              BroadPhaseMethod::kOctree, BroadPhaseMethod::kNaive,
                                              BroadPhaseMethod::kGrid, BroadPhaseMethod::kRebuild,
                                              BroadPhaseMethod::kReinsert};
  for (const BroadPhaseMethod m : kAll) {
    if (name == BroadPhaseMethodName(m)) {
      *method = m;
      return true;
    }
  }
  return false;
}

std::string BroadPhaseMethodName(BroadPhaseMethod method) {
  switch (method) {
    case BroadPhaseMethod::kAuto: return "auto";
    case BroadPhaseMethod::kOctree: return "octree";
    case BroadPhaseMethod::kNaive: return "naive";
    case BroadPhaseMethod::kGrid: return "grid";
    case BroadPhaseMethod::kRebuild: return "rebuild";
    case BroadPhaseMethod::kReinsert: return "reinsert";
  }
  return "unknown";
}

namespace {
std::unique_ptr<BroadPhase> MakeOctree(const BroadPhaseOptions& options,
                                       CellUpdateStrategy strategy) {
  auto octree = std::make_unique<OctreeBroadPhase>(options, strategy);
  // Nodes: a generous multiple of the primitives (the seed's 35 primitives needed 33 nodes).
  octree->Reserve(options.reserve_primitives, 8 * options.reserve_primitives + 1);
  return octree;
}
}  // namespace

BroadPhaseMethod ChooseBroadPhaseMethod(std::uint32_t moving, std::uint32_t statics) {
  const bool grid_wins = moving >= kAutoGridMinMoving ||
                         static_cast<double>(statics) >=
                             kAutoGridMinStatics + kAutoGridStaticsPerMover * moving;
  return grid_wins ? BroadPhaseMethod::kGrid : BroadPhaseMethod::kNaive;
}

int GridCellsFor(double world_edge_m, double box_edge_m, int configured) {
  auto is_length = [](double x_m) { return std::isfinite(x_m) && x_m > 0.0; };
  if (!is_length(world_edge_m) || !is_length(box_edge_m)) return configured;
  const double cells = std::clamp(std::round(world_edge_m / box_edge_m),
                                  double{kAutoGridMinCellsPerAxis},
                                  double{kAutoGridMaxCellsPerAxis});
  return std::min(configured, static_cast<int>(cells));
}

std::unique_ptr<BroadPhase> MakeBroadPhase(const BroadPhaseOptions& options) {
  switch (options.method) {
    case BroadPhaseMethod::kAuto: {
      BroadPhaseOptions chosen = options;
      chosen.method = ChooseBroadPhaseMethod(options.auto_moving, options.auto_statics);
      if (chosen.method == BroadPhaseMethod::kGrid) {
        chosen.grid_cells_per_axis =
            GridCellsFor(WorldCubeEdge(options.world_W), options.auto_moving_box_edge_m,
                         options.grid_cells_per_axis);
      }
      return MakeBroadPhase(chosen);
    }
    case BroadPhaseMethod::kNaive: {
      auto naive = std::make_unique<NaiveBroadPhase>();
      naive->Reserve(options.reserve_primitives);
      return naive;
    }
    case BroadPhaseMethod::kGrid: {
      auto grid = std::make_unique<GridBroadPhase>(options);
      grid->Reserve(options.reserve_primitives);
      return grid;
    }
    case BroadPhaseMethod::kOctree:
      return MakeOctree(options, CellUpdateStrategy::kIncremental);
    case BroadPhaseMethod::kRebuild:
      return MakeOctree(options, CellUpdateStrategy::kRebuild);
    case BroadPhaseMethod::kReinsert:
      return MakeOctree(options, CellUpdateStrategy::kReinsert);
  }
  return nullptr;
}

}  // namespace arm_collision_monitor
