// The per-cycle Monitor: joint positions in -> kinematics -> broad-phase update -> narrow phase
// on candidate pairs -> a report of every non-compatible pair closer than the sum of its
// tolerances, and a stop flag. ROS-free; the node only translates messages to and from it.
#pragma once

#include <cstdint>
#include <limits>
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

/// Why a cycle's input was refused. Anything but kOk makes the cycle fail safe (stop = true)
/// and leaves the model at its last good state.
enum class InputStatus : std::uint8_t {
  kOk,
  kWrongSize,   ///< not one position per model joint
  kNonFinite,   ///< a NaN or inf position
  kOutOfLimits  ///< a position outside its joint's limits by more than the configured margin
};

/// One non-compatible pair closer than the sum of its tolerances, or touching / overlapping
/// (overlap is a negative signed distance: it warns even when both tolerances are 0).
struct Warning {
  PrimitiveId a = 0;  ///< a < b
  PrimitiveId b = 0;
  double distance_m = 0.0;   ///< between the real (uninflated) surfaces; 0 when overlapping
  double threshold_m = 0.0;  ///< tolerance(a) + tolerance(b) this cycle
  Eigen::Vector3d p_WA = Eigen::Vector3d::Zero();  ///< closest point on a, world frame
  Eigen::Vector3d p_WB = Eigen::Vector3d::Zero();  ///< closest point on b, world frame
  /// Found by the swept check between the last accepted q and this cycle's (not at this
  /// cycle's q): distance_m and the points are at step_fraction along the step.
  bool between_samples = false;
  double step_fraction = 1.0;  ///< 0 at the last accepted q, 1 at this cycle's
};

/// The rule a Warning follows: closer than the threshold, or touching / overlapping (so a pair
/// without tolerances, threshold 0, still warns on contact).
inline bool IsWarningDistance(double distance_m, double threshold_m) {
  return distance_m < threshold_m || distance_m <= 0.0;
}

/// A step that the samples alone do not cover, with the swept check off (CycleReport).
struct StepBeyondSamples {
  bool is_beyond = false;
  PrimitiveId primitive = 0;  ///< the first moving primitive found moved beyond its tolerance
  double motion_m = 0.0;      ///< its motion bound over the step
  double tolerance_m = 0.0;   ///< its tolerance
};

/// The result of one cycle. Lives in the Monitor's preallocated data: valid until the next
/// Update().
struct CycleReport {
  std::uint64_t cycle = 0;  ///< number of Update() calls so far, refused ones included
  InputStatus input = InputStatus::kOk;
  std::vector<Warning> warnings;  ///< sorted by (a, b)
  bool stop = false;  ///< warnings non-empty, the input refused, or input_jumped
  std::uint32_t moved_primitives = 0;      ///< primitives whose pose changed
  std::uint32_t reindexed_primitives = 0;  ///< of those, the ones moved in the index
  std::uint32_t candidate_pairs = 0;       ///< pairs whose indexed boxes overlap
  std::uint32_t narrow_phase_tests = 0;    ///< exact distance computations
  /// Decided by motion bounds alone, without kinematics: every primitive provably within its
  /// slack and every kept pair provably clear, so no warning (moved_primitives is then 0).
  bool bounded = false;
  /// Largest motion bound over primitives for the step from the last accepted q (m; 0 on the
  /// first good cycle and on refused and idle ones).
  double step_motion_m = 0.0;
  /// The step exceeded MonitorOptions::max_step_m and the sample times given to Update do not
  /// show every joint within kJumpVelocityFactor times its velocity limit since the last
  /// accepted q (a sparse path's large step does); or, without the swept check, its motion
  /// bound for a moving primitive exceeds that one's tolerance, which the samples alone do not
  /// cover (input sparser than cycle_period_s, a joint without a velocity limit, a held object
  /// reaching beyond its holder): accepted, but stop is requested.
  bool input_jumped = false;
  /// input_jumped for the second reason alone (the swept check off, a step the samples do not
  /// cover): which primitive, by how much; is_beyond false otherwise.
  StepBeyondSamples beyond_samples;
  /// Pairs whose swept check needed the path (their distance at the step's start, and
  /// bisection); 0 when every pair was certified by its distance at q less its motion bound.
  std::uint32_t swept_pairs = 0;
  std::uint32_t swept_distance_tests = 0;  ///< exact distances the swept check computed
  BroadPhaseCounters counters;  ///< broad-phase work done during this cycle only
};

