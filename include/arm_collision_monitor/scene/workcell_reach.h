// Reach envelopes of a workcell, valid for every joint vector within the limits: per link, a
// sphere its primitives (and whatever it may hold) never leave; and the world cube derived from
// them when the scene file omits world:.
#pragma once

#include <vector>

#include "arm_collision_monitor/geometry/primitives.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {

/// Per link of a workcell's kinematics (see ComputeWorkcellReach).
struct WorkcellReach {
  /// The sphere (a zero-length capsule) that the link's primitives, every model variant's, and
  /// any attachable object it may hold stay within for every q; radius < 0 for a link that
  /// reaches nothing (no moving joint above it, or nothing to carry).
  std::vector<Capsule> spheres;
  /// The farthest a held object may reach from the link's origin (m); < 0: the link has no
  /// moving joint above it and may hold nothing.
  std::vector<double> hold_radius_m;
};

/// Reach envelopes by the triangle inequality over the chain: a link L's points stay within a
/// sphere centred on the origin of the first moving joint (actuated or mimic) above it, of radius
/// (sum of the joint offsets between that joint and L, plus prismatic travel) + (farthest point
/// of L's primitives, or of an object it may hold, from L's origin). A held object reaches at
/// most kAttachMaxGap_m plus the largest attachable object's AABB diagonal beyond L's geometry.
/// Centres are at the kinematics' X_WRoot. Radii are +inf below a prismatic joint without
/// limits.
WorkcellReach ComputeWorkcellReach(const Workcell& w);

/// The world cube used when the scene file has no world: the smallest cube, centred on their
/// common AABB, enclosing the reach spheres of ComputeWorkcellReach, the primitives of links
/// that never move at their poses, and every object's primitives at their start poses (attachable
/// and frame-bound ones included), each grown by the largest primitive tolerance, plus
/// kDerivedWorldMargin_m on every side. Throws LoadError naming the scene file when a reach is
/// unbounded or the workcell has no primitive.
Aabb DeriveWorldCube(const Workcell& w);

}  // namespace arm_collision_monitor
