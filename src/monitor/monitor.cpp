// The per-cycle Monitor: the seed's update loop (Shaffer & Herb, TR 90-28, section 3: joint
// angles -> kinematics -> index update of the moved primitives -> intersection tests of the
// tolerance-grown primitives), with its section 6 extensions (model switching, grasped objects,
// speed-dependent tolerance) done without allocation in the cycle. Read top-down: Update, then
// the cycle's steps, then the start-up of the data, then the read accessors.
#include "arm_collision_monitor/monitor/monitor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <variant>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "arm_collision_monitor/broadphase/broad_phase_factory.h"
#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "monitor_impl.h"

namespace arm_collision_monitor {
namespace {

/// Bit-identical poses: a link whose pose did not change bit for bit has not moved.
bool IsSamePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::memcmp(a.matrix().data(), b.matrix().data(), sizeof(double) * 16) == 0;
}

/// *shape_W = TransformShape(X_WL, shape_C), a capsule written in place (no temporary shape
/// assigned through the variant: the arms' capsules, moved every kinematics cycle); a sphere
/// (`is_sphere`: a capsule whose endpoints are bit-identical) is transformed once.
[[gnu::always_inline]] inline void MoveShape(const Eigen::Isometry3d& X_WL, const Shape& shape_C,
                                             bool is_sphere, Shape* shape_W) {
  const auto* capsule_C = std::get_if<Capsule>(&shape_C);
  auto* capsule_W = std::get_if<Capsule>(shape_W);
  if (capsule_C == nullptr || capsule_W == nullptr) {
    *shape_W = TransformShape(X_WL, shape_C);
    return;
  }
  capsule_W->p0_W = X_WL * capsule_C->p0_W;
  capsule_W->p1_W = is_sphere ? capsule_W->p0_W : X_WL * capsule_C->p1_W;
  capsule_W->radius_m = capsule_C->radius_m;
}

/// changed[link]: whether the pose of `link` differs between X_WL and X_WL_new, for each of
/// `links` (the kinematics' fk_links: every carrier among them; the other entries are left).
void MarkChangedLinks(const std::vector<int>& links, const std::vector<Eigen::Isometry3d>& X_WL,
                      const std::vector<Eigen::Isometry3d>& X_WL_new,
                      std::vector<std::uint8_t>* changed) {
  for (const int link : links) (*changed)[link] = IsSamePose(X_WL_new[link], X_WL[link]) ? 0 : 1;
}

}  // namespace

// --- the cycle ------------------------------------------------------------------------------

const CycleReport& Monitor::Update(const Eigen::Ref<const Eigen::VectorXd>& q, double time_s) {
  impl_->time_s = time_s;
  impl_->joint_time_s = nullptr;
  return impl_->Cycle(q);
}

const CycleReport& Monitor::Update(const Eigen::Ref<const Eigen::VectorXd>& q,
                                   const Eigen::Ref<const Eigen::VectorXd>& joint_time_s) {
  const bool is_sized = joint_time_s.size() == impl_->joint_time_good_s.size();
  impl_->time_s = std::numeric_limits<double>::quiet_NaN();
  impl_->joint_time_s = is_sized ? joint_time_s.data() : nullptr;
  return impl_->Cycle(q);
}

const CycleReport& Monitor::Impl::Cycle(const Eigen::Ref<const Eigen::VectorXd>& q) {
  if (model.turning_links.empty()) return CycleOf(q);
  const CycleReport& cycle = Unwind(q) ? CycleOf(q_unwound) : CycleOf(q);
  if (cycle.input == InputStatus::kOk) turns_good = turns_next;
  return cycle;
}

