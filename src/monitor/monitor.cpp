// The per-cycle Monitor: the seed's update loop (Shaffer & Herb, TR 90-28, section 3: joint
// angles -> kinematics -> index update of the moved primitives -> intersection tests of the
// tolerance-grown primitives), with its section 6 extensions (model switching, grasped objects,
// speed-dependent tolerance) done without allocation in the cycle.
#include "arm_collision_monitor/monitor/monitor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <utility>

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/monitor/motion_bounds.h"
#include "arm_collision_monitor/monitor/pair_cache.h"

namespace arm_collision_monitor {
namespace {

/// Bit-identical poses: a link whose pose did not change bit for bit has not moved.
bool IsSamePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::memcmp(a.matrix().data(), b.matrix().data(), sizeof(double) * 16) == 0;
}

// An idle or refused cycle does no work.
void ClearCycleWork(CycleReport* report) {
  report->moved_primitives = 0;
  report->reindexed_primitives = 0;
  report->candidate_pairs = 0;
  report->narrow_phase_tests = 0;
  report->bounded = false;
  report->counters = BroadPhaseCounters{};
}

void SetError(std::string* error, const std::string& message) {
  if (error != nullptr) *error = message;
}

}  // namespace

struct Monitor::Impl {
  // --- model: fixed after construction -------------------------------------------------
  std::shared_ptr<const Workcell> workcell;
  MonitorOptions options;
  const KinematicModel* model = nullptr;
  std::uint32_t n = 0;                  // primitive count
  Eigen::VectorXd q_lower, q_upper;     // joint limits by q index, margin included
  std::vector<std::vector<PrimitiveId>> link_prims;  // every variant's primitives per link
  std::vector<std::vector<std::string>> link_variants;  // [0] is always ""
  std::vector<int> variant_index;       // per primitive, into link_variants of its link; 0 for objects
  struct Object {
    std::vector<PrimitiveId> prims;
    Eigen::Isometry3d X_OW_start;  // inverse of the start pose: shape_L = X_WO_start * shape_O
    bool is_attachable = false;
    bool is_frame_bound = false;   // moved by SetObjectPose
  };
  std::vector<Object> objects;     // parallel to Workcell::objects
  std::vector<int> object_of;           // per primitive, -1 for link primitives
  std::vector<double> tol_base;         // per primitive, m
  std::vector<double> hold_radius_m;    // per link: farthest a held object may reach from its origin
  double speed_tol_gain_s = 0.0;        // reaction + stopping time when speed-scaled, else 0

  // --- live state --------------------------------------------------------------------------
  std::unique_ptr<BroadPhase> broad_phase;
  CompatibilityMatrix compatible;
  std::vector<std::uint8_t> grasp;      // link_count x object_count: is a grasp target
  std::vector<int> holder;              // per object: holding link, -1 if none
  std::vector<int> active_variant;      // per link
  std::vector<Shape> shape_C;           // per primitive: in its carrier link's frame (attached or link)
  std::vector<int> carrier;             // per primitive: link it moves with, -1 for none
  std::vector<Shape> shape_W;
  std::vector<Shape> shape_prev_W;      // at the last good cycle (speed-scaled tolerance only)
  std::vector<std::uint8_t> is_moving;  // Motion it is indexed with
  std::vector<std::uint8_t> is_reachable;  // false: static no moving primitive can reach
  std::vector<std::uint8_t> in_broad_phase;
  std::vector<std::uint8_t> moved;      // pose changed since the last good cycle
  std::vector<double> tol_now;          // per primitive this cycle, m
  std::vector<Eigen::Isometry3d> X_WL, X_WL_next;
  std::vector<std::uint8_t> link_changed;
  Eigen::VectorXd q_good;
  bool has_good = false;
  bool scene_changed = true;
  // Index slack (MonitorOptions::index_slack_m): the indexed copies and the kept pairs.
  PairCache cache;
  // Bounded cycles (see TryBoundedCycle): joint-space bounds on each primitive's motion.
  MotionBounds motion;
  Eigen::VectorXd q_kinematics;         // q of the last forward kinematics
  bool kinematics_behind = false;       // bounded cycles since: shape_W is at q_kinematics
  double world_edge_m = 0.0;
  CycleReport report;
  BroadPhaseCounters total;
  std::uint64_t refused = 0;

  Impl(std::shared_ptr<const Workcell> wc, const MonitorOptions& opts);
  void ValidateOptions() const;
  void BuildModel();
  void ComputeReachability();
  // A static left out as unreachable becomes active for good once `mover` (a frame-bound
  // object) comes within the sum of their indexed tolerances.
  void MarkStaticsNearReachable(PrimitiveId mover);
  void BuildBroadPhase();

  bool IsActiveVariant(PrimitiveId id) const {
    const int link = workcell->primitives[id].link_index;
    return link < 0 || variant_index[id] == active_variant[link];
  }
  bool ShouldBeInBroadPhase(PrimitiveId id) const {
    return IsActiveVariant(id) && (is_moving[id] || is_reachable[id]);
  }
  double BroadTolerance(PrimitiveId id, bool moving) const {
    return tol_base[id] + (moving ? options.max_speed_mps * speed_tol_gain_s : 0.0);
  }
  // What the index grows a primitive's box by: its largest tolerance, plus the slack when it
  // moves.
  double IndexTolerance(PrimitiveId id) const {
    return BroadTolerance(id, is_moving[id]) + (is_moving[id] ? options.index_slack_m : 0.0);
  }
  void AddToBroadPhase(PrimitiveId id) {
    broad_phase->Add(id, ComputeAabb(shape_W[id]), IndexTolerance(id),
                     is_moving[id] ? Motion::kMoving : Motion::kStatic);
    in_broad_phase[id] = 1;
    cache.SetIndexed(id, shape_W[id]);
  }
  void RemoveFromBroadPhase(PrimitiveId id) {
    broad_phase->Remove(id);
    in_broad_phase[id] = 0;
    cache.MarkStale();
  }
  // Re-indexes `id` with its current motion and tolerance (Add fixes both).
  void Reindex(PrimitiveId id, bool moving) {
    const bool was_in = in_broad_phase[id];
    if (was_in) RemoveFromBroadPhase(id);
    is_moving[id] = moving;
    if (was_in || ShouldBeInBroadPhase(id)) AddToBroadPhase(id);
  }
  bool CompatibleNow(PrimitiveId link_prim, PrimitiveId object_prim, int link, int object) const {
    return workcell->compatible.AreCompatible(link_prim, object_prim) ||
           grasp[static_cast<std::size_t>(link) * objects.size() + object] ||
           holder[object] == link;
  }
  void RefreshCompatibility(int link, int object) {
    cache.MarkStale();
    for (const PrimitiveId l : link_prims[link]) {
      for (const PrimitiveId o : objects[object].prims) {
        compatible.Set(l, o, CompatibleNow(l, o, link, object));
      }
    }
  }

