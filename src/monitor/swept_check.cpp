// The swept check (MonitorOptions::swept_check): nothing slips between two samples. Each step
// runs from the last accepted q to the new one along the straight joint-space path (what a
// driver interpolates). On that path the joint motion over a sub-interval [s0, s1] is
// (s1 - s0) |q1 - q0|, so the motion bounds of the whole step (MotionBounds: joint deltas times
// lever arms) scale linearly to any sub-interval. A pair is certified clear when its distance,
// less its relative motion bound, clears the threshold (conservative advancement, after
// B. Mirtich, Impulse-based Dynamic Simulation of Rigid Body Systems, PhD thesis, UC Berkeley,
// 1996); else the interval is bisected until a sample warns or the interval's relative motion
// is at most twice the resolution, where a sample within threshold + resolution exists (and
// up to kSweptRefineLevels levels further while its refinement samples last, to certify it).
// The step itself comes first: a continuous joint's wrapped reading unwound (Unwind) and the
// jump test (IsWithinVelocityLimits).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "monitor_impl.h"

namespace arm_collision_monitor {
namespace {

bool IsBefore(const Warning& w, const CandidatePair& p) {
  return w.a < p.a || (w.a == p.a && w.b < p.b);
}

/// The distance between two boxes (0 when they meet): a lower bound on the distance of the
/// shapes they hold.
double BoxGap_m(const Aabb& a, const Aabb& b) {
  return (b.min_W - a.max_W).cwiseMax(a.min_W - b.max_W).cwiseMax(0.0).norm();
}

}  // namespace

// --- the step: wrapped readings unwound, the jump test ------------------------------------

bool Monitor::Impl::Unwind(const Eigen::Ref<const Eigen::VectorXd>& q) {
  is_turn_ambiguous = false;
  if (q.size() != q_good.size()) return false;  // refused as it is
  bool has_turns = false;
  for (const int link : model.turning_links) {
    const JointSpec& joint = model.kinematics->joint(link);
    const int i = joint.q_index;
    // A reading outside the limits (NaN, infinities, beyond kMaxUnlimitedPosition_rad) is taken
    // as given, without the kept turns either, for CheckInput to refuse as ~check does: the
    // turns could shift it back within, and a turn count taken from it would carry over to
    // every later reading. The first cycle's reading takes none (no q_good yet).
    const bool is_within = q[i] >= model.q_lower[i] && q[i] <= model.q_upper[i];
    double turns = is_within ? turns_good[i] : 0.0;
    // The move in q_good's turns: 0 for the same reading (an idle cycle stays idle).
    const double move = (q[i] + turns) - q_good[i];
    if (has_good && is_within && std::abs(move) > 0.5 * kTurn) {
      const double wrap = kTurn * std::round(move / kTurn);
      if (IsWithinVelocityLimit(joint, std::abs(move - wrap))) {
        // Either way round within the bound (after a pause of over half a turn at the top
        // speed): the short way, and a stop, as nothing tells which.
        is_turn_ambiguous |= IsWithinVelocityLimit(joint, std::abs(move));
        turns -= wrap;
      }
    }
    turns_next[i] = turns;
    has_turns |= turns != 0.0;
  }
  if (has_turns) q_unwound = q + turns_next;
  return has_turns;
}

bool Monitor::Impl::IsWithinVelocityLimit(const JointSpec& joint, double move) const {
  const int i = joint.q_index;
  const double elapsed_s = (joint_time_s != nullptr ? joint_time_s[i] : time_s) -
                           (is_joint_time_good ? joint_time_good_s[i] : time_good_s);
  return !(move > 0.0) ||
         (elapsed_s > 0.0 && move <= kJumpVelocityFactor * joint.max_velocity * elapsed_s);
}

bool Monitor::Impl::IsWithinVelocityLimits(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  const KinematicModel& kinematics = *model.kinematics;
  for (int link = 1; link < kinematics.link_count(); ++link) {
    const JointSpec& joint = kinematics.joint(link);
    if (joint.q_index < 0) continue;
    if (!IsWithinVelocityLimit(joint, std::abs(q[joint.q_index] - q_good[joint.q_index]))) {
      return false;
    }
  }
  return true;
}

bool Monitor::Impl::IsBeyondSampleCheck(double step_m, StepBeyondSamples* beyond) {
  if (!(step_m > 0.0)) return false;
  // step_m is the largest of the bounds below (ComputeLargestBound_m; a sum in another order,
  // which a mimic joint's levers may take, can differ in its last bits: kBoundSumRounding
  // covers that): a step within the smallest tolerance of those with levers (the others'
  // bound is 0) is within each, without the primitives' own bounds.
  const MotionBounds& step = StepMotion();
  double smallest_tol_m = std::numeric_limits<double>::infinity();
  for (const PrimitiveId id : carried) {
    if (in_broad_phase[id] && step.lever_count(id) > 0) {
      smallest_tol_m = std::min(smallest_tol_m, tol_base[id]);
    }
  }
  if (step_m * (1.0 + kBoundSumRounding) <= smallest_tol_m) return false;
  for (const PrimitiveId id : carried) {
    if (!in_broad_phase[id]) continue;
    const double motion_m = StepBound_m(id);
    if (motion_m > tol_base[id]) {
      *beyond = StepBeyondSamples{true, id, motion_m, tol_base[id]};
      return true;
    }
  }
  return false;
}

// --- the swept check ----------------------------------------------------------------------

void Monitor::Impl::InitSwept() {
  const std::uint32_t n = model.primitive_count;
  swept.q_start = model.q_start;
  swept.q_s = model.q_start;
  swept.X_WL_start = model.X_WL_start;
  swept.X_WL_s = model.X_WL_start;
  swept.X_WL_at.assign(kSweptPoseCacheSize, model.X_WL_start);
  swept.box_W.assign(n, Aabb{});
  swept.grown_W.assign(n, Aabb{});
  swept.leaves_slack.assign(n, 0);
  swept.is_step_bound_known.assign(n, 0);
  swept.leavers.reserve(n);
  swept.near.reserve(n);
  swept.grown_by_id_W.Reserve(n);
  swept.leaver_words.assign((n + 63) / 64, 0);
  swept.q_kinematics = model.q_start;
  swept.pairs.reserve(model.max_tested_pairs);
  swept.start_box_W.assign(n, Aabb{});
  swept.start_box_step.assign(n, 0);
  CheckStepTolerance();
}

double Monitor::Impl::UrdfCycleMotion_m(PrimitiveId id) const {
  const MotionBounds::Lever* levers = motion.levers(id);
  double sum_m = 0.0;
  for (int k = 0; k < motion.lever_count(id); ++k) {
    sum_m += cycle_dq[levers[k].q_index] * levers[k].m_per_unit;
  }
  return sum_m;
}

void Monitor::Impl::CheckStepTolerance() {
  const MonitorOptions& options = model.options;
  const KinematicModel& kinematics = *model.kinematics;
  const double speed_step_m = options.max_speed_mps * options.cycle_period_s;
  cycle_dq = Eigen::VectorXd::Zero(kinematics.q_size());
  for (int link = 1; link < kinematics.link_count(); ++link) {
    const JointSpec& joint = kinematics.joint(link);
    if (joint.q_index >= 0) cycle_dq[joint.q_index] = joint.max_velocity * options.cycle_period_s;
  }
  double worst_gap_m = 0.0;
  PrimitiveId worst = 0;
  int below = 0;  // moving primitives whose tolerance is below their motion
  for (PrimitiveId id = 0; id < model.primitive_count; ++id) {
    if (!is_moving[id] || motion.lever_count(id) == 0) continue;
    const double gap_m = CycleMotionExcess_m(id);
    below += gap_m > 0.0;
    if (gap_m > worst_gap_m) {
      worst_gap_m = gap_m;
      worst = id;
    }
  }
  if (worst_gap_m <= 0.0) return;
  const double urdf_step_m = UrdfCycleMotion_m(worst);
  std::ostringstream msg;
  msg << "the tolerance of primitive '" << model.workcell->primitives[worst].name << "' ("
      << tol_base[worst] << " m) is below its motion in one cycle, "
      << std::max(speed_step_m, urdf_step_m)
      << " m: the larger of max_speed_mps * cycle_period_s (" << speed_step_m
      << " m, cycle_period_s " << options.cycle_period_s
      << " s, the input's expected period: the monitor options' cycle_period_s, to be set to "
         "the period of faster input) and what the URDF velocity limits allow in a cycle ("
      << urdf_step_m << " m, a bound: every joint at its limit at once, each at its longest "
      << "lever; joints without a velocity limit not counted) (of the " << below
      << " moving primitive" << (below == 1 ? "" : "s")
      << " whose tolerance is below their motion, the one furthest "
      << "below)";
  if (!options.swept_check) {
    throw LoadError("monitor options: swept_check is false and " + msg.str() +
                    ": a contact could pass between two cycles (raise tolerance_m, give the "
                    "joints' real top speeds in the scene file, joint_limits: {<joint>: "
                    "{velocity: v}}, or switch swept_check on)");
  }
  notices.push_back(msg.str() + "; the swept check covers the motion between cycles");
}

void Monitor::Impl::SweepStep(const Eigen::Ref<const Eigen::VectorXd>& q, CycleWork* work) {
  swept.has_start = false;
  swept.pose_count = 0;
  const std::size_t discrete = report.warnings.size();
  std::size_t w = 0;
  // Every point of the step is within the pair's relative motion bound of its end, which is
  // at most twice the largest step bound: the one test most pairs need, then the pair's own
  // bound (kept in pair_motion_m for `sweep`), both made before `sweep`.
  const double two_largest_m = 2.0 * swept.largest_step_m;
  double pair_motion_m = 0.0;
  auto is_near = [&](const CandidatePair& pair, double end_bound_m) {
    const double threshold_m = tol_now[pair.a] + tol_now[pair.b];
    if (cache.IsClear(end_bound_m, two_largest_m, threshold_m)) return false;
    pair_motion_m = PairStepBound_m(pair.a, pair.b);
    return !cache.IsClear(end_bound_m, pair_motion_m, threshold_m);
  };
  auto sweep = [&](const CandidatePair& pair, double end_bound_m, bool is_exact) {
    const PrimitiveId a = pair.a;
    const PrimitiveId b = pair.b;
    // A pair warned at q already stops the arm.
    while (w < discrete && IsBefore(report.warnings[w], pair)) ++w;
    if (w < discrete && report.warnings[w].a == a && report.warnings[w].b == b) return;
    const double threshold_m = tol_now[a] + tol_now[b];
    // The exact distance at q (unless the narrow phase just computed it, a kept pair's bound
    // is its indexed copies' distance less their displacements).
    double end_m = end_bound_m;
    if (!is_exact) {
      end_m = ShapeDistance(shape_W[a], shape_W[b]).distance_m;
      ++work->swept_tests;
      if (cache.IsClear(end_m, pair_motion_m, threshold_m)) return;
    }
    ++work->swept_pairs;
    SweepPair(a, b, pair_motion_m, end_m, q, work);
  };
  // The kept pairs and, merged in order, the others of primitives leaving their slack. A kept
  // pair's first test is on its gap, whose smallest the next IsProvablyClear then has.
  CollectSweptPairs();
  std::size_t extra = 0;
  const std::vector<SweptPair>& others = swept.pairs;
  double smallest_gap_m = std::numeric_limits<double>::infinity();
  for (const KeptPair& k : cache.pairs()) {
    for (; extra < others.size() && !(k.pair < others[extra].pair); ++extra) {
      const SweptPair& o = others[extra];
      if (!(o.pair == k.pair) && is_near(o.pair, o.end_bound_m)) {
        sweep(o.pair, o.end_bound_m, false);
      }
    }
    const double gap_m = PairGap_m(k);
    if (!(gap_m >= smallest_gap_m)) smallest_gap_m = gap_m;  // NaN stays
    if (gap_m > two_largest_m) continue;
    pair_motion_m = PairStepBound_m(k.pair.a, k.pair.b);
    if (!(gap_m > pair_motion_m)) sweep(k.pair, k.kinematics_bound_m, k.is_exact);
  }
  smallest_pair_gap_m = smallest_gap_m;
  is_pair_gap_known = true;
  for (; extra < others.size(); ++extra) {
    const SweptPair& o = others[extra];
    if (is_near(o.pair, o.end_bound_m)) sweep(o.pair, o.end_bound_m, false);
  }
  if (report.warnings.size() > discrete) {
    std::sort(report.warnings.begin(), report.warnings.end(),
              [](const Warning& x, const Warning& y) {
                return x.a < y.a || (x.a == y.a && x.b < y.b);
              });
  }
}

void Monitor::Impl::BeginStep(double step_m) {
  swept.largest_step_m = step_m;
  ++swept.step_count;  // the start boxes of earlier steps go
  swept.has_start_displacement = has_good && !cache.is_stale();
  swept.is_since_kinematics_set = false;
  // The kinematics overwrites it; the motion bounds since are left to the few primitives that
  // need them (StartDisplacement_m).
  if (swept.has_start_displacement && kinematics_behind) swept.q_kinematics = q_kinematics;
  for (const PrimitiveId id : swept.leavers) swept.leaves_slack[id] = 0;
  swept.leavers.clear();
}

void Monitor::Impl::FollowStep(PrimitiveId id, bool is_moved, double kinematics_m) {
  // Those without levers have no displacement.
  if (StepMotion().lever_count(id) == 0) return;
  const bool is_start_copy = !cache.is_reindexed(id);
  if (!MayLeaveSlack(id, is_start_copy, kinematics_m)) return;
  // A primitive that may leave its slack during the step needs its pairs with every primitive
  // swept (CollectSweptPairs). A moved one indexed at q instead is within its step bound
  // B <= slack of its copy all along the step, so the kept pairs cover it; it would be
  // re-indexed a few cycles later anyway.
  if (is_moved && is_start_copy && StepBound_m(id) <= model.options.index_slack_m) {
    cache.Reindex(id, shape_W[id]);
    broad_phase->Move(id, ComputeAabb(shape_W[id]));
    return;
  }
  swept.leaves_slack[id] = 1;
  swept.leavers.push_back(id);
}

double Monitor::Impl::StartDisplacement_m(PrimitiveId id, double kinematics_m) {
  // Without bounded cycles since, the last kinematics was at q_start.
  if (!swept.is_behind || motion.lever_count(id) == 0) return kinematics_m;
  // After the kinematics `motion` is free (the step's bounds are in swept.step then).
  if (!swept.is_since_kinematics_set) {
    motion.SetJointMotion(swept.q_start, swept.q_kinematics);
    swept.is_since_kinematics_set = true;
  }
  return kinematics_m + motion.ComputeBound_m(id);
}

bool Monitor::Impl::MayLeaveSlack(PrimitiveId id, bool is_start_copy, double kinematics_m) {
  const double slack_m = model.options.index_slack_m;
  const double end_m = cache.displacement_m(id);
  const double step_m = StepBound_m(id);
  if (end_m + step_m <= slack_m) return false;  // NaN may leave
  return !(is_start_copy && swept.has_start_displacement &&
           LargestOverStretch_m(StartDisplacement_m(id, kinematics_m), end_m, step_m) <= slack_m);
}

bool Monitor::Impl::CollectSweptPairs() {
  // Beside the kept pairs: any other pair's indexed boxes, grown by tolerance + slack, are
  // apart, so it is clear along the step while both primitives stay within their slack. At
  // fraction s a primitive is within d1 + (1 - s) B of its indexed copy (d1: its displacement
  // at q, B: its step bound) and, when its copy is the one it had at the start, within
  // d0 + s B too (d0: its displacement there); the larger of the smaller is (d0 + d1 + B) / 2.
  // The leavers are those ReindexMoved found (FollowStep).
  const std::uint32_t n = live_end;  // free live slots are not indexed
  const MotionBounds& step = StepMotion();
  const double largest_m = swept.largest_step_m;
  swept.pairs.clear();
  if (swept.leavers.empty()) return false;
  // The pairs of a primitive that may leave its slack, generated in order (a < b); the kept
  // ones among them are dropped in SweepStep's merge. Boxes grown by g = (tol + B + k W) /
  // (1 - k) (B: at least the step bound, k W: BoundMargin_m(0)) that are apart have a gap over
  // (threshold + B_a + B_b + 2 k W) / (1 - k), which SweepStep's test (cache.IsClear,
  // PairStepBound_m <= B_a + B_b) clears with k W to spare for the rounding of the growth; a
  // NaN bound grows a box to everything. A leaver's B is its step bound, any other's the
  // largest (its own is needed only for the few pairs whose boxes meet).
  const double margin_m = cache.BoundMargin_m(0.0);
  auto grow = [&](PrimitiveId id) {
    // Without levers a primitive moves only with the scene (Monitor::Impl::RunCycle).
    const bool is_fixed = step.lever_count(id) == 0;
    if (!in_broad_phase[id] || (is_fixed && swept.are_fixed_boxes_current)) return;
    swept.box_W[id] = ComputeAabb(shape_W[id]);
    double reach_m = swept.leaves_slack[id] ? StepBound_m(id) : largest_m;
    if (is_fixed) reach_m = 0.0;
    const double grow_m = (tol_now[id] + reach_m + margin_m) / (1.0 - kLowerBoundMarginPerMetre);
    swept.grown_W[id] =
        swept.box_W[id].Inflated(std::isnan(grow_m) ? std::numeric_limits<double>::infinity()
                                                    : grow_m);
  };
  if (swept.are_fixed_boxes_current) {
    for (const PrimitiveId id : carried) grow(id);  // those with levers are carried
  } else {
    for (PrimitiveId id = 0; id < n; ++id) grow(id);
  }
  swept.are_fixed_boxes_current = true;
  // The indexed primitives whose boxes meet the leavers' hull: one pass over all of them,
  // then each leaver with those (two leavers once), then in pair order.
  Aabb hull_W = swept.grown_W[swept.leavers.front()];
  for (const PrimitiveId leaver : swept.leavers) {
    hull_W.Enclose(swept.grown_W[leaver]);
  }
  swept.near.clear();
  for (PrimitiveId id = 0; id < n; ++id) {
    if (in_broad_phase[id] && hull_W.Overlaps(swept.grown_W[id])) swept.near.push_back(id);
  }
  if (swept.leavers.size() * swept.near.size() >= kSweptScanMinTests) {
    ScanSweptPairs();
  } else {
    for (const PrimitiveId leaver : swept.leavers) {
      const Aabb& grown_W = swept.grown_W[leaver];
      for (const PrimitiveId other : swept.near) {
        // A pair of two leavers is taken from the smaller id's side.
        if (other == leaver || (swept.leaves_slack[other] && other < leaver) ||
            !grown_W.Overlaps(swept.grown_W[other])) {
          continue;
        }
        AddSweptPairIfNear(std::min(leaver, other), std::max(leaver, other));
      }
    }
  }
  std::sort(swept.pairs.begin(), swept.pairs.end(),
            [](const SweptPair& x, const SweptPair& y) { return x.pair < y.pair; });
  return true;
}

void Monitor::Impl::ScanSweptPairs() {
  // The grown boxes by id (NaN, overlapping nothing, for those not indexed), so that a word of
  // hits lines up with the leaver's compatibility row: the compatible pairs, and the pairs with
  // a leaver of a smaller id (taken from that side), are masked before any exact test.
  const std::uint32_t n = live_end;
  const Aabb not_indexed_W = Aabb::Nowhere();
  swept.grown_by_id_W.Clear();
  for (PrimitiveId id = 0; id < n; ++id) {
    swept.grown_by_id_W.PushBack(in_broad_phase[id] ? swept.grown_W[id] : not_indexed_W);
  }
  std::fill(swept.leaver_words.begin(), swept.leaver_words.end(), std::uint64_t{0});
  for (const PrimitiveId leaver : swept.leavers) {
    swept.leaver_words[leaver / 64] |= std::uint64_t{1} << (leaver % 64);
  }
  // The bits of word w that `leaver` pairs with: not compatible with it, and not a leaver up
  // to its own id (2 << 63 wraps to 0: every bit), whose side takes the pair.
  auto pairable = [&](PrimitiveId leaver, std::uint32_t w) {
    const std::uint64_t* compatible_row = compatible.RowWords(leaver);
    const std::uint32_t row_words = compatible_row != nullptr ? compatible.words_per_row() : 0;
    const std::uint32_t leaver_word = leaver / 64;
    const std::uint64_t up_to_leaver = (std::uint64_t{2} << (leaver % 64)) - 1;
    const std::uint64_t earlier =
        w < leaver_word ? ~std::uint64_t{0} : (w == leaver_word ? up_to_leaver : 0);
    return ~(swept.leaver_words[w] & earlier) &
           ~(w < row_words ? compatible_row[w] : std::uint64_t{0});
  };
  // The leavers of one link come in a row (ForEachMayHaveMoved goes by id, and a link's
  // primitives have consecutive ids): they share one scan, for the hull of their boxes, whose
  // hits each of them then tests itself (a link modelled by spheres has most of them leave
  // together).
  const std::vector<PrimitiveId>& leavers = swept.leavers;
  for (std::size_t first = 0; first < leavers.size();) {
    std::size_t end = first + 1;
    Aabb hull_W = swept.grown_W[leavers[first]];
    for (; end < leavers.size() && carrier[leavers[end]] == carrier[leavers[first]]; ++end) {
      hull_W.Enclose(swept.grown_W[leavers[end]]);
    }
    // Each leaver of the run decides the hull's flags against its own box (alone, its box is
    // the hull).
    swept.grown_by_id_W.MarkOverlaps(hull_W);
    for (; first < end; ++first) {
      const PrimitiveId leaver = leavers[first];
      swept.grown_by_id_W.ForEachHitOf(
          swept.grown_W[leaver], [&](std::uint32_t w) { return pairable(leaver, w); },
          [&](std::uint32_t other) {
            AddSweptPairIfNear(std::min(leaver, other), std::max(leaver, other));
          });
    }
  }
}

void Monitor::Impl::AddSweptPairIfNear(PrimitiveId a, PrimitiveId b) {
  if (compatible.AreCompatible(a, b)) return;
  // The boxes' gap bounds the distance at q from below (they hold the shapes): a pair it clears
  // by more than the step's motion of both is clear along the step (SweepStep's test, with the
  // larger motion B_a + B_b).
  const double gap_m = BoxGap_m(swept.box_W[a], swept.box_W[b]);
  const double threshold_m = tol_now[a] + tol_now[b];
  if (cache.IsClear(gap_m, StepBound_m(a) + StepBound_m(b), threshold_m)) return;
  // SweepStep's test on the pair's own bound, made here for its list, then that of both ends
  // (the end distance a box gap, so it spares SweepPair the distances at both ends).
  const double pair_motion_m = PairStepBound_m(a, b);
  if (cache.IsClear(gap_m, pair_motion_m, threshold_m) ||
      IsClearFromBothEnds(a, b, gap_m, pair_motion_m)) {
    return;
  }
  swept.pairs.push_back({CandidatePair{a, b}, gap_m, false});
}

const std::vector<Eigen::Isometry3d>& Monitor::Impl::StepPoses(
    double s, const Eigen::Ref<const Eigen::VectorXd>& q) {
  for (int i = 0; i < swept.pose_count; ++i) {
    if (swept.pose_s[i] == s) return swept.X_WL_at[i];
  }
  std::vector<Eigen::Isometry3d>* X_WL_s = &swept.X_WL_s;  // once the cache is full
  if (swept.pose_count < kSweptPoseCacheSize) {
    swept.pose_s[swept.pose_count] = s;
    X_WL_s = &swept.X_WL_at[swept.pose_count++];
  }
  swept.q_s = swept.q_start + s * (q - swept.q_start);
  model.kinematics->ComputeLinkPosesOf(swept.q_s, fk_links, X_WL_s);
  return *X_WL_s;
}

const std::vector<Eigen::Isometry3d>& Monitor::Impl::StartPoses() {
  // Without bounded cycles since, the kinematics before the last was at q_start: X_WL_before
  // holds the poses the last one changed, X_WL the others.
  if (!swept.is_behind) {
    if (!is_before_complete) {
      for (const int link : fk_links) {
        if (!link_changed[link]) X_WL_before[link] = X_WL[link];
      }
      is_before_complete = true;
    }
    return X_WL_before;
  }
  if (!swept.has_start) {
    model.kinematics->ComputeLinkPosesOf(swept.q_start, fk_links, &swept.X_WL_start);
    swept.has_start = true;
  }
  return swept.X_WL_start;
}

bool Monitor::Impl::IsClearFromBothEnds(PrimitiveId a, PrimitiveId b, double end_bound_m,
                                         double pair_motion_m) {
  for (const PrimitiveId id : {a, b}) {
    if (swept.start_box_step[id] == swept.step_count) continue;
    swept.start_box_step[id] = swept.step_count;
    swept.start_box_W[id] = ComputeAabb(ShapeAt(id, StartPoses()));
  }
  // SweepPair's first interval, [0, 1], on lower bounds of the distances at its ends.
  const double start_bound_m = BoxGap_m(swept.start_box_W[a], swept.start_box_W[b]);
  return cache.IsClear(SmallestOverStretch_m(start_bound_m, end_bound_m, pair_motion_m), 0.0,
                       tol_now[a] + tol_now[b]);
}

void Monitor::Impl::SweepPair(PrimitiveId a, PrimitiveId b, double pair_motion_m, double d1_m,
                              const Eigen::Ref<const Eigen::VectorXd>& q, CycleWork* work) {
  const double threshold_m = tol_now[a] + tol_now[b];
  const std::vector<Eigen::Isometry3d>& X_WL_start = StartPoses();
  // Appends the pair's warning at fraction s of the step, for the link poses X there.
  auto warn_at = [&](double s, const std::vector<Eigen::Isometry3d>& X) {
    Warning warning =
        MakeWarning(a, b, ShapeDistance(ShapeAt(a, X), ShapeAt(b, X)), threshold_m);
    warning.between_samples = true;
    warning.step_fraction = s;
    report.warnings.push_back(warning);
  };
  const double d0_m = ShapeDistance(ShapeAt(a, X_WL_start), ShapeAt(b, X_WL_start))
                          .distance_m;
  ++work->swept_tests;
  if (IsWarningDistance(d0_m, threshold_m)) {  // the step starts in the tolerance zone
    warn_at(0.0, X_WL_start);
    return;
  }
  const double resolved_m = 2.0 * model.options.swept_resolution_m;
  const double finest_m = resolved_m / (1 << kSweptRefineLevels);
  // The first resolved interval's nearer end (NaN: none yet), and the samples left after it.
  double resolved_s = std::numeric_limits<double>::quiet_NaN();
  int samples_left = kSweptSamplesPastResolved;
  // Samples left to bisect intervals within the resolution: those of one interval refined to
  // the finest, shared by the pair's intervals.
  int refinements_left = (1 << kSweptRefineLevels) - 1;
  int top = 0;
  swept.stack[top++] = SweptInterval{0.0, 1.0, d0_m, d1_m, 0};
  while (top > 0) {
    const SweptInterval iv = swept.stack[--top];
    // On [s0, s1] the distance is at least max(d0 - P (s - s0), d1 - P (s1 - s)), whose
    // smallest value is (d0 + d1 - P (s1 - s0)) / 2; NaN is not clear.
    const double motion_m = pair_motion_m * (iv.s1 - iv.s0);
    const double lower_m = SmallestOverStretch_m(iv.d0_m, iv.d1_m, motion_m);
    if (lower_m - cache.BoundMargin_m(lower_m) > threshold_m) continue;
    // Within the resolution the interval is bisected only to certify it, while refinement
    // samples last (a pair near its threshold that a fast input's step moves less than twice
    // the resolution, which the bound alone would leave uncertified).
    const bool is_within_resolution = motion_m <= resolved_m;
    if (iv.depth >= kMaxSweptBisections ||
        (is_within_resolution && (motion_m <= finest_m || refinements_left == 0))) {
      // Resolved: the nearer end is within threshold + motion / 2 <= threshold + resolution.
      // The pair warns; the search goes on for a sample within the threshold to report (a
      // contact just past a sample a hair above it), for a bounded number of samples.
      if (std::isnan(resolved_s)) resolved_s = iv.d0_m <= iv.d1_m ? iv.s0 : iv.s1;
      continue;
    }
    if (is_within_resolution) --refinements_left;
    if (!std::isnan(resolved_s) && samples_left-- == 0) break;
    // The step's tests spent (a step of absurd length): the interval is not certified.
    if (work->swept_tests >= kMaxSweptTests + kSweptTestsPerPair * work->swept_pairs) {
      if (std::isnan(resolved_s)) resolved_s = iv.d0_m <= iv.d1_m ? iv.s0 : iv.s1;
      break;
    }
    const double mid = 0.5 * (iv.s0 + iv.s1);
    const std::vector<Eigen::Isometry3d>& X_WL_mid = StepPoses(mid, q);
    const double mid_m = ShapeDistance(ShapeAt(a, X_WL_mid), ShapeAt(b, X_WL_mid)).distance_m;
    ++work->swept_tests;
    if (IsWarningDistance(mid_m, threshold_m)) {
      warn_at(mid, X_WL_mid);
      return;
    }
    // The earlier half first: the first contact along the step is the one reported.
    swept.stack[top++] = SweptInterval{mid, iv.s1, mid_m, iv.d1_m, iv.depth + 1};
    swept.stack[top++] = SweptInterval{iv.s0, mid, iv.d0_m, mid_m, iv.depth + 1};
  }
  if (!std::isnan(resolved_s)) warn_at(resolved_s, StepPoses(resolved_s, q));
}

}  // namespace arm_collision_monitor