const CycleReport& Monitor::Impl::CycleOf(const Eigen::Ref<const Eigen::VectorXd>& q) {
  // Idle cycle: same input bit for bit and an unchanged scene give the same report (the joints
  // were at q_good at these times too).
  // With speed-scaled tolerances, joints that come to rest lower theirs: not idle.
  if (IsIdle(q) && !(model.speed_tol_gain_s != 0.0 && NoteJointMotion(q))) {
    DateGood();
    RecordCycle(CycleKind::kIdle, InputStatus::kOk, {});
    return report;
  }
  const InputStatus status = CheckInput(q);
  if (status != InputStatus::kOk) {
    // Fail safe: keep the last good state (and its warnings), request a stop.
    ++refused;
    RecordCycle(CycleKind::kRefused, status, {});
    return report;
  }
  RunCycle(q);
  return report;
}

void Monitor::Impl::RunCycle(const Eigen::Ref<const Eigen::VectorXd>& q) {
  // Work done by scene changes since the last cycle belongs to the run, not to this cycle.
  total += broad_phase->counters();
  broad_phase->ResetCounters();
  CycleWork work;
  // The step from the last accepted q (none before the first good cycle: q_good is then only
  // the model's start pose).
  swept.q_start = q_good;
  swept.is_behind = kinematics_behind;
  // Each primitive's step bound is computed when first needed (StepBound_m).
  std::fill_n(swept.is_step_bound_known.begin(), live_end, std::uint8_t{0});
  // Scene changes may move the primitives without levers: their cached boxes go.
  if (scene_changed) swept.are_fixed_boxes_current = false;
  if (has_good) {
    MotionBounds& step = StepMotion();
    step.SetJointMotion(q, swept.q_start);
    work.step_m = step.ComputeLargestBound_m();
    work.is_jumped = (!(work.step_m <= model.options.max_step_m) &&
                      !IsWithinVelocityLimits(q)) ||
                     is_turn_ambiguous ||
                     (!model.options.swept_check &&
                      IsBeyondSampleCheck(work.step_m, &work.beyond_samples));
  }
  if (model.speed_tol_gain_s != 0.0) NoteJointMotion(q);
  DateGood();  // q is accepted: q_good below
  if (IsProvablyClear(q, work.step_m)) {
    // Every kept pair is clear, and every other pair's indexed boxes are apart while both
    // primitives stay within their slack: no warning, and the kinematics can wait.
    q_good = q;
    kinematics_behind = true;
    work.candidate_pairs = static_cast<std::uint32_t>(cache.pairs().size());
    RecordCycle(CycleKind::kBounded, InputStatus::kOk, work);
    return;
  }
  // Steps small enough for bounded cycles: the primitives past half their slack are re-indexed
  // together, leaving the other half to the bounded cycles (pair_cache.h); a larger step would
  // use it up at once, so only those past the slack are.
  const double half_slack_m = PairCache::kReindexSlackFraction * model.options.index_slack_m;
  const double reindex_at_m =
      work.step_m <= half_slack_m ? half_slack_m : model.options.index_slack_m;
  const bool is_swept = model.options.swept_check && work.step_m > 0.0;
  if (is_swept) BeginStep(work.step_m);
  work.moved = FollowKinematics(q, is_swept, reindex_at_m);
  q_good = q;
  work.narrow_phase_tests = TestCandidatePairs();
  // A jump is swept too: its stop is requested anyway, and what its path meets is reported.
  if (is_swept) SweepStep(q, &work);
  work.reindexed = static_cast<std::uint32_t>(cache.reindexed().size());
  work.candidate_pairs = static_cast<std::uint32_t>(cache.pairs().size());
  RecordCycle(CycleKind::kKinematics, InputStatus::kOk, work);
  has_good = true;
  scene_changed = false;
}