  InputStatus CheckInput(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  bool IsIdle(const Eigen::Ref<const Eigen::VectorXd>& q) const {
    return has_good && !scene_changed && report.input == InputStatus::kOk &&
           q.size() == q_good.size() &&
           std::memcmp(q.data(), q_good.data(), sizeof(double) * q.size()) == 0;
  }
  // Writes into `shapes` the primitives carried by links whose pose differs between the live X_WL
  // and `X_WL_new`, and flags them in `moved_flags`; `changed` is per-link scratch.
  void MoveCarried(const std::vector<Eigen::Isometry3d>& X_WL_new,
                   std::vector<std::uint8_t>* changed, std::vector<Shape>* shapes,
                   std::vector<std::uint8_t>* moved_flags) const;
  // This cycle's tolerance of every primitive (speed-scaled for the moving ones when enabled).
  void ComputeTolerances(const std::vector<Shape>& shapes,
                         const std::vector<std::uint8_t>& moved_flags,
                         std::vector<double>* tol) const;
  // Narrow phase of one pair: appends a warning when closer than the sum of the tolerances (or
  // touching); returns the distance.
  static double TestPair(PrimitiveId a, PrimitiveId b, const std::vector<Shape>& shapes,
                         const std::vector<double>& tol, std::vector<Warning>* warnings);
  // Moves in the index the moved primitives that left their slack; counts the moved ones.
  std::uint32_t ReindexMoved();
  // The narrow phase over the kept pairs, skipping the pairs whose lower bound clears them.
  void TestCandidatePairs();
  // The motion bounds of primitive `id` for its current carrier.
  void ComputeLevers(PrimitiveId id) { motion.SetCarrier(id, carrier[id], is_moving[id], shape_C[id]); }
  // Forward kinematics at q, the moved primitives re-indexed, the kept pairs brought up to
  // date: the model then follows q. Returns the number of primitives that moved.
  std::uint32_t FollowKinematics(const Eigen::Ref<const Eigen::VectorXd>& q);
  // A cycle without kinematics: true (and the report written) when every moving primitive's
  // joint-space motion bound keeps it within its slack and every kept pair's lower bound, less
  // those bounds, still clears its threshold -- then no pair can warn. False: nothing changed.
  bool TryBoundedCycle(const Eigen::Ref<const Eigen::VectorXd>& q);
  // After bounded cycles: the kinematics (shapes, index, kept pairs) brought to q_good, for
  // SyncShapes and the scene changes that read or re-express shapes.
  void SyncKinematics() {
    if (kinematics_behind) FollowKinematics(q_good);
  }
  void RunCycle(const Eigen::Ref<const Eigen::VectorXd>& q);
  // Monitor::Validate's part for the index slack: displacements, the kept pair set against the
  // indexed boxes by brute force, and the pairs' lower bounds.
  void ValidateSlack(std::ostringstream* msg) const;
  // After a bounded cycle: its motion bounds and its claims (every primitive within its slack,
  // every kept pair clear) against the true shapes at q_good.
  void ValidateBoundedCycle(std::ostringstream* msg) const;
};

Monitor::Impl::Impl(std::shared_ptr<const Workcell> wc, const MonitorOptions& opts)
    : workcell(std::move(wc)), options(opts) {
  if (!workcell) throw LoadError("monitor: no workcell given");
  model = &workcell->kinematics;
  n = static_cast<std::uint32_t>(workcell->primitives.size());
  options.broad_phase.world_W = workcell->world_W;
  options.broad_phase.min_cell_size_m = MinCellSize_m(options);
  options.broad_phase.reserve_primitives = std::max(options.broad_phase.reserve_primitives, n);
  world_edge_m = (workcell->world_W.max_W - workcell->world_W.min_W).maxCoeff();
  speed_tol_gain_s =
      options.speed_scaled_tolerance ? options.reaction_time_s + options.stopping_time_s : 0.0;
  ValidateOptions();
  BuildModel();
  ComputeReachability();
  BuildBroadPhase();
}

void Monitor::Impl::ValidateOptions() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!positive(options.max_speed_mps)) {
    throw LoadError("monitor options: max_speed_mps must be a positive number");
  }
  if (!positive(options.cycle_period_s)) {
    throw LoadError("monitor options: cycle_period_s must be a positive number");
  }
  if (!non_negative(options.reaction_time_s) || !non_negative(options.stopping_time_s)) {
    throw LoadError("monitor options: reaction_time_s and stopping_time_s must be >= 0");
  }
  if (!non_negative(options.index_slack_m)) {
    throw LoadError("monitor options: index_slack_m must be >= 0");
  }
  if (options.broad_phase.max_objects_per_leaf < 1) {
    throw LoadError("monitor options: broad_phase max_objects_per_leaf must be >= 1");
  }
  const Aabb& world = options.broad_phase.world_W;
  if (!world.min_W.allFinite() || !world.max_W.allFinite() ||
      !(world.min_W.array() < world.max_W.array()).all()) {
    throw LoadError(workcell->scene_path + ": world box must have min < max on every axis");
  }
  if (static_cast<int>(workcell->joint_names.size()) != model->q_size()) {
    throw LoadError(workcell->urdf_path + ": " + std::to_string(workcell->joint_names.size()) +
                    " joint names for " + std::to_string(model->q_size()) + " actuated joints");
  }
  if (workcell->compatible.size() != n) {
    throw LoadError(workcell->scene_path + ": compatibility matrix size " +
                    std::to_string(workcell->compatible.size()) + " for " + std::to_string(n) +
                    " primitives");
  }
}

