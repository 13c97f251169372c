// The Monitor's model, built once (see monitor_model.h): options checked against the workcell,
// primitives sorted by link, variant and object, the start pose, the reach envelope of the arms,
// and the broad phase chosen.
#include "arm_collision_monitor/monitor/monitor_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include "arm_collision_monitor/broadphase/broad_phase_util.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/scene/workcell_reach.h"

namespace arm_collision_monitor {
MonitorModel::MonitorModel(std::shared_ptr<const Workcell> wc, const MonitorOptions& opts)
    : workcell(WithLiveSlots(std::move(wc), opts.live_objects)), options(opts) {
  if (!workcell) throw LoadError("monitor: no workcell given");
  kinematics = &workcell->kinematics;
  primitive_count = static_cast<std::uint32_t>(workcell->primitives.size());
  const LiveObjectOptions& live = options.live_objects;
  first_live_primitive = primitive_count - live.capacity * live.max_primitives_per_object;
  first_live_object = static_cast<int>(workcell->objects.size() - live.capacity);
  options.broad_phase.world_W = workcell->world_W;
  options.broad_phase.min_cell_size_m = MinCellSize_m(options);
  options.broad_phase.reserve_primitives =
      std::max(options.broad_phase.reserve_primitives, primitive_count);
  world_edge_m = WorldCubeEdge(workcell->world_W);
  speed_tol_gain_s =
      options.speed_scaled_tolerance ? options.reaction_time_s + options.stopping_time_s : 0.0;
  ValidateOptions();
  BuildPrimitives();
  BuildStartPose();
  ComputeReachability();
  ChooseBroadPhase();
}

bool MonitorModel::Reaches(const Shape& mover_W, double mover_tol_m, const Shape& static_W,
                           double static_tol_m) const {
  return ShapeDistance(mover_W, static_W).distance_m <=
         static_tol_m + BroadTolerance_m(mover_tol_m, true);
}

void MonitorModel::ValidateOptions() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!positive(options.max_speed_mps)) {
    throw LoadError("monitor options: max_speed_mps must be a positive number");
  }
  if (!positive(options.cycle_period_s)) {
    throw LoadError("monitor options: cycle_period_s must be a positive number");
  }
  if (!non_negative(options.reaction_time_s) || !non_negative(options.stopping_time_s)) {
    throw LoadError("monitor options: reaction_time_s and stopping_time_s must be >= 0");
  }
  if (!non_negative(options.index_slack_m)) {
    throw LoadError("monitor options: index_slack_m must be >= 0");
  }
  if (options.broad_phase.max_objects_per_leaf < 1) {
    throw LoadError("monitor options: broad_phase max_objects_per_leaf must be >= 1");
  }
  const Aabb& world = options.broad_phase.world_W;
  if (!world.min_W.allFinite() || !world.max_W.allFinite() ||
      !(world.min_W.array() < world.max_W.array()).all()) {
    throw LoadError(workcell->scene_path + ": world box must have min < max on every axis");
  }
  if (static_cast<int>(workcell->joint_names.size()) != kinematics->q_size()) {
    throw LoadError(workcell->urdf_path + ": " + std::to_string(workcell->joint_names.size()) +
                    " joint names for " + std::to_string(kinematics->q_size()) +
                    " actuated joints");
  }
  if (workcell->compatible.size() != primitive_count) {
    throw LoadError(workcell->scene_path + ": compatibility matrix size " +
                    std::to_string(workcell->compatible.size()) + " for " +
                    std::to_string(primitive_count) + " primitives");
  }
}

