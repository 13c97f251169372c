// Reach envelopes of a workcell and the world cube derived from them (see workcell_reach.h).
#include "arm_collision_monitor/scene/workcell_reach.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

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

// The refusal of a derived world cube of edge `edge_m` over kMaxWorldEdge_m. Where the arms'
// reach (`reach_W`, the reach spheres' box) alone fits, the primitive fixed in the world (an
// object, a link fixed to the root; links at their poses `X_WL`) farthest from it is named;
// else the link that reaches farthest and the prismatic joints above it.
LoadError TooLargeWorld(const Workcell& w, const WorkcellReach& reach,
                        const std::vector<Eigen::Isometry3d>& X_WL, const Aabb& reach_W,
                        double edge_m) {
  const KinematicModel& model = w.kinematics;
  char text[256];
  std::snprintf(text, sizeof(text), "%.6g m wide, over the %.0f m", edge_m, kMaxWorldEdge_m);
  const std::string why = w.scene_path + ": world: missing, and the cube derived from the " +
                          "arms' reach and the objects is " + text +
                          " a world may span (the monitor's distance bounds keep 1e-9 of the "
                          "edge in hand against rounding)";
  const bool has_reach = (reach_W.min_W.array() <= reach_W.max_W.array()).all();
  if (!has_reach || (reach_W.max_W - reach_W.min_W).maxCoeff() < 0.5 * kMaxWorldEdge_m) {
    const Eigen::Vector3d centre_W =
        has_reach ? Eigen::Vector3d(0.5 * (reach_W.min_W + reach_W.max_W))
                  : Eigen::Vector3d::Zero();
    double farthest_m = -1.0;
    PrimitiveId farthest = 0;
    for (PrimitiveId id = 0; id < w.primitives.size(); ++id) {
      const PrimitiveSpec& p = w.primitives[id];
      if (p.link_index >= 0 && reach.spheres[p.link_index].radius_m >= 0.0) continue;
      const Shape shape_W =
          p.link_index >= 0 ? TransformShape(X_WL[p.link_index], p.shape_L) : p.shape_L;
      const double distance_m = MaxDistanceFromPoint_m(shape_W, centre_W);
      if (distance_m > farthest_m) {
        farthest_m = distance_m;
        farthest = id;
      }
    }
    std::snprintf(text, sizeof(text), "%.6g", farthest_m);
    return LoadError(why + ": '" + w.primitives[farthest].name + "' reaches " + text +
                     " m from the middle of the arms' reach (a unit or origin error in its "
                     "object or link?): the objects and the links fixed to the root must fit in "
                     "one world cube with the arms");
  }
  int farthest = 0;
  for (int link = 1; link < model.link_count(); ++link) {
    if (reach.spheres[link].radius_m > reach.spheres[farthest].radius_m) farthest = link;
  }
  std::string sliders;
  for (int link = farthest; link > 0; link = model.parent_link(link)) {
    const JointSpec& joint = model.joint(link);
    const double travel_m = model.Travel_m(joint);
    if (!(travel_m > 0.0)) continue;
    std::string mimicked;  // a mimic joint's travel is the joint it mimics' to narrow
    if (const JointSpec* target = model.MimickedJoint(joint)) {
      mimicked = "mimics '" + target->name + "', ";
    }
    std::snprintf(text, sizeof(text), "%.6g", travel_m);
    sliders += (sliders.empty() ? "" : ", ") + std::string("'") + joint.name + "' (" + mimicked +
               "up to " + text + " m)";
  }
  std::snprintf(text, sizeof(text), "%.6g", reach.spheres[farthest].radius_m);
  return LoadError(why + ": link '" + model.link_name(farthest) + "' reaches " + text +
                   " m from the first moving joint above it" +
                   (sliders.empty() ? std::string()
                                    : ", prismatic joints of " + w.urdf_path +
                                          " above it: " + sliders) +
                   "; give world: {center_m: [x, y, z], edge_m: e}, or the joints their real "
                   "limits (joint_limits: in the scene file)");
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
    const double travel_m = model.Travel_m(joint);
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
    if (sphere.radius_m >= 0.0) all.Enclose(sphere.ComputeAabb());
  }
  const Aabb reach_W = all;
  for (const PrimitiveSpec& p : w.primitives) {
    if (p.link_index >= 0 && reach.spheres[p.link_index].radius_m >= 0.0) continue;  // above
    // Objects at their start poses (shape_L is in W), links that never move at their poses.
    all.Enclose(ComputeAabb(p.link_index >= 0 ? TransformShape(X_WL[p.link_index], p.shape_L)
                                              : p.shape_L));
  }
  all = all.Inflated(max_tolerance_m);
  const double edge_m = (all.max_W - all.min_W).maxCoeff() + 2.0 * kDerivedWorldMargin_m;
  if (!(edge_m <= kMaxWorldEdge_m)) throw TooLargeWorld(w, reach, X_WL, reach_W, edge_m);
  return Aabb::Cube(0.5 * (all.min_W + all.max_W), edge_m);
}

}  // namespace arm_collision_monitor
