// Monitor::Impl, shared by the Monitor's sources (monitor.cpp: the cycle; monitor_scene.cpp: the
// run-time scene changes; monitor_check.cpp: Check and the validation). Private to the module.
//
// Model / Data split: `model` is built once and const; every other member is the data, all of
// it preallocated at construction -- the scene state (what Attach, Detach, SetGraspTarget,
// SwitchModel and SetObjectPose change) and the per-cycle state.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/monitor/monitor_model.h"
#include "arm_collision_monitor/monitor/motion_bounds.h"
#include "arm_collision_monitor/monitor/pair_cache.h"
#include "swept_check.h"

namespace arm_collision_monitor {

/// Relative margin on motion bounds summed in another order, or a sum of two (IsProvablyClear,
/// IsBeyondSampleCheck): each is a sum of a few dozen non-negative products, within 1e-14 of
/// its exact value, as their sum is.
inline constexpr double kBoundSumRounding = 1e-12;

/// Finite, its rotation orthonormal and proper (kLiveObjectRotationTolerance): a pose an object
/// may be moved to (AddObject, MoveObject, SetObjectPose).
bool IsRigidPose(const Eigen::Isometry3d& X);

struct Monitor::Impl {
  const MonitorModel model;

  // --- scene state -----------------------------------------------------------------------
  CompatibilityMatrix compatible;       // start-up's, plus held objects and grasp targets
  std::vector<std::uint8_t> grasp;      // link_count x object_count: is a grasp target
  std::vector<int> holder;              // per object: holding link, -1 if none
  // Per object, for speed-scaled tolerances of a free frame-bound one posed with its sample
  // time (SetObjectPoseAt): that time (s; NaN before the first) and its speed since the timed
  // pose before (m/s; NaN: none, its move in the cycle gives it; inf: unknown, max_speed_mps),
  // kept until its next timed pose.
  std::vector<double> object_sample_s;
  std::vector<double> object_speed_mps;
  std::vector<int> active_variant;      // per link
  std::vector<Shape> shape_C;           // per primitive: in its carrier link's frame
  std::vector<int> carrier;             // per primitive: link it moves with, -1 for none
  std::vector<double> tol_base;         // per primitive, m (a held object: at least its holder's)
  std::vector<std::uint8_t> is_moving;  // per primitive: Motion it is indexed with
  std::vector<std::uint8_t> is_reachable;  // false: a static no moving primitive can reach
  MotionBounds motion;                  // levers per primitive for its current carrier
  std::vector<std::uint8_t> is_present;    // per primitive: 0 for a free live slot
  // The primitives from here on are free live slots (none carried, indexed or moved): the
  // cycle's per-primitive loops stop here, so free slots cost the cycle nothing.
  PrimitiveId live_end = 0;

  // --- live objects (monitor_live_objects.cpp), per slot s of MonitorModel::WithLiveSlots ---
  struct LiveObjects {
    std::vector<std::string> name;               // per slot; "" when free
    std::vector<std::uint8_t> is_attachable;     // per slot
    std::vector<int> shape_count;                // per slot: primitives in use (the first ones)
    std::vector<PrimitiveSpec> spec;             // per slot primitive: what primitive() shows
    std::vector<Shape> shape_O;                  // per slot primitive: in the object's frame
    std::uint32_t count = 0;                     // slots in use
  } live;

