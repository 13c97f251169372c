// replay: checks a recorded or planned trajectory offline, without ROS running. Reads a bag of
// sensor_msgs/JointState (any topics, merged by joint name with the node's JointMerger) or
// a joint CSV file (tasks/joint_csv.h), runs the Monitor (or a peer checker) once per cycle and
// prints the warnings, the cycle times and the broad-phase counters, as text or JSON.
//
//   rosrun arm_collision_monitor replay [options] <file.bag | file.csv>
//
// Start-up is the node's (MonitorNode): the config's tolerance_m reaches LoadWorkcell and the
// workcell's start-up findings are printed (on stderr) before the run.
// A bag cycle is one sample of every arm: consecutive messages with the same header stamp are
// merged, then the Monitor runs once (the node instead runs once per message; see README).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <iterator>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ros/package.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/JointState.h>

#include "arm_collision_monitor/core/timing_summary.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/monitor/monitor_startup.h"
#include "arm_collision_monitor/ros/conversions.h"
#include "arm_collision_monitor/ros/resource_fetch_ros.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"
#include "arm_collision_monitor/tasks/joint_csv.h"
#include "arm_collision_monitor/tasks/task_trajectories.h"
#ifdef ACM_HAVE_PEERS
#include "arm_collision_monitor/peers/peer_checker.h"
#endif

namespace arm_collision_monitor {
namespace {

struct Options {
  std::string urdf, scene, config;
  std::string method = "auto";
  bool json = false;
  std::vector<TaskGraspTarget> grasp_targets;
  std::string input;
  bool help = false;  ///< -h or --help: print the usage on stdout and exit 0
};

const char* kUsage =
    "usage: replay [options] <file.bag | file.csv>\n"
    "  Runs the collision monitor offline over a trajectory and reports, per cycle, every pair\n"
    "  closer than its tolerances, plus cycle times and broad-phase counters.\n"
    "  file.bag: sensor_msgs/JointState on any topics, merged by joint name; messages with\n"
    "            equal header stamps form one cycle.\n"
    "  file.csv: a header row of joint names (optionally 'time_s' first), one row per cycle.\n"
    "options:\n"
    "  --urdf F --scene F --config F   workcell and monitor options (default: the package's\n"
    "                                  urdf/workcell.urdf, config/scene.yaml,\n"
    "                                  config/monitor.yaml)\n"
    "  --method M     auto | octree | naive | grid | rebuild | reinsert"
#ifdef ACM_HAVE_PEERS
    " | fcl | bullet"
#endif
    "\n"
    "                 (default auto; overrides the config's broad_phase)\n"
    "  --grasp L:O    declare object O the grasp target of link L before the first cycle\n"
    "                 (repeatable)\n"
    "  --task N       the grasp targets of the seed's task N (task 3: right_link7:front_box)\n"
    "  --json         machine-readable output\n"
    "  -h, --help     this text (on stdout)\n"
    "The monitor options are loaded before the workcell and give it the default arm tolerance,\n"
    "as in the node; the workcell's start-up findings are printed on stderr before the run.\n";

bool ParseOptions(int argc, char** argv, Options* options, std::string* error) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](std::string* out) {
      if (i + 1 >= argc) {
        *error = arg + " needs a value";
        return false;
      }
      *out = argv[++i];
      return true;
    };
    std::string v;
    if (arg == "--json") {
      options->json = true;
    } else if (arg == "--urdf") {
      if (!value(&options->urdf)) return false;
    } else if (arg == "--scene") {
      if (!value(&options->scene)) return false;
    } else if (arg == "--config") {
      if (!value(&options->config)) return false;
    } else if (arg == "--method") {
      if (!value(&options->method)) return false;
    } else if (arg == "--grasp") {
      if (!value(&v)) return false;
      const std::size_t colon = v.find(':');
      if (colon == std::string::npos || colon == 0 || colon + 1 == v.size()) {
        *error = "--grasp expects link:object, got '" + v + "'";
        return false;
      }
      options->grasp_targets.push_back({v.substr(0, colon), v.substr(colon + 1)});
    } else if (arg == "--task") {
      if (!value(&v)) return false;
      const int task = std::atoi(v.c_str());
      if (task < 1 || task > kTaskCount || v != std::to_string(task)) {
        *error = "--task expects 1.." + std::to_string(kTaskCount) + ", got '" + v + "'";
        return false;
      }
      for (const TaskGraspTarget& t : GetTaskSpec(task).grasp_targets) {
        options->grasp_targets.push_back(t);
      }
    } else if (arg == "-h" || arg == "--help") {
      options->help = true;
      return true;
    } else if (!arg.empty() && arg[0] == '-') {
      *error = "unknown option " + arg;
      return false;
    } else if (options->input.empty()) {
      options->input = arg;
    } else {
      *error = "one input file only";
      return false;
    }
  }
  if (options->input.empty()) *error = "no input file";
  return error->empty();
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The input as one q per cycle (model order) with its time, plus what was refused on the way.
struct Input {
  std::vector<Eigen::VectorXd> q;
  std::vector<double> time_s;  ///< since the first cycle
  std::uint64_t messages = 0;
  std::map<std::string, std::uint64_t> refused;  ///< MergeStatusName -> count
  std::uint64_t incomplete_cycles = 0;           ///< before every joint was received
};