InputStatus Monitor::Impl::CheckInput(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  if (q.size() != model.q_lower.size()) return InputStatus::kWrongSize;
  // One pass without early exits (every cycle that is not idle runs it), two comparisons a
  // joint: the limits are finite (MonitorModel), so they also refuse NaN and infinities.
  const double* const x = q.data();
  const double* const lower = model.q_lower.data();
  const double* const upper = model.q_upper.data();
  const Eigen::Index n = q.size();
  Eigen::Index i = 0;
  bool is_within = true;
#if defined(__SSE2__)
  // Two joints at a time (GCC leaves the scalar loop scalar).
  __m128d within = _mm_castsi128_pd(_mm_set1_epi64x(-1));
  for (; i + 2 <= n; i += 2) {
    const __m128d x2 = _mm_loadu_pd(x + i);
    within = _mm_and_pd(within, _mm_and_pd(_mm_cmpge_pd(x2, _mm_loadu_pd(lower + i)),
                                           _mm_cmple_pd(x2, _mm_loadu_pd(upper + i))));
  }
  is_within = _mm_movemask_pd(within) == 3;
#endif
  for (; i < n; ++i) is_within &= (x[i] >= lower[i]) & (x[i] <= upper[i]);
  if (is_within) return InputStatus::kOk;
  return q.allFinite() ? InputStatus::kOutOfLimits : InputStatus::kNonFinite;
}

bool Monitor::Impl::IsProvablyClear(const Eigen::Ref<const Eigen::VectorXd>& q, double step_m) {
  // Speed-scaled tolerances need the motion itself; a scene change re-plans the pairs.
  if (!has_good || scene_changed || cache.is_stale() || model.speed_tol_gain_s != 0.0 ||
      report.input != InputStatus::kOk) {
    return false;
  }
  // With the swept check, bounds for every point of the step from q_good to q: what they
  // certify then holds along the whole path. Without bounded cycles since the kinematics
  // (q_kinematics == q_good) both are the step's motion |q - q_good|, already set (RunCycle).
  if (kinematics_behind && model.options.swept_check) {
    motion.SetSegmentMotion(q_good, q, q_kinematics);
  } else if (kinematics_behind) {
    motion.SetJointMotion(q, q_kinematics);
  }
  // In a run of bounded cycles, the largest bound since the kinematics is at most the last
  // cycle's plus this step's: the bounds are lever sums, linear in the joint motion, and
  // |q - q_kinematics| <= |q_good - q_kinematics| + |q - q_good| joint by joint (the segment
  // motion's larger end too). Many bounded cycles clear on that sum alone, without the
  // primitives' own sums (sphere_robot 640 of 1,209 after the first of a run, tasks 301 of
  // 1,746); a margin far above both sums' rounding keeps it an upper bound.
  const double slack_m = model.options.index_slack_m;
  if (kinematics_behind && is_pair_gap_known) {
    const double sum_m = (largest_since_m + step_m) * (1.0 + kBoundSumRounding);
    if (largest_displacement_m + sum_m <= slack_m && smallest_pair_gap_m > 2.0 * sum_m) {
      largest_since_m = sum_m;
      return true;
    }
  }
  // A primitive's own bound is computed only where the largest does not settle it. Without
  // bounded cycles since the kinematics, `motion` is the step's (StepMotion), whose largest
  // bound RunCycle has, and what is computed here serves StepBound_m too.
  const double largest_m = kinematics_behind ? motion.ComputeLargestBound_m() : step_m;
  largest_since_m = largest_m;  // read only after this returns true (kinematics_behind)
  std::vector<std::uint8_t>* known = kinematics_behind ? &bound_known : &swept.is_step_bound_known;
  if (kinematics_behind) std::fill_n(known->begin(), live_end, std::uint8_t{0});
  // Motion since indexed <= motion until the kinematics + motion since; NaN fails. All at once
  // by the largest of both (most bounded cycles), else one by one.
  if (!(largest_displacement_m + largest_m <= slack_m)) {
    for (const PrimitiveId id : carried) {
      if (!in_broad_phase[id] || motion.lever_count(id) == 0) continue;
      const double displacement_m = cache.displacement_m(id);
      if (displacement_m + largest_m <= slack_m) continue;
      if (!(displacement_m + BoundOnce(&motion, known, id) <= slack_m)) return false;
    }
  }
  // Every kept pair at once when its smallest gap (kinematics bound less margin and threshold:
  // fixed until the next kinematics) clears twice the largest bound, else one by one.
  if (!is_pair_gap_known) {
    smallest_pair_gap_m = std::numeric_limits<double>::infinity();
    for (const KeptPair& kept : cache.pairs()) {
      const double gap_m = PairGap_m(kept);
      if (!(gap_m >= smallest_pair_gap_m)) smallest_pair_gap_m = gap_m;  // NaN stays
    }
    is_pair_gap_known = true;
  }
  if (smallest_pair_gap_m > 2.0 * largest_m) return true;
  for (const KeptPair& kept : cache.pairs()) {
    const PrimitiveId a = kept.pair.a;
    const PrimitiveId b = kept.pair.b;
    const double threshold_m = tol_now[a] + tol_now[b];
    // The pair's bound is at most the sum of the two primitives' (NaN is not clear).
    const double at_most_m = (motion.lever_count(a) > 0 ? largest_m : 0.0) +
                             (motion.lever_count(b) > 0 ? largest_m : 0.0);
    if (cache.IsClear(kept.kinematics_bound_m, at_most_m, threshold_m)) continue;
    BoundOnce(&motion, known, a);
    BoundOnce(&motion, known, b);
    if (!cache.IsClear(kept.kinematics_bound_m, motion.PairBound_m(a, b), threshold_m)) {
      return false;
    }
  }
  return true;
}