  // --- per-cycle state -------------------------------------------------------------------
  std::unique_ptr<BroadPhase> broad_phase;
  std::vector<std::uint8_t> in_broad_phase;
  PairCache cache;                      // the index slack's indexed copies and kept pairs
  std::vector<Shape> shape_W;           // at q_kinematics
  std::vector<Shape> shape_prev_W;      // at the last good cycle (speed-scaled tolerance only)
  std::vector<std::uint8_t> moved;      // pose changed since the last kinematics
  // The primitives carried by a link (carrier >= 0), ascending: only they move with q, so the
  // per-cycle loops visit them rather than every static (SetCarrierBounds keeps the list).
  std::vector<PrimitiveId> carried;
  // Per primitive: a capsule whose endpoints in its carrier's frame are bit-identical (a sphere:
  // ReindexMoved transforms and compares one point; SetCarrierBounds keeps it).
  std::vector<std::uint8_t> is_sphere_C;
  std::vector<double> tol_now;          // per primitive this cycle, m
  // At q_kinematics, bit for bit, for every link in fk_links (Validate checks it): the
  // kinematics recomputes only the links a joint's change moves, so a link joins fk_links with
  // its pose computed (PrepareBounds). LinkPose computes any other link on demand.
  std::vector<Eigen::Isometry3d> X_WL;
  // At the kinematics before the last one: current for the links the last one moved
  // (link_changed; UpdateLinkPosesOf leaves them here), for the others of fk_links only once
  // is_before_complete (StartPoses copies them when the swept check first needs them).
  std::vector<Eigen::Isometry3d> X_WL_before;
  bool is_before_complete = false;
  // The moving links the kinematics computes: those carrying a primitive (of any variant, or a
  // held object) and the moving links between them and the root (KinematicModel::MovingLinksTo;
  // PrepareBounds keeps it). A real robot's frames without geometry (cameras, tool points,
  // sensor mounts: 13 of a Baxter's 35 moving links) are skipped.
  std::vector<int> fk_links;
  std::vector<std::uint8_t> fk_targets;  // scratch of PrepareBounds: per link
  // Per link: whether the last kinematics moved it (a joint between it and the root changed);
  // current for the links of fk_links, 0 for the links that do not move.
  std::vector<std::uint8_t> link_changed;
  std::vector<int> fk_scratch;  // KinematicModel::UpdateLinkPosesOf's, fk_links.size() entries
  // Speed-scaled tolerances: per joint (q index), whether its newest sample moved it; per link,
  // whether every joint between it and the root is at rest so (both NoteJointMotion's). An
  // unmoved primitive of a link not at rest keeps its speed: with one topic per arm, in the
  // other arm's cycles, until its own joints are sampled unmoved.
  // joint_sampled: whether this cycle sampled it anew; joint_step: |its move| at its newest
  // sample (infinite before the first good cycle). A moved primitive adds the steps of the
  // joints above it moving but not sampled in the cycle (ComputeTolerances).
  std::vector<std::uint8_t> joint_moving;
  std::vector<std::uint8_t> joint_sampled;
  std::vector<double> joint_step;
  std::vector<std::uint8_t> link_at_rest;
  // The smallest PairGap_m over the kept pairs since the last kinematics (SweepStep or
  // IsProvablyClear, whichever comes first).
  bool is_pair_gap_known = false;
  double smallest_pair_gap_m = 0.0;
  std::vector<std::uint8_t> bound_known;  // IsProvablyClear after bounded cycles: per primitive,
                                          // its bound in `motion` computed this cycle
  // The largest displacement from its indexed copy of an indexed primitive that may move, as of
  // the last kinematics (ReindexMoved; NaN if any is), for IsProvablyClear's test of all at once.
  double largest_displacement_m = std::numeric_limits<double>::quiet_NaN();
  // The largest motion bound since the kinematics that the last bounded cycle was proved clear
  // with (IsProvablyClear: an upper bound for every primitive; read in the next bounded cycle).
  double largest_since_m = 0.0;
  Eigen::VectorXd q_good;               // the last accepted q
  // Per joint, the whole turns added to its readings (MonitorModel::turning_links; 0 for the
  // others): turns_good those of q_good, turns_next the cycle's (Unwind); q_unwound the
  // cycle's q with them. Preallocated.
  Eigen::VectorXd turns_good, turns_next, q_unwound;
  bool is_turn_ambiguous = false;  // Unwind took a short way that the long way could have been
  // When q_good was sampled (Update's times, s): one time for every joint, or, when
  // is_joint_time_good, each joint's own in joint_time_good_s (preallocated).
  double time_good_s = std::numeric_limits<double>::quiet_NaN();
  bool is_joint_time_good = false;
  Eigen::VectorXd joint_time_good_s;
  // This cycle's q likewise: time_s for every joint, or each joint's own at joint_time_s (the
  // caller's, one per joint, valid during its Update).
  double time_s = std::numeric_limits<double>::quiet_NaN();
  const double* joint_time_s = nullptr;
  Eigen::VectorXd q_kinematics;         // q of the last forward kinematics
  bool has_good = false;
  bool scene_changed = true;
  bool kinematics_behind = false;       // bounded cycles since: q_kinematics != q_good
  CycleReport report;
  BroadPhaseCounters total;
  std::uint64_t refused = 0;
  SweptScratch swept;                   // the swept check's scratch (swept_check.h)
  std::uint64_t swept_cycles = 0;       // cycles whose swept check bisected some pair
  std::vector<std::string> notices;     // start-up notices (CheckStepTolerance)
  Eigen::VectorXd cycle_dq;             // per joint: its velocity limit x cycle_period_s