Input ReadBag(const std::string& path, const Workcell& workcell) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TypeQuery("sensor_msgs/JointState"));
  if (view.size() == 0) throw LoadError(path + ": no sensor_msgs/JointState message");
  // The stamp checks compare each message with its own stamp as "now": offline, time is the
  // bag's. The timeout only bounds stamps going backwards, which is still refused.
  JointMerger input(workcell.joint_names, 1.0);
  Input result;
  ros::Time group_stamp, first_stamp;
  bool has_group = false;
  auto flush = [&] {
    if (!has_group) return;
    if (!input.is_complete()) {
      ++result.incomplete_cycles;
      return;
    }
    if (result.q.empty()) first_stamp = group_stamp;
    result.q.push_back(input.q());
    result.time_s.push_back((group_stamp - first_stamp).toSec());
  };
  for (const rosbag::MessageInstance& m : view) {
    const sensor_msgs::JointState::ConstPtr msg = m.instantiate<sensor_msgs::JointState>();
    if (!msg) continue;
    ++result.messages;
    if (has_group && msg->header.stamp != group_stamp) flush();
    if (!has_group || msg->header.stamp != group_stamp) {
      group_stamp = msg->header.stamp;
      has_group = true;
    }
    const MergeStatus status =
        input.Merge(ToNamedPositions(*msg), msg->header.stamp.toSec());
    if (status != MergeStatus::kAccepted) ++result.refused[MergeStatusName(status)];
  }
  flush();
  return result;
}

Input ReadCsv(const std::string& path, const Workcell& workcell) {
  const JointCsv csv = ReadJointCsv(path);
  Input result;
  result.q = JointCsvInModelOrder(csv, workcell.joint_names);
  for (const double t : csv.time_s) result.time_s.push_back(t - csv.time_s.front());
  result.messages = result.q.size();
  return result;
}

// One cycle's outcome: warning pairs with their distances at the cycle's q, those the swept
// check found between the previous cycle's q and this one's (the Monitor only: the peers check
// the samples), and the wall time of the check.
struct CycleResult {
  std::vector<Warning> warnings;
  std::vector<Warning> between_samples;
  bool refused = false;
  bool is_jumped = false;
  double time_s = 0.0;
};

// The checker under test: the Monitor with a broad phase, or (when built with them) a peer.
class Checker {
 public:
  virtual ~Checker() = default;
  virtual void Run(const Eigen::VectorXd& q, CycleResult* result) = 0;
  virtual BroadPhaseCounters counters() const { return {}; }
  /// Whether the steps between samples are checked too (the Monitor's swept check).
  virtual bool is_swept() const { return false; }
};

