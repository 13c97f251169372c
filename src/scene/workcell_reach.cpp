// Reach envelopes of a workcell and the world cube derived from them (see workcell_reach.h).
#include "arm_collision_monitor/scene/workcell_reach.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {
namespace {

// The largest AABB diagonal of an attachable object (it bounds the object's diameter, which a
// rigid motion keeps); < 0 when there is none.
double MaxAttachableDiameter_m(const Workcell& w) {
  double diameter_m = -1.0;
  for (const ObjectSpec& object : w.objects) {
    if (!object.is_attachable) continue;
    Aabb box = ComputeAabb(w.primitives[object.primitive].shape_L);
    for (int k = 1; k < object.primitive_count; ++k) {
      const Aabb b = ComputeAabb(w.primitives[object.primitive + k].shape_L);
      box.Enclose(b);
    }
    diameter_m = std::max(diameter_m, (box.max_W - box.min_W).norm());
  }
  return diameter_m;
}

// The refusal of a derived world cube of edge `edge_m` over kMaxWorldEdge_m: the link that
// reaches farthest and the prismatic joint above it that slides farthest (the usual cause:
// URDF limits of +/-1e9 m for a joint that has none).
LoadError TooLargeWorld(const Workcell& w, const WorkcellReach& reach, double edge_m) {
  const KinematicModel& model = w.kinematics;
  int farthest = 0;
  for (int link = 1; link < model.link_count(); ++link) {
    if (reach.spheres[link].radius_m > reach.spheres[farthest].radius_m) farthest = link;
  }
  int slider = -1;
  for (int link = farthest; link > 0; link = model.parent_link(link)) {
    const double travel_m = PrismaticTravel_m(model.joint(link));
    if (travel_m > 0.0 && (slider < 0 || travel_m > PrismaticTravel_m(model.joint(slider)))) {
      slider = link;
    }
  }
  char text[256];
  std::snprintf(text, sizeof(text), "%.6g m wide, over the %.0f m", edge_m, kMaxWorldEdge_m);
  std::string why = w.scene_path + ": world: missing, and the cube derived from the arms' " +
                    "reach and the objects is " + text +
                    " a world may span (the monitor's distance bounds keep 1e-9 of the edge in "
                    "hand against rounding)";
  if (reach.spheres[farthest].radius_m >= 0.0) {
    std::snprintf(text, sizeof(text), "%.6g", reach.spheres[farthest].radius_m);
    why += ": link '" + model.link_name(farthest) + "' reaches " + text + " m";
    if (slider > 0) {
      std::snprintf(text, sizeof(text), "%.6g", PrismaticTravel_m(model.joint(slider)));
      why += ", below prismatic joint '" + model.joint(slider).name + "' of " + w.urdf_path +
             ", which slides " + text + " m within its limits";
    }
  }
  return LoadError(why + "; give the joint its real limits (joint_limits: in the scene file "
                         "narrows them) or world: {center_m: [x, y, z], edge_m: e}");
}

}  // namespace