  Impl(std::shared_ptr<const Workcell> workcell, const MonitorOptions& options);
  // The data's start state (from the model's) and the index.
  void InitData();
  void BuildBroadPhase();

  // --- the cycle (monitor.cpp) --------------------------------------------------------------
  // What a cycle did, for RecordCycle.
  enum class CycleKind : std::uint8_t { kIdle, kRefused, kBounded, kKinematics };
  struct CycleWork {
    std::uint32_t moved = 0;
    std::uint32_t reindexed = 0;
    std::uint32_t candidate_pairs = 0;
    std::uint32_t narrow_phase_tests = 0;
    double step_m = 0.0;  // largest motion bound over primitives since the last accepted q
    bool is_jumped = false;
    StepBeyondSamples beyond_samples;
    std::uint32_t swept_pairs = 0;
    std::uint32_t swept_tests = 0;
  };
  InputStatus CheckInput(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  bool IsIdle(const Eigen::Ref<const Eigen::VectorXd>& q) const {
    return has_good && !scene_changed && report.input == InputStatus::kOk &&
           q.size() == q_good.size() &&
           std::memcmp(q.data(), q_good.data(), sizeof(double) * q.size()) == 0;
  }
  // An idle cycle is a step of zero: the last step's between-samples warnings go (in place).
  static void EraseBetweenSamples(std::vector<Warning>* warnings) {
    warnings->erase(std::remove_if(warnings->begin(), warnings->end(),
                                   [](const Warning& w) { return w.between_samples; }),
                    warnings->end());
  }
  // A good q: a bounded cycle if the bounds allow, else the kinematics and the narrow phase.
  void RunCycle(const Eigen::Ref<const Eigen::VectorXd>& q);
  // Monitor::Update, with its sample times in time_s or joint_time_s: CycleOf q, or of
  // q_unwound (Unwind), whose turns are kept when the cycle accepts it.
  const CycleReport& Cycle(const Eigen::Ref<const Eigen::VectorXd>& q);
  // The cycle of q: idle, refused or run (RunCycle).
  const CycleReport& CycleOf(const Eigen::Ref<const Eigen::VectorXd>& q);
  // q_good is q now: its times are this cycle's.
  void DateGood() {
    is_joint_time_good = joint_time_s != nullptr;
    if (is_joint_time_good) {
      std::copy_n(joint_time_s, joint_time_good_s.size(), joint_time_good_s.data());
    } else {
      time_good_s = time_s;
    }
  }
  // Whether `joint`'s move by `move` (>= 0) from q_good is within kJumpVelocityFactor times its
  // velocity limit over its time since then (from q_good's sample time to this cycle's; false
  // when that is not positive, or the joint moves and has no limit).
  bool IsWithinVelocityLimit(const JointSpec& joint, double move) const;
  // IsWithinVelocityLimit for every joint's move from q_good to q.
  bool IsWithinVelocityLimits(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  // For a Monitor without the swept check: whether this cycle's step (largest bound `step_m`)
  // moves an indexed primitive farther than its tolerance, which the samples alone do not cover
  // (start-up checked a cycle_period_s step at max_speed_mps or the velocity limits; sparser
  // input); the first such primitive goes to *beyond.
  bool IsBeyondSampleCheck(double step_m, StepBeyondSamples* beyond);
  // The readings of a continuous joint without limits (MonitorModel::turning_links) in
  // q_good's turns: turns_next is turns_good but where a reading's move from the last
  // accepted one is more than half a turn and the move the other way round is within the
  // joint's velocity bound over the time since (IsWithinVelocityLimit) -- the driver reported
  // the angle wrapped (into [-pi, pi]: Kinova's kortex driver), and the joint took the short
  // way: whole turns are added there. Where the move as given is within the bound too (after
  // a pause), is_turn_ambiguous: the cycle is an 'input jumped' stop. Any other move stays as
  // given (a trajectory controller turns the joint along a plan's points as they are; without
  // a velocity limit or sample times nothing tells a wrap). True when some joint has turns: q
  // with them is then in q_unwound.
  bool Unwind(const Eigen::Ref<const Eigen::VectorXd>& q);
  // True when, without kinematics, every moving primitive's joint-space motion bound since
  // q_kinematics keeps it within its slack and every kept pair's bound, less those motions,
  // still clears its threshold -- then no pair can warn. `step_m`: the step's largest bound
  // (RunCycle). Changes nothing but bound scratch.
  bool IsProvablyClear(const Eigen::Ref<const Eigen::VectorXd>& q, double step_m);
  // A kept pair's gap: its kinematics bound less its rounding margin and threshold (a motion
  // bound below it leaves the pair clear: PairCache::IsClear). The smallest over the kept pairs
  // is fixed from the narrow phase to the next kinematics (smallest_pair_gap_m).
  double PairGap_m(const KeptPair& kept) const {
    return kept.kinematics_bound_m - cache.BoundMargin_m(kept.kinematics_bound_m) -
           (tol_now[kept.pair.a] + tol_now[kept.pair.b]);
  }
  // Forward kinematics at q, the moved primitives re-indexed, the kept pairs brought up to
  // date: the shapes then follow q. Returns the number of primitives that moved. `is_step`:
  // q ends the step of this cycle (RunCycle), whose bounds StepBound_m gives. `reindex_at_m`:
  // how far a moved primitive may be from its indexed copy and stay (PairCache::FollowMoved).
  std::uint32_t FollowKinematics(const Eigen::Ref<const Eigen::VectorXd>& q, bool is_step,
                                 double reindex_at_m);
  // In one pass over the primitives that may have moved: moves the shapes carried by the links
  // flagged in link_changed (X_WL: the new poses), moves in the index the moved primitives
  // farther than `reindex_at_m` from their indexed copies and, with `is_step`, follows the step
  // (FollowStep); counts the moved ones.
  std::uint32_t ReindexMoved(bool is_step, double reindex_at_m);
  // The narrow phase over the kept pairs into report.warnings; returns the tests done.
  std::uint32_t TestCandidatePairs();
  // --- the swept check (swept_check.cpp) -----------------------------------------------------
  // Start-up: the swept scratch, and the notice (or, with swept_check off, the LoadError) for
  // a moving primitive whose tolerance is below its per-cycle motion.
  void InitSwept();
  void CheckStepTolerance();
  // Bound (m) on the motion of `id` in one cycle_period_s with every joint above it at its URDF
  // velocity limit (joints without a limit count as 0), each at its longest lever.
  double UrdfCycleMotion_m(PrimitiveId id) const;
  // How far (m) one cycle may move `id` beyond its tolerance (> 0: beyond): the larger of
  // max_speed_mps * cycle_period_s and UrdfCycleMotion_m, less tol_base. Start-up's check of
  // the links (CheckStepTolerance) and the held-object notice (DescribeHeldMotionBeyondTolerance).
  double CycleMotionExcess_m(PrimitiveId id) const {
    const MonitorOptions& options = model.options;
    return std::max(options.max_speed_mps * options.cycle_period_s, UrdfCycleMotion_m(id)) -
           tol_base[id];
  }
  // The step's motion bounds, from swept.q_start to the cycle's q (lever sums for PairBound_m;
  // the motion set in RunCycle, each bound computed on first use): see SweptScratch::step.
  MotionBounds& StepMotion() { return swept.is_behind ? swept.step : motion; }
  const MotionBounds& StepMotion() const { return swept.is_behind ? swept.step : motion; }
  // After the narrow phase at q (shapes at q): every pair certified clear along the straight
  // path from swept.q_start to q, or warned between samples (appended, then sorted).
  void SweepStep(const Eigen::Ref<const Eigen::VectorXd>& q, CycleWork* work);
  // Into swept.pairs (sorted), the pairs SweepStep looks at besides the kept ones: those of
  // each primitive that may leave its slack during the step whose boxes at q are not apart by
  // more than threshold + both step bounds. False when no primitive may leave it (none).
  bool CollectSweptPairs();
  // CollectSweptPairs' search when leavers x near boxes reach kSweptScanMinTests: each leaver's
  // grown box against every grown box at once (BoxArray by id), the hits masked by its
  // compatibility row and by the leavers that take the pair themselves; the leavers of one
  // link in a row share one scan, of their hull.
  void ScanSweptPairs();
  // Whether `id` may leave its slack during the step: its displacement at q plus its step bound
  // B exceeds the slack and, when `is_start_copy` (its indexed copy is the one it had at the
  // step's start) and the start displacements are known, so does (d0 + d1 + B) / 2 (NaN: may;
  // d0 from `kinematics_m`, its displacement as of the last kinematics: StartDisplacement_m).
  bool MayLeaveSlack(PrimitiveId id, bool is_start_copy, double kinematics_m);
  // Appends (a, b), a < b, whose grown boxes meet (CollectSweptPairs), to swept.pairs unless
  // compatible or clear by its boxes.
  void AddSweptPairIfNear(PrimitiveId a, PrimitiveId b);
  // Before the kinematics of a step whose largest bound is `step_m`: the step's scratch reset,
  // and what StartDisplacement_m needs besides a primitive's displacement, unless the index
  // changed since the last kinematics (swept.has_start_displacement).
  void BeginStep(double step_m);
  // In ReindexMoved, once `id` (indexed; `is_moved` this cycle; `kinematics_m` its displacement
  // before) has its displacement at q, if that is not within the largest step bound of its
  // slack: if it may leave the slack during the step (MayLeaveSlack), re-indexed at q when that
  // keeps it within the slack all along, else into swept.leavers.
  void FollowStep(PrimitiveId id, bool is_moved, double kinematics_m);
  // After the kinematics, when swept.has_start_displacement: a bound on the displacement of
  // `id` from its indexed copy at the step's start (its displacement `kinematics_m` at the last
  // kinematics plus its motion bound since), m.
  double StartDisplacement_m(PrimitiveId id, double kinematics_m);
  // The link poses at the step's start (q_start).
  const std::vector<Eigen::Isometry3d>& StartPoses();
  // Whether (a, b) is clear all along the step by SweepPair's first test (the whole step) on
  // lower bounds of its distances at the ends: `end_bound_m` at q, its boxes' gap at q_start
  // (on the same shapes as SweepPair's start distance, so what this clears SweepPair would
  // clear without a warning); `pair_motion_m`: the pair's relative motion bound. For the pairs
  // of AddSweptPairIfNear (a kept pair's bound at q is often exact: little left to spare).
  bool IsClearFromBothEnds(PrimitiveId a, PrimitiveId b, double end_bound_m,
                           double pair_motion_m);
  // Bisects one pair along the step (conservative advancement) from its distance d1_m at q;
  // appends its warning if any.
  void SweepPair(PrimitiveId a, PrimitiveId b, double pair_motion_m, double d1_m,
                 const Eigen::Ref<const Eigen::VectorXd>& q, CycleWork* work);
  // The step bound of `id` (0 without levers), m; computed on first use in a SweepStep.
  double StepBound_m(PrimitiveId id) {
    return BoundOnce(&StepMotion(), &swept.is_step_bound_known, id);
  }
  // The bound of `id` in `bounds` (0 without levers), computed at most once while `known[id]`
  // stays set.
  static double BoundOnce(MotionBounds* bounds, std::vector<std::uint8_t>* known,
                          PrimitiveId id) {
    if (bounds->lever_count(id) == 0) return 0.0;
    if ((*known)[id]) return bounds->bound_m(id);
    (*known)[id] = 1;
    return bounds->ComputeBound_m(id);
  }
  // The relative motion bound of (a, b) over the step (MotionBounds::PairBound_m), m.
  double PairStepBound_m(PrimitiveId a, PrimitiveId b) {
    StepBound_m(a);
    StepBound_m(b);
    return StepMotion().PairBound_m(a, b);
  }
  // Link poses at fraction s of the step: kept for the other pairs' samples of this cycle
  // (swept.X_WL_at), or in swept.X_WL_s (valid until the next call) once the cache is full.
  const std::vector<Eigen::Isometry3d>& StepPoses(double s,
                                                  const Eigen::Ref<const Eigen::VectorXd>& q);
  // The world shape of `id` for link poses X_WL (the static and free ones: as they are).
  Shape ShapeAt(PrimitiveId id, const std::vector<Eigen::Isometry3d>& X_WL_at) const {
    return carrier[id] < 0 ? shape_W[id] : TransformShape(X_WL_at[carrier[id]], shape_C[id]);
  }

  // The one place the report is written (the narrow phase fills its warnings).
  void RecordCycle(CycleKind kind, InputStatus input, const CycleWork& work);
  // After bounded cycles: the kinematics (shapes, index, kept pairs) brought to q_good, for
  // SyncShapes and the scene changes that read or re-express shapes (no bounded cycle follows
  // a scene change at once: re-indexed only past the slack).
  void SyncKinematics() {
    if (kinematics_behind) FollowKinematics(q_good, false, model.options.index_slack_m);
  }
  // Writes into `shapes` the primitives carried by links whose pose differs between X_WL and
  // `X_WL_new`, and flags them in `moved_flags`; `changed` is per-link scratch (Check: the
  // cycle moves them in ReindexMoved).
  void MoveCarried(const std::vector<Eigen::Isometry3d>& X_WL_new,
                   std::vector<std::uint8_t>* changed, std::vector<Shape>* shapes,
                   std::vector<std::uint8_t>* moved_flags) const;
  // Before DateGood, for an accepted q (idle or run): joint_moving of every joint sampled anew
  // (its time not q_good's, or not finite: one never received, or no time given; or its value
  // not q_good's) is whether it moved from q_good; the others keep theirs. Before the first
  // good cycle all are moving; then link_at_rest from them. Returns whether a joint came to
  // rest.
  bool NoteJointMotion(const Eigen::Ref<const Eigen::VectorXd>& q);
  // A primitive of a free object whose speed its timed poses give (object_speed_mps).
  bool IsTimedFreeObject(PrimitiveId id) const {
    const int o = model.object_of[id];
    return o >= 0 && holder[o] < 0 && !std::isnan(object_speed_mps[o]);
  }
  // No timed pose of object `o` is known (posed untimed, or let go): its move in the cycle
  // gives its speed.
  void ForgetObjectTimes(int o) {
    object_sample_s[o] = std::numeric_limits<double>::quiet_NaN();
    object_speed_mps[o] = std::numeric_limits<double>::quiet_NaN();
  }
  // Monitor::SetObjectPose, and SetObjectPoseAt with `time_s` (NaN: untimed).
  bool SetObjectPose(const std::string& object, const Eigen::Isometry3d& X_WO, double time_s,
                     std::string* error);
  // Whether no joint moved at its newest sample (always, without speed-scaled tolerances): an
  // idle Update(q) with one time for every joint keeps every tolerance.
  bool IsAtRest() const {
    return model.speed_tol_gain_s == 0.0 ||
           std::find(joint_moving.begin(), joint_moving.end(), 1) == joint_moving.end();
  }
  // This cycle's tolerance of every primitive (speed-scaled for the moving ones when enabled).
  // A speed is the primitive's move over cycle_period_s, 0 unmoved; with `at_rest` (per link)
  // an unmoved one carried by a link not at rest keeps its speed: its entry of `tol` is left.
  void ComputeTolerances(const std::vector<Shape>& shapes,
                         const std::vector<std::uint8_t>& moved_flags,
                         const std::vector<std::uint8_t>* at_rest,
                         std::vector<double>* tol) const;
  // Narrow phase of one pair: appends a warning when closer than the sum of the tolerances (or
  // touching); returns the distance.
  static double TestPair(PrimitiveId a, PrimitiveId b, const std::vector<Shape>& shapes,
                         const std::vector<double>& tol, std::vector<Warning>* warnings);
  // The warning of pair (a, b) at distance result `d` (at the sample: between_samples false).
  static Warning MakeWarning(PrimitiveId a, PrimitiveId b, const DistanceResult& d,
                             double threshold_m);

  // --- the index (monitor_scene.cpp) ----------------------------------------------------------
  bool IsActiveVariant(PrimitiveId id) const {
    const int link = model.workcell->primitives[id].link_index;
    return link < 0 || model.variant_index[id] == active_variant[link];
  }
  bool ShouldBeInBroadPhase(PrimitiveId id) const {
    return is_present[id] && IsActiveVariant(id) && (is_moving[id] || is_reachable[id]);
  }
  // What the index grows a primitive's box by: its largest tolerance, plus the slack when it
  // moves.
  double IndexTolerance(PrimitiveId id) const {
    return model.BroadTolerance_m(tol_base[id], is_moving[id]) +
           (is_moving[id] ? model.options.index_slack_m : 0.0);
  }
  void AddToBroadPhase(PrimitiveId id);
  void RemoveFromBroadPhase(PrimitiveId id);
  // After SetCarrierBounds calls: the motion bounds' undominated sets found now, in the scene
  // change, rather than in the next cycle, and the links the kinematics computes (fk_links).
  void PrepareBounds() {
    motion.PrepareLargestBound();
    swept.step.PrepareLargestBound();
    std::fill(fk_targets.begin(), fk_targets.end(), std::uint8_t{0});
    for (const PrimitiveId id : carried) fk_targets[carrier[id]] = 1;
    model.kinematics->MovingLinksTo(&fk_targets, &fk_links);
    fk_scratch.resize(fk_links.size());  // within its reserve
    // The links new to fk_links at q_kinematics too (Attach's LinkPose has computed them; the
    // kinematics then recomputes only the links a joint's change moves).
    model.kinematics->ComputeLinkPoses(q_kinematics, &X_WL);
  }
  // X_WL[link] at q_kinematics, computed first when the kinematics skips it (not in fk_links).
  const Eigen::Isometry3d& LinkPose(int link) {
    if (model.kinematics->is_moving(link) &&
        !std::binary_search(fk_links.begin(), fk_links.end(), link)) {
      model.kinematics->ComputeLinkPoses(q_kinematics, &X_WL);
    }
    return X_WL[link];
  }
  // Re-indexes `id` with its current motion and tolerance (Add fixes both).
  void Reindex(PrimitiveId id, bool moving);
  // The motion bounds of primitive `id` for its current carrier, its place in `carried` and its
  // is_sphere_C (after any change of its carrier or shape_C).
  void SetCarrierBounds(PrimitiveId id) {
    motion.SetCarrier(id, carrier[id], is_moving[id], shape_C[id]);
    swept.step.SetCarrier(id, carrier[id], is_moving[id], shape_C[id]);
    const auto it = std::lower_bound(carried.begin(), carried.end(), id);
    const bool is_listed = it != carried.end() && *it == id;
    if (carrier[id] >= 0 && !is_listed) carried.insert(it, id);  // within its reserve
    if (carrier[id] < 0 && is_listed) carried.erase(it);
    const auto* capsule_C = std::get_if<Capsule>(&shape_C[id]);
    is_sphere_C[id] = capsule_C != nullptr && std::memcmp(capsule_C->p0_W.data(),
                                                          capsule_C->p1_W.data(),
                                                          sizeof(double) * 3) == 0;
  }
  // Calls f(id) for every primitive that may have moved since the last kinematics: the carried
  // ones, and after a scene change every live one (SetObjectPose moves free objects). One loop,
  // so that f is inlined once (ReindexMoved's per-primitive pass).
  template <typename F>
  void ForEachMayHaveMoved(F&& f) {
    const std::size_t count = scene_changed ? live_end : carried.size();
    for (std::size_t i = 0; i < count; ++i) {
      f(scene_changed ? static_cast<PrimitiveId>(i) : carried[i]);
    }
  }
  // A static left out as unreachable becomes active for good once `mover` (a frame-bound
  // object) comes within the sum of their indexed tolerances.
  void MarkStaticsNearReachable(PrimitiveId mover);
  bool CompatibleNow(PrimitiveId link_prim, PrimitiveId object_prim, int link, int object) const {
    return model.workcell->compatible.AreCompatible(link_prim, object_prim) ||
           grasp[static_cast<std::size_t>(link) * model.objects.size() + object] ||
           holder[object] == link;
  }
  void RefreshCompatibility(int link, int object);

  // --- live objects (monitor_live_objects.cpp) --------------------------------------------
  // The live data's start state: every slot free (before BuildBroadPhase).
  void InitLiveObjects();
  // Object `name` among the scene file's objects and the live ones in use; -1 if none.
  int FindObject(const std::string& name) const;
  // What primitive() shows: the workcell's spec, or the live object's for a slot.
  const PrimitiveSpec& Spec(PrimitiveId id) const {
    return model.is_live(id) ? live.spec[id - model.first_live_primitive]
                             : model.workcell->primitives[id];
  }
  bool IsAttachable(int object) const {
    const int slot = model.LiveSlot(object);
    return slot >= 0 ? live.is_attachable[slot] != 0 : model.objects[object].is_attachable;
  }
  // Every static becomes reachable for good (indexed): a held live object was not part of the
  // start-up reach envelope (MonitorModel::ComputeReachSpheres).
  void MarkAllStaticsReachable();
  // Whether link `link` may hold object `object` where it is (else why, for Attach's error): a
  // scene object within the link's hold radius (the start-up reach envelope counts on it), a
  // live one within kAttachMaxGap_m of the geometry of the link and the links it carries (of its
  // origin if none has any).
  bool IsWithinHoldReach(int object, int link, std::string* why);
  // Whether `name` names a link, an object or a primitive (scene file or live) already.
  bool IsNameTaken(const std::string& name) const;
  // Slot use, presence flags and the objects' own compatible pairs agree.
  void ValidateLiveObjects(std::ostringstream* msg) const;

  // --- validation (monitor_check.cpp) ---------------------------------------------------------
  // Shapes follow their carriers, index membership, tolerances, holders.
  void ValidatePrimitives(std::ostringstream* msg) const;
  // The compatibility matrix against the attach / grasp state.
  void ValidateCompatibility(std::ostringstream* msg) const;
  // The index slack: displacements, the kept pair set against the indexed boxes by brute force,
  // and the pairs' bounds.
  void ValidateSlack(std::ostringstream* msg) const;
  // After a bounded cycle: its motion bounds and its claims (every primitive within its slack,
  // every kept pair clear) against the true shapes at q_good.
  void ValidateBoundedCycle(std::ostringstream* msg) const;
};

/// Writes `message` into `error` when given.
inline void SetError(std::string* error, const std::string& message) {
  if (error != nullptr) *error = message;
}

}  // namespace arm_collision_monitor
