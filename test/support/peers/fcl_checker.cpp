// FCL 0.7 as a peer: the usual FCL set-up of a robot monitor (one dynamic AABB tree for the
// environment, one for the moving links; moving-vs-environment plus moving self-collision).
#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <fcl/fcl.h>

#include "arm_collision_monitor/peers/peer_checker.h"
#include "arm_collision_monitor/peers/peer_frames.h"

namespace arm_collision_monitor {
namespace {

using Geometry = std::shared_ptr<fcl::CollisionGeometryd>;

// FCL geometry of `shape` grown by `grow_m` (capsule radius, box half extents), and its pose.
std::pair<Geometry, Eigen::Isometry3d> MakeFclShape(const Shape& shape, double grow_m) {
  if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    const CapsuleFrame frame = ComputeCapsuleFrame(*capsule);
    return {std::make_shared<fcl::Capsuled>(capsule->radius_m + grow_m, frame.length_m),
            frame.X_WC};
  }
  const Box& box = std::get<Box>(shape);
  const Eigen::Vector3d size_m = 2.0 * (box.half_extents_m.array() + grow_m).matrix();
  return {std::make_shared<fcl::Boxd>(size_m), box.X_WB};
}

Eigen::Isometry3d PoseOf(const Shape& shape) {
  if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    return ComputeCapsuleFrame(*capsule).X_WC;
  }
  return std::get<Box>(shape).X_WB;
}

class FclChecker final : public PeerChecker {
 public:
  FclChecker(const std::vector<PeerPrimitive>& primitives, const CompatibilityMatrix& compatible,
             PeerTolerance mode)
      : compatible_(compatible), mode_(mode), objects_(primitives.size()),
        ungrown_(primitives.size()), tolerance_m_(primitives.size(), 0.0) {
    for (std::size_t id = 0; id < primitives.size(); ++id) {
      const PeerPrimitive& p = primitives[id];
      if (!p.is_present) continue;
      tolerance_m_[id] = p.tolerance_m;
      auto [grown, X_WS] = MakeFclShape(p.shape_W, p.tolerance_m);
      objects_[id] = std::make_unique<fcl::CollisionObjectd>(grown, X_WS);
      // The id travels in the user-data pointer (no per-object allocation).
      objects_[id]->setUserData(reinterpret_cast<void*>(static_cast<std::uintptr_t>(id)));
      objects_[id]->computeAABB();
      if (mode_ == PeerTolerance::kRounded) ungrown_[id] = MakeFclShape(p.shape_W, 0.0).first;
      if (p.is_moving) {
        moving_.push_back(objects_[id].get());
      } else {
        statics_.push_back(objects_[id].get());
      }
    }
    // FCL's default GJK stopping tolerance (1e-6) leaves capsule-box and sphere-box distances
    // up to ~40 um long (libccd), so pairs that close inside their threshold were missed;
    // 1e-9 decides them right down to 0.1 um (test_peers_agreement's near-threshold table).
    distance_request_.distance_tolerance = 1e-9;
    static_manager_.registerObjects(statics_);
    static_manager_.setup();
    moving_manager_.registerObjects(moving_);
    moving_manager_.setup();
  }

  std::string name() const override {
    return mode_ == PeerTolerance::kRounded ? "fcl_rounded" : "fcl_sharp";
  }

  void SetShape(PrimitiveId id, const Shape& shape_W) override {
    fcl::CollisionObjectd& object = *objects_[id];
    object.setTransform(PoseOf(shape_W));
    object.computeAABB();
  }

  void FindWarnings(std::vector<CandidatePair>* pairs) override {
    pairs->clear();
    pairs_ = pairs;
    moving_manager_.update();
    moving_manager_.collide(&static_manager_, this, &FclChecker::OnCandidate);
    moving_manager_.collide(this, &FclChecker::OnCandidate);
    std::sort(pairs->begin(), pairs->end());
    pairs_ = nullptr;
  }

 private:
  static PrimitiveId IdOf(const fcl::CollisionObjectd* object) {
    return static_cast<PrimitiveId>(reinterpret_cast<std::uintptr_t>(object->getUserData()));
  }

  // FCL broad-phase callback: narrow phase on one candidate pair. Returns false (never stop).
  static bool OnCandidate(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
    auto* self = static_cast<FclChecker*>(data);
    PrimitiveId a = IdOf(o1);
    PrimitiveId b = IdOf(o2);
    if (a > b) std::swap(a, b);
    if (self->compatible_.AreCompatible(a, b)) return false;
    bool is_warning = false;
    if (self->mode_ == PeerTolerance::kSharp) {
      fcl::CollisionResultd result;
      fcl::collide(o1, o2, self->collision_request_, result);
      is_warning = result.isCollision();
    } else {
      fcl::DistanceResultd result;
      const double distance_m =
          fcl::distance(self->ungrown_[a].get(), self->objects_[a]->getTransform(),
                        self->ungrown_[b].get(), self->objects_[b]->getTransform(),
                        self->distance_request_, result);
      is_warning = distance_m < self->tolerance_m_[a] + self->tolerance_m_[b];
    }
    if (is_warning) self->pairs_->push_back(CandidatePair{a, b});
    return false;
  }

  CompatibilityMatrix compatible_;
  PeerTolerance mode_;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects_;  // grown shapes, by id
  std::vector<Geometry> ungrown_;  // kRounded: the shapes themselves, for the distance query
  std::vector<double> tolerance_m_;
  std::vector<fcl::CollisionObjectd*> statics_, moving_;
  fcl::DynamicAABBTreeCollisionManagerd static_manager_, moving_manager_;
  fcl::CollisionRequestd collision_request_;  // boolean: one contact, no contact details
  fcl::DistanceRequestd distance_request_;    // distance only, no witness points
  std::vector<CandidatePair>* pairs_ = nullptr;
};

}  // namespace

std::unique_ptr<PeerChecker> MakeFclChecker(const std::vector<PeerPrimitive>& primitives,
                                            const CompatibilityMatrix& compatible,
                                            PeerTolerance mode) {
  return std::make_unique<FclChecker>(primitives, compatible, mode);
}

}  // namespace arm_collision_monitor
