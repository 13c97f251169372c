// The Monitor's run-time scene changes (the seed's section 6: grasped objects, model switching,
// moving environment objects) and the index bookkeeping they share. None allocates: every
// structure they touch was sized at start-up.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "arm_collision_monitor/geometry/distance.h"
#include "monitor_impl.h"

namespace arm_collision_monitor {

// --- the index ------------------------------------------------------------------------------

void Monitor::Impl::AddToBroadPhase(PrimitiveId id) {
  broad_phase->Add(id, ComputeAabb(shape_W[id]), IndexTolerance(id),
                   is_moving[id] ? Motion::kMoving : Motion::kStatic);
  in_broad_phase[id] = 1;
  cache.SetIndexed(id, shape_W[id]);
}

void Monitor::Impl::RemoveFromBroadPhase(PrimitiveId id) {
  broad_phase->Remove(id);
  in_broad_phase[id] = 0;
  cache.MarkStale();
}

void Monitor::Impl::Reindex(PrimitiveId id, bool moving) {
  const bool was_in = in_broad_phase[id];
  if (was_in) RemoveFromBroadPhase(id);
  is_moving[id] = moving;
  if (was_in || ShouldBeInBroadPhase(id)) AddToBroadPhase(id);
}

void Monitor::Impl::MarkStaticsNearReachable(PrimitiveId mover) {
  for (PrimitiveId id = 0; id < model.primitive_count; ++id) {
    if (is_moving[id] || is_reachable[id]) continue;
    if (model.Reaches(shape_W[mover], tol_base[mover], shape_W[id], tol_base[id])) {
      is_reachable[id] = 1;
      if (ShouldBeInBroadPhase(id)) AddToBroadPhase(id);
    }
  }
}

void Monitor::Impl::RefreshCompatibility(int link, int object) {
  cache.MarkStale();
  for (const PrimitiveId l : model.link_prims[link]) {
    for (const PrimitiveId o : model.objects[object].prims) {
      compatible.Set(l, o, CompatibleNow(l, o, link, object));
    }
  }
}

// --- the scene changes ------------------------------------------------------------------------

bool Monitor::Attach(const std::string& object, const std::string& link, std::string* error) {
  Impl& m = *impl_;
  m.SyncKinematics();  // the object is re-expressed in the link frame at the link's pose now
  const int o = m.FindObject(object);
  if (o < 0) {
    SetError(error, "Attach: unknown object '" + object + "'");
    return false;
  }
  const int l = m.model.kinematics->FindLink(link);
  if (l < 0) {
    SetError(error, "Attach: unknown link '" + link + "'");
    return false;
  }
  if (!m.has_good) {
    SetError(error, "Attach: no joint state yet, the link's pose is unknown");
    return false;
  }
  if (!m.IsAttachable(o)) {
    SetError(error, "Attach: object '" + object + "' is not attachable " +
                        (m.model.LiveSlot(o) >= 0 ? std::string("(added with attachable false)")
                                                  : "in " + m.model.workcell->scene_path));
    return false;
  }
  if (m.model.hold_radius_m[l] < 0.0) {
    SetError(error, "Attach: link '" + link + "' has no moving joint above it");
    return false;
  }
  std::string why;
  if (!m.IsWithinHoldReach(o, l, &why)) {
    SetError(error, "Attach: object '" + object + "' " + why);
    return false;
  }
  const Eigen::Isometry3d X_LW = m.LinkPose(l).inverse(Eigen::Isometry);
  // A held object moves with the arm, so it gets at least the holder's tolerance zone (the
  // seed's tolerance around each moving object): that of the nearest link up the chain with
  // geometry, for a holder without (a tool frame, the usual one to attach to).
  int with_geometry = l;
  while (with_geometry > 0 && m.model.link_prims[with_geometry].empty()) {
    with_geometry = m.model.kinematics->parent_link(with_geometry);
  }
  double holder_tol_m = 0.0;
  for (const PrimitiveId id : m.model.link_prims[with_geometry]) {
    holder_tol_m = std::max(holder_tol_m, m.tol_base[id]);
  }
  // Speed-scaled tolerances: a holder not at rest may move it at any speed until its joints
  // are sampled again (the object's speed is unknown until then).
  const double speed_margin_m =
      m.link_at_rest[l] ? 0.0 : m.model.options.max_speed_mps * m.model.speed_tol_gain_s;
  // A live object was not in the start-up reach envelope, whose hold radius it need not keep:
  // every static comes back into the check instead.
  if (m.model.LiveSlot(o) >= 0) m.MarkAllStaticsReachable();
  const int previous = m.holder[o];
  for (const PrimitiveId id : m.model.objects[o].prims) {
    // A live object's free slots stay out: carried, they would widen every step's bounds.
    if (!m.is_present[id]) continue;
    m.shape_C[id] = TransformShape(X_LW, m.shape_W[id]);
    m.carrier[id] = l;
    m.tol_base[id] = std::max(m.Spec(id).tolerance_m, holder_tol_m);
    m.tol_now[id] = m.tol_base[id] + speed_margin_m;
    m.Reindex(id, true);
    m.SetCarrierBounds(id);
  }
  m.PrepareBounds();
  m.holder[o] = l;
  if (previous >= 0 && previous != l) m.RefreshCompatibility(previous, o);
  m.RefreshCompatibility(l, o);
  m.scene_changed = true;
  return true;
}

bool Monitor::Impl::IsWithinHoldReach(int object, int link, std::string* why) {
  const Eigen::Isometry3d& X_WL = LinkPose(link);  // a tool point may have no geometry
  const std::string link_name = "'" + model.kinematics->link_name(link) + "'";
  std::ostringstream msg;
  if (model.LiveSlot(object) < 0) {
    for (const PrimitiveId id : model.objects[object].prims) {
      const double reach_m = MaxDistanceFromPoint_m(shape_W[id], X_WL.translation());
      if (reach_m > model.hold_radius_m[link]) {
        msg << "reaches " << reach_m << " m from link " << link_name << ", more than the "
            << model.hold_radius_m[link]
            << " m a held object may (link extent + kAttachMaxGap_m + largest object)";
        *why = msg.str();
        return false;
      }
    }
    return true;
  }
  // Live: the gap to the geometry of the link and of the links it carries (a hand's fingers, a
  // tool frame's gripper), or to its origin if none has any.
  const KinematicModel& kinematics = *model.kinematics;
  double gap_m = std::numeric_limits<double>::infinity();
  bool has_geometry = false;
  for (int carried = link; carried < kinematics.link_count(); ++carried) {
    int up = carried;  // parents precede their children
    while (up > link) up = kinematics.parent_link(up);
    if (up != link) continue;
    for (const PrimitiveId held_by : model.link_prims[carried]) {
      has_geometry = true;
      for (const PrimitiveId id : model.objects[object].prims) {
        gap_m = std::min(gap_m, ShapeDistance(shape_W[held_by], shape_W[id]).distance_m);
      }
    }
  }
  if (!has_geometry) {
    const Capsule origin{X_WL.translation(), X_WL.translation(), 0.0};
    for (const PrimitiveId id : model.objects[object].prims) {
      gap_m = std::min(gap_m, ShapeDistance(origin, shape_W[id]).distance_m);
    }
  }
  if (gap_m <= kAttachMaxGap_m) return true;
  msg << "is " << gap_m << " m from the " << (has_geometry ? "geometry" : "origin")
      << " of link " << link_name << (has_geometry ? " and the links it carries" : "")
      << ", more than the " << kAttachMaxGap_m
      << " m a held object may be (kAttachMaxGap_m): attach it in the grasp";
  *why = msg.str();
  return false;
}

std::string Monitor::HolderOf(const std::string& object) const {
  const Impl& m = *impl_;
  const int o = m.FindObject(object);
  return o < 0 || m.holder[o] < 0 ? "" : m.model.kinematics->link_name(m.holder[o]);
}

bool Monitor::IsHeld(const std::string& object) const {
  const int o = impl_->FindObject(object);
  return o >= 0 && impl_->holder[o] >= 0;
}

std::string Monitor::DescribeHeldMotionBeyondTolerance(const std::string& object) const {
  const Impl& m = *impl_;
  const MonitorOptions& options = m.model.options;
  const int o = m.FindObject(object);
  if (options.swept_check || o < 0 || m.holder[o] < 0) return "";
  const double speed_step_m = options.max_speed_mps * options.cycle_period_s;
  double worst_gap_m = 0.0;
  PrimitiveId worst = 0;
  for (const PrimitiveId id : m.model.objects[o].prims) {
    if (!m.in_broad_phase[id]) continue;  // not checked at run time either
    const double gap_m = m.CycleMotionExcess_m(id);
    if (gap_m > worst_gap_m) {
      worst_gap_m = gap_m;
      worst = id;
    }
  }
  if (worst_gap_m <= 0.0) return "";
  std::ostringstream msg;
  msg << "with swept_check off, held '" << object << "' may move "
      << std::max(speed_step_m, m.UrdfCycleMotion_m(worst)) << " m in one cycle (primitive '"
      << m.Spec(worst).name << "': the larger of max_speed_mps * cycle_period_s, " << speed_step_m
      << " m, and what the URDF velocity limits allow), more than its tolerance ("
      << m.tol_base[worst]
      << " m): a step that fast is beyond what the samples check, a stop (raise the object's "
         "tolerance_m, give the joints' real top speeds, or switch swept_check on)";
  return msg.str();
}

bool Monitor::Detach(const std::string& object, std::string* error) {
  Impl& m = *impl_;
  m.SyncKinematics();  // the object stays where it is let go: at the last good q
  const int o = m.FindObject(object);
  if (o < 0) {
    SetError(error, "Detach: unknown object '" + object + "'");
    return false;
  }
  const int l = m.holder[o];
  if (l < 0) {
    SetError(error, "Detach: object '" + object + "' is not attached");
    return false;
  }
  // It stays where it was let go; a static object rests again (no static-static tests).
  const bool stays_moving = m.model.objects[o].is_frame_bound;
  for (const PrimitiveId id : m.model.objects[o].prims) {
    m.carrier[id] = -1;
    m.is_reachable[id] = 1;  // it was let go within its holder's reach
    m.tol_base[id] = m.Spec(id).tolerance_m;
    m.tol_now[id] = m.tol_base[id];
    m.Reindex(id, stays_moving);
    m.SetCarrierBounds(id);
  }
  m.PrepareBounds();
  m.holder[o] = -1;
  m.ForgetObjectTimes(o);  // its last timed pose is from before it was held
  m.RefreshCompatibility(l, o);
  m.scene_changed = true;
  return true;
}

bool Monitor::SetGraspTarget(const std::string& link, const std::string& object, bool is_target,
                             std::string* error) {
  Impl& m = *impl_;
  // No sync: only the compatibility changes (the pair set is rebuilt by the next cycle).
  const int l = m.model.kinematics->FindLink(link);
  if (l < 0) {
    SetError(error, "SetGraspTarget: unknown link '" + link + "'");
    return false;
  }
  const int o = m.FindObject(object);
  if (o < 0) {
    SetError(error, "SetGraspTarget: unknown object '" + object + "'");
    return false;
  }
  // A scene object only with the links its scene file names; a live object (whose caller
  // placed it) with any link.
  const auto& targets = m.model.workcell->grasp_targets;
  if (m.model.LiveSlot(o) < 0 &&
      std::none_of(targets.begin(), targets.end(), [&](const GraspTargetSpec& t) {
        return t.link_index == l && t.object_index == o;
      })) {
    SetError(error, "SetGraspTarget: '" + object + "' is not a grasp target of link '" + link +
                        "' in " + m.model.workcell->scene_path);
    return false;
  }
  m.grasp[static_cast<std::size_t>(l) * m.model.objects.size() + o] = is_target ? 1 : 0;
  m.RefreshCompatibility(l, o);
  m.scene_changed = true;
  return true;
}

bool Monitor::SwitchModel(const std::string& link, const std::string& variant,
                          std::string* error) {
  Impl& m = *impl_;
  m.SyncKinematics();  // the new variant is placed at the link's pose now
  const int l = m.model.kinematics->FindLink(link);
  if (l < 0) {
    SetError(error, "SwitchModel: unknown link '" + link + "'");
    return false;
  }
  const auto& variants = m.model.link_variants[l];
  const auto it = std::find(variants.begin(), variants.end(), variant);
  if (it == variants.end()) {
    SetError(error, "SwitchModel: link '" + link + "' has no model variant '" + variant + "'");
    return false;
  }
  const int v = static_cast<int>(it - variants.begin());
  if (v == m.active_variant[l]) return true;
  for (const PrimitiveId id : m.model.link_prims[l]) {
    if (m.in_broad_phase[id]) m.RemoveFromBroadPhase(id);
  }
  m.active_variant[l] = v;
  for (const PrimitiveId id : m.model.link_prims[l]) {
    if (m.model.variant_index[id] != v) continue;
    m.shape_W[id] = TransformShape(m.X_WL[l], m.shape_C[id]);
    m.shape_prev_W[id] = m.shape_W[id];
    m.AddToBroadPhase(id);
  }
  m.scene_changed = true;
  return true;
}

bool Monitor::SetObjectPose(const std::string& object, const Eigen::Isometry3d& X_WO,
                            std::string* error) {
  return impl_->SetObjectPose(object, X_WO, std::numeric_limits<double>::quiet_NaN(), error);
}

bool Monitor::SetObjectPoseAt(const std::string& object, const Eigen::Isometry3d& X_WO,
                              double time_s, std::string* error) {
  if (!std::isfinite(time_s)) {
    SetError(error, "SetObjectPoseAt: time of object '" + object + "' not finite");
    return false;
  }
  return impl_->SetObjectPose(object, X_WO, time_s, error);
}

bool Monitor::Impl::SetObjectPose(const std::string& object, const Eigen::Isometry3d& X_WO,
                                  double time_s, std::string* error) {
  // No sync: a free object's shape does not depend on q.
  const int o = FindObject(object);
  if (o < 0) {
    SetError(error, "SetObjectPose: unknown object '" + object + "'");
    return false;
  }
  if (!model.objects[o].is_frame_bound) {
    SetError(error, "SetObjectPose: object '" + object + "' is static, not frame-bound");
    return false;
  }
  if (holder[o] >= 0) {
    SetError(error, "SetObjectPose: object '" + object + "' is held by link '" +
                        model.kinematics->link_name(holder[o]) + "'");
    return false;
  }
  // A rotation that is not one (a quaternion off unit norm) would stretch or shrink the shapes.
  if (!IsRigidPose(X_WO)) {
    SetError(error, "SetObjectPose: pose of object '" + object +
                        "' not finite or its rotation not orthonormal");
    return false;
  }
  // shape_L is the object at X_WO_start; the cycle moves it in the index.
  const Eigen::Isometry3d X_WW = X_WO * model.objects[o].X_OW_start;
  // A finite pose near the largest double overflows here with a start pose far out.
  if (!X_WW.matrix().allFinite()) {
    SetError(error, "SetObjectPose: pose of object '" + object + "' out of range");
    return false;
  }
  // Where it is (a frame broadcast again unmoved, a tracker's next sample) it is not moved.
  double step_m = 0.0;
  for (const PrimitiveId id : model.objects[o].prims) {
    const Shape now_W = TransformShape(X_WW, model.workcell->primitives[id].shape_L);
    if (IsSameShape(shape_W[id], now_W)) continue;
    step_m = std::max(step_m, MaxPointDisplacement_m(shape_W[id], now_W));
    shape_W[id] = now_W;
    moved[id] = 1;
    MarkStaticsNearReachable(id);
    scene_changed = true;
  }
  // Timed: its speed over the interval since its timed pose before, kept until the next; after
  // none, at a time not later or after a long gap (kObjectSpeedMaxGapCycles) a move's speed is
  // unknown: the largest. Untimed: none kept, its move in the cycle gives it. A new speed is a
  // change of the scene: the next cycle computes the tolerances.
  const double before_mps = object_speed_mps[o];
  if (std::isnan(time_s)) {
    ForgetObjectTimes(o);
  } else {
    const double since_s = time_s - object_sample_s[o];
    const double longest_s = kObjectSpeedMaxGapCycles * model.options.cycle_period_s;
    if (since_s > 0.0 && (since_s <= longest_s || step_m == 0.0)) {
      object_speed_mps[o] = step_m / since_s;
    } else if (step_m > 0.0) {
      object_speed_mps[o] = std::numeric_limits<double>::infinity();
    }
    object_sample_s[o] = time_s;
  }
  const bool is_same_speed = object_speed_mps[o] == before_mps ||
                             (std::isnan(object_speed_mps[o]) && std::isnan(before_mps));
  if (!is_same_speed) scene_changed = true;
  return true;
}

}  // namespace arm_collision_monitor
