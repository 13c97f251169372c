// Seeded random scenes for the broad-phase tests and benchmarks: static boxes scattered through
// a world cube and moving capsule-like boxes (arm links) that drift and turn within a speed
// bound, with optional jumps beyond it, excursions out of the world cube, add/remove at run
// time, lattice-aligned coordinates (boxes exactly on cell faces, edges, corners) and random
// compatibility marks. Every random draw comes from one std::mt19937_64 seeded by the caller.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/broadphase/broad_phase_factory.h"

namespace arm_collision_monitor {
namespace test {

struct SceneConfig {
  std::uint64_t seed = 1;
  int statics = 35;
  int movers = 14;
  Eigen::Vector3d world_min_W = Eigen::Vector3d::Constant(-3.175);
  double world_edge_m = 6.35;
  double max_speed_mps = 0.61;  // bound on any surface point's speed
  double period_s = 0.05;
  double mover_length_m = 0.4;  // capsule segment length
  double mover_radius_m = 0.06;
  double static_half_min_m = 0.01, static_half_max_m = 0.3;
  double tolerance_max_m = 0.03;
  double jump_probability = 0.0;      // per mover per cycle: teleport anywhere in the world
  double leave_probability = 0.0;     // per mover per cycle: teleport partly or fully outside
  double remove_probability = 0.0;    // per cycle: remove one present primitive (re-added later)
  double compatible_fraction = 0.05;  // share of pairs marked compatible at start
  double flip_probability = 0.0;      // per cycle: flip one random compatibility mark
  /// Snap every coordinate to the lattice origin + i * snap_m (0: off). With snap_m a cell edge
  /// divided by a power of two and tolerance 0, boxes sit exactly on cell faces/edges/corners.
  double snap_m = 0.0;
  /// The broad phase's world cube, when not the scene's: edge (m) of a cube centred on the
  /// scene's (0: the scene's cube). Smaller than the scene: primitives outside the index;
  /// larger: the scene is a crowded cluster in a large index.
  double index_world_edge_m = 0.0;
  /// The speed (m/s) the broad phase's minimum cell is sized for (0: max_speed_mps). Below
  /// max_speed_mps: steps larger than the cells.
  double index_speed_mps = 0.0;
};

/// One change to apply to every broad phase under test.
struct SceneOp {
  enum class Kind { kAdd, kRemove, kMove } kind = Kind::kMove;
  PrimitiveId id = 0;
  Aabb box_W;
  double tolerance_m = 0.0;
  Motion motion = Motion::kStatic;
};

class RandomScene {
 public:
  explicit RandomScene(const SceneConfig& config)
      : config_(config), rng_(config.seed), compatible_(Count()) {
    const int n = Count();
    prims_.resize(n);
    for (int id = 0; id < n; ++id) {
      Prim& p = prims_[id];
      p.moving = id >= config_.statics;
      p.tolerance_m = config_.snap_m > 0.0 ? 0.0 : Uniform(0.0, config_.tolerance_max_m);
      if (p.moving) {
        p.centre_W = RandomPointInWorld(0.3);
        p.axis_W = RandomUnit();
        p.velocity_W = RandomUnit() * Uniform(0.0, 0.5 * config_.max_speed_mps);
        p.spin_W = RandomUnit();
      } else {
        p.centre_W = RandomPointInWorld(0.0);
        for (int a = 0; a < 3; ++a) {
          p.half_W[a] = Uniform(config_.static_half_min_m, config_.static_half_max_m);
        }
      }
    }
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b) {
        if (Uniform(0.0, 1.0) < config_.compatible_fraction) compatible_.Set(a, b, true);
      }
    }
    removed_.reserve(n);
  }

  int Count() const { return config_.statics + config_.movers; }
  const CompatibilityMatrix& compatible() const { return compatible_; }
  std::mt19937_64& rng() { return rng_; }

