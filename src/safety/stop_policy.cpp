#include "arm_collision_monitor/safety/stop_policy.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace arm_collision_monitor {
namespace {

// Longest reason kept (characters): names of two primitives with where between samples, or a
// joint and a TF error, fit, and the note of a held stop after them.
// Of which the other stale joints' names may take (characters), leaving room for the rest.
constexpr std::size_t kReasonNamesCapacity = 120;

}  // namespace

SafetyStatus ToSafetyStatus(InputStatus status) {
  switch (status) {
    case InputStatus::kOk:
      return SafetyStatus::kOk;
    case InputStatus::kWrongSize:
      return SafetyStatus::kWrongSize;
    case InputStatus::kNonFinite:
      return SafetyStatus::kNonFinite;
    case InputStatus::kOutOfLimits:
      return SafetyStatus::kOutOfLimits;
  }
  return SafetyStatus::kWrongSize;
}

StopPolicy::StopPolicy(double stop_hold_s) : stop_hold_s_(stop_hold_s) {
  reason_.reserve(kReasonCapacity);
  condition_.reserve(kReasonCapacity);
  reason_ = "waiting for joint states";
}

void StopPolicy::Raise(Rank rank, SafetyStatus status, const char* format, ...) {
  if (rank <= rank_) {
    return;
  }
  char text[kReasonCapacity];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof(text), format, args);
  va_end(args);
  condition_.assign(text);
  rank_ = rank;
  if (status != SafetyStatus::kOk) {
    status_ = status;
  }
}

void StopPolicy::RaiseRefused(SafetyStatus status, const std::string& why) {
  Raise(Rank::kRefused, status, "input refused: %s%s%s%s", SafetyStatusName(status),
        why.empty() ? "" : " (", why.c_str(), why.empty() ? "" : ")");
}

void StopPolicy::RaiseStale(const JointMerger& input, double now_s) {
  const int oldest = input.OldestJoint();
  if (input.IsAwaitingInput(oldest)) {
    Raise(Rank::kStale, SafetyStatus::kStale,
          "joint '%s' not received since the clock went back %.3f s ago",
          input.joint_name(oldest).c_str(), input.JointAge(oldest, now_s));
    return;
  }
  // Every stale joint (a driver that died leaves all of its own), the oldest first, as many as
  // fit; the rest counted. A joint never received (one held at its default: the model is
  // complete) has no age and is not stale.
  const double timeout_s = input.input_timeout_s();
  char others[kReasonCapacity];
  std::size_t used = 0;
  int stale = 1;
  int unnamed = 0;
  others[0] = '\0';
  for (int i = 0; i < input.joint_count(); ++i) {
    const double age_s = input.JointAge(i, now_s);
    if (i == oldest || !(age_s > timeout_s) || std::isinf(age_s)) continue;
    ++stale;
    const std::string& name = input.joint_name(i);
    if (unnamed > 0 || used + name.size() + 4 > kReasonNamesCapacity) {
      ++unnamed;
      continue;
    }
    used += static_cast<std::size_t>(
        std::snprintf(others + used, sizeof(others) - used, ", '%s'", name.c_str()));
  }
  if (stale == 1) {
    Raise(Rank::kStale, SafetyStatus::kStale, "joint '%s' not received for %.3f s",
          input.joint_name(oldest).c_str(), input.JointAge(oldest, now_s));
    return;
  }
  char more[32] = "";
  if (unnamed > 0) std::snprintf(more, sizeof(more), " and %d more", unnamed);
  Raise(Rank::kStale, SafetyStatus::kStale,
        "%d joints not received for over input_timeout_s (%.3f s): '%s' for %.3f s%s%s", stale,
        timeout_s, input.joint_name(oldest).c_str(), input.JointAge(oldest, now_s), others, more);
}

double StopPolicy::ObserveClock(double now_s) {
  const double back_s = now_s < last_now_s_ ? last_now_s_ - now_s : 0.0;
  if (back_s > 0.0) {
    hold_until_s_ = now_s;
  }
  last_now_s_ = now_s;
  return back_s;
}

