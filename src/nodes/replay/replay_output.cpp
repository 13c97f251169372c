// replay's outputs (replay_output.h).
#include "replay_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <utility>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {
namespace replay {
namespace {

// "1 cycle", "2 cycles": a count with its noun, plural unless one.
std::string Counted(unsigned long long count, const char* noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string PairSetKey(const std::vector<Warning>& warnings) {
  std::string key;
  for (const Warning& w : warnings) key += std::to_string(w.a) + "-" + std::to_string(w.b) + ";";
  return key;
}

// The broad-phase counters, by the names both outputs print them under.
constexpr std::pair<const char*, std::uint64_t BroadPhaseCounters::*> kCounters[] = {
    {"object_node_tests", &BroadPhaseCounters::object_node_tests},
    {"object_object_tests", &BroadPhaseCounters::object_object_tests},
    {"neighbours_visited", &BroadPhaseCounters::neighbours_visited},
    {"splits", &BroadPhaseCounters::splits},
    {"merges", &BroadPhaseCounters::merges},
    {"reinsert_fallbacks", &BroadPhaseCounters::reinsert_fallbacks},
    {"outside_world", &BroadPhaseCounters::outside_world},
    {"unlinked_changes", &BroadPhaseCounters::unlinked_changes}};

// The JSON header: input, method, grasp targets, message and cycle counts.
void PrintJsonCounts(const Options& options, const Input& input, std::size_t cycle_count,
                     const RunSummary& summary, bool is_swept) {
  std::printf("{\n  \"input\": %s,\n  \"every\": %d,\n  \"method\": %s,\n",
              JsonString(options.input).c_str(), options.every,
              JsonString(options.method).c_str());
  std::printf("  \"swept_check\": %s,\n", is_swept ? "true" : "false");
  std::printf("  \"grasp_targets\": [");
  for (std::size_t i = 0; i < options.grasp_targets.size(); ++i) {
    std::printf("%s[%s, %s]", i ? ", " : "", JsonString(options.grasp_targets[i].link).c_str(),
                JsonString(options.grasp_targets[i].object).c_str());
  }
  std::printf("],\n  \"messages\": %llu,\n  \"refused_messages\": {",
              static_cast<unsigned long long>(input.messages));
  bool comma = false;
  for (const auto& [status, count] : input.refused) {
    std::printf("%s%s: %llu", comma ? ", " : "", JsonString(status).c_str(),
                static_cast<unsigned long long>(count));
    comma = true;
  }
  std::printf("},\n  \"first_refused_message\": %s,\n",
              input.first_refused_message.empty()
                  ? "null"
                  : JsonString(input.first_refused_message).c_str());
  std::printf("  \"superseded_points\": %llu,\n  \"position_less_messages\": %llu,\n",
              static_cast<unsigned long long>(input.superseded_points),
              static_cast<unsigned long long>(input.position_less));
  std::printf("  \"clock_offsets\": {");
  comma = false;
  for (const auto& [topic, offset_s] : input.clock_offsets) {
    std::printf("%s%s: %.9g", comma ? ", " : "", JsonString(topic).c_str(), offset_s);
    comma = true;
  }
  std::printf("},\n");
  for (const auto& [key, names] : {std::pair{"ignored_columns", &input.ignored_columns},
                                   std::pair{"mimic_columns", &input.mimic_columns},
                                   std::pair{"ignored_names", &input.ignored_names},
                                   std::pair{"mimic_names", &input.mimic_names}}) {
    std::printf("  \"%s\": [", key);
    for (std::size_t i = 0; i < names->size(); ++i) {
      std::printf("%s%s", i > 0 ? ", " : "", JsonString((*names)[i]).c_str());
    }
    std::printf("],\n");
  }
  std::printf("  \"more_ignored_names\": %s,\n  \"more_mimic_names\": %s,\n",
              input.more_ignored_names ? "true" : "false",
              input.more_mimic_names ? "true" : "false");
  std::printf("  \"incomplete_cycles\": %llu,\n  \"cycles\": %zu,\n"
              "  \"refused_cycles\": %llu,\n  \"warning_cycles\": %llu,\n"
              "  \"between_samples_cycles\": %llu,\n  \"warned_cycles\": %llu,\n"
              "  \"jumped_cycles\": %llu,\n  \"beyond_samples_cycles\": %llu,\n",
              static_cast<unsigned long long>(input.incomplete_cycles), cycle_count,
              static_cast<unsigned long long>(summary.refused_cycles),
              static_cast<unsigned long long>(summary.warning_cycles),
              static_cast<unsigned long long>(summary.between_cycles),
              static_cast<unsigned long long>(summary.warned_cycles),
              static_cast<unsigned long long>(summary.jumped_cycles),
              static_cast<unsigned long long>(summary.beyond_samples_cycles));
}

// "[x, y, z]" of a vector, to the bit (17 significant digits).
std::string JsonVector(const Eigen::Vector3d& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "[%.17g, %.17g, %.17g]", v.x(), v.y(), v.z());
  return text;
}

// Every primitive as the monitor models it: its name, owner, model variant ("": the one active
// at start), the frame its geometry is given in (its link's, or for an object the fixed frame,
// the URDF's root, at its start pose) and that geometry to the bit, for a user's own reference
// to check the monitor's distances against; an object that moves at run time says how (the TF
// frame it follows, or attachable: a link may pick it up).
void PrintJsonPrimitives(const Workcell& wc) {
  std::printf("  \"primitives\": [");
  for (std::size_t id = 0; id < wc.primitives.size(); ++id) {
    const PrimitiveSpec& p = wc.primitives[id];
    const std::string frame =
        p.link_index >= 0 ? wc.kinematics.link_name(p.link_index) : wc.fixed_frame;
    std::printf("%s\n    {\"name\": %s, \"owner\": %s, \"variant\": %s, \"frame\": %s, "
                "\"tolerance_m\": %.17g, ",
                id > 0 ? "," : "", JsonString(p.name).c_str(), JsonString(p.owner).c_str(),
                JsonString(p.variant).c_str(), JsonString(frame).c_str(), p.tolerance_m);
    if (p.object_index >= 0) {
      const ObjectSpec& object = wc.objects[p.object_index];
      std::printf("\"follows_frame\": %s, \"attachable\": %s, ",
                  JsonString(object.frame).c_str(), object.is_attachable ? "true" : "false");
    }
    if (const auto* c = std::get_if<Capsule>(&p.shape_L)) {
      std::printf("\"capsule\": {\"p0_m\": %s, \"p1_m\": %s, \"radius_m\": %.17g}}",
                  JsonVector(c->p0_W).c_str(), JsonVector(c->p1_W).c_str(), c->radius_m);
      continue;
    }
    const Box& b = std::get<Box>(p.shape_L);
    const Eigen::Matrix3d& R = b.X_WB.linear();
    std::printf("\"box\": {\"center_m\": %s, \"axes\": [%s, %s, %s], "
                "\"half_extents_m\": %s}}",
                JsonVector(b.X_WB.translation()).c_str(), JsonVector(R.col(0)).c_str(),
                JsonVector(R.col(1)).c_str(), JsonVector(R.col(2)).c_str(),
                JsonVector(b.half_extents_m).c_str());
  }
  std::printf("\n  ],\n");
}

// Runs of consecutive cycles with the same warning pairs, one line per pair, with the smallest
// distance over the run.
void PrintWarningRuns(const Workcell& wc, const Input& input,
                      const std::vector<CycleResult>& cycles) {
  auto name = [&](PrimitiveId id) { return wc.primitives[id].name; };
  std::size_t k = 0;
  while (k < cycles.size()) {
    if (cycles[k].warnings.empty()) {
      ++k;
      continue;
    }
    const std::string key = PairSetKey(cycles[k].warnings);
    std::size_t end = k + 1;
    while (end < cycles.size() && PairSetKey(cycles[end].warnings) == key) ++end;
    std::printf("cycles %zu-%zu (%.2f-%.2f s):\n", CycleNumber(input, k),
                CycleNumber(input, end - 1), input.time_s[k], input.time_s[end - 1]);
    for (std::size_t i = 0; i < cycles[k].warnings.size(); ++i) {
      const Warning& w = cycles[k].warnings[i];
      double closest_m = w.distance_m;
      for (std::size_t j = k; j < end; ++j) {
        closest_m = std::min(closest_m, cycles[j].warnings[i].distance_m);
      }
      std::printf("  %-22s -- %-22s  %.4f m at first, closest %.4f m (threshold %.4f m)\n",
                  name(w.a).c_str(), name(w.b).c_str(), w.distance_m, closest_m, w.threshold_m);
    }
    k = end;
  }
}

// What a between-samples warning is, beside a contact strictly between the samples: the step
// starts within the zone (the previous sample's warning, and the pair left the zone during the
// step), or the swept check could not certify the pair clear to swept_resolution_m there (at a
// point whose own distance is above the threshold).
enum class BetweenKind { kStrictlyBetween, kFromTheStart, kWithinResolution };

BetweenKind KindOf(const Warning& w) {
  if (!IsWarningDistance(w.distance_m, w.threshold_m)) return BetweenKind::kWithinResolution;
  return w.step_fraction == 0.0 ? BetweenKind::kFromTheStart : BetweenKind::kStrictlyBetween;
}

// Per BetweenKind, in its order: its name in --json and its note in the text.
struct BetweenKindText {
  const char* name;
  const char* note;
};
constexpr BetweenKindText kBetweenKinds[] = {
    {"strictly_between", ""},
    {"step_starts_within", " (the step starts within: the previous sample's warning)"},
    {"within_resolution",
     " (above the threshold here; not certified clear near it)"}};

const char* KindName(const Warning& w) { return kBetweenKinds[static_cast<int>(KindOf(w))].name; }

// The swept check's warnings, one line each (the first kMaxLines, then how many more) with what
// each is, and the counts.
void PrintBetweenSamples(const Workcell& wc, const Input& input,
                         const std::vector<CycleResult>& cycles, const RunSummary& summary) {
  constexpr int kMaxLines = 20;
  int lines = 0;
  // Cycles by their between-samples warnings: any contact strictly between the samples, else
  // only of one other kind, else of both.
  std::uint64_t strictly = 0, only_start = 0, only_resolution = 0, both = 0;
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    if (cycles[k].between_samples.empty()) continue;
    bool has_kind[3] = {false, false, false};
    for (const Warning& w : cycles[k].between_samples) {
      const BetweenKind kind = KindOf(w);
      has_kind[static_cast<int>(kind)] = true;
      if (lines++ >= kMaxLines) continue;
      std::printf("cycle %zu (%.2f s), between samples at %.3f of the step: %s -- %s  %.4f m "
                  "(threshold %.4f m)%s\n",
                  CycleNumber(input, k), input.time_s[k], w.step_fraction,
                  wc.primitives[w.a].name.c_str(),
                  wc.primitives[w.b].name.c_str(), w.distance_m, w.threshold_m,
                  kBetweenKinds[static_cast<int>(kind)].note);
    }
    const bool is_start = has_kind[static_cast<int>(BetweenKind::kFromTheStart)];
    const bool is_resolution = has_kind[static_cast<int>(BetweenKind::kWithinResolution)];
    if (has_kind[static_cast<int>(BetweenKind::kStrictlyBetween)]) {
      ++strictly;
    } else if (is_start && is_resolution) {
      ++both;
    } else {
      only_start += is_start;
      only_resolution += is_resolution;
    }
  }
  if (lines > kMaxLines) {
    std::printf("... and %d more between-samples warnings, not printed (--json lists all)\n",
                lines - kMaxLines);
  }
  std::printf("swept check: %llu cycles warn between samples: %llu with a pair within its "
              "threshold strictly between them, %llu only where the step starts within, %llu "
              "only within swept_resolution_m, %llu with both of those; %llu steps beyond "
              "max_step_m\n",
              static_cast<unsigned long long>(summary.between_cycles),
              static_cast<unsigned long long>(strictly),
              static_cast<unsigned long long>(only_start),
              static_cast<unsigned long long>(only_resolution),
              static_cast<unsigned long long>(both),
              static_cast<unsigned long long>(summary.jumped_cycles));
}

// The "input:" lines: what the input had that no cycle checks (refused messages and cycles,
// ignored columns and mimic joints' ones, a bag's ignored and mimic joint names, position-less
// messages, superseded planned points). An ignored name of one of the `model`'s fixed joints
// says so.
void PrintInputLines(const Input& input, const std::vector<CycleResult>& cycles,
                     const RunSummary& summary, const KinematicModel& model) {
  if (summary.refused_messages > 0 || input.incomplete_cycles > 0 || summary.refused_cycles > 0) {
    std::printf("input: %s refused", Counted(summary.refused_messages, "message").c_str());
    for (const auto& [status, count] : input.refused) {
      std::printf(" (%s: %llu)", status.c_str(), static_cast<unsigned long long>(count));
    }
    if (!input.first_refused_message.empty()) {
      std::printf(" (the first %s)", input.first_refused_message.c_str());
    }
    std::printf(", %s before every joint was received, %s refused by the monitor",
                Counted(input.incomplete_cycles, "cycle").c_str(),
                Counted(summary.refused_cycles, "cycle").c_str());
    if (summary.first_refused >= 0) {
      std::printf(" (the first, cycle %zu at %.3f s: %s)",
                  CycleNumber(input, summary.first_refused),
                  input.time_s[summary.first_refused],
                  cycles[summary.first_refused].refusal.c_str());
    }
    std::printf("\n");
  }
  // The names, quoted; a fixed joint's marked, since a driver may publish one (a Sawyer's
  // torso_t0) and a user reading "no joints of the model" looks for a typo.
  auto described = [&](const std::vector<std::string>& names) {
    std::string text;
    for (const std::string& name : names) {
      text += (text.empty() ? "'" : ", '") + name + "'" +
              (model.IsFixedJoint(name) ? " (a fixed joint of the URDF)" : "");
    }
    return text;
  };
  if (!input.ignored_columns.empty()) {
    std::printf("input: %zu column%s ignored, not joints of the model: %s\n",
                input.ignored_columns.size(), input.ignored_columns.size() == 1 ? "" : "s",
                described(input.ignored_columns).c_str());
  }
  if (!input.mimic_columns.empty()) {
    std::printf("input: %zu column%s of mimic joints not read (their positions follow from the "
                "joints they mimic in the URDF): %s\n",
                input.mimic_columns.size(), input.mimic_columns.size() == 1 ? "" : "s",
                QuotedNames(input.mimic_columns).c_str());
  }
  // A bag's names, noted up to kNotedNames of each kind.
  auto noted = [&](const std::vector<std::string>& names, bool more) {
    return described(names) + (more ? ", and more" : "");
  };
  if (!input.ignored_names.empty()) {
    std::printf("input: joint names in the messages that are no joints of the model, ignored: "
                "%s\n", noted(input.ignored_names, input.more_ignored_names).c_str());
  }
  if (!input.mimic_names.empty()) {
    std::printf("input: mimic joints in the messages, not read (their positions follow from the "
                "joints they mimic in the URDF): %s\n",
                noted(input.mimic_names, input.more_mimic_names).c_str());
  }
  for (const auto& [topic, offset_s] : input.clock_offsets) {
    std::printf("input: %s is stamped %.3f s %s the times the bag recorded it, as a rule: read "
                "as it is (a robot's clock off the recorder's), where a node on the recorder's "
                "clock refuses such stamps as %s beyond its input_timeout_s (%.2f s by default): "
                "set the robot's clock (chrony, NTP)\n",
                topic.c_str(), std::abs(offset_s), offset_s < 0.0 ? "behind" : "ahead of",
                offset_s < 0.0 ? "stale" : "future_stamp", kDefaultInputTimeout_s);
  }
  if (input.position_less > 0) {
    std::printf("input: %llu messages named joints without positions (ignored)\n",
                static_cast<unsigned long long>(input.position_less));
  }
  if (input.superseded_points > 0) {
    std::printf("input: %llu planned points superseded (for some or all of their joints) by a "
                "later plan\n",
                static_cast<unsigned long long>(input.superseded_points));
  }
}

}  // namespace