std::uint32_t Monitor::Impl::FollowKinematics(const Eigen::Ref<const Eigen::VectorXd>& q,
                                              bool is_step, double reindex_at_m) {
  model.kinematics->UpdateLinkPosesOf(q, q_kinematics, fk_links, &X_WL, &X_WL_before,
                                      &link_changed, &fk_scratch);
  is_before_complete = false;
  is_pair_gap_known = false;
  q_kinematics = q;
  kinematics_behind = false;
  const std::uint32_t moved_count = ReindexMoved(is_step, reindex_at_m);
  // Fixed tolerances: tol_now already equals tol_base (Attach / Detach keep both).
  const bool is_speed_scaled = model.speed_tol_gain_s != 0.0;
  if (is_speed_scaled) ComputeTolerances(shape_W, moved, &link_at_rest, &tol_now);
  // Only speed estimates read shape_prev_W (ReindexMoved cleared the moved flags without them).
  if (is_speed_scaled) {
    ForEachMayHaveMoved([&](PrimitiveId id) {
      if (moved[id]) shape_prev_W[id] = shape_W[id];
      moved[id] = 0;
    });
  }
  cache.Update(broad_phase.get(), compatible, &carrier);
  return moved_count;
}

void Monitor::Impl::MoveCarried(const std::vector<Eigen::Isometry3d>& X_WL_new,
                                std::vector<std::uint8_t>* changed, std::vector<Shape>* shapes,
                                std::vector<std::uint8_t>* moved_flags) const {
  MarkChangedLinks(fk_links, X_WL, X_WL_new, changed);
  for (const PrimitiveId id : carried) {
    const int link = carrier[id];
    if (!(*changed)[link]) continue;
    MoveShape(X_WL_new[link], shape_C[id], is_sphere_C[id] != 0, &(*shapes)[id]);
    (*moved_flags)[id] = 1;
  }
}

