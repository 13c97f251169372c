// The task configurations of config/task_poses.yaml do in the bundled workcell what the file
// says: walked linearly in joint space from home, task 1 never comes within the tolerances,
// tasks 2 and 3 first warn on the stated pair. Distances from the geometry module's routines.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>
#include <utility>

#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {
namespace {

const std::string kSource = ACM_SOURCE_DIR;
constexpr int kSteps = 400;  // 2.5 mrad of joint motion per step at most: far below a tolerance

Eigen::VectorXd ReadGoal(const YAML::Node& goal) {
  Eigen::VectorXd q(14);
  for (int i = 0; i < 7; ++i) {
    q[i] = goal["left"][i].as<double>();
    q[7 + i] = goal["right"][i].as<double>();
  }
  return q;
}

struct PathResult {
  std::optional<std::pair<std::string, std::string>> first_warning;
  double first_warning_fraction = 1.0;
  double min_clearance_m = 1e9;  // smallest distance minus threshold over the path
};

// Checks every default-model pair the monitor would check (non-compatible, not both static).
PathResult WalkFromHome(const Workcell& w, const Eigen::VectorXd& goal) {
  PathResult result;
  std::vector<Eigen::Isometry3d> X_WL(w.kinematics.link_count());
  std::vector<Shape> shapes_W(w.primitives.size());
  for (int step = 0; step <= kSteps; ++step) {
    const double fraction = static_cast<double>(step) / kSteps;
    w.kinematics.ComputeLinkPoses(fraction * goal, &X_WL);
    for (std::size_t i = 0; i < w.primitives.size(); ++i) {
      const PrimitiveSpec& p = w.primitives[i];
      shapes_W[i] = p.link_index >= 0 ? TransformShape(X_WL[p.link_index], p.shape_L) : p.shape_L;
    }
    for (std::size_t a = 0; a < shapes_W.size(); ++a) {
      for (std::size_t b = a + 1; b < shapes_W.size(); ++b) {
        const PrimitiveSpec& pa = w.primitives[a];
        const PrimitiveSpec& pb = w.primitives[b];
        if (!pa.variant.empty() || !pb.variant.empty() || (pa.is_static && pb.is_static) ||
            w.compatible.AreCompatible(a, b)) {
          continue;
        }
        const double clearance_m =
            ShapeDistance(shapes_W[a], shapes_W[b]).distance_m - pa.tolerance_m - pb.tolerance_m;
        result.min_clearance_m = std::min(result.min_clearance_m, clearance_m);
        if (clearance_m < 0.0 && !result.first_warning) {
          result.first_warning = std::make_pair(pa.name, pb.name);
          result.first_warning_fraction = fraction;
        }
      }
    }
    if (result.first_warning) break;
  }
  return result;
}

class TaskPoses : public ::testing::Test {
 protected:
  void SetUp() override {
    workcell_ = LoadWorkcell(kSource + "/urdf/workcell.urdf", kSource + "/config/scene.yaml");
    tasks_ = YAML::LoadFile(kSource + "/config/task_poses.yaml")["tasks"];
  }
  Workcell workcell_;
  YAML::Node tasks_;
};

TEST_F(TaskPoses, Task1ApproachesBothBoxesWithoutWarning) {
  const PathResult r = WalkFromHome(workcell_, ReadGoal(tasks_["task1"]["goal"]));
  EXPECT_FALSE(r.first_warning) << r.first_warning->first << " / " << r.first_warning->second;
  EXPECT_TRUE(tasks_["task1"]["first_warning"].IsNull());
  // A close approach: within 5 cm beyond the tolerances somewhere on the path.
  EXPECT_LT(r.min_clearance_m, 0.05);
  // The goal puts each gripper above its box.
  std::vector<Eigen::Isometry3d> X_WL(workcell_.kinematics.link_count());
  workcell_.kinematics.ComputeLinkPoses(ReadGoal(tasks_["task1"]["goal"]), &X_WL);
  const Eigen::Vector3d left_tip = X_WL[workcell_.kinematics.FindLink("left_tool")].translation();
  const Eigen::Vector3d right_tip = X_WL[workcell_.kinematics.FindLink("right_tool")].translation();
  EXPECT_NEAR((left_tip - Eigen::Vector3d(0.95, 0.0, 1.01)).norm(), 0.0, 0.005);
  EXPECT_NEAR((right_tip - Eigen::Vector3d(0.10, -1.55, 1.10)).norm(), 0.0, 0.005);
}

TEST_F(TaskPoses, Tasks2And3RunIntoTheFrontTable) {
  for (const std::string task : {"task2", "task3"}) {
    const PathResult r = WalkFromHome(workcell_, ReadGoal(tasks_[task]["goal"]));
    ASSERT_TRUE(r.first_warning) << task;
    EXPECT_EQ(r.first_warning->first, tasks_[task]["first_warning"][0].as<std::string>()) << task;
    EXPECT_EQ(r.first_warning->second, tasks_[task]["first_warning"][1].as<std::string>()) << task;
    EXPECT_GT(r.first_warning_fraction, 0.9) << task;  // late: most of the path is clear
  }
}

}  // namespace
}  // namespace arm_collision_monitor
