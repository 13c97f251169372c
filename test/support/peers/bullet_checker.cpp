// Bullet as a peer: a btCollisionWorld over btDbvtBroadphase (two dynamic AABB trees, the
// moving and the fixed set), discrete collision detection, contacts read from the manifolds.
// Built against Bullet's double-precision libraries when they are installed
// (BT_USE_DOUBLE_PRECISION set by CMake), so both sides compute in double.
#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include <btBulletCollisionCommon.h>

#include "arm_collision_monitor/peers/peer_checker.h"
#include "arm_collision_monitor/peers/peer_frames.h"

namespace arm_collision_monitor {
namespace {

btTransform ToBullet(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d& R = X.linear();
  return btTransform(btMatrix3x3(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2),
                                 R(2, 0), R(2, 1), R(2, 2)),
                     btVector3(X.translation().x(), X.translation().y(), X.translation().z()));
}

// Bullet's shapes are convex cores plus a margin, and its queries act on the core grown by the
// margin (a Minkowski sum with a ball). A capsule's margin is its radius, so radius + tolerance
// is exact in both modes. A box keeps its outer half extents when its margin changes: outer =
// half extents + tolerance with margin = tolerance leaves the core at the box itself, i.e. the
// box grown by a ball of the tolerance (kRounded); margin 0 gives the sharp grown box.
std::unique_ptr<btCollisionShape> MakeBulletShape(const Shape& shape, double tolerance_m,
                                                  PeerTolerance mode,
                                                  Eigen::Isometry3d* X_WS) {
  if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    const CapsuleFrame frame = ComputeCapsuleFrame(*capsule);
    *X_WS = frame.X_WC;
    return std::make_unique<btCapsuleShapeZ>(capsule->radius_m + tolerance_m, frame.length_m);
  }
  const Box& box = std::get<Box>(shape);
  *X_WS = box.X_WB;
  const Eigen::Vector3d outer_m = box.half_extents_m.array() + tolerance_m;
  auto bt_box = std::make_unique<btBoxShape>(btVector3(outer_m.x(), outer_m.y(), outer_m.z()));
  bt_box->setMargin(mode == PeerTolerance::kRounded ? tolerance_m : 0.0);
  return bt_box;
}

// Leaves out compatible pairs and static-static pairs before any narrow phase, as our broad
// phase does (it replaces Bullet's group/mask test).
class CompatibilityFilter final : public btOverlapFilterCallback {
 public:
  CompatibilityFilter(const CompatibilityMatrix& compatible, const std::vector<char>& is_moving)
      : compatible_(compatible), is_moving_(is_moving) {}
  bool needBroadphaseCollision(btBroadphaseProxy* proxy0,
                               btBroadphaseProxy* proxy1) const override {
    const int a = static_cast<const btCollisionObject*>(proxy0->m_clientObject)->getUserIndex();
    const int b = static_cast<const btCollisionObject*>(proxy1->m_clientObject)->getUserIndex();
    if (!is_moving_[a] && !is_moving_[b]) return false;
    return !compatible_.AreCompatible(a, b);
  }

 private:
  const CompatibilityMatrix& compatible_;
  const std::vector<char>& is_moving_;
};