  BroadPhaseOptions Options(BroadPhaseMethod method) const {
    BroadPhaseOptions options;
    options.method = method;
    options.world_W.min_W = config_.world_min_W;
    options.world_W.max_W = config_.world_min_W + Eigen::Vector3d::Constant(config_.world_edge_m);
    if (config_.index_world_edge_m > 0.0) {
      options.world_W = Aabb::Cube(0.5 * (options.world_W.min_W + options.world_W.max_W),
                                   config_.index_world_edge_m);
    }
    const double speed_mps =
        config_.index_speed_mps > 0.0 ? config_.index_speed_mps : config_.max_speed_mps;
    options.min_cell_size_m = speed_mps * config_.period_s;
    options.reserve_primitives = static_cast<std::uint32_t>(Count());
    options.auto_moving = static_cast<std::uint32_t>(config_.movers);
    // The statics the cells will hold: one wholly outside the index's cube is in its outside list
    // alone, tested all-pairs like naive (the Monitor refuses statics outside its world cube).
    options.auto_statics = 0;
    double edge_sum_m = 0.0;
    for (const Prim& p : prims_) {
      if (!p.moving) {
        options.auto_statics += options.world_W.Overlaps(BoxOf(p).Inflated(p.tolerance_m));
        continue;
      }
      const Aabb box_W = BoxOf(p).Inflated(p.tolerance_m);
      edge_sum_m += (box_W.max_W - box_W.min_W).maxCoeff();
    }
    options.auto_moving_box_edge_m = config_.movers > 0 ? edge_sum_m / config_.movers : 0.0;
    return options;
  }

  /// The Add operations for every primitive.
  void Initial(std::vector<SceneOp>* ops) {
    ops->clear();
    for (int id = 0; id < Count(); ++id) ops->push_back(AddOp(id));
  }

  /// One cycle: every present mover moves (within the bound unless it jumps or leaves); maybe
  /// one primitive is removed or one removed primitive comes back; maybe a mark flips.
  void Step(std::vector<SceneOp>* ops) {
    ops->clear();
    const double dt = config_.period_s;
    for (int id = config_.statics; id < Count(); ++id) {
      Prim& p = prims_[id];
      if (p.removed) continue;
      const double u = Uniform(0.0, 1.0);
      if (u < config_.jump_probability) {
        p.centre_W = RandomPointInWorld(0.3);
      } else if (u < config_.jump_probability + config_.leave_probability) {
        // Straddling a face of the world cube, or wholly beyond it.
        p.centre_W = RandomPointInWorld(0.0);
        const int a = static_cast<int>(Uniform(0.0, 3.0)) % 3;
        const double beyond_m = Uniform(-0.1, 0.5);
        p.centre_W[a] = Uniform(0.0, 1.0) < 0.5
                            ? config_.world_min_W[a] - beyond_m
                            : config_.world_min_W[a] + config_.world_edge_m + beyond_m;
      } else {
        // Drift: centre speed <= half the bound, endpoint speed from turning <= the other half.
        if (Uniform(0.0, 1.0) < 0.05) {
          p.velocity_W = RandomUnit() * Uniform(0.0, 0.5 * config_.max_speed_mps);
          p.spin_W = RandomUnit();
        }
        p.centre_W += p.velocity_W * dt;
        const double omega = 0.5 * config_.max_speed_mps / (0.5 * config_.mover_length_m);
        p.axis_W = (p.axis_W + p.spin_W.cross(p.axis_W) * omega * dt).normalized();
        // Bounce back toward the middle when drifting out (a centre beyond the world after a
        // "leave" also comes back this way, re-entering the cube).
        for (int a = 0; a < 3; ++a) {
          const double lo = config_.world_min_W[a] + 0.3, hi = lo + config_.world_edge_m - 0.6;
          if ((p.centre_W[a] < lo && p.velocity_W[a] < 0) ||
              (p.centre_W[a] > hi && p.velocity_W[a] > 0)) {
            p.velocity_W[a] = -p.velocity_W[a];
          }
        }
      }
      ops->push_back(SceneOp{SceneOp::Kind::kMove, static_cast<PrimitiveId>(id), BoxOf(p), 0.0,
                             Motion::kMoving});
    }
    if (Uniform(0.0, 1.0) < config_.remove_probability) {
      const int id = static_cast<int>(Uniform(0.0, Count())) % Count();
      if (!prims_[id].removed) {
        prims_[id].removed = true;
        removed_.push_back(id);
        ops->push_back(SceneOp{SceneOp::Kind::kRemove, static_cast<PrimitiveId>(id), Aabb{}, 0.0,
                               Motion::kStatic});
      }
    }
    if (!removed_.empty() && Uniform(0.0, 1.0) < config_.remove_probability) {
      const int id = removed_.front();
      removed_.erase(removed_.begin());
      Prim& p = prims_[id];
      p.removed = false;
      p.centre_W = RandomPointInWorld(p.moving ? 0.3 : 0.0);
      ops->push_back(AddOp(id));
    }
    if (Uniform(0.0, 1.0) < config_.flip_probability) {
      const PrimitiveId a = static_cast<PrimitiveId>(Uniform(0.0, Count())) % Count();
      const PrimitiveId b = static_cast<PrimitiveId>(Uniform(0.0, Count())) % Count();
      if (a != b) compatible_.Set(a, b, !compatible_.AreCompatible(a, b));
    }
  }