RunSummary Summarize(const Input& input, const std::vector<CycleResult>& cycles,
                     const BroadPhaseCounters& counters) {
  RunSummary summary;
  std::vector<double> times, moving_times;
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    times.push_back(cycles[k].time_s);
    if (cycles[k].is_moving) moving_times.push_back(cycles[k].time_s);
    summary.refused_cycles += cycles[k].refused;
    if (cycles[k].refused && summary.first_refused < 0) {
      summary.first_refused = static_cast<int>(k);
    }
    if (!cycles[k].warnings.empty()) {
      ++summary.warning_cycles;
      if (summary.first < 0) summary.first = static_cast<int>(k);
    }
    if (!cycles[k].between_samples.empty()) {
      ++summary.between_cycles;
      if (summary.first_between < 0) summary.first_between = static_cast<int>(k);
    }
    summary.warned_cycles += !cycles[k].warnings.empty() || !cycles[k].between_samples.empty();
    summary.jumped_cycles += cycles[k].is_jumped;
    summary.beyond_samples_cycles += cycles[k].is_beyond_samples;
  }
  summary.time_s = SummarizeTimings(std::move(times));
  summary.moving_time_s = SummarizeTimings(std::move(moving_times));
  summary.counters = counters;
  for (const auto& [status, count] : input.refused) summary.refused_messages += count;
  return summary;
}

