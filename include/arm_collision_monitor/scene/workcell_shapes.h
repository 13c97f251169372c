// The world-frame shapes of a workcell's default model (or of all its models) at joint positions
// q: forward kinematics, then each link primitive's shape moved by its carrier link's pose X_WL.
// For the loader's start-up check and the checkers that see the workcell from outside the
// Monitor (the peers, brute force, replay's peer mode).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "arm_collision_monitor/geometry/primitives.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {

/// World-frame shapes of every primitive of a workcell (Model/Data split: the workcell is the
/// model, this the per-cycle data). Environment objects stay at the scene file's pose (no TF,
/// no attachments); unless all models are evaluated, primitives of non-default model variants
/// keep their home-pose (q = 0) shapes.
class WorkcellShapes {
 public:
  /// Which link primitives Evaluate moves.
  enum class Models {
    kDefault,  ///< the default model only (variant ""): what the monitor checks at start
    kAll,      ///< every model variant too (the loader's start-up check of all of them)
  };

  /// Sizes the storage and evaluates the home pose (q = 0). `workcell` must outlive this.
  explicit WorkcellShapes(const Workcell& workcell, Models models = Models::kDefault);

  /// Forward kinematics at `q` (one position per Workcell::joint_names entry, the kinematics'
  /// q order), then the world shape of every primitive in moving(). Allocates nothing.
  void Evaluate(const Eigen::Ref<const Eigen::VectorXd>& q);

  /// Pose of every link in W at the last Evaluate (KinematicModel link order).
  const std::vector<Eigen::Isometry3d>& X_WL() const { return X_WL_; }
  /// Shape of primitive `id` in W (uninflated).
  const Shape& shape_W(PrimitiveId id) const { return shapes_W_[id]; }
  /// The primitives of the evaluated models (Models) that move with q (carried by a link that
  /// is not fixed to the root): what Evaluate updates. Ascending.
  const std::vector<PrimitiveId>& moving() const { return moving_; }
  /// True iff primitive `id` belongs to the default model (variant ""), the model checked
  /// while no SwitchModel has been made.
  bool is_default_model(PrimitiveId id) const { return is_default_model_[id] != 0; }

 private:
  const Workcell& workcell_;
  std::vector<Eigen::Isometry3d> X_WL_;
  std::vector<Shape> shapes_W_;
  std::vector<PrimitiveId> moving_;
  std::vector<char> is_default_model_;  // char, not bool: plain storage, indexed per primitive
};

}  // namespace arm_collision_monitor