std::uint32_t Monitor::Impl::ReindexMoved(bool is_step, double reindex_at_m) {
  std::uint32_t moved_count = 0;
  cache.BeginReindex();
  const double slack_m = model.options.index_slack_m;
  // Speed-scaled tolerances read the moved flags afterwards (FollowKinematics clears them).
  const bool is_clearing_moved = model.speed_tol_gain_s == 0.0;
  double largest_m = 0.0;
  bool is_any_nan = false;
  // The arrays through local pointers: each byte flag stored below could otherwise alias every
  // member, and the compiler would reload their data pointers after it.
  const int* const carrier_of = carrier.data();
  const std::uint8_t* const is_link_changed = link_changed.data();
  const std::uint8_t* const is_indexed = in_broad_phase.data();
  const std::uint8_t* const is_sphere = is_sphere_C.data();
  const Shape* const shapes_C = shape_C.data();
  Shape* const shapes_W = shape_W.data();
  std::uint8_t* const moved_flags = moved.data();
  const Eigen::Isometry3d* const X = X_WL.data();
  ForEachMayHaveMoved([&](PrimitiveId id) {
    // The shape follows its link (one pass with its re-indexing: its shape is at hand).
    const int link = carrier_of[id];
    const bool is_link_moved = link >= 0 && is_link_changed[link];
    if (is_link_moved) MoveShape(X[link], shapes_C[id], is_sphere[id] != 0, &shapes_W[id]);
    const bool is_moved = is_link_moved || moved_flags[id] != 0;
    moved_flags[id] = is_moved && !is_clearing_moved ? 1 : 0;
    if (!is_indexed[id]) return;
    const double kinematics_m = cache.displacement_m(id);  // as of the last kinematics
    if (is_moved) {
      ++moved_count;
      // A sphere's displacement is its centre's (MaxPointDisplacement_m for one point).
      const Shape& now = shapes_W[id];
      const bool is_reindexed =
          is_sphere[id] && is_link_moved
              ? cache.FollowMovedBy(id,
                                    (std::get<Capsule>(now).p0_W -
                                     std::get<Capsule>(cache.indexed_shape_W(id)).p0_W)
                                        .norm(),
                                    now, reindex_at_m)
              : cache.FollowMoved(id, now, reindex_at_m);
      if (is_reindexed) broad_phase->Move(id, ComputeAabb(now));
    }
    // The swept check: most stay within the largest step bound of their slack at q, and so
    // in it all along the step.
    if (is_step && !(cache.displacement_m(id) + swept.largest_step_m <= slack_m)) {
      FollowStep(id, is_moved, kinematics_m);
    }
    const double displacement_m = cache.displacement_m(id);
    largest_m = std::max(largest_m, displacement_m);
    is_any_nan |= std::isnan(displacement_m);
  });
  largest_displacement_m = is_any_nan ? std::numeric_limits<double>::quiet_NaN() : largest_m;
  return moved_count;
}

bool Monitor::Impl::NoteJointMotion(const Eigen::Ref<const Eigen::VectorXd>& q) {
  bool is_any_at_rest_now = false;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    const double t_s = joint_time_s != nullptr ? joint_time_s[i] : time_s;
    const double good_s = is_joint_time_good ? joint_time_good_s[i] : time_good_s;
    const bool is_moving_now = !has_good || !(q[i] == q_good[i]);
    // Not sampled anew (the same time and value): its motion stands.
    joint_sampled[i] = !(std::isfinite(t_s) && t_s == good_s && !is_moving_now) ? 1 : 0;
    if (!joint_sampled[i]) continue;
    is_any_at_rest_now |= joint_moving[i] && !is_moving_now;
    joint_moving[i] = is_moving_now ? 1 : 0;
    joint_step[i] = has_good ? std::abs(q[i] - q_good[i]) : std::numeric_limits<double>::infinity();
  }
  // Parents first (KinematicModel's order); the root's entry stays 1.
  const KinematicModel& kinematics = *model.kinematics;
  for (int link = 1; link < kinematics.link_count(); ++link) {
    const int i = DrivingQIndex(kinematics.joint(link));
    link_at_rest[link] = link_at_rest[kinematics.parent_link(link)] & (i < 0 || !joint_moving[i]);
  }
  return is_any_at_rest_now;
}