void PrintJson(const Options& options, const Workcell& wc, const Input& input,
               const std::vector<CycleResult>& cycles, const RunSummary& summary,
               bool is_swept) {
  auto name = [&](PrimitiveId id) { return JsonString(wc.primitives[id].name); };
  PrintJsonCounts(options, input, cycles.size(), summary, is_swept);
  PrintJsonPrimitives(wc);
  if (summary.first >= 0) {
    const Warning& w = cycles[summary.first].warnings.front();
    std::printf("  \"first_warning\": {\"cycle\": %zu, \"time_s\": %.9f, \"a\": %s, \"b\": %s, "
                "\"distance_m\": %.17g, \"threshold_m\": %.17g},\n",
                CycleNumber(input, summary.first), input.time_s[summary.first], name(w.a).c_str(),
                name(w.b).c_str(), w.distance_m, w.threshold_m);
  } else {
    std::printf("  \"first_warning\": null,\n");
  }
  if (summary.first_between >= 0) {
    const Warning& w = cycles[summary.first_between].between_samples.front();
    std::printf("  \"first_between_samples\": {\"cycle\": %zu, \"time_s\": %.9f, \"a\": %s, "
                "\"b\": %s, \"distance_m\": %.17g, \"threshold_m\": %.17g, \"step_fraction\": "
                "%.17g, \"kind\": \"%s\"},\n",
                CycleNumber(input, summary.first_between), input.time_s[summary.first_between],
                name(w.a).c_str(),
                name(w.b).c_str(), w.distance_m, w.threshold_m, w.step_fraction, KindName(w));
  } else {
    std::printf("  \"first_between_samples\": null,\n");
  }
  if (summary.first_refused >= 0) {
    std::printf("  \"first_refusal\": {\"cycle\": %zu, \"time_s\": %.9f, \"reason\": %s},\n",
                CycleNumber(input, summary.first_refused), input.time_s[summary.first_refused],
                JsonString(cycles[summary.first_refused].refusal).c_str());
  } else {
    std::printf("  \"first_refusal\": null,\n");
  }
  for (const auto& [key, t] : {std::make_pair("cycle_time_s", summary.time_s),
                                std::make_pair("moving_cycle_time_s", summary.moving_time_s)}) {
    std::printf("  \"%s\": {\"p50\": %.9g, \"p99\": %.9g, \"max\": %.9g, \"mean\": %.9g},\n",
                key, t.median, t.p99, t.max, t.mean);
  }
  std::printf("  \"moving_cycles\": %llu,\n",
              static_cast<unsigned long long>(summary.moving_time_s.count));
  std::printf("  \"counters\": {");
  for (std::size_t i = 0; i < std::size(kCounters); ++i) {
    std::printf("%s\"%s\": %llu", i ? ", " : "", kCounters[i].first,
                static_cast<unsigned long long>(summary.counters.*kCounters[i].second));
  }
  std::printf("},\n");
  // One entry per cycle: [[a, b, distance_m, threshold_m], ...] at its q (empty when clear),
  // and the swept check's [[a, b, distance_m, step_fraction, kind, threshold_m], ...] between
  // the previous cycle's q and this (kind: KindName). Distances, thresholds and fractions to the
  // bit (17 digits; a fraction is k / 2^n, n up to kMaxSweptBisections), as in first_warning and
  // first_between_samples: a warning a few ULP inside its threshold reads as one.
  std::printf("  \"per_cycle\": [");
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    std::printf("%s\n    {\"cycle\": %zu, \"time_s\": %.9f, \"refused\": %s, \"warnings\": [",
                k ? "," : "", CycleNumber(input, k), input.time_s[k],
                cycles[k].refused ? "true" : "false");
    for (std::size_t i = 0; i < cycles[k].warnings.size(); ++i) {
      const Warning& w = cycles[k].warnings[i];
      std::printf("%s[%s, %s, %.17g, %.17g]", i ? ", " : "", name(w.a).c_str(),
                  name(w.b).c_str(), w.distance_m, w.threshold_m);
    }
    std::printf("], \"between_samples\": [");
    for (std::size_t i = 0; i < cycles[k].between_samples.size(); ++i) {
      const Warning& w = cycles[k].between_samples[i];
      std::printf("%s[%s, %s, %.17g, %.17g, \"%s\", %.17g]", i ? ", " : "", name(w.a).c_str(),
                  name(w.b).c_str(), w.distance_m, w.step_fraction, KindName(w), w.threshold_m);
    }
    std::printf("]}");
  }
  std::printf("\n  ]\n}\n");
}

