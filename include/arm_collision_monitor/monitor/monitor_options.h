// The Monitor's options (format: config/monitor.yaml) and the values derived from them.
#pragma once

#include <cstdint>
#include <string>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {

/// Room for objects added at run time (Monitor::AddObject): capacity x max_primitives_per_object
/// primitive slots, preallocated at start-up with everything they need (index entries,
/// compatibility rows, kept pairs, report), so that adding, moving and removing never makes the
/// cycle allocate.
struct LiveObjectOptions {
  std::uint32_t capacity = 16;                 ///< live objects at once; 0: none
  std::uint32_t max_primitives_per_object = 8;  ///< e.g. a mesh's capsules:K fit needs K
};

/// The Monitor's options (LoadMonitorOptions; format: config/monitor.yaml).
struct MonitorOptions {
  /// The broad phase; world_W and min_cell_size_m are filled in by the Monitor from the
  /// workcell and from MinCellSize_m(). method kAuto (the default): the Monitor picks naive
  /// or the grid at start-up from its active moving and static primitives
  /// (ChooseBroadPhaseMethod).
  BroadPhaseOptions broad_phase;
  double max_speed_mps = 0.61;   ///< 24 in/s: bounds the per-cycle motion
  double cycle_period_s = 0.05;  ///< 20 Hz
  /// Optional speed-dependent tolerance (ISO/TS 15066 protective separation distance): each
  /// moving primitive's tolerance grows by its current speed times (reaction + stopping time):
  /// its move in the cycle over cycle_period_s, plus a bound of the newest steps of the joints
  /// above it not sampled in the cycle that moved at their own (Monitor::Update's per-joint
  /// times); unmoved, it keeps its speed while a joint above it moved at its newest sample,
  /// else it is at rest.
  bool speed_scaled_tolerance = false;
  double reaction_time_s = 0.1;
  double stopping_time_s = 0.02;
  /// Slack of the index (m): a moving primitive is indexed by its box grown by this much, and
  /// re-indexed once a point of it has moved farther than this since it was last indexed, or
  /// than half of this after steps small enough for bounded cycles (PairCache);
  /// candidate pairs whose last distance, less both primitives' motion since, still exceeds
  /// their threshold skip the narrow phase. 0: every moved primitive is re-indexed and every
  /// candidate pair tested each cycle (the seed's loop). The warnings are the same either way.
  double index_slack_m = kDefaultIndexSlack_m;
  /// Swept check of every step (swept_check.h): each non-compatible pair is certified clear
  /// along the straight joint-space path from the last accepted q to the new one, or warned
  /// (Warning::between_samples). Off: only the samples are checked, and a tolerance below the
  /// per-cycle motion is a start-up error.
  bool swept_check = true;
  /// What the swept check resolves (m of relative motion bound): a between-samples warning
  /// means the path comes within threshold + this; no closer contact is missed.
  double swept_resolution_m = 0.001;
  /// Largest plausible step (m): a step whose motion bound (the largest over primitives from
  /// the last accepted q; lever arms, so up to a few times the true motion) exceeds it -- a
  /// teleport after a driver restart -- requests a stop, "input jumped", until a normal step,
  /// unless the samples' times show every joint within kJumpVelocityFactor times its velocity
  /// limit (Monitor::Update). The step is still swept.
  double max_step_m = 1.0;
  /// Default tolerance of an arm whose scene entry gives none (pass it to LoadWorkcell).
  double tolerance_m = kDefaultArmTolerance_m;
  /// The frame reports and markers are expressed in: "" (the default) for the URDF root link
  /// (Workcell::fixed_frame), in which the monitor computes; a name only relabels that frame.
  std::string fixed_frame;
  LiveObjectOptions live_objects;
};

/// The octree's and the grid's smallest cell (m): the farthest an indexed box moves in one
/// index update, i.e. the slack it may already have used plus one cycle at the speed bound
/// (seed, section 3). Cells no smaller keep the seed's incremental update (a move within one cell
/// of the old cells) the common case.
inline double MinCellSize_m(const MonitorOptions& options) {
  return options.max_speed_mps * options.cycle_period_s + options.index_slack_m;
}

/// Loads Monitor options from a YAML file. Throws LoadError naming the file and the element.
MonitorOptions LoadMonitorOptions(const std::string& path);

}  // namespace arm_collision_monitor