class BulletChecker final : public PeerChecker {
 public:
  BulletChecker(const std::vector<PeerPrimitive>& primitives,
                const CompatibilityMatrix& compatible, PeerTolerance mode)
      : compatible_(compatible), mode_(mode), is_moving_(primitives.size(), 0),
        dispatcher_(&configuration_), world_(&dispatcher_, &broadphase_, &configuration_),
        filter_(compatible_, is_moving_), shapes_(primitives.size()),
        objects_(primitives.size()) {
    broadphase_.getOverlappingPairCache()->setOverlapFilterCallback(&filter_);
    // Bullet's box-box algorithm (btBoxBoxCollisionAlgorithm) works on the outer half extents
    // and ignores margins, i.e. on sharp grown boxes: kRounded sends box pairs to the general
    // convex algorithm (GJK/EPA on the core plus margin) like every other pair.
    if (mode == PeerTolerance::kRounded) {
      dispatcher_.registerCollisionCreateFunc(
          BOX_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE,
          configuration_.getCollisionAlgorithmCreateFunc(CONVEX_HULL_SHAPE_PROXYTYPE,
                                                         CONVEX_HULL_SHAPE_PROXYTYPE));
    }
    // Only moving objects get their AABB recomputed each call (static ones never change).
    world_.setForceUpdateAllAabbs(false);
    for (std::size_t id = 0; id < primitives.size(); ++id) {
      const PeerPrimitive& p = primitives[id];
      if (!p.is_present) continue;
      is_moving_[id] = p.is_moving ? 1 : 0;
      Eigen::Isometry3d X_WS;
      shapes_[id] = MakeBulletShape(p.shape_W, p.tolerance_m, mode, &X_WS);
      auto object = std::make_unique<btCollisionObject>();
      object->setCollisionShape(shapes_[id].get());
      object->setWorldTransform(ToBullet(X_WS));
      object->setUserIndex(static_cast<int>(id));
      if (p.is_moving) {
        object->setActivationState(DISABLE_DEACTIVATION);
        world_.addCollisionObject(object.get(), btBroadphaseProxy::DefaultFilter,
                                  btBroadphaseProxy::AllFilter);
      } else {
        object->setCollisionFlags(object->getCollisionFlags() |
                                  btCollisionObject::CF_STATIC_OBJECT);
        object->setActivationState(ISLAND_SLEEPING);
        world_.addCollisionObject(object.get(), btBroadphaseProxy::StaticFilter,
                                  btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
      }
      objects_[id] = std::move(object);
    }
  }

  ~BulletChecker() override {
    for (auto& object : objects_) {
      if (object) world_.removeCollisionObject(object.get());
    }
  }

  std::string name() const override {
    return mode_ == PeerTolerance::kRounded ? "bullet_rounded" : "bullet_sharp";
  }

  void SetShape(PrimitiveId id, const Shape& shape_W) override {
    Eigen::Isometry3d X_WS;
    if (const auto* capsule = std::get_if<Capsule>(&shape_W)) {
      X_WS = ComputeCapsuleFrame(*capsule).X_WC;
    } else {
      X_WS = std::get<Box>(shape_W).X_WB;
    }
    objects_[id]->setWorldTransform(ToBullet(X_WS));
  }

  void FindWarnings(std::vector<CandidatePair>* pairs) override {
    pairs->clear();
    // Persistent manifolds carry last cycle's points forward (re-projected, not recomputed):
    // cleared so that every point read below comes from this cycle's narrow phase.
    for (int i = 0; i < dispatcher_.getNumManifolds(); ++i) {
      dispatcher_.getManifoldByIndexInternal(i)->clearManifold();
    }
    world_.performDiscreteCollisionDetection();
    for (int i = 0; i < dispatcher_.getNumManifolds(); ++i) {
      const btPersistentManifold* manifold = dispatcher_.getManifoldByIndexInternal(i);
      bool is_warning = false;
      for (int c = 0; c < manifold->getNumContacts() && !is_warning; ++c) {
        // Negative distance: the grown shapes overlap (Bullet also keeps points of separated
        // shapes up to its contact-breaking threshold).
        is_warning = manifold->getContactPoint(c).getDistance() < 0.0;
      }
      if (!is_warning) continue;
      PrimitiveId a = static_cast<PrimitiveId>(manifold->getBody0()->getUserIndex());
      PrimitiveId b = static_cast<PrimitiveId>(manifold->getBody1()->getUserIndex());
      if (a > b) std::swap(a, b);
      pairs->push_back(CandidatePair{a, b});
    }
    std::sort(pairs->begin(), pairs->end());
  }

 private:
  CompatibilityMatrix compatible_;
  PeerTolerance mode_;
  std::vector<char> is_moving_;
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btCollisionWorld world_;
  CompatibilityFilter filter_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btCollisionObject>> objects_;
};

}  // namespace

std::unique_ptr<PeerChecker> MakeBulletChecker(const std::vector<PeerPrimitive>& primitives,
                                               const CompatibilityMatrix& compatible,
                                               PeerTolerance mode) {
  return std::make_unique<BulletChecker>(primitives, compatible, mode);
}

}  // namespace arm_collision_monitor