void Monitor::Impl::BuildModel() {
  const int link_count = model->link_count();
  q_lower = Eigen::VectorXd::Constant(model->q_size(), -std::numeric_limits<double>::infinity());
  q_upper = Eigen::VectorXd::Constant(model->q_size(), std::numeric_limits<double>::infinity());
  for (int link = 1; link < link_count; ++link) {
    const JointSpec& joint = model->joint(link);
    if (joint.q_index < 0 || joint.type == JointType::kContinuous) continue;
    q_lower[joint.q_index] = joint.lower - kJointLimitMargin;
    q_upper[joint.q_index] = joint.upper + kJointLimitMargin;
  }

  link_prims.assign(link_count, {});
  link_variants.assign(link_count, std::vector<std::string>{""});
  variant_index.assign(n, 0);
  object_of.assign(n, -1);
  tol_base.resize(n);
  carrier.assign(n, -1);
  shape_C.resize(n);
  is_moving.assign(n, 0);
  for (PrimitiveId id = 0; id < n; ++id) {
    const PrimitiveSpec& spec = workcell->primitives[id];
    tol_base[id] = spec.tolerance_m;
    shape_C[id] = spec.shape_L;
    if (spec.link_index >= 0) {
      if (spec.link_index >= link_count) {
        throw LoadError(workcell->scene_path + ": primitive '" + spec.name +
                        "' has link index " + std::to_string(spec.link_index) + " of " +
                        std::to_string(link_count) + " links");
      }
      link_prims[spec.link_index].push_back(id);
      auto& variants = link_variants[spec.link_index];
      const auto it = std::find(variants.begin(), variants.end(), spec.variant);
      variant_index[id] = static_cast<int>(it - variants.begin());
      if (it == variants.end()) variants.push_back(spec.variant);
      carrier[id] = spec.link_index;
      is_moving[id] = spec.is_static ? 0 : 1;  // links with only fixed joints above never move
    } else {
      const int o = spec.object_index;
      if (o < 0 || o >= static_cast<int>(workcell->objects.size())) {
        throw LoadError(workcell->scene_path + ": primitive '" + spec.name +
                        "' has neither a link nor an object");
      }
      object_of[id] = o;
    }
  }
  objects.resize(workcell->objects.size());
  for (std::size_t o = 0; o < objects.size(); ++o) {
    const ObjectSpec& spec = workcell->objects[o];
    objects[o].X_OW_start = spec.X_WO_start.inverse(Eigen::Isometry);
    objects[o].is_attachable = spec.is_attachable;
    objects[o].is_frame_bound = !spec.frame.empty();
    for (PrimitiveId id = 0; id < n; ++id) {
      if (object_of[id] == static_cast<int>(o)) objects[o].prims.push_back(id);
    }
    // Resting objects are static (never tested against other statics) until held; only the
    // frame-bound ones move on their own.
    for (const PrimitiveId id : objects[o].prims) is_moving[id] = objects[o].is_frame_bound;
  }
  active_variant.assign(link_count, 0);
  grasp.assign(static_cast<std::size_t>(link_count) * objects.size(), 0);
  holder.assign(objects.size(), -1);
  compatible = workcell->compatible;

  // Start-up pose: every joint at 0 clamped into its limits; the first good Update moves all.
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(model->q_size());
  for (int i = 0; i < q0.size(); ++i) {
    q0[i] = std::min(std::max(0.0, q_lower[i] + kJointLimitMargin), q_upper[i] - kJointLimitMargin);
    if (!std::isfinite(q0[i])) q0[i] = 0.0;
  }
  X_WL.assign(link_count, Eigen::Isometry3d::Identity());
  link_changed.assign(link_count, 0);
  model->ComputeLinkPoses(q0, &X_WL);
  X_WL_next = X_WL;  // the links fixed to the root keep these poses (ComputeMovingLinkPoses)
  q_good = q0;
  shape_W.resize(n);
  for (PrimitiveId id = 0; id < n; ++id) {
    shape_W[id] = carrier[id] >= 0 ? TransformShape(X_WL[carrier[id]], shape_C[id]) : shape_C[id];
  }
  shape_prev_W = shape_W;
  q_kinematics = q0;
  motion = MotionBounds(*model, n);
  for (PrimitiveId id = 0; id < n; ++id) ComputeLevers(id);
  moved.assign(n, 0);
  tol_now = tol_base;
}