class MonitorChecker : public Checker {
 public:
  MonitorChecker(std::shared_ptr<const Workcell> workcell, const MonitorOptions& options,
                 const std::vector<TaskGraspTarget>& targets)
      : monitor_(std::move(workcell), options) {
    for (const std::string& notice : monitor_.startup_notices()) {
      std::fprintf(stderr, "replay: %s\n", notice.c_str());
    }
    for (const TaskGraspTarget& t : targets) {
      std::string error;
      if (!monitor_.SetGraspTarget(t.link, t.object, true, &error)) {
        throw LoadError("--grasp " + t.link + ":" + t.object + ": " + error);
      }
    }
  }
  void Run(const Eigen::VectorXd& q, CycleResult* result) override {
    const auto start = std::chrono::steady_clock::now();
    const CycleReport& report = monitor_.Update(q);
    result->time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result->warnings.clear();
    result->between_samples.clear();
    for (const Warning& w : report.warnings) {
      (w.between_samples ? result->between_samples : result->warnings).push_back(w);
    }
    result->refused = report.input != InputStatus::kOk;
    result->is_jumped = report.input_jumped;
  }
  BroadPhaseCounters counters() const override { return monitor_.total_counters(); }
  bool is_swept() const override { return monitor_.options().swept_check; }

 private:
  Monitor monitor_;
};

#ifdef ACM_HAVE_PEERS
// A peer (FCL, Bullet) on the workcell's default model: the primitives of every link's default
// variant move with their link, environment objects stay where the scene puts them (replay has
// no TF); grasp targets are compatible. The peers return pairs only: the distances printed are
// computed afterwards with ShapeDistance, outside the timed part.
class PeerCycleChecker : public Checker {
 public:
  PeerCycleChecker(std::shared_ptr<const Workcell> workcell, const std::string& name,
                   const std::vector<TaskGraspTarget>& targets)
      : workcell_(std::move(workcell)), shapes_(*workcell_) {
    const Workcell& wc = *workcell_;
    CompatibilityMatrix compatible = wc.compatible;
    for (const TaskGraspTarget& t : targets) {
      const int link = wc.kinematics.FindLink(t.link);
      const int object = wc.FindObject(t.object);
      if (link < 0 || object < 0) {
        throw LoadError("--grasp " + t.link + ":" + t.object + ": unknown link or object");
      }
      const ObjectSpec& target = wc.objects[object];
      for (std::size_t i = 0; i < wc.primitives.size(); ++i) {
        if (wc.primitives[i].link_index != link) continue;
        for (int k = 0; k < target.primitive_count; ++k) {
          compatible.Set(static_cast<PrimitiveId>(i), target.primitive + k, true);
        }
      }
    }
    // Home-pose shapes; only link primitives move (objects stay where the scene puts them).
    std::vector<PeerPrimitive> primitives(wc.primitives.size());
    for (std::size_t i = 0; i < wc.primitives.size(); ++i) {
      const PrimitiveSpec& p = wc.primitives[i];
      const auto id = static_cast<PrimitiveId>(i);
      primitives[i] = PeerPrimitive{shapes_.shape_W(id), p.tolerance_m,
                                    p.link_index >= 0 && !p.is_static,
                                    shapes_.is_default_model(id)};
    }
    peer_ = name == "fcl" ? MakeFclChecker(primitives, compatible, PeerTolerance::kRounded)
                          : MakeBulletChecker(primitives, compatible, PeerTolerance::kRounded);
  }
  void Run(const Eigen::VectorXd& q, CycleResult* result) override {
    const Workcell& wc = *workcell_;
    const auto start = std::chrono::steady_clock::now();
    shapes_.Evaluate(q);
    for (const PrimitiveId id : shapes_.moving()) peer_->SetShape(id, shapes_.shape_W(id));
    peer_->FindWarnings(&pairs_);
    result->time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result->refused = false;
    result->warnings.clear();
    for (const CandidatePair& pair : pairs_) {
      const DistanceResult d = ShapeDistance(shapes_.shape_W(pair.a), shapes_.shape_W(pair.b));
      Warning w;
      w.a = pair.a;
      w.b = pair.b;
      w.distance_m = d.distance_m;
      w.threshold_m = wc.primitives[pair.a].tolerance_m + wc.primitives[pair.b].tolerance_m;
      result->warnings.push_back(w);
    }
  }

