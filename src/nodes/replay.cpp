// replay: checks a recorded or planned trajectory offline, without ROS running. Reads a bag of
// joint states and planned paths (any topics, merged by joint name with the node's JointMerger:
// replay/replay_bag.h) or a joint CSV file (tasks/joint_csv.h), runs the Monitor (or a peer
// checker) once per cycle and prints the warnings, the cycle times and the broad-phase
// counters, as text or JSON (replay/replay_output.cpp).
//
//   rosrun arm_collision_monitor replay [options] <file.bag | file.csv>
//
// Start-up is the node's (MonitorNode): the config's tolerance_m reaches LoadWorkcell and the
// workcell's start-up findings are printed (on stderr) before the run.
// A bag cycle is one sample of every arm: consecutive samples (messages, trajectory points) with
// the same stamp are merged, then the Monitor runs once (the node instead runs once per message;
// see README).
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ros/package.h>

#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/monitor/monitor_startup.h"
#include "arm_collision_monitor/ros/resource_fetch_ros.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"
#include "arm_collision_monitor/tasks/joint_csv.h"
#include "arm_collision_monitor/tasks/task_trajectories.h"
#ifdef ACM_HAVE_PEERS
#include "arm_collision_monitor/peers/peer_checker.h"
#endif
#include "replay/replay_bag.h"
#include "replay/replay_output.h"