/// Per-cycle collision monitor (the seed's update loop). Rules it follows:
/// - Only primitives whose carrier link's pose changed (bit for bit) are moved in the broad
///   phase; a q bit-identical to the last good one with no scene change since is an idle cycle:
///   the previous report with cycle + 1 (and zero moved / counters), no work -- a step of zero,
///   so without the previous step's between-samples warnings and input_jumped.
/// - Static primitives (links with only fixed joints above them, resting objects) are never
///   tested against each other. A resting attachable object is static; it moves (and is tested
///   against statics) while attached. Frame-bound objects always move.
/// - Statics that no arm can reach -- with anything it may hold -- are left out at start-up
///   (is_active false): the reach envelope of each link is a sphere about the first actuated
///   joint above it (see MonitorModel, monitor_model.cpp). A frame-bound object brings the
///   statics near its pose back in (SetObjectPose).
/// - A held object gets at least its holder's tolerance and is compatible with its holder link.
/// - broad_phase auto (the default): naive or the grid, chosen at start-up from the active
///   moving and static primitives (ChooseBroadPhaseMethod).
/// - Index slack (MonitorOptions::index_slack_m): moving primitives are indexed by boxes grown
///   by the slack and re-indexed once moved farther (farther than half of it after steps small
///   enough for the bounded cycles below); the candidate pairs are kept with a
///   lower bound on their distance, and a pair is tested exactly only when that bound, less both
///   primitives' motion since, no longer clears its threshold (PairCache, pair_cache.h). When
///   bounds on the motion taken from the joint deltas alone (lever arms from the URDF chain;
///   MotionBounds, motion_bounds.h) clear every kept pair, the cycle skips the kinematics too
///   (CycleReport::bounded).
/// - Synchronisation is explicit: a bounded cycle leaves the shapes, the index and the kept
///   pairs at the q of the last kinematics, which is sound since every bound is taken from
///   there, and keeps bounded cycles cheap (no kinematics at all). The next kinematics cycle,
///   Attach, Detach and SwitchModel (which read or re-express shapes), and SyncShapes() bring
///   them to the last good q; SetGraspTarget (only the compatibility), SetObjectPose (a free
///   object, whatever q) and Check (on a copy, from the poses the shapes are at) need not. No
///   const accessor computes: shape_W() is a plain read.
/// - Swept check (MonitorOptions::swept_check; swept_check.cpp): every step from the last
///   accepted q to the new one is checked along the straight joint-space path between them. A
///   bounded cycle certifies the whole path (its bounds hold for every point between); a
///   kinematics cycle certifies each pair by its bound at the new q less its relative motion
///   over the step, and bisects the others (conservative advancement) down to
///   swept_resolution_m. Contacts found between samples are warnings with between_samples set.
/// - A refused input keeps the last good model and its warnings, sets input and stop.
class Monitor {
 public:
  /// Start-up: builds the live model from a loaded workcell (see scene/workcell.h) and the
  /// monitor options. Throws LoadError on inconsistent options.
  Monitor(std::shared_ptr<const Workcell> workcell, const MonitorOptions& options);
  ~Monitor();
  Monitor(const Monitor&) = delete;
  Monitor& operator=(const Monitor&) = delete;

  /// The loaded workcell plus the live objects' slots (placeholder primitives and objects,
  /// appended after the loaded ones; see AddObject).
  const Workcell& workcell() const;
  const MonitorOptions& options() const;