 private:
  std::shared_ptr<const Workcell> workcell_;
  WorkcellShapes shapes_;
  std::vector<CandidatePair> pairs_;
  std::unique_ptr<PeerChecker> peer_;
};
#endif

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

// The checker that --method names: the Monitor with that broad phase (overriding the config's),
// or a peer.
std::unique_ptr<Checker> MakeChecker(const Options& options,
                                     const std::shared_ptr<const Workcell>& workcell,
                                     MonitorOptions monitor_options) {
  BroadPhaseMethod method;
  if (ParseBroadPhaseMethod(options.method, &method)) {
    monitor_options.broad_phase.method = method;
    return std::make_unique<MonitorChecker>(workcell, monitor_options, options.grasp_targets);
  }
#ifdef ACM_HAVE_PEERS
  if (options.method == "fcl" || options.method == "bullet") {
    return std::make_unique<PeerCycleChecker>(workcell, options.method, options.grasp_targets);
  }
#endif
  throw LoadError("--method: unknown method '" + options.method + "'");
}

// What both output formats report about the whole run.
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

struct RunSummary {
  std::uint64_t warning_cycles = 0, refused_cycles = 0;
  int first = -1;  ///< the first cycle with a warning at its q, -1 if none
  std::uint64_t between_cycles = 0;  ///< cycles with a warning between samples (swept check)
  int first_between = -1;            ///< the first of those, -1 if none
  std::uint64_t jumped_cycles = 0;   ///< steps beyond max_step_m
  TimingSummary time_s;
  BroadPhaseCounters counters;
  std::uint64_t refused_messages = 0;
};

RunSummary Summarize(const Input& input, const std::vector<CycleResult>& cycles,
                     const Checker& checker) {
  RunSummary summary;
  std::vector<double> times;
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    times.push_back(cycles[k].time_s);
    summary.refused_cycles += cycles[k].refused;
    if (!cycles[k].warnings.empty()) {
      ++summary.warning_cycles;
      if (summary.first < 0) summary.first = static_cast<int>(k);
    }
    if (!cycles[k].between_samples.empty()) {
      ++summary.between_cycles;
      if (summary.first_between < 0) summary.first_between = static_cast<int>(k);
    }
    summary.jumped_cycles += cycles[k].is_jumped;
  }
  summary.time_s = SummarizeTimings(std::move(times));
  summary.counters = checker.counters();
  for (const auto& [status, count] : input.refused) summary.refused_messages += count;
  return summary;
}

// The JSON header: input, method, grasp targets, message and cycle counts.
void PrintJsonCounts(const Options& options, const Input& input, std::size_t cycle_count,
                     const RunSummary& summary, bool is_swept) {
  std::printf("{\n  \"input\": %s,\n  \"method\": %s,\n  \"swept_check\": %s,\n",
              JsonString(options.input).c_str(), JsonString(options.method).c_str(),
              is_swept ? "true" : "false");
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
  std::printf("},\n  \"incomplete_cycles\": %llu,\n  \"cycles\": %zu,\n"
              "  \"refused_cycles\": %llu,\n  \"warning_cycles\": %llu,\n"
              "  \"between_samples_cycles\": %llu,\n  \"jumped_cycles\": %llu,\n",
              static_cast<unsigned long long>(input.incomplete_cycles), cycle_count,
              static_cast<unsigned long long>(summary.refused_cycles),
              static_cast<unsigned long long>(summary.warning_cycles),
              static_cast<unsigned long long>(summary.between_cycles),
              static_cast<unsigned long long>(summary.jumped_cycles));
}

