// The collision primitives: capsules (the seed's "cylspheres") for links, oriented boxes (its
// "rectangular solids") for the environment, and the axis-aligned bounding boxes the broad
// phase indexes them by; with the rigid transforms that place them. All coordinates in metres,
// in the world frame W unless named otherwise.
#pragma once

#include <cstdint>
#include <limits>
#include <variant>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace arm_collision_monitor {

/// Dense primitive ids 0..n-1, assigned by the caller (the scene): the index of a primitive in
/// the workcell, in the broad phase and in the compatibility matrix alike.
using PrimitiveId = std::uint32_t;

/// Axis-aligned bounding box, closed: a box touching another at a face, edge or corner
/// overlaps it. Every broad phase decides pairs with these same predicates, so their answers
/// can be compared exactly.
struct Aabb {
  Eigen::Vector3d min_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_W = Eigen::Vector3d::Zero();

  /// True iff the closed boxes share at least one point.
  bool Overlaps(const Aabb& other) const {
    return (min_W.array() <= other.max_W.array()).all() &&
           (other.min_W.array() <= max_W.array()).all();
  }
  /// True iff `other` lies inside this box (boundaries may touch).
  bool Contains(const Aabb& other) const {
    return (min_W.array() <= other.min_W.array()).all() &&
           (other.max_W.array() <= max_W.array()).all();
  }
  /// Grows this box to enclose `other` too (a NaN bound may void it: callers leave NaN out).
  void Enclose(const Aabb& other) {
    min_W = min_W.cwiseMin(other.min_W);
    max_W = max_W.cwiseMax(other.max_W);
  }
  /// This box grown by `margin_m` (>= 0) on every side.
  Aabb Inflated(double margin_m) const {
    return Aabb{(min_W.array() - margin_m).matrix(), (max_W.array() + margin_m).matrix()};
  }
  /// The box of NaN bounds, which overlaps nothing (Overlaps is false on either side): the
  /// place holder of an absent primitive in lists kept by id.
  static Aabb Nowhere() {
    const double nan_m = std::numeric_limits<double>::quiet_NaN();
    return Aabb{Eigen::Vector3d::Constant(nan_m), Eigen::Vector3d::Constant(nan_m)};
  }
  /// The cube of edge `edge_m` (> 0) centred on `center_W`.
  static Aabb Cube(const Eigen::Vector3d& center_W, double edge_m) {
    return Aabb{(center_W.array() - 0.5 * edge_m).matrix(),
                (center_W.array() + 0.5 * edge_m).matrix()};
  }
};

/// A capsule (cylsphere): every point within `radius_m` of the segment p0_W--p1_W.
/// A zero-length segment makes it a sphere.
struct Capsule {
  Eigen::Vector3d p0_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d p1_W = Eigen::Vector3d::Zero();
  double radius_m = 0.0;

  /// Tight AABB: the endpoints' min/max grown by the radius (exact for a capsule).
  Aabb ComputeAabb() const {
    return Aabb{(p0_W.cwiseMin(p1_W).array() - radius_m).matrix(),
                (p0_W.cwiseMax(p1_W).array() + radius_m).matrix()};
  }
};

/// An oriented box: pose of the box frame B in W (centre at the origin of B, edges along B's
/// axes) and the half extents along those axes (each >= 0).
struct Box {
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d half_extents_m = Eigen::Vector3d::Zero();

  /// Tight AABB: centre +/- |R_WB| * half extents (exact for a box).
  Aabb ComputeAabb() const {
    const Eigen::Vector3d reach_W = X_WB.linear().cwiseAbs() * half_extents_m;
    return Aabb{X_WB.translation() - reach_W, X_WB.translation() + reach_W};
  }
  /// Vertex k (0 to 7) in the box frame: coordinate i is +h_i when bit i of k is set, else -h_i.
  Eigen::Vector3d Vertex_B(int k) const {
    return Eigen::Vector3d((k & 1) ? half_extents_m.x() : -half_extents_m.x(),
                           (k & 2) ? half_extents_m.y() : -half_extents_m.y(),
                           (k & 4) ? half_extents_m.z() : -half_extents_m.z());
  }
};

/// Any primitive. New primitive types are added here and to every pairwise routine.
using Shape = std::variant<Capsule, Box>;

/// Whether two shapes are the same to the bit (-0 and +0 alike).
inline bool IsSameShape(const Shape& a, const Shape& b) {
  if (a.index() != b.index()) return false;
  if (const auto* c = std::get_if<Capsule>(&a)) {
    const Capsule& d = std::get<Capsule>(b);
    return c->p0_W == d.p0_W && c->p1_W == d.p1_W && c->radius_m == d.radius_m;
  }
  const Box& x = std::get<Box>(a);
  const Box& y = std::get<Box>(b);
  return x.X_WB.matrix() == y.X_WB.matrix() && x.half_extents_m == y.half_extents_m;
}

/// Tight AABB of any primitive.
inline Aabb ComputeAabb(const Shape& shape) {
  return std::visit([](const auto& s) { return s.ComputeAabb(); }, shape);
}

/// The shape `shape_L`, given in frame L, expressed in W (rigid transform X_WL).
Shape TransformShape(const Eigen::Isometry3d& X_WL, const Shape& shape_L);

/// Distance (m) from point p to the farthest point of `shape` (both in the same frame).
double MaxDistanceFromPoint_m(const Shape& shape, const Eigen::Vector3d& p);
/// Distance (m) from the line through the origin along the unit vector `axis` to the farthest
/// point of `shape` (both in the same frame).
double MaxDistanceFromAxis_m(const Shape& shape, const Eigen::Vector3d& axis);

/// The pose of a frame F in W from its origin `p_WF_m` and URDF-convention angles `rpy_rad`
/// (fixed-axis roll about x, then pitch about y, then yaw about z: R = Rz(yaw) Ry(pitch) Rx(roll)).
Eigen::Isometry3d PoseFromXyzRpy(const Eigen::Vector3d& p_WF_m, const Eigen::Vector3d& rpy_rad);

}  // namespace arm_collision_monitor
