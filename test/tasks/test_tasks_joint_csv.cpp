// Joint CSV files (the replay tool's non-bag input): exact round trip of a task trajectory,
// re-ordering by name, and a clear start-up error for each malformed file.
#include <cstdio>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/tasks/joint_csv.h"
#include "arm_collision_monitor/tasks/task_trajectories.h"
#include "../core/test_monitor_util.h"

namespace arm_collision_monitor {
namespace {

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/test_tasks_joint_csv_" + name + ".csv";
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

// The LoadError message of reading `text`, "" if it loads.
std::string ErrorOf(const std::string& name, const std::string& text,
                    const std::vector<std::string>& model = {"a", "b"}) {
  try {
    JointCsvInModelOrder(ReadJointCsv(WriteFile(name, text)), model);
  } catch (const LoadError& e) {
    return e.what();
  }
  return "";
}

TEST(JointCsv, RoundTripsATaskInReversedColumnOrder) {
  const auto workcell = test::LoadBundledWorkcell();
  const std::vector<Eigen::VectorXd> trajectory = MakeTaskTrajectory(2, *workcell);
  const std::size_t n = workcell->joint_names.size();
  // Columns in reverse model order, %.17g: every double prints and parses back exactly.
  std::string text = "# task 2, reversed columns\ntime_s";
  for (std::size_t j = n; j-- > 0;) text += "," + workcell->joint_names[j];
  text += "\n";
  char field[64];
  for (std::size_t k = 0; k < trajectory.size(); ++k) {
    std::snprintf(field, sizeof(field), "%.17g", k * kTaskCyclePeriod_s);
    text += field;
    for (std::size_t j = n; j-- > 0;) {
      std::snprintf(field, sizeof(field), ",%.17g", trajectory[k][j]);
      text += field;
    }
    text += "\n";
  }
  const JointCsv csv = ReadJointCsv(WriteFile("round_trip", text));
  ASSERT_EQ(csv.rows.size(), trajectory.size());
  EXPECT_EQ(csv.joint_names.front(), workcell->joint_names.back());
  const std::vector<Eigen::VectorXd> rows = JointCsvInModelOrder(csv, workcell->joint_names);
  for (std::size_t k = 0; k < trajectory.size(); ++k) {
    EXPECT_TRUE((rows[k].array() == trajectory[k].array()).all()) << "row " << k;
    EXPECT_EQ(csv.time_s[k], k * kTaskCyclePeriod_s);
  }
}

TEST(JointCsv, WithoutTimeColumnRowsAreOneCycleApart) {
  const JointCsv csv = ReadJointCsv(WriteFile("no_time", "b, a\n1, 2\n\n3,4\n"));
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.time_s[1], kTaskCyclePeriod_s);
  const std::vector<Eigen::VectorXd> rows = JointCsvInModelOrder(csv, {"a", "b"});
  EXPECT_EQ(rows[1][0], 4.0);
  EXPECT_EQ(rows[1][1], 3.0);
}

// A planned path of some joints only: the scene file's joint_defaults fill the others.
TEST(JointCsv, JointDefaultsFillMissingColumns) {
  const JointCsv csv = ReadJointCsv(WriteFile("partial", "c, a\n1, 2\n3, 4\n"));
  const std::vector<Eigen::VectorXd> rows =
      JointCsvInModelOrder(csv, {"a", "b", "c"}, {{1, 0.5}});
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1], Eigen::Vector3d(4.0, 0.5, 3.0));
  // A default does not override a column.
  EXPECT_EQ(JointCsvInModelOrder(csv, {"a", "b", "c"}, {{1, 0.5}, {0, -1.0}})[0],
            Eigen::Vector3d(2.0, 0.5, 1.0));
  try {
    JointCsvInModelOrder(csv, {"a", "b", "c"});
    ADD_FAILURE() << "no error for the missing column";
  } catch (const LoadError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no column for model joint 'b'"), std::string::npos) << what;
    EXPECT_NE(what.find("joint_defaults"), std::string::npos) << what;
  }
}

// A recorded joint state may give a URDF mimic joint, which is no joint of the model (its
// position follows from its target's), or a joint the URDF lacks (a gripper the driver
// publishes): both columns are ignored, as the node ignores such names, and listed apart.
TEST(JointCsv, ColumnsOfNoModelJointAreIgnored) {
  const JointCsv csv =
      ReadJointCsv(WriteFile("mimic", "b, finger_mimic, gripper, a\n1, 9, 8, 2\n"));
  std::vector<std::string> ignored, derived;
  const std::vector<Eigen::VectorXd> rows =
      JointCsvInModelOrder(csv, {"a", "b"}, {}, {"finger_mimic"}, &ignored, &derived);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0], Eigen::Vector2d(2.0, 1.0));
  EXPECT_EQ(ignored, std::vector<std::string>{"gripper"});
  EXPECT_EQ(derived, std::vector<std::string>{"finger_mimic"});
  ignored.clear();
  derived.clear();
  JointCsvInModelOrder(csv, {"a", "b"}, {}, {"other_mimic"}, &ignored, &derived);
  EXPECT_EQ(ignored, (std::vector<std::string>{"finger_mimic", "gripper"}));
  EXPECT_TRUE(derived.empty());
}