  static void Apply(const std::vector<SceneOp>& ops, BroadPhase* bp) {
    for (const SceneOp& op : ops) {
      switch (op.kind) {
        case SceneOp::Kind::kAdd:
          bp->Add(op.id, op.box_W, op.tolerance_m, op.motion);
          break;
        case SceneOp::Kind::kRemove:
          bp->Remove(op.id);
          break;
        case SceneOp::Kind::kMove:
          bp->Move(op.id, op.box_W);
          break;
      }
    }
  }

 private:
  struct Prim {
    bool moving = false;
    bool removed = false;
    double tolerance_m = 0.0;
    Eigen::Vector3d centre_W = Eigen::Vector3d::Zero();
    Eigen::Vector3d half_W = Eigen::Vector3d::Zero();   // statics
    Eigen::Vector3d axis_W = Eigen::Vector3d::UnitX();  // movers
    Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();
    Eigen::Vector3d spin_W = Eigen::Vector3d::UnitZ();
  };

  SceneOp AddOp(int id) const {
    const Prim& p = prims_[id];
    return SceneOp{SceneOp::Kind::kAdd, static_cast<PrimitiveId>(id), BoxOf(p), p.tolerance_m,
                   p.moving ? Motion::kMoving : Motion::kStatic};
  }

  Aabb BoxOf(const Prim& p) const {
    Aabb box_W;
    if (p.moving) {
      const Eigen::Vector3d half_W = 0.5 * config_.mover_length_m * p.axis_W;
      box_W.min_W =
          (p.centre_W - half_W).cwiseMin(p.centre_W + half_W).array() - config_.mover_radius_m;
      box_W.max_W =
          (p.centre_W - half_W).cwiseMax(p.centre_W + half_W).array() + config_.mover_radius_m;
    } else {
      box_W.min_W = p.centre_W - p.half_W;
      box_W.max_W = p.centre_W + p.half_W;
    }
    if (config_.snap_m > 0.0) {
      // Round outward to the lattice; the same expression as the structures' boundaries.
      for (int a = 0; a < 3; ++a) {
        box_W.min_W[a] = Snap(a, box_W.min_W[a], false);
        box_W.max_W[a] = Snap(a, box_W.max_W[a], true);
      }
    }
    return box_W;
  }

  double Snap(int axis, double x, bool up) const {
    const double q = (x - config_.world_min_W[axis]) / config_.snap_m;
    const double i = up ? std::ceil(q) : std::floor(q);
    if (i < 0) return config_.world_min_W[axis] + i * config_.snap_m;  // outside: any value
    return config_.world_min_W[axis] +
           static_cast<double>(static_cast<std::uint32_t>(i)) * config_.snap_m;
  }

  double Uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  Eigen::Vector3d RandomUnit() {
    std::normal_distribution<double> normal;
    Eigen::Vector3d v(normal(rng_), normal(rng_), normal(rng_));
    return v.norm() > 1e-9 ? v.normalized() : Eigen::Vector3d::UnitX();
  }
  Eigen::Vector3d RandomPointInWorld(double margin_m) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) {
      p[a] = Uniform(config_.world_min_W[a] + margin_m,
                     config_.world_min_W[a] + config_.world_edge_m - margin_m);
    }
    return p;
  }

  SceneConfig config_;
  std::mt19937_64 rng_;
  CompatibilityMatrix compatible_;
  std::vector<Prim> prims_;
  std::vector<int> removed_;
};

}  // namespace test
}  // namespace arm_collision_monitor