// The first line: the input, the method, what was checked.
void PrintHeader(const Options& options, const Input& input, std::size_t cycle_count,
                 bool is_swept) {
  std::printf("replay %s: method %s (%s), %s", options.input.c_str(), options.method.c_str(),
              is_swept ? "swept check on" : "samples only",
              Counted(cycle_count, "cycle").c_str());
  if (options.every > 1) {
    std::printf(" of %zu (--every %d: cycles 0, %d, %d, ...)", input.all_cycles, options.every,
                options.every, 2 * options.every);
  }
  std::printf(" from %s", Counted(input.messages, "message").c_str());
  for (const TaskGraspTarget& t : options.grasp_targets) {
    std::printf(", grasp target %s:%s", t.link.c_str(), t.object.c_str());
  }
  std::printf("\n");
}

void PrintText(const Options& options, const Workcell& wc, const Input& input,
               const std::vector<CycleResult>& cycles, const RunSummary& summary,
               bool is_swept) {
  PrintHeader(options, input, cycles.size(), is_swept);
  PrintInputLines(input, cycles, summary, wc.kinematics);
  PrintWarningRuns(wc, input, cycles);
  if (is_swept) PrintBetweenSamples(wc, input, cycles, summary);
  // Refused cycles and messages are not checked (the monitor asks a stop instead), and a step
  // beyond max_step_m is a stop too (checked all the same): the summary says how many, so that
  // such input never reads as clear.
  const unsigned long long refused = summary.refused_cycles;
  std::string unchecked;
  if (refused > 0) {
    unchecked += "; " + Counted(refused, "cycle") + " refused, not checked (the monitor " +
                 "asks a stop on each; see 'input:' above)";
  }
  const std::uint64_t jumped = summary.jumped_cycles - summary.beyond_samples_cycles;
  if (jumped > 0) {
    unchecked += "; " + Counted(jumped, "step") +
                 " beyond max_step_m (input_jumped: the monitor asks a stop on each)";
  }
  if (summary.beyond_samples_cycles > 0) {
    unchecked += "; " + Counted(summary.beyond_samples_cycles, "step") +
                 " the samples do not cover, each moving a primitive farther than its tolerance "
                 "(swept_check false; input_jumped: the monitor asks a stop on each)";
  }
  std::string refused_messages;
  if (summary.refused_messages > 0) {
    refused_messages = "; " + Counted(summary.refused_messages, "message") + " or planned " +
                       (summary.refused_messages == 1 ? "point" : "points") +
                       " refused, no cycle (the node asks a stop on a message; see 'input:' " +
                       "above)";
  }
  unchecked += refused_messages;
  // The first warning, at a sample or between two (the node stops on either).
  const bool is_first_between =
      summary.first_between >= 0 && (summary.first < 0 || summary.first_between < summary.first);
  const int first = is_first_between ? summary.first_between : summary.first;
  if (first >= 0) {
    const Warning& w = is_first_between ? cycles[first].between_samples.front()
                                        : cycles[first].warnings.front();
    char where[64] = "";
    if (is_first_between) {
      std::snprintf(where, sizeof(where), " between samples, at %.3f of the step",
                    w.step_fraction);
    }
    std::printf("summary: %llu of %zu cycles warn (%llu at their sample, %llu only between "
                "samples); first at cycle %zu (%.2f s): %s -- %s at %.4f m%s%s\n",
                static_cast<unsigned long long>(summary.warned_cycles), cycles.size(),
                static_cast<unsigned long long>(summary.warning_cycles),
                static_cast<unsigned long long>(summary.warned_cycles - summary.warning_cycles),
                CycleNumber(input, first), input.time_s[first], wc.primitives[w.a].name.c_str(),
                wc.primitives[w.b].name.c_str(), w.distance_m, where, unchecked.c_str());
  } else if (refused > 0 && refused == cycles.size()) {
    std::printf("summary: no cycle checked: all %llu refused (the monitor asks a stop on each; "
                "see 'input:' above)%s\n",
                refused, refused_messages.c_str());
  } else {
    std::printf("summary: no warning in %s%s\n", Counted(cycles.size(), "cycle").c_str(),
                unchecked.c_str());
  }
  const TimingSummary& t = summary.time_s;
  const TimingSummary& m = summary.moving_time_s;
  std::printf("cycle time: p50 %.1f us, p99 %.1f us, max %.1f us, mean %.1f us; the %s "
              "(the first, and q changed): p50 %.1f us, p99 %.1f us, max %.1f us, mean %.1f "
              "us\n",
              t.median * 1e6, t.p99 * 1e6, t.max * 1e6, t.mean * 1e6,
              Counted(m.count, "moving cycle").c_str(), m.median * 1e6, m.p99 * 1e6,
              m.max * 1e6, m.mean * 1e6);
  std::printf("broad phase:");
  for (std::size_t i = 0; i < std::size(kCounters); ++i) {
    std::string label = kCounters[i].first;
    std::replace(label.begin(), label.end(), '_', ' ');
    std::printf("%s %llu %s", i ? "," : "",
                static_cast<unsigned long long>(summary.counters.*kCounters[i].second),
                label.c_str());
  }
  std::printf("\n");
}

}  // namespace replay
}  // namespace arm_collision_monitor