namespace arm_collision_monitor {
namespace {

using replay::CycleResult;
using replay::Input;
using replay::Options;

const char* kUsage =
    "usage: replay [options] <file.bag | file.csv>\n"
    "  Runs the collision monitor offline over a trajectory and reports, per cycle, every pair\n"
    "  closer than its tolerances, plus cycle times and broad-phase counters.\n"
    "  file.bag: sensor_msgs/JointState, trajectory_msgs/JointTrajectory (a planned path:\n"
    "            each point a sample at header.stamp, or the bag's time when 0, plus its\n"
    "            time_from_start) and moveit_msgs/DisplayTrajectory (move_group's\n"
    "            display_planned_path: its start state, then its trajectories in turn), and\n"
    "            the trajectories of control_msgs/FollowJointTrajectoryActionGoal and\n"
    "            moveit_msgs/ExecuteTrajectoryActionGoal, on any topics, merged by joint\n"
    "            name: the states in bag order, the planned points in time order, merged by\n"
    "            stamp; a plan supersedes earlier plans of its joints after its start.\n"
    "            Consecutive samples with equal stamps form one cycle.\n"
    "  file.csv: a header row of joint names (optionally 'time_s' first), one row per cycle:\n"
    "            positions in radians (metres for a prismatic joint), separated by commas;\n"
    "            without time_s the rows are 0.05 s apart.\n"
    "options:\n"
    "  --urdf F --scene F --config F   workcell and monitor options (default: the package's\n"
    "                                  urdf/workcell.urdf, config/scene.yaml,\n"
    "                                  config/monitor.yaml); the scene file names the\n"
    "                                  SRDF and the planning scene, if any\n"
    "  --method M     auto | octree | naive | grid | rebuild | reinsert"
#ifdef ACM_HAVE_PEERS
    " | fcl | bullet"
#endif
    "\n"
    "                 (default auto; overrides the config's broad_phase)\n"
    "  --topic T      read only topic T of the bag (repeatable): a bag that records both the\n"
    "                 joint states and planned paths of the same joints needs it\n"
    "  --joint-prefix T=P  put P in front of the joint names of the bag's topic T\n"
    "                 (repeatable): drivers of alike arms that publish the same names, one\n"
    "                 topic each, as the node's ~input_joint_prefixes\n"
    "  --grasp L:O    declare object O the grasp target of link L before the first cycle\n"
    "                 (repeatable)\n"
    "  --task N       the grasp targets of the seed's task N (task 3: right_link7:front_box)\n"
    "  --every N      check cycles 0, N, 2N, ... only: the same path sampled N times\n"
    "                 sparser (what sparser input costs and what the swept check finds)\n"
    "  --json         machine-readable output\n"
    "  -h, --help     this text (on stdout)\n"
    "The monitor options are loaded before the workcell and give it the default arm tolerance,\n"
    "as in the node; the workcell's start-up findings are printed on stderr before the run.\n";

// --every's value `v` in *every, a whole number from 1 to kMaxEvery; else false with *error.
bool ParseEvery(const std::string& v, int* every, std::string* error) {
  constexpr int kMaxEvery = 1000000;
  // Digits only, so that std::atoi stays in range (its result is undefined out of it).
  const bool is_digits =
      !v.empty() && v.size() <= 7 && v.find_first_not_of("0123456789") == std::string::npos;
  *every = is_digits ? std::atoi(v.c_str()) : 0;
  if (*every >= 1 && *every <= kMaxEvery) return true;
  *error = "--every expects a whole number of cycles from 1 to " + std::to_string(kMaxEvery) +
           ", got '" + v + "'";
  return false;
}

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
    } else if (arg == "--topic") {
      if (!value(&v)) return false;
      options->topics.push_back(v);
    } else if (arg == "--joint-prefix") {
      if (!value(&v)) return false;
      const std::size_t equals = v.find('=');
      if (equals == std::string::npos || equals == 0 || equals + 1 == v.size()) {
        *error = "--joint-prefix expects topic=prefix, got '" + v + "'";
        return false;
      }
      if (!options->joint_prefixes.emplace(v.substr(0, equals), v.substr(equals + 1)).second) {
        *error = "--joint-prefix: topic '" + v.substr(0, equals) + "' given twice";
        return false;
      }
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
    } else if (arg == "--every") {
      if (!value(&v) || !ParseEvery(v, &options->every, error)) return false;
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

Input ReadCsv(const std::string& path, const Workcell& workcell) {
  const JointCsv csv = ReadJointCsv(path);
  Input result;
  result.q = JointCsvInModelOrder(csv, workcell.joint_names, workcell.joint_defaults,
                                  workcell.kinematics.MimicJointNames(), &result.ignored_columns,
                                  &result.mimic_columns);
  for (const double t : csv.time_s) result.time_s.push_back(t - csv.time_s.front());
  result.messages = result.q.size();
  return result;
}

// Keeps cycles 0, every, 2 every, ... of `input` (--every): the same path sampled sparser, each
// kept cycle with its own time and joint times.
void KeepEvery(int every, Input* input) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < input->q.size(); k += static_cast<std::size_t>(every), ++kept) {
    input->q[kept] = input->q[k];
    input->time_s[kept] = input->time_s[k];
    if (!input->joint_time_s.empty()) input->joint_time_s[kept] = input->joint_time_s[k];
  }
  input->cycle_stride = static_cast<std::size_t>(every);
  input->all_cycles = input->q.size();
  input->q.resize(kept);
  input->time_s.resize(kept);
  if (!input->joint_time_s.empty()) input->joint_time_s.resize(kept);
}