bool StopPolicy::BeginCycle(MergeStatus pending, const std::string& pending_why,
                            const JointMerger& input) {
  condition_.clear();
  rank_ = Rank::kNone;
  status_ = SafetyStatus::kOk;
  if (pending != MergeStatus::kAccepted) {
    RaiseRefused(ToSafetyStatus(pending), pending_why);
    return false;
  }
  if (!input.is_complete()) {
    const int count = input.missing_count();
    const char* first = input.joint_name(input.FirstMissingJoint()).c_str();
    if (count == 1) {
      Raise(Rank::kRefused, SafetyStatus::kIncomplete, "joint '%s' never received (%s)", first,
            JointDefaultsHint(1));
    } else {
      Raise(Rank::kRefused, SafetyStatus::kIncomplete,
            "%d joints never received, the first '%s' (%s)", count, first,
            JointDefaultsHint(static_cast<std::size_t>(count)));
    }
    return false;
  }
  return true;
}

void StopPolicy::OnObjectPoseUnavailable(const std::string& object, const std::string& frame,
                                         const std::string& error) {
  Raise(Rank::kObjectPose, SafetyStatus::kOk, "object '%s': pose from frame '%s' unavailable: %s",
        object.c_str(), frame.c_str(), error.c_str());
}

void StopPolicy::OnCycleReport(const CycleReport& report, const std::string& refusal,
                               const std::vector<PrimitiveSpec>& primitives,
                               const JointMerger& input, double now_s) {
  if (report.input != InputStatus::kOk) {
    RaiseRefused(ToSafetyStatus(report.input), refusal);
    return;
  }
  if (input.IsStale(now_s)) {
    RaiseStale(input, now_s);
  } else if (report.beyond_samples.is_beyond) {
    const StepBeyondSamples& beyond = report.beyond_samples;
    Raise(Rank::kJumped, SafetyStatus::kOk,
          "a step the samples do not cover (swept_check false): '%s' may move %.4f m in it, "
          "over its tolerance %.4f m",
          primitives[beyond.primitive].name.c_str(), beyond.motion_m, beyond.tolerance_m);
  } else if (report.input_jumped) {
    Raise(Rank::kJumped, SafetyStatus::kOk, "input jumped: a %.3f m step in one cycle",
          report.step_motion_m);
  } else if (!report.warnings.empty()) {
    char text[kReasonCapacity];
    FormatWarningsReason(report.warnings, primitives, text, sizeof(text));
    Raise(Rank::kWarning, SafetyStatus::kOk, "%s", text);
  }
}

void FormatWarningsReason(const std::vector<Warning>& warnings,
                          const std::vector<PrimitiveSpec>& primitives, char* text,
                          std::size_t size) {
  // The pair deepest in its tolerance zone (a touching pair before one near its threshold).
  const Warning& w = *std::min_element(
      warnings.begin(), warnings.end(), [](const Warning& x, const Warning& y) {
        return x.distance_m - x.threshold_m < y.distance_m - y.threshold_m;
      });
  // A pair found between samples says where; one not certified clear there (no sample inside
  // its threshold) says so.
  char where[128] = "";
  if (w.between_samples) {
    std::snprintf(where, sizeof(where), " between samples, at %.3f of the step%s",
                  w.step_fraction,
                  w.distance_m < w.threshold_m
                      ? ""
                      : " (above its threshold there: not certified clear)");
  }
  std::snprintf(text, size, "%zu warning(s), the deepest %s - %s at %.4f m (threshold %.4f m)%s",
                warnings.size(), primitives[w.a].name.c_str(), primitives[w.b].name.c_str(),
                w.distance_m, w.threshold_m, where);
}

void StopPolicy::EndCycle(double now_s) {
  if (rank_ != Rank::kNone) {
    stop_ = true;
    is_held_ = false;
    reason_.assign(condition_);
    hold_until_s_ = now_s + stop_hold_s_;
  } else if (stop_ && now_s >= hold_until_s_) {
    stop_ = false;
    reason_.clear();
  } else if (stop_ && !is_held_ && !reason_.empty()) {
    // The reason's own text stays first (a reader may match its start), within the capacity.
    char text[kReasonCapacity];
    std::snprintf(text, sizeof(text),
                  "%s (no longer seen; the stop is held for stop_hold_s, %g s)", reason_.c_str(),
                  stop_hold_s_);
    reason_.assign(text);
    is_held_ = true;
  }
}

StaleCheck StopPolicy::CheckStaleness(const JointMerger& input, double now_s) {
  StaleCheck check;
  if (!input.is_complete() || !input.IsStale(now_s)) {
    is_stale_episode_ = false;
    return check;
  }
  condition_.clear();
  rank_ = Rank::kNone;
  status_ = SafetyStatus::kOk;
  RaiseStale(input, now_s);
  EndCycle(now_s);
  check.is_stale = true;
  check.is_new_episode = !is_stale_episode_;
  is_stale_episode_ = true;
  return check;
}

}  // namespace arm_collision_monitor