// Reach envelope (the seed's observation that stationary objects only cost time when they share
// cells with moving ones, taken to the limit): a link L's points stay within a sphere centred on
// the origin of the first moving joint above it, of radius (sum of the joint offsets between
// that joint and L, plus prismatic travel) + (farthest point of L's geometry, or of an object it
// may hold, from L's origin) -- the triangle inequality over the chain, valid for every q.
// Frame-bound objects reach what is near their current pose (SetObjectPose re-checks).
void Monitor::Impl::ComputeReachability() {
  const int link_count = model->link_count();
  double max_attach_diameter_m = 0.0;
  bool has_attachable = false;
  double max_moving_tol_m = 0.0;
  for (PrimitiveId id = 0; id < n; ++id) {
    const int o = object_of[id];
    if (is_moving[id] || (o >= 0 && objects[o].is_attachable)) {
      max_moving_tol_m = std::max(max_moving_tol_m, BroadTolerance(id, true));
    }
  }
  for (const Object& object : objects) {
    if (!object.is_attachable) continue;
    has_attachable = true;
    Aabb box = ComputeAabb(workcell->primitives[object.prims.front()].shape_L);
    for (const PrimitiveId id : object.prims) {
      const Aabb b = ComputeAabb(workcell->primitives[id].shape_L);
      box.min_W = box.min_W.cwiseMin(b.min_W);
      box.max_W = box.max_W.cwiseMax(b.max_W);
    }
    // The AABB diagonal bounds the object's diameter (which a rigid motion keeps).
    max_attach_diameter_m = std::max(max_attach_diameter_m, (box.max_W - box.min_W).norm());
  }

  // Per link: world centre of its reach sphere and the chain length from that centre.
  std::vector<Eigen::Vector3d> centre_W(link_count, Eigen::Vector3d::Zero());
  std::vector<double> chain_m(link_count, 0.0);
  std::vector<std::uint8_t> is_below_joint(link_count, 0);  // a non-fixed joint above it
  for (int link = 1; link < link_count; ++link) {
    const int parent = model->parent_link(link);
    const JointSpec& joint = model->joint(link);
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
  // Only links below a moving joint may hold objects (holding with a fixed link would make a
  // static object "moving" for nothing); hold_radius_m < 0 marks the others.
  hold_radius_m.assign(link_count, -1.0);
  std::vector<double> reach_m(link_count, -1.0);  // < 0: reaches nothing
  for (int link = 0; link < link_count; ++link) {
    if (!is_below_joint[link]) continue;
    double extent_m = 0.0;
    for (const PrimitiveId id : link_prims[link]) {
      extent_m = std::max(extent_m, MaxDistanceFromPoint_m(shape_C[id], Eigen::Vector3d::Zero()));
    }
    hold_radius_m[link] = extent_m + kAttachMaxGap_m + max_attach_diameter_m;
    if (has_attachable) {
      reach_m[link] = chain_m[link] + hold_radius_m[link];
    } else if (!link_prims[link].empty()) {
      reach_m[link] = chain_m[link] + extent_m;
    }
  }

  is_reachable.assign(n, 1);
  for (PrimitiveId id = 0; id < n; ++id) {
    if (is_moving[id] || (object_of[id] >= 0 && objects[object_of[id]].is_attachable)) continue;
    bool reachable = false;
    for (int link = 0; link < link_count && !reachable; ++link) {
      if (reach_m[link] < 0.0) continue;
      if (!std::isfinite(reach_m[link])) {
        reachable = true;
        break;
      }
      const Capsule sphere{centre_W[link], centre_W[link], reach_m[link]};
      // <=, as the broad phase's closed boxes: touching counts.
      reachable = ShapeDistance(sphere, shape_W[id]).distance_m <=
                  tol_base[id] + max_moving_tol_m;
    }
    is_reachable[id] = reachable ? 1 : 0;
  }
  for (const Object& object : objects) {
    if (!object.is_frame_bound) continue;
    for (const PrimitiveId id : object.prims) MarkStaticsNearReachable(id);
  }
}

void Monitor::Impl::MarkStaticsNearReachable(PrimitiveId mover) {
  for (PrimitiveId id = 0; id < n; ++id) {
    if (is_moving[id] || is_reachable[id]) continue;
    if (ShapeDistance(shape_W[mover], shape_W[id]).distance_m <=
        tol_base[id] + BroadTolerance(mover, true)) {
      is_reachable[id] = 1;
      if (broad_phase && ShouldBeInBroadPhase(id)) AddToBroadPhase(id);
    }
  }
}

void Monitor::Impl::BuildBroadPhase() {
  in_broad_phase.assign(n, 0);
  std::uint32_t active = 0;
  for (PrimitiveId id = 0; id < n; ++id) active += ShouldBeInBroadPhase(id) ? 1 : 0;
  if (options.auto_broad_phase) {
    options.broad_phase.method =
        active >= kAutoOctreeMinPrimitives ? BroadPhaseMethod::kOctree : BroadPhaseMethod::kNaive;
  }
  broad_phase = MakeBroadPhase(options.broad_phase);
  cache = PairCache(n, options.index_slack_m, world_edge_m);
  for (PrimitiveId id = 0; id < n; ++id) {
    if (ShouldBeInBroadPhase(id)) AddToBroadPhase(id);
  }
  const std::size_t max_pairs = static_cast<std::size_t>(n) * (n > 0 ? n - 1 : 0) / 2;
  report.warnings.reserve(max_pairs);
  report.stop = true;  // nothing is known before the first good input
  total = BroadPhaseCounters{};
  broad_phase->ResetCounters();
}

InputStatus Monitor::Impl::CheckInput(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  if (q.size() != q_lower.size()) return InputStatus::kWrongSize;
  if (!q.allFinite()) return InputStatus::kNonFinite;
  if ((q.array() < q_lower.array()).any() || (q.array() > q_upper.array()).any()) {
    return InputStatus::kOutOfLimits;
  }
  return InputStatus::kOk;
}

void Monitor::Impl::MoveCarried(const std::vector<Eigen::Isometry3d>& X_WL_new,
                                std::vector<std::uint8_t>* changed, std::vector<Shape>* shapes,
                                std::vector<std::uint8_t>* moved_flags) const {
  for (std::size_t link = 0; link < X_WL_new.size(); ++link) {
    (*changed)[link] = IsSamePose(X_WL_new[link], X_WL[link]) ? 0 : 1;
  }
  for (PrimitiveId id = 0; id < n; ++id) {
    const int link = carrier[id];
    if (link < 0 || !(*changed)[link]) continue;
    (*shapes)[id] = TransformShape(X_WL_new[link], shape_C[id]);
    (*moved_flags)[id] = 1;
  }
}

void Monitor::Impl::ComputeTolerances(const std::vector<Shape>& shapes,
                                      const std::vector<std::uint8_t>& moved_flags,
                                      std::vector<double>* tol) const {
  if (speed_tol_gain_s == 0.0) {
    std::copy(tol_base.begin(), tol_base.end(), tol->begin());
    return;
  }
  // ISO/TS 15066 protective separation: speed x (reaction + stopping time) added per primitive.
  // Speeds are clamped to max_speed_mps so the broad phase, inflated for that speed, stays
  // conservative; before the first good cycle the speed is unknown and taken as the maximum.
  for (PrimitiveId id = 0; id < n; ++id) {
    double speed_mps = 0.0;
    if (!is_moving[id]) {
      speed_mps = 0.0;
    } else if (!has_good) {
      speed_mps = options.max_speed_mps;
    } else if (moved_flags[id]) {
      speed_mps = std::min(MaxPointDisplacement_m(shape_prev_W[id], shapes[id]) /
                               options.cycle_period_s,
                           options.max_speed_mps);
    }
    (*tol)[id] = tol_base[id] + speed_mps * speed_tol_gain_s;
  }
}

double Monitor::Impl::TestPair(PrimitiveId a, PrimitiveId b, const std::vector<Shape>& shapes,
                               const std::vector<double>& tol, std::vector<Warning>* warnings) {
  const double threshold_m = tol[a] + tol[b];
  const DistanceResult d = ShapeDistance(shapes[a], shapes[b]);
  // Overlap is a negative signed distance, closer than any threshold: two parts without a
  // tolerance zone (threshold 0) still warn when they touch or overlap.
  if (d.distance_m < threshold_m || d.distance_m <= 0.0) {
    Warning w;
    w.a = a;
    w.b = b;
    w.distance_m = d.distance_m;
    w.threshold_m = threshold_m;
    w.p_WA = d.p_WA;
    w.p_WB = d.p_WB;
    warnings->push_back(w);
  }
  return d.distance_m;
}

std::uint32_t Monitor::Impl::FollowKinematics(const Eigen::Ref<const Eigen::VectorXd>& q) {
  model->ComputeMovingLinkPoses(q, &X_WL_next);
  MoveCarried(X_WL_next, &link_changed, &shape_W, &moved);
  X_WL.swap(X_WL_next);
  q_kinematics = q;
  kinematics_behind = false;
  const std::uint32_t moved_count = ReindexMoved();
  // Fixed tolerances: tol_now already equals tol_base (Attach / Detach keep both).
  if (speed_tol_gain_s != 0.0) ComputeTolerances(shape_W, moved, &tol_now);
  const bool keeps_previous = speed_tol_gain_s != 0.0;  // only speed estimates read it
  for (PrimitiveId id = 0; id < n; ++id) {
    if (moved[id]) {
      if (keeps_previous) shape_prev_W[id] = shape_W[id];
      moved[id] = 0;
    }
  }
  cache.Update(broad_phase.get(), compatible);
  return moved_count;
}

bool Monitor::Impl::TryBoundedCycle(const Eigen::Ref<const Eigen::VectorXd>& q) {
  // Speed-scaled tolerances need the motion itself; a scene change re-plans the pairs.
  if (!has_good || scene_changed || cache.is_stale() || speed_tol_gain_s != 0.0 ||
      report.input != InputStatus::kOk) {
    return false;
  }
  motion.SetJointMotion(q, q_kinematics);
  const double slack_m = options.index_slack_m;
  for (PrimitiveId id = 0; id < n; ++id) {
    if (motion.lever_count(id) == 0) continue;
    const double bound_m = motion.ComputeBound_m(id);
    // Motion since indexed <= motion until the kinematics + motion since; NaN fails.
    if (in_broad_phase[id] && !(cache.displacement_m(id) + bound_m <= slack_m)) return false;
  }
  for (const KeptPair& kept : cache.pairs()) {
    const PrimitiveId a = kept.pair.a;
    const PrimitiveId b = kept.pair.b;
    // NaN (no bound) is not clear.
    if (!cache.IsClear(kept.kinematics_bound_m, motion.PairBound_m(a, b), tol_now[a] + tol_now[b])) {
      return false;
    }
  }
  // Every kept pair is clear, and every other pair's indexed boxes are apart while both
  // primitives stay within their slack: no warning.
  q_good = q;
  report.input = InputStatus::kOk;
  report.warnings.clear();
  report.stop = false;
  ClearCycleWork(&report);
  report.candidate_pairs = static_cast<std::uint32_t>(cache.pairs().size());
  report.bounded = true;
  kinematics_behind = true;
  return true;
}

std::uint32_t Monitor::Impl::ReindexMoved() {
  std::uint32_t moved_count = 0;
  cache.BeginReindex();
  for (PrimitiveId id = 0; id < n; ++id) {
    if (!moved[id] || !in_broad_phase[id]) continue;
    ++moved_count;
    if (cache.FollowMoved(id, shape_W[id])) broad_phase->Move(id, ComputeAabb(shape_W[id]));
  }
  return moved_count;
}

void Monitor::Impl::TestCandidatePairs() {
  report.warnings.clear();
  report.narrow_phase_tests = cache.TestPairs(tol_now, [this](PrimitiveId a, PrimitiveId b) {
    return TestPair(a, b, shape_W, tol_now, &report.warnings);
  });
}

void Monitor::Impl::RunCycle(const Eigen::Ref<const Eigen::VectorXd>& q) {
  // Work done by scene changes since the last cycle belongs to the run, not to this cycle.
  total += broad_phase->counters();
  broad_phase->ResetCounters();
  if (TryBoundedCycle(q)) return;

  const std::uint32_t moved_count = FollowKinematics(q);
  q_good = q;
  TestCandidatePairs();

  report.input = InputStatus::kOk;
  report.stop = !report.warnings.empty();
  report.moved_primitives = moved_count;
  report.reindexed_primitives = static_cast<std::uint32_t>(cache.reindexed().size());
  report.candidate_pairs = static_cast<std::uint32_t>(cache.pairs().size());
  report.bounded = false;
  report.counters = broad_phase->counters();
  total += report.counters;
  broad_phase->ResetCounters();
  has_good = true;
  scene_changed = false;
}

void Monitor::Impl::ValidateBoundedCycle(std::ostringstream* msg) const {
  std::vector<Eigen::Isometry3d> X(model->link_count());
  model->ComputeLinkPoses(q_good, &X);
  std::vector<Shape> now(shape_W);
  for (PrimitiveId id = 0; id < n; ++id) {
    if (carrier[id] < 0) continue;
    now[id] = TransformShape(X[carrier[id]], shape_C[id]);
    if (motion.lever_count(id) == 0 || !in_broad_phase[id]) continue;
    const double moved_m = MaxPointDisplacement_m(shape_W[id], now[id]);
    const double bound_m = motion.bound_m(id);
    const double from_ref_m = MaxPointDisplacement_m(cache.indexed_shape_W(id), now[id]);
    if (moved_m > bound_m + cache.BoundMargin_m(bound_m) ||
        from_ref_m > options.index_slack_m + cache.BoundMargin_m(options.index_slack_m)) {
      *msg << "bounded cycle: primitive " << id << " moved " << moved_m << " m, bound "
           << bound_m << " m; " << from_ref_m << " m from its indexed copy, slack "
           << options.index_slack_m << " m";
      return;
    }
  }
  for (const KeptPair& kept : cache.pairs()) {
    const PrimitiveId a = kept.pair.a;
    const PrimitiveId b = kept.pair.b;
    const double then_m = ShapeDistance(shape_W[a], shape_W[b]).distance_m;
    const double now_m = ShapeDistance(now[a], now[b]).distance_m;
    const double motion_m = motion.PairBound_m(a, b);
    if (now_m < then_m - motion_m - cache.BoundMargin_m(then_m) || now_m <= tol_now[a] + tol_now[b]) {
      *msg << "bounded cycle: pair (" << a << "," << b << ") at " << now_m << " m, was "
           << then_m << " m, relative motion bound " << motion_m << " m, threshold "
           << tol_now[a] + tol_now[b] << " m";
      return;
    }
  }
}

void Monitor::Impl::ValidateSlack(std::ostringstream* msg) const {
  std::string why;
  for (PrimitiveId id = 0; id < n; ++id) {
    if (!in_broad_phase[id] || moved[id]) continue;
    if (!cache.ValidatePrimitive(id, shape_W[id], &why)) {
      *msg << why;
      return;
    }
  }
  if (cache.is_stale()) return;  // a scene change since the last cycle: rebuilt in the next one
  // The pairs whose indexed boxes overlap, by brute force.
  std::vector<CandidatePair> expected;
  for (PrimitiveId a = 0; a < n; ++a) {
    if (!in_broad_phase[a]) continue;
    const Aabb box_a = ComputeAabb(cache.indexed_shape_W(a)).Inflated(IndexTolerance(a));
    for (PrimitiveId b = a + 1; b < n; ++b) {
      if (!in_broad_phase[b] || (!is_moving[a] && !is_moving[b]) ||
          compatible.AreCompatible(a, b)) {
        continue;
      }
      if (box_a.Overlaps(ComputeAabb(cache.indexed_shape_W(b)).Inflated(IndexTolerance(b)))) {
        expected.push_back({a, b});
      }
    }
  }
  // shape_W is at q_kinematics (also after bounded cycles).
  if (!cache.ValidatePairs(expected, shape_W, &why)) *msg << why;
}

// --- Monitor ------------------------------------------------------------------------------

Monitor::Monitor(std::shared_ptr<const Workcell> workcell, const MonitorOptions& options)
    : impl_(std::make_unique<Impl>(std::move(workcell), options)) {}

Monitor::~Monitor() = default;

const Workcell& Monitor::workcell() const { return *impl_->workcell; }
const MonitorOptions& Monitor::options() const { return impl_->options; }

const CycleReport& Monitor::Update(const Eigen::Ref<const Eigen::VectorXd>& q) {
  Impl& m = *impl_;
  CycleReport& report = m.report;
  ++report.cycle;
  // Idle cycle: same input bit for bit and an unchanged scene give the same report.
  if (m.IsIdle(q)) {
    ClearCycleWork(&report);
    return report;
  }
  const InputStatus status = m.CheckInput(q);
  if (status != InputStatus::kOk) {
    // Fail safe: keep the last good model (and its warnings), request a stop.
    ++m.refused;
    report.input = status;
    report.stop = true;
    ClearCycleWork(&report);
    return report;
  }
  m.RunCycle(q);
  return report;
}

const CycleReport& Monitor::report() const { return impl_->report; }

CycleReport Monitor::Check(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  const Impl& m = *impl_;
  CycleReport r;
  r.cycle = m.report.cycle + 1;
  if (m.IsIdle(q)) {
    r = m.report;
    r.cycle = m.report.cycle + 1;
    ClearCycleWork(&r);
    return r;
  }
  r.input = m.CheckInput(q);
  if (r.input != InputStatus::kOk) {
    r.warnings = m.report.warnings;
    r.stop = true;
    return r;
  }
  // No sync (const): the shapes and X_WL are both at q_kinematics, and the carried shapes are
  // recomputed for q from the links whose pose differs.
  std::vector<Eigen::Isometry3d> X_WL_q(m.X_WL.size());
  m.model->ComputeLinkPoses(q, &X_WL_q);
  std::vector<std::uint8_t> changed(m.X_WL.size(), 0);
  std::vector<Shape> shapes = m.shape_W;
  std::vector<std::uint8_t> moved_flags = m.moved;
  m.MoveCarried(X_WL_q, &changed, &shapes, &moved_flags);
  std::vector<double> tol(m.n);
  m.ComputeTolerances(shapes, moved_flags, &tol);
  // Generate-and-test by brute force over every active, non-compatible, not-both-static pair.
  for (PrimitiveId a = 0; a < m.n; ++a) {
    if (!m.in_broad_phase[a]) continue;
    if (moved_flags[a]) ++r.moved_primitives;
    for (PrimitiveId b = a + 1; b < m.n; ++b) {
      if (!m.in_broad_phase[b] || (!m.is_moving[a] && !m.is_moving[b]) ||
          m.compatible.AreCompatible(a, b)) {
        continue;
      }
      Impl::TestPair(a, b, shapes, tol, &r.warnings);
      ++r.narrow_phase_tests;
    }
  }
  r.stop = !r.warnings.empty();
  return r;
}

bool Monitor::Attach(const std::string& object, const std::string& link, std::string* error) {
  Impl& m = *impl_;
  m.SyncKinematics();
  const int o = m.workcell->FindObject(object);
  if (o < 0) {
    SetError(error, "Attach: unknown object '" + object + "'");
    return false;
  }
  const int l = m.model->FindLink(link);
  if (l < 0) {
    SetError(error, "Attach: unknown link '" + link + "'");
    return false;
  }
  if (!m.has_good) {
    SetError(error, "Attach: no joint state yet, the link's pose is unknown");
    return false;
  }
  if (!m.objects[o].is_attachable) {
    SetError(error, "Attach: object '" + object + "' is not attachable in " +
                        m.workcell->scene_path);
    return false;
  }
  if (m.hold_radius_m[l] < 0.0) {
    SetError(error, "Attach: link '" + link + "' has no moving joint above it");
    return false;
  }
  const Eigen::Isometry3d X_LW = m.X_WL[l].inverse(Eigen::Isometry);
  const Eigen::Vector3d p_WLo = m.X_WL[l].translation();
  for (const PrimitiveId id : m.objects[o].prims) {
    const double reach_m = MaxDistanceFromPoint_m(m.shape_W[id], p_WLo);
    if (reach_m > m.hold_radius_m[l]) {
      std::ostringstream msg;
      msg << "Attach: object '" << object << "' reaches " << reach_m << " m from link '" << link
          << "', more than the " << m.hold_radius_m[l]
          << " m a held object may (link extent + kAttachMaxGap_m + largest object)";
      SetError(error, msg.str());
      return false;
    }
  }
  // A held object moves with the arm, so it gets at least the holder's tolerance zone (the
  // seed's tolerance around each moving object).
  double holder_tol_m = 0.0;
  for (const PrimitiveId id : m.link_prims[l]) holder_tol_m = std::max(holder_tol_m, m.tol_base[id]);
  const int previous = m.holder[o];
  for (const PrimitiveId id : m.objects[o].prims) {
    m.shape_C[id] = TransformShape(X_LW, m.shape_W[id]);
    m.carrier[id] = l;
    m.tol_base[id] = std::max(m.workcell->primitives[id].tolerance_m, holder_tol_m);
    m.tol_now[id] = m.tol_base[id];
    m.Reindex(id, true);
    m.ComputeLevers(id);
  }
  m.holder[o] = l;
  if (previous >= 0 && previous != l) m.RefreshCompatibility(previous, o);
  m.RefreshCompatibility(l, o);
  m.scene_changed = true;
  return true;
}

bool Monitor::Detach(const std::string& object, std::string* error) {
  Impl& m = *impl_;
  m.SyncKinematics();
  const int o = m.workcell->FindObject(object);
  if (o < 0) {
    SetError(error, "Detach: unknown object '" + object + "'");
    return false;
  }
  const int l = m.holder[o];
  if (l < 0) {
    SetError(error, "Detach: object '" + object + "' is not attached");
    return false;
  }
  // It stays where it was let go; a static object rests again (no static-static tests).
  const bool stays_moving = m.objects[o].is_frame_bound;
  for (const PrimitiveId id : m.objects[o].prims) {
    m.carrier[id] = -1;
    m.is_reachable[id] = 1;  // it was let go within its holder's reach
    m.tol_base[id] = m.workcell->primitives[id].tolerance_m;
    m.tol_now[id] = m.tol_base[id];
    m.Reindex(id, stays_moving);
    m.ComputeLevers(id);
  }
  m.holder[o] = -1;
  m.RefreshCompatibility(l, o);
  m.scene_changed = true;
  return true;
}

bool Monitor::SetGraspTarget(const std::string& link, const std::string& object, bool is_target,
                             std::string* error) {
  Impl& m = *impl_;
  // No sync: only the compatibility changes (the pair set is rebuilt by the next cycle).
  const int l = m.model->FindLink(link);
  if (l < 0) {
    SetError(error, "SetGraspTarget: unknown link '" + link + "'");
    return false;
  }
  const int o = m.workcell->FindObject(object);
  if (o < 0) {
    SetError(error, "SetGraspTarget: unknown object '" + object + "'");
    return false;
  }
  const auto& targets = m.workcell->grasp_targets;
  if (std::none_of(targets.begin(), targets.end(), [&](const GraspTargetSpec& t) {
        return t.link_index == l && t.object_index == o;
      })) {
    SetError(error, "SetGraspTarget: '" + object + "' is not a grasp target of link '" + link +
                        "' in " + m.workcell->scene_path);
    return false;
  }
  m.grasp[static_cast<std::size_t>(l) * m.objects.size() + o] = is_target ? 1 : 0;
  m.RefreshCompatibility(l, o);
  m.scene_changed = true;
  return true;
}

bool Monitor::SwitchModel(const std::string& link, const std::string& variant,
                          std::string* error) {
  Impl& m = *impl_;
  m.SyncKinematics();
  const int l = m.model->FindLink(link);
  if (l < 0) {
    SetError(error, "SwitchModel: unknown link '" + link + "'");
    return false;
  }
  const auto& variants = m.link_variants[l];
  const auto it = std::find(variants.begin(), variants.end(), variant);
  if (it == variants.end()) {
    SetError(error, "SwitchModel: link '" + link + "' has no model variant '" + variant + "'");
    return false;
  }
  const int v = static_cast<int>(it - variants.begin());
  if (v == m.active_variant[l]) return true;
  for (const PrimitiveId id : m.link_prims[l]) {
    if (m.in_broad_phase[id]) m.RemoveFromBroadPhase(id);
  }
  m.active_variant[l] = v;
  for (const PrimitiveId id : m.link_prims[l]) {
    if (m.variant_index[id] != v) continue;
    m.shape_W[id] = TransformShape(m.X_WL[l], m.shape_C[id]);
    m.shape_prev_W[id] = m.shape_W[id];
    m.AddToBroadPhase(id);
  }
  m.scene_changed = true;
  return true;
}

bool Monitor::SetObjectPose(const std::string& object, const Eigen::Isometry3d& X_WO,
                            std::string* error) {
  Impl& m = *impl_;
  // No sync: a free object's shape does not depend on q.
  const int o = m.workcell->FindObject(object);
  if (o < 0) {
    SetError(error, "SetObjectPose: unknown object '" + object + "'");
    return false;
  }
  if (!m.objects[o].is_frame_bound) {
    SetError(error, "SetObjectPose: object '" + object + "' is static, not frame-bound");
    return false;
  }
  if (m.holder[o] >= 0) {
    SetError(error, "SetObjectPose: object '" + object + "' is held by link '" +
                        m.model->link_name(m.holder[o]) + "'");
    return false;
  }
  if (!X_WO.matrix().allFinite()) {
    SetError(error, "SetObjectPose: non-finite pose for object '" + object + "'");
    return false;
  }
  // shape_L is the object at X_WO_start; the cycle moves it in the index.
  const Eigen::Isometry3d X_WW = X_WO * m.objects[o].X_OW_start;
  for (const PrimitiveId id : m.objects[o].prims) {
    m.shape_W[id] = TransformShape(X_WW, m.workcell->primitives[id].shape_L);
    m.moved[id] = 1;
    m.MarkStaticsNearReachable(id);
  }
  m.scene_changed = true;
  return true;
}

std::uint32_t Monitor::primitive_count() const { return impl_->n; }
const Shape& Monitor::shape_W(PrimitiveId id) const { return impl_->shape_W[id]; }
bool Monitor::are_shapes_current() const { return !impl_->kinematics_behind; }
void Monitor::SyncShapes() { impl_->SyncKinematics(); }
bool Monitor::is_active(PrimitiveId id) const { return impl_->in_broad_phase[id] != 0; }
bool Monitor::AreCompatibleNow(PrimitiveId a, PrimitiveId b) const {
  return impl_->compatible.AreCompatible(a, b);
}
void Monitor::CollectIndexCells(std::vector<IndexCell>* cells) const {
  impl_->broad_phase->CollectCells(cells);
}
const BroadPhaseCounters& Monitor::total_counters() const { return impl_->total; }
std::uint64_t Monitor::refused_inputs() const { return impl_->refused; }
std::string Monitor::broad_phase_name() const { return impl_->broad_phase->name(); }
double Monitor::tolerance_m(PrimitiveId id) const { return impl_->tol_now[id]; }

bool Monitor::Validate(std::string* error) const {
  const Impl& m = *impl_;
  std::ostringstream msg;
  for (PrimitiveId id = 0; id < m.n; ++id) {
    const bool should = m.ShouldBeInBroadPhase(id);
    if (static_cast<bool>(m.in_broad_phase[id]) != should) {
      msg << "primitive " << id << " in broad phase: " << int(m.in_broad_phase[id])
          << ", expected " << should;
      break;
    }
    const int link = m.carrier[id];
    if (link >= 0 && !m.moved[id] && m.IsActiveVariant(id)) {
      const Shape expected = TransformShape(m.X_WL[link], m.shape_C[id]);
      // Attach re-expresses the shape in the link frame: equal up to rounding, not bit for bit.
      const Aabb a = ComputeAabb(expected);
      const Aabb b = ComputeAabb(m.shape_W[id]);
      if (!a.min_W.isApprox(b.min_W, kValidateShapeTolerance_rel) ||
          !a.max_W.isApprox(b.max_W, kValidateShapeTolerance_rel)) {
        msg << "primitive " << id << " does not follow link " << link;
        break;
      }
    }
    if (m.speed_tol_gain_s == 0.0 && m.tol_now[id] != m.tol_base[id]) {
      msg << "primitive " << id << " tolerance " << m.tol_now[id] << " != " << m.tol_base[id];
      break;
    }
    const int o = m.object_of[id];
    if (o >= 0 && (m.holder[o] >= 0) != (link >= 0)) {
      msg << "object primitive " << id << " carrier disagrees with its holder";
      break;
    }
  }
  if (msg.tellp() == 0) {
    for (std::size_t o = 0; o < m.objects.size() && msg.tellp() == 0; ++o) {
      for (int l = 0; l < m.model->link_count() && msg.tellp() == 0; ++l) {
        for (const PrimitiveId lp : m.link_prims[l]) {
          for (const PrimitiveId op : m.objects[o].prims) {
            if (m.compatible.AreCompatible(lp, op) !=
                m.CompatibleNow(lp, op, l, static_cast<int>(o))) {
              msg << "compatibility of " << lp << " and " << op << " is stale";
            }
          }
        }
      }
    }
  }
  if (msg.tellp() == 0) m.ValidateSlack(&msg);
  if (msg.tellp() == 0 && m.kinematics_behind) m.ValidateBoundedCycle(&msg);
  const auto& w = m.report.warnings;
  for (std::size_t i = 0; i < w.size() && msg.tellp() == 0; ++i) {
    if (w[i].a >= w[i].b || (i > 0 && !(w[i - 1].a < w[i].a ||
                                        (w[i - 1].a == w[i].a && w[i - 1].b < w[i].b)))) {
      msg << "report warnings not sorted or not a < b at index " << i;
    }
  }
  if (msg.tellp() == 0) return true;
  SetError(error, msg.str());
  return false;
}

bool Monitor::ValidateIndex(std::string* error) const {
  std::string why;
  if (impl_->broad_phase->Validate(&why)) return true;
  SetError(error, "broad phase " + impl_->broad_phase->name() + ": " + why);
  return false;
}

void Monitor::ForceIndexStampsNearWrap(std::uint32_t steps_before_wrap) {
  impl_->broad_phase->ForceStampsNearWrap(steps_before_wrap);
}

}  // namespace arm_collision_monitor
