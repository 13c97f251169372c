// replay's input and results, and its two outputs (text and JSON) of a run (src/nodes/replay.cpp
// reads the input and runs the checker; this file summarises and prints).
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arm_collision_monitor/broadphase/broad_phase.h"
#include "arm_collision_monitor/core/timing_summary.h"
#include "arm_collision_monitor/monitor/monitor.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "arm_collision_monitor/tasks/task_trajectories.h"

namespace arm_collision_monitor {
namespace replay {

// The command line (replay.cpp: ParseOptions).
struct Options {
  std::string urdf, scene, config;
  std::string method = "auto";
  bool json = false;
  std::vector<TaskGraspTarget> grasp_targets;
  std::vector<std::string> topics;  ///< --topic: the bag topics read (empty: all)
  /// --joint-prefix: per bag topic, what its joint names get in front (drivers of alike arms
  /// that publish the same names)
  std::map<std::string, std::string> joint_prefixes;
  std::string input;
  int every = 1;  ///< --every: only cycles 0, every, 2 every, ... are checked
  bool help = false;  ///< -h or --help: print the usage on stdout and exit 0
};

// The input as one q per cycle (model order) with its time, plus what was refused on the way.
struct Input {
  std::vector<Eigen::VectorXd> q;
  /// --every: q[k] is the input's cycle k * cycle_stride, of its all_cycles (the others were
  /// left out)
  std::size_t cycle_stride = 1;
  std::size_t all_cycles = 0;
  std::vector<double> time_s;  ///< since the first cycle
  /// a bag's: per cycle, each joint's sample time on the same clock (the message that gave
  /// it); empty for a CSV, whose rows date every joint at once
  std::vector<Eigen::VectorXd> joint_time_s;
  std::uint64_t messages = 0;  ///< samples read: JointState messages, trajectory points, rows
  /// MergeStatusName (or "time_out_of_range": a trajectory point's stamp) -> count
  std::map<std::string, std::uint64_t> refused;
  /// the refused message or planned point met first in the replay's time (s, on the bag's
  /// clock; a message stamped backwards is met when it comes, NoteRefusal):
  /// "stamped <t> s: <message>: <status> (<why>)", <message> with ", point <k>" for a point ("" if
  /// none), and the time it was met
  std::string first_refused_message;
  double first_refused_arrival_s = std::numeric_limits<double>::infinity();
  bool is_first_refused_planned = true;  ///< a planned point's (met after a message's)
  std::uint64_t incomplete_cycles = 0;           ///< before every joint was received
  std::uint64_t superseded_points = 0;  ///< planned points (partly) replaced by a later plan
  std::uint64_t position_less = 0;      ///< messages and points naming joints without positions
  std::vector<std::string> ignored_columns;  ///< a CSV's columns that are no model joints
  /// a CSV's columns of the URDF's mimic joints, not read: their positions follow from the
  /// joints they mimic
  std::vector<std::string> mimic_columns;
  /// a bag's joint names that are no model joints, and those of the URDF's mimic joints (not
  /// read, as a CSV's columns): the first kNotedNames of each
  std::vector<std::string> ignored_names, mimic_names;
  /// whether the bag gave more such names than those noted
  bool more_ignored_names = false, more_mimic_names = false;
  /// a bag's topics whose JointState stamps are, as a rule, more than kDefaultInputTimeout_s off
  /// the times the bag recorded them (s, negative: behind; of its model joints' usual offsets
  /// the farthest): read as they are, where a node on the recorder's clock refuses them
  std::map<std::string, double> clock_offsets;
};

/// The input's number of checked cycle `k` (the output's cycle numbers: with --every, the
/// cycles' own, not their places among those kept).
inline std::size_t CycleNumber(const Input& input, std::size_t k) {
  return k * input.cycle_stride;
}

/// How many names of each kind Input notes from a bag.
inline constexpr std::size_t kNotedNames = 8;

// One cycle's outcome: warning pairs with their distances at the cycle's q, those the swept
// check found between the previous cycle's q and this one's (the Monitor only: the peers check
// the samples), and the wall time of the check.
struct CycleResult {
  std::vector<Warning> warnings;
  std::vector<Warning> between_samples;
  bool refused = false;
  std::string refusal;  ///< why, when refused (Monitor::DescribeRefusal)
  bool is_jumped = false;
  /// is_jumped as a step the samples do not cover (the swept check off; the Monitor only)
  bool is_beyond_samples = false;
  bool is_moving = true;  ///< its q differs from the previous cycle's (the first one's does)
  double time_s = 0.0;
};

// What both output formats report about the whole run.
struct RunSummary {
  std::uint64_t warning_cycles = 0, refused_cycles = 0;
  int first_refused = -1;  ///< the first refused cycle, -1 if none
  int first = -1;  ///< the first cycle with a warning at its q, -1 if none
  std::uint64_t between_cycles = 0;  ///< cycles with a warning between samples (swept check)
  int first_between = -1;            ///< the first of those, -1 if none
  /// cycles with a warning at their q or between samples: those the node asks a stop in
  std::uint64_t warned_cycles = 0;
  std::uint64_t jumped_cycles = 0;   ///< input_jumped steps: beyond max_step_m, or beyond_samples
  std::uint64_t beyond_samples_cycles = 0;  ///< of those, steps the samples do not cover
  TimingSummary time_s;
  TimingSummary moving_time_s;  ///< over the moving cycles: the Monitor's idle ones left out
  BroadPhaseCounters counters;
  std::uint64_t refused_messages = 0;
};

// The run's counts and timings; `counters`: the checker's broad-phase counters.
RunSummary Summarize(const Input& input, const std::vector<CycleResult>& cycles,
                     const BroadPhaseCounters& counters);

// The run as JSON (--json): counts, first warning, timings, counters and every cycle's warnings.
void PrintJson(const Options& options, const Workcell& wc, const Input& input,
               const std::vector<CycleResult>& cycles, const RunSummary& summary,
               bool is_swept);

// The run as text: the runs of warning cycles, the swept check's warnings, the summary lines.
void PrintText(const Options& options, const Workcell& wc, const Input& input,
               const std::vector<CycleResult>& cycles, const RunSummary& summary,
               bool is_swept);

}  // namespace replay
}  // namespace arm_collision_monitor
