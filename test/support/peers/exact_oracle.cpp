// The exact oracle: URDF collision geometry through FCL's distance query (GJK/EPA via libccd,
// or FCL's closed forms where it has them), all owner pairs with an AABB pre-test.
#include "arm_collision_monitor/peers/exact_oracle.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fcl/fcl.h>
#include <urdf_parser/urdf_parser.h>

namespace arm_collision_monitor {

struct ExactOracle::Impl {
  struct Element {
    std::unique_ptr<fcl::CollisionObjectd> object;
    Eigen::Isometry3d X_LC = Eigen::Isometry3d::Identity();  // in the owner's link frame
  };
  struct Owner {
    int link_index = -1;  // -1: a scene object (its element pose is in W)
    bool is_moving = false;
    double tolerance_m = 0.0;
    PrimitiveId primitive = 0;  // one of its primitives, for compatibility
    std::vector<Element> elements;
    Aabb box_W;
  };
  std::vector<std::string> names;
  std::vector<Owner> owners;
  std::vector<int> owner_of;  // by primitive id
  std::vector<LinkElement> link_elements;
  fcl::DistanceRequestd request;
};

namespace {

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  X.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y,
                                  pose.rotation.z).toRotationMatrix();
  return X;
}

}  // namespace

ExactOracle::ExactOracle(const Workcell& wc) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDFFile(wc.urdf_path);
  if (!urdf) throw LoadError(wc.urdf_path + ": cannot parse the URDF");
  std::map<std::string, int> owner_by_name;
  m.owner_of.assign(wc.primitives.size(), -1);
  for (std::size_t id = 0; id < wc.primitives.size(); ++id) {
    const PrimitiveSpec& p = wc.primitives[id];
    if (!p.variant.empty()) continue;
    const std::string owner_name = p.link_index >= 0 ? wc.kinematics.link_name(p.link_index)
                                                     : p.owner;
    auto it = owner_by_name.find(owner_name);
    if (it == owner_by_name.end()) {
      Impl::Owner owner;
      owner.link_index = p.link_index;
      owner.is_moving = !p.is_static;
      owner.tolerance_m = p.tolerance_m;
      owner.primitive = static_cast<PrimitiveId>(id);
      if (p.link_index < 0) {
        const Box& box = std::get<Box>(p.shape_L);
        Impl::Element e;
        e.object = std::make_unique<fcl::CollisionObjectd>(
            std::make_shared<fcl::Boxd>(2.0 * box.half_extents_m), box.X_WB);
        owner.elements.push_back(std::move(e));
      } else {
        const urdf::LinkConstSharedPtr link = urdf->getLink(owner_name);
        if (!link) throw LoadError(wc.urdf_path + ": no link '" + owner_name + "'");
        for (const urdf::CollisionSharedPtr& c : link->collision_array) {
          Impl::Element e;
          e.X_LC = ToIsometry(c->origin);
          std::shared_ptr<fcl::CollisionGeometryd> g;
          LinkElement element;
          element.link_index = p.link_index;
          element.X_LC = e.X_LC;
          switch (c->geometry->type) {
            case urdf::Geometry::CYLINDER: {
              const auto& cyl = static_cast<const urdf::Cylinder&>(*c->geometry);
              g = std::make_shared<fcl::Cylinderd>(cyl.radius, cyl.length);
              element.kind = LinkElement::Kind::kCylinder;
              element.radius_m = cyl.radius;
              element.length_m = cyl.length;
              break;
            }
            case urdf::Geometry::SPHERE:
              element.kind = LinkElement::Kind::kSphere;
              element.radius_m = static_cast<const urdf::Sphere&>(*c->geometry).radius;
              g = std::make_shared<fcl::Sphered>(element.radius_m);
              break;
            case urdf::Geometry::BOX: {
              const auto& b = static_cast<const urdf::Box&>(*c->geometry);
              element.kind = LinkElement::Kind::kBox;
              element.size_m = Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z);
              g = std::make_shared<fcl::Boxd>(b.dim.x, b.dim.y, b.dim.z);
              break;
            }
            default:
              throw LoadError(wc.urdf_path + ": link '" + owner_name +
                              "': the exact oracle needs cylinders, spheres or boxes");
          }
          e.object = std::make_unique<fcl::CollisionObjectd>(g, e.X_LC);
          owner.elements.push_back(std::move(e));
          m.link_elements.push_back(element);
        }
      }
      it = owner_by_name.emplace(owner_name, static_cast<int>(m.owners.size())).first;
      m.names.push_back(owner_name);
      m.owners.push_back(std::move(owner));
    }
    m.owner_of[id] = it->second;
  }
}

