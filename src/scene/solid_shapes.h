// The solids of the scene inputs (URDF collision elements, scene-file objects, planning-scene
// primitives) as the monitor's primitives: one rule per solid, shared by every reader.
#pragma once

#include <Eigen/Geometry>
#include <utility>

#include "arm_collision_monitor/geometry/primitives.h"
#include "arm_collision_monitor/scene/solid_spec.h"  // CylinderModel

namespace arm_collision_monitor {

/// The ends of the axis of the cylinder of length `length_m` centred on the origin of frame C
/// along C's z, in frame L (X_LC: the pose of C in L).
std::pair<Eigen::Vector3d, Eigen::Vector3d> CylinderAxisEnds_L(const Eigen::Isometry3d& X_LC,
                                                              double length_m);

/// A sphere centred on the origin of frame S (pose X_LS in L): the zero-length capsule (exact).
Shape SphereShape_L(const Eigen::Isometry3d& X_LS, double radius_m);

/// The capsule whose segment of length `length_m` lies on C's z axis, centred on C's origin.
Shape CapsuleShape_L(const Eigen::Isometry3d& X_LC, double radius_m, double length_m);

/// The cylinder of C (axis on C's z, centred on C's origin) as `model` says: the capsule with
/// the cylinder's axis as segment and its radius, or the box of half extents (r, r, length/2) in
/// C, or (kTighter) the one of the two with the smaller volume. Either encloses the cylinder.
Shape CylinderShape_L(const Eigen::Isometry3d& X_LC, double radius_m, double length_m,
                      CylinderModel model);

}  // namespace arm_collision_monitor