// A misspelt or prefixed column leaves its model joint without one: the error shows the columns
// the model does not know beside it (a Reachy 2 user's typo was named only as the joint missing).
TEST(JointCsv, AMissingJointIsShownWithTheColumnsOfNoModelJoint) {
  const JointCsv csv =
      ReadJointCsv(WriteFile("typo", "b, finger_mimic, l_elbow_yaw_joint, c\n1, 9, 8, 2\n"));
  try {
    JointCsvInModelOrder(csv, {"l_elbow_yaw", "b", "left_c"}, {}, {"finger_mimic"});
    ADD_FAILURE() << "no error for the missing columns";
  } catch (const LoadError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no column for 2 model joints: 'l_elbow_yaw', 'left_c' ("),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("; the header's columns that are no joints of the model: "
                        "'l_elbow_yaw_joint', 'c'; the model has 'c' as 'left_c'"),
              std::string::npos)
        << what;
    EXPECT_EQ(what.find("'finger_mimic'"), std::string::npos) << what;  // a mimic joint's
  }
}

// A position may be nan or inf (the monitor refuses that cycle, as the node refuses such a
// message); a time may not.
TEST(JointCsv, NonFinitePositionsAreReadForTheMonitorToRefuse) {
  const JointCsv csv = ReadJointCsv(WriteFile("non_finite", "a, b\n1, nan\ninf, -inf\n3, 4\n"));
  const std::vector<Eigen::VectorXd> rows = JointCsvInModelOrder(csv, {"a", "b"});
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_TRUE(std::isnan(rows[0][1]));
  EXPECT_EQ(rows[1], Eigen::Vector2d(INFINITY, -INFINITY));
  EXPECT_EQ(rows[2], Eigen::Vector2d(3.0, 4.0));
  EXPECT_NE(ErrorOf("time_nan", "time_s,a,b\n0,1,2\nnan,1,2\n")
                .find(":3: column 'time_s': 'nan' is not a finite number"),
            std::string::npos);
}

// Spreadsheets export UTF-8 with a byte order mark before the first name.
TEST(JointCsv, ByteOrderMarkIsNotPartOfTheFirstName) {
  const JointCsv csv = ReadJointCsv(WriteFile("bom", "\xEF\xBB\xBFtime_s,b,a\n0.5,1,2\n"));
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_EQ(csv.time_s[0], 0.5);
  EXPECT_EQ(JointCsvInModelOrder(csv, {"a", "b"})[0], Eigen::Vector2d(2.0, 1.0));
  EXPECT_EQ(ErrorOf("bom_names", "\xEF\xBB\xBF" "a,b\n1,2\n"), "");
}

TEST(JointCsv, MalformedFilesAreRejectedWithFileLineAndColumn) {
  EXPECT_NE(ErrorOf("missing", "a\n1\n").find("no column for model joint 'b' (publish it,"),
            std::string::npos);
  // Every missing joint at once, so that one run names all that the scene must default.
  EXPECT_NE(ErrorOf("missing_many", "b\n1\n", {"a", "b", "c", "d"})
                .find("no column for 3 model joints: 'a', 'c', 'd' (publish them,"),
            std::string::npos);
  EXPECT_NE(ErrorOf("duplicate", "a,b,a\n").find(":1: joint 'a' appears twice"),
            std::string::npos);
  // A file without its header row: said so, not taken for joints named by numbers.
  EXPECT_NE(ErrorOf("no_header", "0.0, 1.5, -2e-3\n0.05, 1.5, -2e-3\n")
                .find(":1: the first row holds numbers only: expected a header row"),
            std::string::npos);
  EXPECT_NE(ErrorOf("count", "a,b\n1,2\n1\n").find(":3: 1 fields, expected 2"),
            std::string::npos);
  EXPECT_NE(ErrorOf("empty", "a,b\n1,\n").find(":2: column 'b': '' is not a number"),
            std::string::npos);
  EXPECT_NE(ErrorOf("text", "a,b\n1,2x\n").find("column 'b': '2x'"), std::string::npos);
  EXPECT_NE(ErrorOf("empty_field", "a,b\n1,\n").find("column 'b': ''"), std::string::npos);
  EXPECT_NE(ErrorOf("time", "time_s,a,b\n0.1,1,2\n0.1,1,2\n").find(":3: time_s 0.1 does not"),
            std::string::npos);
  EXPECT_NE(ErrorOf("empty", "# nothing\n").find("empty: expected a header"), std::string::npos);
  EXPECT_NE(ErrorOf("empty_name", "a,,b\n").find("header column 2 is empty"), std::string::npos);
  // A header without rows checks nothing: an error, not a clean run of no cycles.
  EXPECT_NE(ErrorOf("header_only", "# c\na,b\n").find(":2: no row after the header"),
            std::string::npos);
  // Another separator (a spreadsheet's ';' or a tab) is named, not taken for one joint.
  EXPECT_NE(ErrorOf("semicolon", "a;b\n1;2\n").find("header column 1 'a;b' holds a ';' or a "
                                                       "tab: expected columns separated by "
                                                       "commas"),
            std::string::npos);
  EXPECT_NE(ErrorOf("tab", "a\tb\n1\t2\n").find("holds a ';' or a tab"), std::string::npos);
  const std::string path = TempPath("count");
  EXPECT_EQ(ErrorOf("count", "a,b\n1,2\n1\n").rfind(path, 0), 0u) << "names the file first";
  EXPECT_THROW(ReadJointCsv(TempPath("does_not_exist")), LoadError);
  EXPECT_EQ(ErrorOf("good", "a,b\n1,2\n"), "");
}

}  // namespace
}  // namespace arm_collision_monitor