  /// One cycle. `q` holds one position per Workcell::joint_names() entry (rad or m). Never
  /// throws and does not allocate in the steady state; a malformed `q` is refused (see
  /// InputStatus), counted, and fails safe. `time_s`: when `q` was sampled (s, any epoch; NaN
  /// when unknown), which tells a sparse path's large step from a jump (input_jumped), and a
  /// wrapped reading of a continuous joint without limits (MonitorModel::turning_links): one
  /// that moves more than half a turn where the move the other way round is within the joint's
  /// velocity bound over the time since gets whole turns added (one pose), so that the step
  /// takes the short way (an input_jumped stop where the move as given was within the bound
  /// too: nothing tells which way it turned); the idle test and the swept path then see q so
  /// unwound. Without a velocity limit or a time, q is taken as given.
  const CycleReport& Update(const Eigen::Ref<const Eigen::VectorXd>& q,
                            double time_s = std::numeric_limits<double>::quiet_NaN());
  /// The same with each joint's own sample time (one per joint, as q; any other size counts as
  /// unknown): input merged from several topics (one arm's driver each), whose joints were
  /// sampled apart -- the jump test then times each joint's move from its own last sample.
  const CycleReport& Update(const Eigen::Ref<const Eigen::VectorXd>& q,
                            const Eigen::Ref<const Eigen::VectorXd>& joint_time_s);
  /// The last report (cycle 0 and stop = true before the first good Update()).
  const CycleReport& report() const;
  /// Why Update(q) refuses `q`, for a person: its size against the model's, or the first joint
  /// that is not finite or outside its limits, with its position and the limits (margin
  /// included; a joint without limits: beyond kMaxUnlimitedPosition_rad), as given, else with
  /// the whole turns the last Update unwound (call it right after Update(q) for those); "" when
  /// q is acceptable. Allocates: for reports of refused cycles, not the cycle.
  std::string DescribeRefusal(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  /// Generate-and-test for planners: the report `q` would give, computed on a copy; the live
  /// model is not touched. Allocates.
  CycleReport Check(const Eigen::Ref<const Eigen::VectorXd>& q) const;

  // --- run-time changes to the scene (none allocates) -------------------------------------
  /// Object `object` is held by link `link` and moves with it from now on, in its current pose
  /// relative to the link; it becomes compatible with that link. False (with `error`) on
  /// unknown names.
  bool Attach(const std::string& object, const std::string& link, std::string* error);
  bool Detach(const std::string& object, std::string* error);
  /// The link holding `object`; "" when none holds it (or no such object).
  std::string HolderOf(const std::string& object) const;
  /// Whether a link holds `object` (HolderOf without the name: the node asks every cycle).
  bool IsHeld(const std::string& object) const;
  /// With the swept check off, for a held `object` a primitive of which may move farther in one
  /// cycle than its tolerance (the larger of max_speed_mps * cycle_period_s and what the URDF
  /// velocity limits allow, as start-up checks the links): a notice naming the one furthest
  /// beyond, as a step that fast is beyond the samples and a stop (beyond_samples); else "".
  std::string DescribeHeldMotionBeyondTolerance(const std::string& object) const;
  /// Declares (or clears) `object` a grasp target of `link`: compatible while set. A scene
  /// object only with a link its scene file lists under grasp_targets; a live object with any
  /// link (until it is removed).
  bool SetGraspTarget(const std::string& link, const std::string& object, bool is_target,
                      std::string* error);
  /// Replaces a link's primitives by its model variant `variant` (declared in the scene file;
  /// "" is the default), e.g. one coarse gripper capsule in gross motion, a detailed set while
  /// grasping.
  bool SwitchModel(const std::string& link, const std::string& variant, std::string* error);
  /// Moves a free object (for one bound to a TF frame) to pose X_WO.
  bool SetObjectPose(const std::string& object, const Eigen::Isometry3d& X_WO,
                     std::string* error);
  /// SetObjectPose of a pose sampled at `time_s` (s, finite; a TF stamp). With speed-scaled
  /// tolerance the object's speed is then its move over the time since its timed pose before,
  /// kept in the cycles until its next one (a 10 Hz tracker in a 20 Hz monitor: not at rest
  /// every other cycle); the same pose at a later time takes it to rest. A move with no timed
  /// pose before, at a time not later, or more than kObjectSpeedMaxGapCycles cycle periods
  /// after the one before takes max_speed_mps. Detach forgets its times.
  bool SetObjectPoseAt(const std::string& object, const Eigen::Isometry3d& X_WO, double time_s,
                       std::string* error);

  // --- live objects: added, moved and removed at run time ----------------------------------
  // Room for them is preallocated at start-up (MonitorOptions::live_objects: capacity objects of
  // up to max_primitives_per_object primitives each), so the cycle never allocates for them.
  // Each is checked from the next Update like a resting scene object: against the arms, held
  // and frame-bound objects (never against other statics), excused with nothing; an
  // attachable one may be held (Attach, Detach) like any attachable object. Every call below
  // changes nothing when it fails (false, with `error`). Objects of the scene file cannot be
  // moved or removed here (frame-bound ones follow SetObjectPose).

  /// Adds object `name` made of `shapes_O` (its primitives in its frame O; see
  /// scene/solid_spec.h for solids and meshes) at pose X_WO, with tolerance `tolerance_m` (m,
  /// >= 0) on each primitive. Its primitives are named `name` (one) or `name`/k (k = 0, 1, ...)
  /// in primitive(). Refused: no free slot, more shapes than max_primitives_per_object, an
  /// empty name or one (or a primitive name) already used by a link, object or primitive, a
  /// non-finite or non-rigid pose, a shape not finite or of a non-positive size, a shape
  /// outside the world cube, a negative or non-finite tolerance. May allocate (the names),
  /// never in Update afterwards.
  bool AddObject(const std::string& name, const std::vector<Shape>& shapes_O,
                 const Eigen::Isometry3d& X_WO, double tolerance_m, bool is_attachable,
                 std::string* error);
  /// Moves live object `name` to pose X_WO. Refused: unknown or scene-file object, held by a
  /// link, non-finite or non-rigid pose, a primitive leaving the world cube.
  bool MoveObject(const std::string& name, const Eigen::Isometry3d& X_WO, std::string* error);
  /// Removes live object `name` (a held one is let go first); its slot is free again.
  /// Refused: unknown or scene-file object.
  bool RemoveObject(const std::string& name, std::string* error);
  /// Live objects present now.
  std::uint32_t live_object_count() const;
  /// The description of primitive `id`: the workcell's, or for the slot of a live object the
  /// live object's (name, owner, tolerance_m, is_static = not attachable). workcell() holds the
  /// slots too, under placeholder names, so that ids index it; translate ids to names here.
  const PrimitiveSpec& primitive(PrimitiveId id) const;

  // --- read access for visualisation and diagnostics ---------------------------------------
  std::uint32_t primitive_count() const;
  /// World-frame shape of primitive `id` (uninflated), a plain read: at the last good q, except
  /// after bounded cycles (see SyncShapes), when the link-carried shapes are still at the q of
  /// the last kinematics -- within the index slack of where they are.
  const Shape& shape_W(PrimitiveId id) const;
  /// Whether shape_W() is at the last good q (false only after bounded cycles).
  bool are_shapes_current() const;
  /// Brings the shapes to the last good q after bounded cycles: the forward kinematics a bounded
  /// cycle skipped, with the index and the kept pairs following (its broad-phase work is counted
  /// in the run's totals at the next Update). A no-op when the shapes are current. Call it
  /// before reading shape_W() for display; the cycle itself does not, so that bounded cycles
  /// stay cheap. Does not allocate.
  void SyncShapes();
  /// Whether primitive `id` is currently part of the checked scene (false for inactive model
  /// variants and primitives no moving part can reach).
  bool is_active(PrimitiveId id) const;
  /// Whether the pair (a, b) is excused right now: compatible at start-up, or a held object and
  /// its holder, or a declared grasp target and its link.
  bool AreCompatibleNow(PrimitiveId a, PrimitiveId b) const;
  /// Leaf cells of the spatial index (empty when the broad phase has no cells).
  void CollectIndexCells(std::vector<IndexCell>* cells) const;
  /// Counters accumulated over the whole run.
  const BroadPhaseCounters& total_counters() const;
  std::uint64_t refused_inputs() const;
  /// The broad phase in use ("octree", "naive", ...; auto's choice once started).
  std::string broad_phase_name() const;
  /// Start-up notices (e.g. a tolerance below the per-cycle motion, covered by the swept check),
  /// for the caller to show.
  const std::vector<std::string>& startup_notices() const;
  /// Cycles whose swept check needed the path (CycleReport::swept_pairs > 0), over the run.
  std::uint64_t swept_cycles() const;
  /// Tolerance of primitive `id` in the last cycle (speed-scaled when enabled), metres.
  double tolerance_m(PrimitiveId id) const;

  /// Checks the live model's invariants (shapes follow their carriers, compatibility matches
  /// the attach / grasp state, the report is sorted). False with a message in `error`.
  bool Validate(std::string* error) const;
  /// The spatial index's own invariants (BroadPhase::Validate: cells, location links, stamps).
  /// Slow (every cell): for soaks and tests, not every cycle.
  bool ValidateIndex(std::string* error) const;
  /// Test hook (soak, tests): brings the spatial index's 32-bit visit stamps to
  /// `steps_before_wrap` stamps short of their wrap-around (BroadPhase::ForceStampsNearWrap).
  /// Valid between any two calls; the reports must not change.
  void ForceIndexStampsNearWrap(std::uint32_t steps_before_wrap);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace arm_collision_monitor