void Monitor::Impl::ComputeTolerances(const std::vector<Shape>& shapes,
                                      const std::vector<std::uint8_t>& moved_flags,
                                      const std::vector<std::uint8_t>* at_rest,
                                      std::vector<double>* tol) const {
  if (model.speed_tol_gain_s == 0.0) {
    std::copy(tol_base.begin(), tol_base.end(), tol->begin());
    return;
  }
  // ISO/TS 15066 protective separation: speed x (reaction + stopping time) added per primitive.
  // Speeds are clamped to max_speed_mps so the broad phase, inflated for that speed, stays
  // conservative; before the first good cycle the speed is unknown and taken as the maximum.
  const MonitorOptions& options = model.options;
  for (PrimitiveId id = 0; id < live_end; ++id) {
    const bool is_carrier_moving =
        at_rest != nullptr && carrier[id] >= 0 && !(*at_rest)[carrier[id]];
    double speed_mps = 0.0;
    if (!is_moving[id]) {
      speed_mps = 0.0;
    } else if (!has_good) {
      speed_mps = options.max_speed_mps;
    } else if (IsTimedFreeObject(id)) {
      // Between its timed poses (a tracker's TF samples, sparser than the cycles), it keeps
      // its speed over the interval of the last two: not at rest in the cycles between.
      speed_mps = std::min(object_speed_mps[model.object_of[id]], options.max_speed_mps);
    } else if (moved_flags[id]) {
      double step_m = MaxPointDisplacement_m(shape_prev_W[id], shapes[id]);
      if (is_carrier_moving) {
        // Moved by the joints sampled in this cycle; those above it that moved at their newest
        // sample, not this cycle's (a torso on its own topic), move it too: their step's bound.
        const MotionBounds::Lever* levers = motion.levers(id);
        for (int k = 0; k < motion.lever_count(id); ++k) {
          const int i = levers[k].q_index;
          if (joint_moving[i] && !joint_sampled[i]) step_m += joint_step[i] * levers[k].m_per_unit;
        }
      }
      speed_mps = step_m / options.cycle_period_s;
      if (!(speed_mps <= options.max_speed_mps)) speed_mps = options.max_speed_mps;  // NaN too
    } else if (is_carrier_moving) {
      continue;  // a joint above it moved at its newest sample: it keeps its speed
    }
    (*tol)[id] = tol_base[id] + speed_mps * model.speed_tol_gain_s;
  }
}

std::uint32_t Monitor::Impl::TestCandidatePairs() {
  report.warnings.clear();
  return cache.TestPairs(shape_W, tol_now, [this](PrimitiveId a, PrimitiveId b) {
    return TestPair(a, b, shape_W, tol_now, &report.warnings);
  });
}

Warning Monitor::Impl::MakeWarning(PrimitiveId a, PrimitiveId b, const DistanceResult& d,
                                  double threshold_m) {
  Warning w;
  w.a = a;
  w.b = b;
  w.distance_m = d.distance_m;
  w.threshold_m = threshold_m;
  w.p_WA = d.p_WA;
  w.p_WB = d.p_WB;
  return w;
}

double Monitor::Impl::TestPair(PrimitiveId a, PrimitiveId b, const std::vector<Shape>& shapes,
                               const std::vector<double>& tol, std::vector<Warning>* warnings) {
  const double threshold_m = tol[a] + tol[b];
  const DistanceResult d = ShapeDistance(shapes[a], shapes[b]);
  if (IsWarningDistance(d.distance_m, threshold_m)) {
    warnings->push_back(MakeWarning(a, b, d, threshold_m));
  }
  return d.distance_m;
}

