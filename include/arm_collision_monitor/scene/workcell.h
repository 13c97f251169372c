// The workcell model, loaded once at start-up and immutable afterwards (Model/Data split): the
// arms' kinematics (from a URDF), every primitive with its owner and tolerance, the
// environment (from a scene YAML file) and the compatibility matrix; plus the Monitor's options.
#pragma once

#include <string>
#include <vector>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/broadphase/compatibility_matrix.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/geometry/primitives.h"
#include "arm_collision_monitor/kinematics/kinematic_model.h"

namespace arm_collision_monitor {

/// One primitive of the model, in the frame of its owner.
struct PrimitiveSpec {
  std::string name;   ///< unique, e.g. "left_link3", "left_gripper/finger1", "front_table"
  std::string owner;  ///< the link or object it belongs to
  int link_index = -1;  ///< KinematicModel link carrying it; -1 for an environment object
  std::string group;    ///< the arm it belongs to ("left", "right"), "" for the environment
  std::string variant;  ///< model variant of its link ("" = default, active at start)
  Shape shape_L;        ///< geometry in the owner's frame (link frame, or world for objects)
  double tolerance_m = 0.0;  ///< tolerance zone beyond the surface
  bool is_static = true;     ///< environment object not attached and not frame-bound
};

struct Workcell {
  std::string urdf_path;
  std::string scene_path;
  std::string fixed_frame = "world";
  Aabb world_W;  ///< the world cube the spatial index covers
  KinematicModel kinematics;
  std::vector<std::string> joint_names;  ///< actuated joints, in the order of Monitor's q
  std::vector<PrimitiveSpec> primitives; ///< PrimitiveId = index
  CompatibilityMatrix compatible;        ///< pairs excused at start-up
};

struct MonitorOptions {
  /// The broad phase; world_W and min_cell_size_m are filled in from the workcell and from
  /// max_speed_mps * cycle_period_s.
  BroadPhaseOptions broad_phase;
  /// Let the Monitor pick the faster of octree and naive for the scene at start-up.
  bool auto_broad_phase = false;
  double max_speed_mps = 0.61;     ///< 24 in/s: bounds the per-cycle motion
  double cycle_period_s = 0.05;    ///< 20 Hz
  /// Optional speed-dependent tolerance (ISO/TS 15066 protective separation distance): each
  /// moving primitive's tolerance grows by its current speed times (reaction + stopping time).
  bool speed_scaled_tolerance = false;
  double reaction_time_s = 0.1;
  double stopping_time_s = 0.02;
};

/// Loads a URDF and a scene YAML file into a workcell. Throws LoadError.
Workcell LoadWorkcell(const std::string& urdf_path, const std::string& scene_path);
/// Loads Monitor options from a YAML file. Throws LoadError.
MonitorOptions LoadMonitorOptions(const std::string& path);

}  // namespace arm_collision_monitor
