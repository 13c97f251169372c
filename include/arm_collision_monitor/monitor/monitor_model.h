// The Monitor's model: everything derived once at start-up from the workcell and the options and
// never changed afterwards (Pinocchio's Model / Data split: what Attach, Detach, SetGraspTarget,
// SwitchModel, SetObjectPose and the cycle change lives in the Monitor's preallocated data, which
// starts as a copy of the *_start members here).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/geometry/primitives.h"
#include "arm_collision_monitor/monitor/monitor_options.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {

/// The immutable part of a Monitor (see the file comment). Built by its constructor, which
/// validates the options against the workcell and throws LoadError naming the file and element.
struct MonitorModel {
  /// A workcell object's primitives and how it may move.
  struct Object {
    std::vector<PrimitiveId> prims;
    /// Inverse of the start pose: the object at pose X_WO is X_WO * X_OW_start * shape_L.
    Eigen::Isometry3d X_OW_start = Eigen::Isometry3d::Identity();
    bool is_attachable = false;
    bool is_frame_bound = false;  ///< moved by SetObjectPose
  };

  MonitorModel(std::shared_ptr<const Workcell> workcell, const MonitorOptions& options);

  /// The tolerance (m) the broad phase grows a primitive of tolerance `tol_m` by: plus the
  /// speed-scaled growth at the speed bound when it moves.
  double BroadTolerance_m(double tol_m, bool is_moving) const {
    return tol_m + (is_moving ? options.max_speed_mps * speed_tol_gain_s : 0.0);
  }
  /// `workcell` with the live objects' slots appended (none when live.capacity is 0): per slot
  /// an object named "~live<s>" of live.max_primitives_per_object placeholder primitives
  /// ("~live<s>/<k>", a point at the world's centre, static), excused with nothing. Throws
  /// LoadError when the options are out of range.
  static std::shared_ptr<const Workcell> WithLiveSlots(std::shared_ptr<const Workcell> workcell,
                                                       const LiveObjectOptions& live);
  /// Whether `id` is the slot of a live object (MonitorModel::WithLiveSlots).
  bool is_live(PrimitiveId id) const { return id >= first_live_primitive; }
  /// The live slot of object `o`, -1 for an object of the scene file.
  int LiveSlot(int o) const { return o >= first_live_object ? o - first_live_object : -1; }

  /// Whether a moving primitive (`mover_W`, tolerance `mover_tol_m`) reaches a static one
  /// (`static_W`, `static_tol_m`): their distance is within the sum of their broad-phase
  /// tolerances (<=, as the broad phase's closed boxes: touching counts).
  bool Reaches(const Shape& mover_W, double mover_tol_m, const Shape& static_W,
               double static_tol_m) const;

  std::shared_ptr<const Workcell> workcell;
  /// The options as used: world box, smallest cell (MinCellSize_m), pool reservation and, for
  /// broad_phase auto, the chosen method filled in.
  MonitorOptions options;
  const KinematicModel* kinematics = nullptr;  ///< workcell->kinematics
  std::uint32_t primitive_count = 0;  ///< the live slots' included
  PrimitiveId first_live_primitive = 0;  ///< slots: first_live_primitive .. primitive_count - 1
  int first_live_object = 0;             ///< their objects: first_live_object .. (one per slot)
  double world_edge_m = 0.0;      ///< the world box's longest edge
  /// The pairs a cycle may test: all but those of two primitives that never move.
  std::size_t max_tested_pairs = 0;
  double speed_tol_gain_s = 0.0;  ///< reaction + stopping time when speed-scaled, else 0
  /// Joint limits by q index, kJointLimitMargin included; always finite (a joint without limits:
  /// +/-kMaxUnlimitedPosition_rad), so that they alone refuse NaN, infinities and absurd values.
  Eigen::VectorXd q_lower, q_upper;
  /// KinematicModel::TurningLinks: joints a driver may report wrapped (Monitor::Update).
  std::vector<int> turning_links;

  std::vector<std::vector<PrimitiveId>> link_prims;     ///< per link: every variant's primitives
  std::vector<std::vector<std::string>> link_variants;  ///< per link; [0] is always ""
  std::vector<int> variant_index;  ///< per primitive, into its link's variants; 0 for objects
  std::vector<Object> objects;     ///< parallel to Workcell::objects
  std::vector<int> object_of;      ///< per primitive, -1 for link primitives
  /// Per link: the farthest a held object may reach from its origin (m); < 0: the link has no
  /// moving joint above it and may hold nothing.
  std::vector<double> hold_radius_m;

  // --- the start state the Monitor's data begins from ----------------------------------------
  /// Every joint at 0 clamped into its limits; the first good Update moves everything.
  Eigen::VectorXd q_start;
  std::vector<Eigen::Isometry3d> X_WL_start;   ///< link poses at q_start
  std::vector<int> carrier_start;              ///< per primitive: its link, -1 for objects
  std::vector<std::uint8_t> is_moving_start;   ///< per primitive: indexed as moving
  std::vector<Shape> shape_W_start;            ///< per primitive, at q_start
  /// Per primitive: false for a static that no moving part can reach (ComputeReachability).
  std::vector<std::uint8_t> is_reachable_start;

 private:
  void ValidateOptions() const;
  void BuildPrimitives();
  void BuildStartPose();
  // Per link, the sphere its points (and what it may hold) stay within for every q; radius < 0
  // for the links that reach nothing. Also sets hold_radius_m.
  std::vector<Capsule> ComputeReachSpheres();
  void ComputeReachability();
  void ChooseBroadPhase();
};

}  // namespace arm_collision_monitor
