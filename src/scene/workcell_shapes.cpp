#include "arm_collision_monitor/scene/workcell_shapes.h"

namespace arm_collision_monitor {

WorkcellShapes::WorkcellShapes(const Workcell& workcell, Models models)
    : workcell_(workcell), X_WL_(workcell.kinematics.link_count()) {
  const std::size_t n = workcell.primitives.size();
  shapes_W_.reserve(n);
  is_default_model_.reserve(n);
  workcell.kinematics.ComputeLinkPoses(Eigen::VectorXd::Zero(workcell.kinematics.q_size()),
                                       &X_WL_);
  for (std::size_t i = 0; i < n; ++i) {
    const PrimitiveSpec& p = workcell.primitives[i];
    shapes_W_.push_back(p.link_index >= 0 ? TransformShape(X_WL_[p.link_index], p.shape_L)
                                          : p.shape_L);
    is_default_model_.push_back(p.variant.empty());
    const bool is_evaluated = p.variant.empty() || models == Models::kAll;
    if (is_evaluated && p.link_index >= 0 && !p.is_static) {
      moving_.push_back(static_cast<PrimitiveId>(i));
    }
  }
}

void WorkcellShapes::Evaluate(const Eigen::Ref<const Eigen::VectorXd>& q) {
  workcell_.kinematics.ComputeLinkPoses(q, &X_WL_);
  for (const PrimitiveId id : moving_) {
    const PrimitiveSpec& p = workcell_.primitives[id];
    shapes_W_[id] = TransformShape(X_WL_[p.link_index], p.shape_L);
  }
}

}  // namespace arm_collision_monitor