void PrintJson(const Options& options, const Workcell& wc, const Input& input,
               const std::vector<CycleResult>& cycles, const RunSummary& summary,
               bool is_swept) {
  auto name = [&](PrimitiveId id) { return JsonString(wc.primitives[id].name); };
  PrintJsonCounts(options, input, cycles.size(), summary, is_swept);
  if (summary.first >= 0) {
    const Warning& w = cycles[summary.first].warnings.front();
    std::printf("  \"first_warning\": {\"cycle\": %d, \"time_s\": %.3f, \"a\": %s, \"b\": %s, "
                "\"distance_m\": %.9g, \"threshold_m\": %.9g},\n",
                summary.first, input.time_s[summary.first], name(w.a).c_str(),
                name(w.b).c_str(), w.distance_m, w.threshold_m);
  } else {
    std::printf("  \"first_warning\": null,\n");
  }
  const TimingSummary& t = summary.time_s;
  std::printf("  \"cycle_time_s\": {\"p50\": %.9g, \"p99\": %.9g, \"max\": %.9g, "
              "\"mean\": %.9g},\n",
              t.median, t.p99, t.max, t.mean);
  std::printf("  \"counters\": {");
  for (std::size_t i = 0; i < std::size(kCounters); ++i) {
    std::printf("%s\"%s\": %llu", i ? ", " : "", kCounters[i].first,
                static_cast<unsigned long long>(summary.counters.*kCounters[i].second));
  }
  std::printf("},\n");
  // One entry per cycle: [[a, b, distance_m], ...] at its q (empty when clear), and the swept
  // check's [[a, b, distance_m, step_fraction], ...] between the previous cycle's q and this.
  std::printf("  \"per_cycle\": [");
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    std::printf("%s\n    {\"cycle\": %zu, \"time_s\": %.3f, \"refused\": %s, \"warnings\": [",
                k ? "," : "", k, input.time_s[k], cycles[k].refused ? "true" : "false");
    for (std::size_t i = 0; i < cycles[k].warnings.size(); ++i) {
      const Warning& w = cycles[k].warnings[i];
      std::printf("%s[%s, %s, %.9g]", i ? ", " : "", name(w.a).c_str(), name(w.b).c_str(),
                  w.distance_m);
    }
    std::printf("], \"between_samples\": [");
    for (std::size_t i = 0; i < cycles[k].between_samples.size(); ++i) {
      const Warning& w = cycles[k].between_samples[i];
      std::printf("%s[%s, %s, %.9g, %.9g]", i ? ", " : "", name(w.a).c_str(), name(w.b).c_str(),
                  w.distance_m, w.step_fraction);
    }
    std::printf("]}");
  }
  std::printf("\n  ]\n}\n");
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
    std::printf("cycles %zu-%zu (%.2f-%.2f s):\n", k, end - 1, input.time_s[k],
                input.time_s[end - 1]);
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

// The swept check's warnings, one line each (first few), and a count.
void PrintBetweenSamples(const Workcell& wc, const Input& input,
                         const std::vector<CycleResult>& cycles, const RunSummary& summary) {
  constexpr int kMaxLines = 20;
  int lines = 0;
  for (std::size_t k = 0; k < cycles.size() && lines < kMaxLines; ++k) {
    for (const Warning& w : cycles[k].between_samples) {
      if (lines++ == kMaxLines) break;
      std::printf("cycle %zu (%.2f s), between samples at %.3f of the step: %s -- %s  %.4f m "
                  "(threshold %.4f m)\n",
                  k, input.time_s[k], w.step_fraction, wc.primitives[w.a].name.c_str(),
                  wc.primitives[w.b].name.c_str(), w.distance_m, w.threshold_m);
    }
  }
  std::printf("swept check: %llu cycles warn between samples, %llu steps beyond max_step_m\n",
              static_cast<unsigned long long>(summary.between_cycles),
              static_cast<unsigned long long>(summary.jumped_cycles));
}