void MonitorModel::BuildPrimitives() {
  const int link_count = kinematics->link_count();
  const std::uint32_t n = primitive_count;
  link_prims.assign(link_count, {});
  link_variants.assign(link_count, std::vector<std::string>{""});
  variant_index.assign(n, 0);
  object_of.assign(n, -1);
  carrier_start.assign(n, -1);
  is_moving_start.assign(n, 0);
  for (PrimitiveId id = 0; id < n; ++id) {
    const PrimitiveSpec& spec = workcell->primitives[id];
    if (spec.link_index >= 0) {
      if (spec.link_index >= link_count) {
        throw LoadError(workcell->scene_path + ": primitive '" + spec.name +
                        "' has link index " + std::to_string(spec.link_index) + " of " +
                        std::to_string(link_count) + " links");
      }
      link_prims[spec.link_index].push_back(id);
      auto& variants = link_variants[spec.link_index];
      const auto it = std::find(variants.begin(), variants.end(), spec.variant);
      variant_index[id] = static_cast<int>(it - variants.begin());
      if (it == variants.end()) variants.push_back(spec.variant);
      carrier_start[id] = spec.link_index;
      // Links with only fixed joints above them never move.
      is_moving_start[id] = spec.is_static ? 0 : 1;
    } else {
      const int o = spec.object_index;
      if (o < 0 || o >= static_cast<int>(workcell->objects.size())) {
        throw LoadError(workcell->scene_path + ": primitive '" + spec.name +
                        "' has neither a link nor an object");
      }
      object_of[id] = o;
    }
  }
  objects.resize(workcell->objects.size());
  for (std::size_t o = 0; o < objects.size(); ++o) {
    const ObjectSpec& spec = workcell->objects[o];
    objects[o].X_OW_start = spec.X_WO_start.inverse(Eigen::Isometry);
    objects[o].is_attachable = spec.is_attachable;
    objects[o].is_frame_bound = !spec.frame.empty();
  }
  // Resting objects are static (never tested against other statics) until held; only the
  // frame-bound ones move on their own.
  for (PrimitiveId id = 0; id < n; ++id) {
    if (object_of[id] < 0) continue;
    Object& object = objects[object_of[id]];
    object.prims.push_back(id);
    is_moving_start[id] = object.is_frame_bound;
  }
  // Two primitives that never move (links fixed to the root, objects no gripper may hold) are
  // never tested: the per-cycle buffers are reserved for the other pairs (all pairs would take
  // gigabytes for 20,000 resting boxes).
  std::size_t may_move = 0;
  for (PrimitiveId id = 0; id < n; ++id) {
    const int o = object_of[id];
    may_move += is_moving_start[id] || is_live(id) || (o >= 0 && objects[o].is_attachable);
  }
  max_tested_pairs = may_move * (may_move > 0 ? may_move - 1 : 0) / 2 + may_move * (n - may_move);
}

void MonitorModel::BuildStartPose() {
  // Without a limit (a continuous joint, unless the scene file's joint_limits give it soft
  // ones): +/-kMaxUnlimitedPosition_rad, so that the limits alone also refuse NaN, infinities
  // and absurd readings (CheckInput).
  q_lower.resize(kinematics->q_size());
  q_upper.resize(kinematics->q_size());
  for (int link = 1; link < kinematics->link_count(); ++link) {
    const JointSpec& joint = kinematics->joint(link);
    if (joint.q_index < 0) continue;
    std::tie(q_lower[joint.q_index], q_upper[joint.q_index]) = KinematicModel::AcceptedRange(joint);
  }
  turning_links = kinematics->TurningLinks();
  // Each joint at 0, or at its limit nearer 0 (finite: so are the limits).
  q_start = Eigen::VectorXd::Zero(kinematics->q_size());
  for (int i = 0; i < q_start.size(); ++i) {
    q_start[i] = std::min(std::max(0.0, q_lower[i] + kJointLimitMargin),
                          q_upper[i] - kJointLimitMargin);
  }
  X_WL_start.assign(kinematics->link_count(), Eigen::Isometry3d::Identity());
  kinematics->ComputeLinkPoses(q_start, &X_WL_start);
  shape_W_start.resize(primitive_count);
  for (PrimitiveId id = 0; id < primitive_count; ++id) {
    const int link = carrier_start[id];
    const Shape& shape_L = workcell->primitives[id].shape_L;
    shape_W_start[id] = link >= 0 ? TransformShape(X_WL_start[link], shape_L) : shape_L;
  }
}