WorkcellReach ComputeWorkcellReach(const Workcell& w) {
  const KinematicModel& model = w.kinematics;
  const int link_count = model.link_count();
  std::vector<Eigen::Isometry3d> X_WL(link_count, Eigen::Isometry3d::Identity());
  // Any q: the links above the first moving joint of a chain, which give the centres, are fixed.
  model.ComputeLinkPoses(Eigen::VectorXd::Zero(model.q_size()), &X_WL);

  // Per link: world centre of its reach sphere and the chain length from that centre.
  std::vector<Eigen::Vector3d> centre_W(link_count, Eigen::Vector3d::Zero());
  std::vector<double> chain_m(link_count, 0.0);
  std::vector<std::uint8_t> is_below_joint(link_count, 0);  // a non-fixed joint above it
  for (int link = 1; link < link_count; ++link) {
    const int parent = model.parent_link(link);
    const JointSpec& joint = model.joint(link);
    const double travel_m = PrismaticTravel_m(joint);
    if (is_below_joint[parent]) {
      is_below_joint[link] = 1;
      centre_W[link] = centre_W[parent];
      chain_m[link] = chain_m[parent] + joint.X_PJ.translation().norm() + travel_m;
    } else if (joint.type != JointType::kFixed) {
      // The first moving joint (actuated or mimic): its origin is fixed (revolute) or slides by
      // `travel_m`.
      is_below_joint[link] = 1;
      centre_W[link] = X_WL[parent] * joint.X_PJ.translation();
      chain_m[link] = travel_m;
    }
  }
  std::vector<double> extent_m(link_count, -1.0);  // < 0: no primitive on the link
  for (const PrimitiveSpec& p : w.primitives) {
    if (p.link_index < 0) continue;
    extent_m[p.link_index] = std::max(extent_m[p.link_index],
                                      MaxDistanceFromPoint_m(p.shape_L, Eigen::Vector3d::Zero()));
  }
  const double attach_diameter_m = MaxAttachableDiameter_m(w);
  const bool has_attachable = attach_diameter_m >= 0.0;

  // Only links below a moving joint may hold objects (holding with a fixed link would make a
  // static object "moving" for nothing).
  WorkcellReach reach;
  reach.hold_radius_m.assign(link_count, -1.0);
  reach.spheres.assign(link_count,
                       Capsule{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), -1.0});
  for (int link = 0; link < link_count; ++link) {
    if (!is_below_joint[link]) continue;
    const double own_m = std::max(extent_m[link], 0.0);
    reach.hold_radius_m[link] = own_m + kAttachMaxGap_m + std::max(attach_diameter_m, 0.0);
    Capsule& sphere = reach.spheres[link];
    sphere.p0_W = sphere.p1_W = centre_W[link];
    if (has_attachable) {
      sphere.radius_m = chain_m[link] + reach.hold_radius_m[link];
    } else if (extent_m[link] >= 0.0) {
      sphere.radius_m = chain_m[link] + extent_m[link];
    }
  }
  return reach;
}

Aabb DeriveWorldCube(const Workcell& w) {
  if (w.primitives.empty()) {
    throw LoadError(w.scene_path + ": world: missing and the workcell has no primitive to derive "
                                   "it from (expected world: {center_m: [x, y, z], edge_m: e})");
  }
  const WorkcellReach reach = ComputeWorkcellReach(w);
  std::vector<Eigen::Isometry3d> X_WL(w.kinematics.link_count(), Eigen::Isometry3d::Identity());
  w.kinematics.ComputeLinkPoses(Eigen::VectorXd::Zero(w.kinematics.q_size()), &X_WL);
  double max_tolerance_m = 0.0;
  for (const PrimitiveSpec& p : w.primitives) {
    max_tolerance_m = std::max(max_tolerance_m, p.tolerance_m);
  }

  constexpr double kInf = std::numeric_limits<double>::infinity();
  Aabb all{Eigen::Vector3d::Constant(kInf), Eigen::Vector3d::Constant(-kInf)};
  for (std::size_t link = 0; link < reach.spheres.size(); ++link) {
    const Capsule& sphere = reach.spheres[link];
    if (sphere.radius_m < 0.0) continue;
    if (!std::isfinite(sphere.radius_m)) {
      throw LoadError(w.scene_path + ": world: missing and link '" +
                      w.kinematics.link_name(static_cast<int>(link)) +
                      "' has an unbounded reach (a prismatic joint without limits above it); "
                      "expected world: {center_m: [x, y, z], edge_m: e}");
    }
    all.Enclose(sphere.ComputeAabb());
  }
  for (const PrimitiveSpec& p : w.primitives) {
    if (p.link_index >= 0 && reach.spheres[p.link_index].radius_m >= 0.0) continue;  // above
    // Objects at their start poses (shape_L is in W), links that never move at their poses.
    all.Enclose(ComputeAabb(p.link_index >= 0 ? TransformShape(X_WL[p.link_index], p.shape_L)
                                              : p.shape_L));
  }
  all = all.Inflated(max_tolerance_m);
  const double edge_m = (all.max_W - all.min_W).maxCoeff() + 2.0 * kDerivedWorldMargin_m;
  if (edge_m > kMaxWorldEdge_m) throw TooLargeWorld(w, reach, edge_m);
  return Aabb::Cube(0.5 * (all.min_W + all.max_W), edge_m);
}

}  // namespace arm_collision_monitor