void Monitor::Impl::RecordCycle(CycleKind kind, InputStatus input, const CycleWork& work) {
  ++report.cycle;
  // An idle cycle repeats the last good report (input kOk) but for the swept check's warnings;
  // a refused one keeps its warnings; a bounded one has none; a kinematics cycle has the narrow
  // phase's and the swept check's.
  if (kind == CycleKind::kBounded) report.warnings.clear();
  report.input = input;
  report.stop = input != InputStatus::kOk || !report.warnings.empty();
  report.moved_primitives = work.moved;
  report.reindexed_primitives = work.reindexed;
  report.candidate_pairs = work.candidate_pairs;
  report.narrow_phase_tests = work.narrow_phase_tests;
  report.bounded = kind == CycleKind::kBounded;
  if (kind == CycleKind::kIdle) {
    EraseBetweenSamples(&report.warnings);
    report.stop = !report.warnings.empty();
  }
  report.step_motion_m = work.step_m;
  report.input_jumped = work.is_jumped;
  report.beyond_samples = work.beyond_samples;
  report.stop = report.stop || report.input_jumped;
  report.swept_pairs = work.swept_pairs;
  report.swept_distance_tests = work.swept_tests;
  if (work.swept_pairs > 0) ++swept_cycles;
  report.counters = BroadPhaseCounters{};
  if (kind == CycleKind::kKinematics) {
    report.counters = broad_phase->counters();
    total += report.counters;
    broad_phase->ResetCounters();
  }
}

void Monitor::SyncShapes() { impl_->SyncKinematics(); }

// --- start-up -------------------------------------------------------------------------------

Monitor::Monitor(std::shared_ptr<const Workcell> workcell, const MonitorOptions& options)
    : impl_(std::make_unique<Impl>(std::move(workcell), options)) {}

Monitor::~Monitor() = default;

Monitor::Impl::Impl(std::shared_ptr<const Workcell> workcell, const MonitorOptions& options)
    : model(std::move(workcell), options) {
  InitData();
  BuildBroadPhase();
  InitSwept();
}

void Monitor::Impl::InitData() {
  const std::uint32_t n = model.primitive_count;
  const int link_count = model.kinematics->link_count();
  compatible = model.workcell->compatible;
  grasp.assign(static_cast<std::size_t>(link_count) * model.objects.size(), 0);
  holder.assign(model.objects.size(), -1);
  object_sample_s.assign(model.objects.size(), std::numeric_limits<double>::quiet_NaN());
  object_speed_mps.assign(model.objects.size(), std::numeric_limits<double>::quiet_NaN());
  active_variant.assign(link_count, 0);
  carrier = model.carrier_start;
  is_moving = model.is_moving_start;
  is_reachable = model.is_reachable_start;
  shape_C.resize(n);
  tol_base.resize(n);
  for (PrimitiveId id = 0; id < n; ++id) {
    shape_C[id] = model.workcell->primitives[id].shape_L;
    tol_base[id] = model.workcell->primitives[id].tolerance_m;
  }
  motion = MotionBounds(*model.kinematics, n);
  swept.step = MotionBounds(*model.kinematics, n);
  carried.reserve(n);
  is_sphere_C.assign(n, 0);
  fk_targets.assign(link_count, 0);
  fk_links.reserve(link_count);
  fk_scratch.reserve(link_count);
  // The links fixed to the root keep their start poses in both (UpdateLinkPosesOf).
  X_WL = model.X_WL_start;
  X_WL_before = model.X_WL_start;
  link_changed.assign(link_count, 0);
  link_at_rest.assign(link_count, 1);
  joint_moving.assign(model.q_start.size(), 1);
  joint_sampled.assign(model.q_start.size(), 1);
  joint_step.assign(model.q_start.size(), std::numeric_limits<double>::infinity());
  q_kinematics = model.q_start;
  for (PrimitiveId id = 0; id < n; ++id) SetCarrierBounds(id);
  PrepareBounds();
  bound_known.assign(n, 0);
  q_good = model.q_start;
  turns_good.setZero(model.q_start.size());
  turns_next.setZero(model.q_start.size());
  q_unwound = model.q_start;
  time_good_s = std::numeric_limits<double>::quiet_NaN();
  is_joint_time_good = false;
  joint_time_good_s.setConstant(model.q_start.size(), std::numeric_limits<double>::quiet_NaN());
  shape_W = model.shape_W_start;
  shape_prev_W = model.shape_W_start;
  moved.assign(n, 0);
  tol_now = tol_base;
  InitLiveObjects();
}

