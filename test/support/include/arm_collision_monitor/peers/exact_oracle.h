// The exact oracle of the model-fidelity study: each link's own URDF collision geometry
// (cylinders, spheres, boxes; no capsule enclosure) and each scene object's box, with FCL's
// distance query. It decides warnings per owner pair (link or object), as a user sees them.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "arm_collision_monitor/broadphase/compatibility_matrix.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {

/// One URDF collision element of a link, in the link frame L: a cylinder (axis along z of its
/// frame C, centred at C's origin), a sphere (centred at C's origin) or a box (centred at C's
/// origin, edges along C's axes).
struct LinkElement {
  enum class Kind { kCylinder, kSphere, kBox };
  int link_index = -1;
  Kind kind = Kind::kCylinder;
  Eigen::Isometry3d X_LC = Eigen::Isometry3d::Identity();
  double radius_m = 0.0;                           ///< cylinder, sphere
  double length_m = 0.0;                           ///< cylinder
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();  ///< box: full edge lengths

  /// True iff point Q (p_LQ, in L) lies in the closed element.
  bool Contains(const Eigen::Vector3d& p_LQ) const;
  /// An AABB in L that encloses the element (tight for spheres and boxes; for a cylinder, the
  /// AABB of the capsule of its axis and radius).
  Aabb ComputeAabb_L() const;
};

class ExactOracle {
 public:
  /// Reads the collision elements of wc.urdf_path for every link that carries a primitive of
  /// the default model. Throws LoadError naming the file on a geometry it cannot represent.
  explicit ExactOracle(const Workcell& wc);
  ~ExactOracle();
  ExactOracle(const ExactOracle&) = delete;
  ExactOracle& operator=(const ExactOracle&) = delete;

  /// Owners are links (by KinematicModel index) and objects; their names index the result.
  const std::vector<std::string>& owner_names() const;
  /// Owner index of a primitive of the workcell, -1 if it has none.
  int OwnerOf(PrimitiveId id) const;
  /// The URDF collision elements of every link the oracle checks, in URDF order per link (the
  /// fidelity study builds its models from them and measures their excess volume).
  const std::vector<LinkElement>& link_elements() const;
  /// Every owner pair (i < j), at least one moving, not compatible in `compatible` (judged on
  /// their primitives), whose exact geometry is closer than the sum of their tolerances, at
  /// link poses X_WL. Sorted.
  void FindWarnings(const std::vector<Eigen::Isometry3d>& X_WL,
                    const CompatibilityMatrix& compatible,
                    std::vector<std::pair<int, int>>* owner_pairs);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace arm_collision_monitor