// The checker under test: the Monitor with a broad phase, or (when built with them) a peer.
class Checker {
 public:
  virtual ~Checker() = default;
  /// One cycle on `q`, each joint sampled at `joint_time_s`.
  virtual void Run(const Eigen::VectorXd& q, const Eigen::VectorXd& joint_time_s,
                   CycleResult* result) = 0;
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
  void Run(const Eigen::VectorXd& q, const Eigen::VectorXd& joint_time_s,
           CycleResult* result) override {
    const auto start = std::chrono::steady_clock::now();
    const CycleReport& report = monitor_.Update(q, joint_time_s);
    result->time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result->warnings.clear();
    result->between_samples.clear();
    for (const Warning& w : report.warnings) {
      (w.between_samples ? result->between_samples : result->warnings).push_back(w);
    }
    result->refused = report.input != InputStatus::kOk;
    result->refusal = result->refused ? monitor_.DescribeRefusal(q) : std::string();
    result->is_jumped = report.input_jumped;
    result->is_beyond_samples = report.beyond_samples.is_beyond;
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
  void Run(const Eigen::VectorXd& q, const Eigen::VectorXd& /*joint_time_s*/,
           CycleResult* result) override {
    const Workcell& wc = *workcell_;
    result->warnings.clear();
    result->refused = !q.allFinite();  // the Monitor refuses it too (the node, its message)
    if (result->refused) {
      result->refusal = "a position is not finite";
      result->time_s = 0.0;
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    shapes_.Evaluate(q);
    for (const PrimitiveId id : shapes_.moving()) peer_->SetShape(id, shapes_.shape_W(id));
    peer_->FindWarnings(&pairs_);
    result->time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
  const bool is_csv = EndsWith(options.input, ".csv");
  if (is_csv && (!options.topics.empty() || !options.joint_prefixes.empty())) {
    throw LoadError(std::string(options.topics.empty() ? "--joint-prefix applies to"
                                                       : "--topic selects") +
                    " a bag's topics; " + options.input + " is a CSV file");
  }
  Input input =
      is_csv ? ReadCsv(options.input, *workcell)
             : replay::ReadBag(options.input, options.topics, options.joint_prefixes, *workcell);
  if (options.every > 1) KeepEvery(options.every, &input);
  std::vector<CycleResult> cycles(input.q.size());
  Eigen::VectorXd row_time_s;  // a CSV row's time, for every joint
  for (std::size_t k = 0; k < input.q.size(); ++k) {
    if (input.joint_time_s.empty()) row_time_s.setConstant(input.q[k].size(), input.time_s[k]);
    checker->Run(input.q[k], input.joint_time_s.empty() ? row_time_s : input.joint_time_s[k],
                 &cycles[k]);
    cycles[k].is_moving = k == 0 || input.q[k] != input.q[k - 1];
  }
  const replay::RunSummary summary = replay::Summarize(input, cycles, checker->counters());
  if (options.json) {
    replay::PrintJson(options, *workcell, input, cycles, summary, checker->is_swept());
  } else {
    replay::PrintText(options, *workcell, input, cycles, summary, checker->is_swept());
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
  // The package's files standing in for options not given: flag, file.
  std::vector<std::pair<std::string, std::string>> defaults_taken;
  try {
    if (options.urdf.empty() || options.scene.empty() || options.config.empty()) {
      const std::string package = ros::package::getPath("arm_collision_monitor");
      if (package.empty()) {
        throw LoadError("cannot find the package arm_collision_monitor (source its "
                        "devel/setup.bash) for the default workcell; pass --urdf, --scene, "
                        "--config");
      }
      auto take = [&](std::string* file, const char* flag, const char* default_file) {
        if (!file->empty()) return;
        *file = package + default_file;
        defaults_taken.emplace_back(flag, *file);
      };
      take(&options.urdf, "--urdf", "/urdf/workcell.urdf");
      take(&options.scene, "--scene", "/config/scene.yaml");
      take(&options.config, "--config", "/config/monitor.yaml");
    }
    return Run(options);
  } catch (const std::exception& e) {
    // LoadError names the file and element; rosbag errors name the bag.
    std::fprintf(stderr, "replay: %s\n", e.what());
    // The bundled workcell's robot files with a robot of one's own fail on its names: say they
    // were taken (the monitor options only where the error names them).
    std::string taken;
    for (const auto& [flag, file] : defaults_taken) {
      if (flag == "--config" && std::string(e.what()).find(file) == std::string::npos) continue;
      taken += (taken.empty() ? "" : ", ") + flag + " " + file;
    }
    if (!taken.empty()) {
      std::fprintf(stderr, "replay: (not given, so the bundled workcell's: %s)\n", taken.c_str());
    }
    return 1;
  }
}