void Monitor::Impl::BuildBroadPhase() {
  const std::uint32_t n = model.primitive_count;
  in_broad_phase.assign(n, 0);
  broad_phase = MakeBroadPhase(model.options.broad_phase);
  cache = PairCache(n, model.max_tested_pairs, model.options.index_slack_m, model.world_edge_m);
  for (PrimitiveId id = 0; id < n; ++id) {
    if (ShouldBeInBroadPhase(id)) AddToBroadPhase(id);
  }
  report.warnings.reserve(model.max_tested_pairs);
  report.stop = true;  // nothing is known before the first good input
  total = BroadPhaseCounters{};
  broad_phase->ResetCounters();
}

// --- read access ----------------------------------------------------------------------------

const Workcell& Monitor::workcell() const { return *impl_->model.workcell; }
const PrimitiveSpec& Monitor::primitive(PrimitiveId id) const { return impl_->Spec(id); }
const MonitorOptions& Monitor::options() const { return impl_->model.options; }
const CycleReport& Monitor::report() const { return impl_->report; }

std::string Monitor::DescribeRefusal(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  const MonitorModel& model = impl_->model;
  const Eigen::Index n = model.q_lower.size();
  if (q.size() != n) {
    return std::to_string(q.size()) + " positions for the model's " + std::to_string(n) +
           " joints";
  }
  // The reading as given (what Check refuses), then as Update unwound it by the whole turns it
  // keeps for a turning joint (Impl::Unwind: the last Update's, for its q).
  const bool has_turns = impl_->turns_next.size() == n && !model.turning_links.empty();
  for (const bool is_unwound : {false, true}) {
    for (Eigen::Index i = 0; i < n && (!is_unwound || has_turns); ++i) {
      const double turns = is_unwound ? impl_->turns_next[i] : 0.0;
      const double x = q[i] + turns;
      if (x >= model.q_lower[i] && x <= model.q_upper[i]) continue;
      std::ostringstream text;
      text << "joint '" << model.workcell->joint_names[static_cast<std::size_t>(i)] << "' at "
           << q[i];
      if (turns != 0.0) text << " (" << x << " with the whole turns unwound so far)";
      // A side without a limit is accepted up to kMaxUnlimitedPosition_rad (no margin).
      const bool is_lower_free = model.q_lower[i] == -kMaxUnlimitedPosition_rad;
      const bool is_upper_free = model.q_upper[i] == kMaxUnlimitedPosition_rad;
      if (std::isfinite(x) && (x > model.q_upper[i] ? is_upper_free : is_lower_free)) {
        text << ", beyond the +/-" << kMaxUnlimitedPosition_rad << " rad a joint may take on a "
             << "side without a limit (a corrupt reading)";
      } else if (std::isfinite(x)) {
        text << ", outside its limits [";
        if (is_lower_free) text << "none"; else text << model.q_lower[i] + kJointLimitMargin;
        text << ", ";
        if (is_upper_free) text << "none"; else text << model.q_upper[i] - kJointLimitMargin;
        text << "] by more than their margin " << kJointLimitMargin;
      }
      return text.str();
    }
  }
  return "";
}
std::uint32_t Monitor::primitive_count() const { return impl_->model.primitive_count; }
const Shape& Monitor::shape_W(PrimitiveId id) const { return impl_->shape_W[id]; }
bool Monitor::are_shapes_current() const { return !impl_->kinematics_behind; }
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
const std::vector<std::string>& Monitor::startup_notices() const { return impl_->notices; }
std::uint64_t Monitor::swept_cycles() const { return impl_->swept_cycles; }
double Monitor::tolerance_m(PrimitiveId id) const { return impl_->tol_now[id]; }

}  // namespace arm_collision_monitor
