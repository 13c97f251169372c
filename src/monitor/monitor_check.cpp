// Monitor::Check (generate-and-test by brute force on a copy) and the Monitor's validation of
// its own invariants (for tests and soaks; slow, allocates).
#include <sstream>
#include <string>
#include <vector>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "monitor_impl.h"

namespace arm_collision_monitor {

CycleReport Monitor::Check(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  const Impl& m = *impl_;
  CycleReport r;
  r.cycle = m.report.cycle + 1;
  if (m.IsIdle(q) && m.IsAtRest()) {  // the last (accepted) report, no work
    // A check has no step: not the last step's between-samples warnings, nor the live stop,
    // which a jump into q may have raised.
    r.warnings = m.report.warnings;
    Impl::EraseBetweenSamples(&r.warnings);
    r.stop = !r.warnings.empty();
    return r;
  }
  r.input = m.CheckInput(q);
  if (r.input != InputStatus::kOk) {
    r.warnings = m.report.warnings;
    r.stop = true;
    return r;
  }
  // No sync (const): the shapes and X_WL are both at q_kinematics, and the carried shapes are
  // recomputed for q from the links whose pose differs.
  std::vector<Eigen::Isometry3d> X_WL_q(m.X_WL.size());
  m.model.kinematics->ComputeLinkPoses(q, &X_WL_q);
  std::vector<std::uint8_t> changed(m.X_WL.size(), 0);
  std::vector<Shape> shapes = m.shape_W;
  std::vector<std::uint8_t> moved_flags = m.moved;
  m.MoveCarried(X_WL_q, &changed, &shapes, &moved_flags);
  std::vector<double> tol(m.model.primitive_count);
  m.ComputeTolerances(shapes, moved_flags, nullptr, &tol);  // Update(q): every joint sampled
  // Generate-and-test by brute force over every active, non-compatible, not-both-static pair.
  for (PrimitiveId a = 0; a < m.model.primitive_count; ++a) {
    if (!m.in_broad_phase[a]) continue;
    if (moved_flags[a]) ++r.moved_primitives;
    for (PrimitiveId b = a + 1; b < m.model.primitive_count; ++b) {
      if (!m.in_broad_phase[b] || (!m.is_moving[a] && !m.is_moving[b]) ||
          m.compatible.AreCompatible(a, b)) {
        continue;
      }
      Impl::TestPair(a, b, shapes, tol, &r.warnings);
      ++r.narrow_phase_tests;
    }
  }
  r.stop = !r.warnings.empty();
  return r;
}

bool Monitor::Validate(std::string* error) const {
  const Impl& m = *impl_;
  std::ostringstream msg;
  m.ValidatePrimitives(&msg);
  if (msg.tellp() == 0) m.ValidateCompatibility(&msg);
  std::string why;
  if (msg.tellp() == 0 && !m.motion.Validate(&why)) msg << "motion bounds: " << why;
  if (msg.tellp() == 0) m.ValidateLiveObjects(&msg);
  if (msg.tellp() == 0) m.ValidateSlack(&msg);
  if (msg.tellp() == 0 && m.kinematics_behind) m.ValidateBoundedCycle(&msg);
  const auto& w = m.report.warnings;
  for (std::size_t i = 0; i < w.size() && msg.tellp() == 0; ++i) {
    if (w[i].a >= w[i].b || (i > 0 && !(w[i - 1].a < w[i].a ||
                                        (w[i - 1].a == w[i].a && w[i - 1].b < w[i].b)))) {
      msg << "report warnings not sorted or not a < b at index " << i;
    }
  }
  if (msg.tellp() == 0) return true;
  SetError(error, msg.str());
  return false;
}

bool Monitor::ValidateIndex(std::string* error) const {
  std::string why;
  if (impl_->broad_phase->Validate(&why)) return true;
  SetError(error, "broad phase " + impl_->broad_phase->name() + ": " + why);
  return false;
}

void Monitor::ForceIndexStampsNearWrap(std::uint32_t steps_before_wrap) {
  impl_->broad_phase->ForceStampsNearWrap(steps_before_wrap);
}

void Monitor::Impl::ValidatePrimitives(std::ostringstream* msg) const {
  // The kinematics recomputes only the links a joint's change moves: every link it keeps
  // current holds its pose at q_kinematics, bit for bit.
  std::vector<Eigen::Isometry3d> X_WL_q(X_WL.size());
  model.kinematics->ComputeLinkPoses(q_kinematics, &X_WL_q);
  for (const int link : fk_links) {
    if (X_WL[link].matrix() != X_WL_q[link].matrix()) {
      *msg << "link " << model.kinematics->link_name(link) << " not at the last kinematics' q";
      return;
    }
  }
  // The per-cycle loops visit `carried`: exactly the primitives with a carrier, ascending.
  std::vector<PrimitiveId> expected_carried;
  for (PrimitiveId id = 0; id < model.primitive_count; ++id) {
    if (carrier[id] >= 0) expected_carried.push_back(id);
  }
  if (carried != expected_carried) {
    *msg << "carried list has " << carried.size() << " primitives, expected "
         << expected_carried.size() << " (or not in order)";
    return;
  }
  for (PrimitiveId id = 0; id < model.primitive_count; ++id) {
    const bool should = ShouldBeInBroadPhase(id);
    if (static_cast<bool>(in_broad_phase[id]) != should) {
      *msg << "primitive " << id << " in broad phase: " << int(in_broad_phase[id])
           << ", expected " << should;
      break;
    }
    const int link = carrier[id];
    if (link >= 0 && !moved[id] && IsActiveVariant(id)) {
      const Shape expected = TransformShape(X_WL[link], shape_C[id]);
      // Attach re-expresses the shape in the link frame: equal up to rounding, not bit for bit.
      const Aabb a = ComputeAabb(expected);
      const Aabb b = ComputeAabb(shape_W[id]);
      if (!a.min_W.isApprox(b.min_W, kValidateShapeTolerance_rel) ||
          !a.max_W.isApprox(b.max_W, kValidateShapeTolerance_rel)) {
        *msg << "primitive " << id << " does not follow link " << link;
        break;
      }
    }
    if (model.speed_tol_gain_s == 0.0 && tol_now[id] != tol_base[id]) {
      *msg << "primitive " << id << " tolerance " << tol_now[id] << " != " << tol_base[id];
      break;
    }
    const int o = model.object_of[id];
    // A held object's primitives have its holder as carrier; a live object's free slots none.
    if (o >= 0 && (holder[o] >= 0 && is_present[id]) != (link >= 0)) {
      *msg << "object primitive " << id << " carrier disagrees with its holder";
      break;
    }
  }
}

void Monitor::Impl::ValidateCompatibility(std::ostringstream* msg) const {
  for (std::size_t o = 0; o < model.objects.size() && msg->tellp() == 0; ++o) {
    for (int l = 0; l < model.kinematics->link_count() && msg->tellp() == 0; ++l) {
      for (const PrimitiveId lp : model.link_prims[l]) {
        for (const PrimitiveId op : model.objects[o].prims) {
          if (compatible.AreCompatible(lp, op) !=
              CompatibleNow(lp, op, l, static_cast<int>(o))) {
            *msg << "compatibility of " << lp << " and " << op << " is stale";
          }
        }
      }
    }
  }
}

void Monitor::Impl::ValidateSlack(std::ostringstream* msg) const {
  std::string why;
  for (PrimitiveId id = 0; id < model.primitive_count; ++id) {
    if (!in_broad_phase[id] || moved[id]) continue;
    if (!cache.ValidatePrimitive(id, shape_W[id], &why)) {
      *msg << why;
      return;
    }
  }
  if (cache.is_stale()) return;  // a scene change since the last cycle: rebuilt in the next one
  // The pairs whose indexed boxes overlap, by brute force.
  std::vector<CandidatePair> expected;
  for (PrimitiveId a = 0; a < model.primitive_count; ++a) {
    if (!in_broad_phase[a]) continue;
    const Aabb box_a = ComputeAabb(cache.indexed_shape_W(a)).Inflated(IndexTolerance(a));
    for (PrimitiveId b = a + 1; b < model.primitive_count; ++b) {
      if (!in_broad_phase[b] || (!is_moving[a] && !is_moving[b]) ||
          compatible.AreCompatible(a, b)) {
        continue;
      }
      if (box_a.Overlaps(ComputeAabb(cache.indexed_shape_W(b)).Inflated(IndexTolerance(b)))) {
        expected.push_back({a, b});
      }
    }
  }
  // shape_W is at q_kinematics (also after bounded cycles), but for the primitives moved since
  // (SetObjectPose, MoveObject; refused cycles keep them pending): their pairs' bounds are of
  // the scene before, which the next cycle re-plans.
  if (!cache.ValidatePairs(expected, shape_W, moved, &why)) *msg << why;
}

void Monitor::Impl::ValidateBoundedCycle(std::ostringstream* msg) const {
  std::vector<Eigen::Isometry3d> X(model.kinematics->link_count());
  model.kinematics->ComputeLinkPoses(q_good, &X);
  std::vector<Shape> now(shape_W);
  const double slack_m = model.options.index_slack_m;
  // Every bound for the joint motion the bounded cycle was proved for (IsProvablyClear
  // computed only those it needed).
  MotionBounds bounds = motion;
  for (PrimitiveId id = 0; id < model.primitive_count; ++id) {
    if (carrier[id] < 0) continue;
    now[id] = TransformShape(X[carrier[id]], shape_C[id]);
    const double bound_m = bounds.ComputeBound_m(id);
    if (motion.lever_count(id) == 0 || !in_broad_phase[id]) continue;
    const double moved_m = MaxPointDisplacement_m(shape_W[id], now[id]);
    const double from_ref_m = MaxPointDisplacement_m(cache.indexed_shape_W(id), now[id]);
    if (moved_m > bound_m + cache.BoundMargin_m(bound_m) ||
        from_ref_m > slack_m + cache.BoundMargin_m(slack_m)) {
      *msg << "bounded cycle: primitive " << id << " moved " << moved_m << " m, bound "
           << bound_m << " m; " << from_ref_m << " m from its indexed copy, slack "
           << slack_m << " m";
      return;
    }
  }
  // Kept pairs of the index before a scene change (stale: rebuilt in the next cycle), or with a
  // primitive a scene change moved since (as ValidateSlack), are for the next cycle to re-plan.
  if (cache.is_stale()) return;
  for (const KeptPair& kept : cache.pairs()) {
    const PrimitiveId a = kept.pair.a;
    const PrimitiveId b = kept.pair.b;
    if (moved[a] || moved[b]) continue;
    const double then_m = ShapeDistance(shape_W[a], shape_W[b]).distance_m;
    const double now_m = ShapeDistance(now[a], now[b]).distance_m;
    const double motion_m = bounds.PairBound_m(a, b);
    if (now_m < then_m - motion_m - cache.BoundMargin_m(then_m) ||
        now_m <= tol_now[a] + tol_now[b]) {
      *msg << "bounded cycle: pair (" << a << "," << b << ") at " << now_m << " m, was "
           << then_m << " m, relative motion bound " << motion_m << " m, threshold "
           << tol_now[a] + tol_now[b] << " m";
      return;
    }
  }
}

}  // namespace arm_collision_monitor