ExactOracle::~ExactOracle() = default;

const std::vector<std::string>& ExactOracle::owner_names() const { return impl_->names; }
int ExactOracle::OwnerOf(PrimitiveId id) const { return impl_->owner_of[id]; }
const std::vector<LinkElement>& ExactOracle::link_elements() const {
  return impl_->link_elements;
}

bool LinkElement::Contains(const Eigen::Vector3d& p_LQ) const {
  const Eigen::Vector3d p_CQ = X_LC.inverse() * p_LQ;
  switch (kind) {
    case Kind::kCylinder:
      return std::abs(p_CQ.z()) <= 0.5 * length_m &&
             p_CQ.head<2>().squaredNorm() <= radius_m * radius_m;
    case Kind::kSphere:
      return p_CQ.squaredNorm() <= radius_m * radius_m;
    case Kind::kBox:
      return (p_CQ.cwiseAbs().array() <= 0.5 * size_m.array()).all();
  }
  return false;
}

Aabb LinkElement::ComputeAabb_L() const {
  switch (kind) {
    case Kind::kCylinder:
      return Capsule{X_LC * Eigen::Vector3d(0, 0, -0.5 * length_m),
                     X_LC * Eigen::Vector3d(0, 0, 0.5 * length_m), radius_m}
          .ComputeAabb();
    case Kind::kSphere:
      return Capsule{X_LC.translation(), X_LC.translation(), radius_m}.ComputeAabb();
    case Kind::kBox:
      return Box{X_LC, 0.5 * size_m}.ComputeAabb();
  }
  return Aabb{};
}

void ExactOracle::FindWarnings(const std::vector<Eigen::Isometry3d>& X_WL,
                               const CompatibilityMatrix& compatible,
                               std::vector<std::pair<int, int>>* owner_pairs) {
  Impl& m = *impl_;
  owner_pairs->clear();
  for (Impl::Owner& owner : m.owners) {
    bool first = true;
    for (Impl::Element& e : owner.elements) {
      if (owner.link_index >= 0) e.object->setTransform(X_WL[owner.link_index] * e.X_LC);
      e.object->computeAABB();
      const fcl::AABBd& box = e.object->getAABB();
      const Aabb element_W{box.min_, box.max_};
      if (first) {
        owner.box_W = element_W;
        first = false;
      } else {
        owner.box_W.min_W = owner.box_W.min_W.cwiseMin(element_W.min_W);
        owner.box_W.max_W = owner.box_W.max_W.cwiseMax(element_W.max_W);
      }
    }
  }
  const int n = static_cast<int>(m.owners.size());
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const Impl::Owner& a = m.owners[i];
      const Impl::Owner& b = m.owners[j];
      if (!a.is_moving && !b.is_moving) continue;
      if (compatible.AreCompatible(a.primitive, b.primitive)) continue;
      const double threshold_m = a.tolerance_m + b.tolerance_m;
      if (!a.box_W.Inflated(threshold_m).Overlaps(b.box_W)) continue;
      bool is_warning = false;
      for (const Impl::Element& ea : a.elements) {
        for (const Impl::Element& eb : b.elements) {
          if (is_warning) break;
          fcl::DistanceResultd result;
          is_warning = fcl::distance(ea.object.get(), eb.object.get(), m.request, result) <
                       threshold_m;
        }
      }
      if (is_warning) owner_pairs->emplace_back(i, j);
    }
  }
}

}  // namespace arm_collision_monitor