// Reach envelope (the seed's observation that stationary objects only cost time when they share
// cells with moving ones, taken to the limit): per link, the sphere of ComputeWorkcellReach.
// Frame-bound objects reach what is near their start pose (SetObjectPose re-checks).
std::vector<Capsule> MonitorModel::ComputeReachSpheres() {
  WorkcellReach reach = ComputeWorkcellReach(*workcell);
  hold_radius_m = std::move(reach.hold_radius_m);
  return std::move(reach.spheres);
}

void MonitorModel::ComputeReachability() {
  const std::uint32_t n = primitive_count;
  double max_moving_tol_m = 0.0;
  for (PrimitiveId id = 0; id < n; ++id) {
    const int o = object_of[id];
    if (is_moving_start[id] || (o >= 0 && objects[o].is_attachable)) {
      max_moving_tol_m =
          std::max(max_moving_tol_m, BroadTolerance_m(workcell->primitives[id].tolerance_m, true));
    }
  }
  const std::vector<Capsule> spheres = ComputeReachSpheres();
  is_reachable_start.assign(n, 1);
  for (PrimitiveId id = 0; id < n; ++id) {
    if (is_moving_start[id] || (object_of[id] >= 0 && objects[object_of[id]].is_attachable)) {
      continue;
    }
    bool reachable = false;
    for (std::size_t link = 0; link < spheres.size() && !reachable; ++link) {
      if (spheres[link].radius_m < 0.0) continue;  // reaches nothing
      if (!std::isfinite(spheres[link].radius_m)) {
        reachable = true;
        break;
      }
      // <=, as the broad phase's closed boxes: touching counts.
      reachable = ShapeDistance(spheres[link], shape_W_start[id]).distance_m <=
                  workcell->primitives[id].tolerance_m + max_moving_tol_m;
    }
    is_reachable_start[id] = reachable ? 1 : 0;
  }
  // A frame-bound object reaches the statics near its start pose.
  for (const Object& object : objects) {
    if (!object.is_frame_bound) continue;
    for (const PrimitiveId mover : object.prims) {
      for (PrimitiveId id = 0; id < n; ++id) {
        if (is_moving_start[id] || is_reachable_start[id]) continue;
        if (Reaches(shape_W_start[mover], workcell->primitives[mover].tolerance_m,
                    shape_W_start[id], workcell->primitives[id].tolerance_m)) {
          is_reachable_start[id] = 1;
        }
      }
    }
  }
}

// broad_phase auto: ChooseBroadPhaseMethod on the primitives active at start-up (the default
// variants; moving, or static and reachable), its choice written into the options.
void MonitorModel::ChooseBroadPhase() {
  if (options.broad_phase.method != BroadPhaseMethod::kAuto) return;
  std::uint32_t moving = 0, statics = 0;
  double edge_sum_m = 0.0;
  for (PrimitiveId id = 0; id < first_live_primitive; ++id) {  // live slots start empty
    if (variant_index[id] != 0) continue;
    if (is_moving_start[id]) {
      ++moving;
      // The box the index holds: grown by the broad-phase tolerance and the index slack.
      const Aabb box_W = ComputeAabb(shape_W_start[id])
                             .Inflated(BroadTolerance_m(workcell->primitives[id].tolerance_m,
                                                        true) +
                                       options.index_slack_m);
      edge_sum_m += (box_W.max_W - box_W.min_W).maxCoeff();
    } else if (is_reachable_start[id]) {
      ++statics;
    }
  }
  options.broad_phase.auto_moving_box_edge_m = moving > 0 ? edge_sum_m / moving : 0.0;
  options.broad_phase.auto_moving = moving;
  options.broad_phase.auto_statics = statics;
  options.broad_phase.method = ChooseBroadPhaseMethod(moving, statics);
}

}  // namespace arm_collision_monitor