void PrintText(const Options& options, const Workcell& wc, const Input& input,
               const std::vector<CycleResult>& cycles, const RunSummary& summary,
               bool is_swept) {
  std::printf("replay %s: method %s (%s), %zu cycles from %llu messages", options.input.c_str(),
              options.method.c_str(), is_swept ? "swept check on" : "samples only",
              cycles.size(), static_cast<unsigned long long>(input.messages));
  for (const TaskGraspTarget& t : options.grasp_targets) {
    std::printf(", grasp target %s:%s", t.link.c_str(), t.object.c_str());
  }
  std::printf("\n");
  if (summary.refused_messages > 0 || input.incomplete_cycles > 0 || summary.refused_cycles > 0) {
    std::printf("input: %llu messages refused",
                static_cast<unsigned long long>(summary.refused_messages));
    for (const auto& [status, count] : input.refused) {
      std::printf(" (%s: %llu)", status.c_str(), static_cast<unsigned long long>(count));
    }
    std::printf(", %llu cycles before every joint was received, %llu cycles refused by the "
                "monitor\n",
                static_cast<unsigned long long>(input.incomplete_cycles),
                static_cast<unsigned long long>(summary.refused_cycles));
  }
  PrintWarningRuns(wc, input, cycles);
  if (is_swept) PrintBetweenSamples(wc, input, cycles, summary);
  if (summary.first >= 0) {
    const Warning& w = cycles[summary.first].warnings.front();
    std::printf("summary: %llu of %zu cycles warn; first at cycle %d (%.2f s): %s -- %s at "
                "%.4f m\n",
                static_cast<unsigned long long>(summary.warning_cycles), cycles.size(),
                summary.first, input.time_s[summary.first], wc.primitives[w.a].name.c_str(),
                wc.primitives[w.b].name.c_str(), w.distance_m);
  } else {
    std::printf("summary: no warning at the samples of %zu cycles%s\n", cycles.size(),
                summary.between_cycles > 0 ? " (but between them: see the swept check)" : "");
  }
  const TimingSummary& t = summary.time_s;
  std::printf("cycle time: p50 %.1f us, p99 %.1f us, max %.1f us, mean %.1f us\n",
              t.median * 1e6, t.p99 * 1e6, t.max * 1e6, t.mean * 1e6);
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

int Run(const Options& options) {
  // Start-up as in the node (MonitorNode's constructor): the monitor options first, for the
  // default arm tolerance the workcell is loaded with; then the start-up findings.
  const MonitorStartup startup =
      LoadMonitorStartup(options.urdf, options.scene, options.config, FetchRosResource);
  const MonitorOptions& monitor_options = startup.options;
  const std::shared_ptr<const Workcell>& workcell = startup.workcell;
  for (const std::string& finding : workcell->warnings) {
    std::fprintf(stderr, "replay: %s\n", finding.c_str());
  }
  for (const std::string& notice : workcell->notices) {
    std::fprintf(stderr, "replay: %s\n", notice.c_str());
  }
  const std::unique_ptr<Checker> checker = MakeChecker(options, workcell, monitor_options);
  const Input input = EndsWith(options.input, ".csv") ? ReadCsv(options.input, *workcell)
                                                      : ReadBag(options.input, *workcell);
  std::vector<CycleResult> cycles(input.q.size());
  for (std::size_t k = 0; k < input.q.size(); ++k) checker->Run(input.q[k], &cycles[k]);
  const RunSummary summary = Summarize(input, cycles, *checker);
  if (options.json) {
    PrintJson(options, *workcell, input, cycles, summary, checker->is_swept());
  } else {
    PrintText(options, *workcell, input, cycles, summary, checker->is_swept());
  }
  return 0;
}

}  // namespace
}  // namespace arm_collision_monitor

int main(int argc, char** argv) {
  using namespace arm_collision_monitor;
  Options options;
  std::string error;
  if (!ParseOptions(argc, argv, &options, &error)) {
    std::fprintf(stderr, "replay: %s\n%s", error.c_str(), kUsage);
    return 2;
  }
  if (options.help) {
    std::printf("%s", kUsage);
    return 0;
  }
  try {
    if (options.urdf.empty() || options.scene.empty() || options.config.empty()) {
      const std::string package = ros::package::getPath("arm_collision_monitor");
      if (package.empty()) {
        throw LoadError("cannot find the package arm_collision_monitor (source its "
                        "devel/setup.bash) for the default workcell; pass --urdf, --scene, "
                        "--config");
      }
      if (options.urdf.empty()) options.urdf = package + "/urdf/workcell.urdf";
      if (options.scene.empty()) options.scene = package + "/config/scene.yaml";
      if (options.config.empty()) options.config = package + "/config/monitor.yaml";
    }
    return Run(options);
  } catch (const std::exception& e) {
    // LoadError names the file and element; rosbag errors name the bag.
    std::fprintf(stderr, "replay: %s\n", e.what());
    return 1;
  }
}
