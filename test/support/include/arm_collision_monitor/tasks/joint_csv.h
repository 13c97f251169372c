// Joint trajectories as CSV, for checking recorded or planned motion offline (the replay tool):
// a header row of joint names, then one row of positions (rad or m) per cycle. An optional
// first column named "time_s" gives each row's time; without it rows are kTaskCyclePeriod_s
// apart. Blank lines and lines starting with '#' are skipped.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace arm_collision_monitor {

struct JointCsv {
  std::string path;
  std::vector<std::string> joint_names;  ///< the header, "time_s" excluded
  std::vector<double> time_s;            ///< one per row (filled in when the file has none)
  std::vector<Eigen::VectorXd> rows;     ///< positions in joint_names order
};

/// Reads and validates a joint CSV file. Throws LoadError naming the file, the line and the
/// column (unreadable file, empty header, a header of numbers only (no header row), duplicate
/// name, wrong field count, a field that is
/// not a number, a time that is not finite, times not increasing). A position may be nan or
/// inf: the monitor refuses that cycle, as the node refuses such a message.
JointCsv ReadJointCsv(const std::string& path);

/// The rows re-ordered as `model_joint_names` (Workcell::joint_names), matched by name. Done
/// once at start-up. A column that is no model joint is ignored, as the node ignores such a
/// name, and listed (when the lists are given): in `derived` for `derived_joint_names` (the
/// URDF's mimic joints, whose positions follow from others), else in `ignored`. Every model
/// joint must be a column or in `defaults` ((q index, position), Workcell::joint_defaults: the
/// position in every row); otherwise throws LoadError naming the file and the joints (every
/// missing one at once), with the columns of no model joint (the first kNotedColumns: a typo,
/// a missing prefix, which PrefixedNamesHint shows).
std::vector<Eigen::VectorXd> JointCsvInModelOrder(
    const JointCsv& csv, const std::vector<std::string>& model_joint_names,
    const std::vector<std::pair<int, double>>& defaults = {},
    const std::vector<std::string>& derived_joint_names = {},
    std::vector<std::string>* ignored = nullptr, std::vector<std::string>* derived = nullptr);

}  // namespace arm_collision_monitor
