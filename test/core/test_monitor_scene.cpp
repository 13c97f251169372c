// The Monitor on named situations of the bundled workcell: known clear and colliding poses,
// self and arm-arm collisions, grasp targets, attached objects, model switching, frame-bound
// objects, refused inputs, speed-scaled tolerance and idle cycles. Every report is also compared
// with the independent brute force of test_monitor_util.h.
#include <limits>
#include <sstream>
#include <string>

#include "load_error_expect.h"
#include "test_monitor_util.h"

namespace arm_collision_monitor {
namespace {

using test::ArmReachDown;
using test::ExpectSameWarnings;
using test::HasWarning;
using test::LoadBundledWorkcell;
using test::MakeQ;
using test::Prim;
using test::ReferenceScene;
using test::ReferenceWarnings;

bool IsArmPrimitive(const Workcell& wc, PrimitiveId id, const std::string& arm) {
  return wc.primitives[id].link_index >= 0 && wc.primitives[id].group == arm;
}

void ExpectValid(const Monitor& monitor) {
  std::string error;
  EXPECT_TRUE(monitor.Validate(&error)) << error;
}

TEST(MonitorScene, StopIsRequestedBeforeTheFirstGoodInput) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  EXPECT_TRUE(monitor.report().stop);
  EXPECT_EQ(monitor.report().cycle, 0u);
  EXPECT_TRUE(monitor.Update(Eigen::VectorXd::Zero(3)).stop);
  EXPECT_TRUE(monitor.Update(MakeQ(*wc, {})).warnings.empty());
  EXPECT_FALSE(monitor.report().stop);
}

TEST(MonitorScene, KnownClearAndColliding) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  // Home: both arms straight up, 1.1 m apart, far from everything.
  const CycleReport& home = monitor.Update(MakeQ(*wc, {}));
  EXPECT_TRUE(home.warnings.empty());
  EXPECT_FALSE(home.stop);
  const PrimitiveId table = Prim(*wc, "front_table_top");
  for (const std::string arm : {"left", "right"}) {
    // Shoulder pitched forward, elbow down: the forearm goes through the front table top.
    const Eigen::VectorXd q =
        MakeQ(*wc, {{arm + "_joint2", M_PI / 2}, {arm + "_joint4", M_PI / 2}});
    const CycleReport& report = monitor.Update(q);
    ExpectSameWarnings(*wc, ReferenceWarnings(*wc, q), report.warnings, arm);
    EXPECT_TRUE(report.stop);
    EXPECT_TRUE(std::any_of(report.warnings.begin(), report.warnings.end(), [&](const Warning& w) {
      return (w.b == table && IsArmPrimitive(*wc, w.a, arm)) ||
             (w.a == table && IsArmPrimitive(*wc, w.b, arm));
    })) << arm;
    for (const Warning& w : report.warnings) {
      EXPECT_LT(w.distance_m, w.threshold_m);
      EXPECT_NEAR((w.p_WA - w.p_WB).norm(), w.distance_m, 1e-9);
    }
    // Back home: the step leaves the table's zone (the swept check warns on its way, between
    // samples), then, idle at home, clear again.
    const CycleReport& back = monitor.Update(MakeQ(*wc, {}));
    EXPECT_TRUE(test::AtSampleWarnings(back.warnings).empty()) << arm;
    EXPECT_FALSE(back.warnings.empty()) << arm;
    EXPECT_FALSE(monitor.Update(MakeQ(*wc, {})).stop) << arm;
  }
}

TEST(MonitorScene, SelfCollisionBetweenNonAdjacentLinks) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  // Shoulder, elbow and wrist folded: the gripper comes back onto the arm's first link.
  const Eigen::VectorXd q =
      MakeQ(*wc, {{"left_joint2", 2.0}, {"left_joint4", 2.09}, {"left_joint6", 2.09}});
  const CycleReport& report = monitor.Update(q);
  ExpectSameWarnings(*wc, ReferenceWarnings(*wc, q), report.warnings, "folded");
  const KinematicModel& model = wc->kinematics;
  bool self = false;
  for (const Warning& w : report.warnings) {
    if (!IsArmPrimitive(*wc, w.a, "left") || !IsArmPrimitive(*wc, w.b, "left")) continue;
    const int la = wc->primitives[w.a].link_index, lb = wc->primitives[w.b].link_index;
    EXPECT_NE(la, lb);
    EXPECT_NE(model.parent_link(la), lb);  // adjacent links are compatible
    EXPECT_NE(model.parent_link(lb), la);
    self = true;
  }
  EXPECT_TRUE(self);
}

TEST(MonitorScene, ArmAgainstArm) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  // The left arm turned towards the right one and stretched horizontally through it.
  const Eigen::VectorXd q = MakeQ(*wc, {{"left_joint1", -M_PI / 2}, {"left_joint2", M_PI / 2}});
  const CycleReport& report = monitor.Update(q);
  ExpectSameWarnings(*wc, ReferenceWarnings(*wc, q), report.warnings, "arm-arm");
  EXPECT_TRUE(std::any_of(report.warnings.begin(), report.warnings.end(), [&](const Warning& w) {
    return IsArmPrimitive(*wc, w.a, "left") && IsArmPrimitive(*wc, w.b, "right");
  }));
}

TEST(MonitorScene, GraspTargetIsExcusedOnlyWhileSet) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  const PrimitiveId gripper = Prim(*wc, "left_link7");
  const PrimitiveId box = Prim(*wc, "front_box");
  // Tool tip 1 cm above the box top (z = 0.95): within the gripper's 3 cm tolerance.
  const Eigen::VectorXd q = ArmReachDown(*wc, "left", 0.95, 0.0, 0.96);
  EXPECT_TRUE(HasWarning(monitor.Update(q).warnings, gripper, box));

  std::string error;
  ASSERT_TRUE(monitor.SetGraspTarget("left_link7", "front_box", true, &error)) << error;
  ExpectValid(monitor);
  ReferenceScene scene;
  scene.grasp.insert({wc->primitives[gripper].link_index, wc->FindObject("front_box")});
  const CycleReport& excused = monitor.Update(q);
  EXPECT_FALSE(HasWarning(excused.warnings, gripper, box));
  ExpectSameWarnings(*wc, ReferenceWarnings(*wc, q, scene), excused.warnings, "grasp set");

  ASSERT_TRUE(monitor.SetGraspTarget("left_link7", "front_box", false, &error)) << error;
  EXPECT_TRUE(HasWarning(monitor.Update(q).warnings, gripper, box));
  ExpectValid(monitor);

  // Only declared (link, object) pairs can be excused.
  EXPECT_FALSE(monitor.SetGraspTarget("left_link7", "right_box", true, &error));
  EXPECT_NE(error.find("right_box"), std::string::npos);
  EXPECT_FALSE(monitor.SetGraspTarget("left_link7", "no_such_object", true, &error));
  EXPECT_FALSE(monitor.SetGraspTarget("no_such_link", "front_box", true, &error));
}

TEST(MonitorScene, AttachedBoxMovesWithTheGripperAndWarnsAgainstAnotherTable) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  const PrimitiveId gripper = Prim(*wc, "right_link7");
  const PrimitiveId box = Prim(*wc, "right_box");
  const PrimitiveId front_table = Prim(*wc, "front_table_top");
  const int gripper_link = wc->primitives[gripper].link_index;
  std::string error;
  // Attach needs a joint state first.
  EXPECT_FALSE(monitor.Attach("right_box", "right_link7", &error));

  // The tool tip touching the top of the box on the right table (z = 0.95).
  Eigen::VectorXd q = ArmReachDown(*wc, "right", 0.1, -1.55, 0.95);
  ASSERT_TRUE(monitor.SetGraspTarget("right_link7", "right_box", true, &error)) << error;
  monitor.Update(q);
  ASSERT_TRUE(monitor.Attach("right_box", "right_link7", &error)) << error;
  ASSERT_TRUE(monitor.SetGraspTarget("right_link7", "right_box", false, &error)) << error;
  EXPECT_TRUE(monitor.is_active(box));
  ExpectValid(monitor);

  std::vector<Eigen::Isometry3d> X_WL(wc->kinematics.link_count());
  wc->kinematics.ComputeLinkPoses(q, &X_WL);
  ReferenceScene scene;
  scene.held[box] = {gripper_link,
                     TransformShape(X_WL[gripper_link].inverse(), monitor.shape_W(box))};

  // Swing the arm (joint 1) from the right table to the front table in 40 smooth steps: the box
  // keeps its pose relative to the gripper and never warns against it.
  const double q1_start = q[test::JointIndex(*wc, "right_joint1")];
  bool warned_front_table = false;
  for (int k = 1; k <= 40; ++k) {
    q[test::JointIndex(*wc, "right_joint1")] = q1_start * (1.0 - k / 40.0);
    const CycleReport& report = monitor.Update(q);
    ExpectSameWarnings(*wc, ReferenceWarnings(*wc, q, scene), report.warnings,
                       "carry step " + std::to_string(k));
    EXPECT_FALSE(HasWarning(report.warnings, gripper, box));
    warned_front_table = warned_front_table || HasWarning(report.warnings, box, front_table);
    wc->kinematics.ComputeLinkPoses(q, &X_WL);
    const Shape expected_shape = TransformShape(X_WL[gripper_link], scene.held[box].shape_L);
    const Box& expected = std::get<Box>(expected_shape);
    monitor.SyncShapes();
    const Box& actual = std::get<Box>(monitor.shape_W(box));
    EXPECT_TRUE(actual.X_WB.isApprox(expected.X_WB, 1e-12));
    ExpectValid(monitor);
  }
  // Joint 1 at 0: the box hangs over the front table, its bottom at the table top's height.
  EXPECT_TRUE(warned_front_table);
  EXPECT_TRUE(monitor.report().stop);

  // Let go: the box rests on the table, a static touching a static is never tested.
  ASSERT_TRUE(monitor.Detach("right_box", &error)) << error;
  EXPECT_FALSE(monitor.Detach("right_box", &error));
  ExpectValid(monitor);
  const Eigen::VectorXd home = MakeQ(*wc, {});
  const CycleReport& after = monitor.Update(home);
  EXPECT_FALSE(HasWarning(after.warnings, box, front_table));
  EXPECT_TRUE(test::AtSampleWarnings(after.warnings).empty());

  EXPECT_FALSE(monitor.Attach("front_table_top", "right_link7", &error));  // not attachable
  EXPECT_FALSE(monitor.Attach("no_such_object", "right_link7", &error));
  EXPECT_FALSE(monitor.Attach("right_box", "no_such_link", &error));
  // Too far from the left gripper at home to be held by it.
  EXPECT_FALSE(monitor.Attach("right_box", "left_link7", &error));
  EXPECT_NE(error.find("reaches"), std::string::npos) << error;
}

// With the swept check off, a held object that can move farther in one cycle than its
// tolerance is named when held (helper-58 M1): the box hangs 0.2 m below the gripper, at the
// longest cycle period at which every link is within its tolerance (start-up's check), so its
// lever is longer. The right arm's joints each at their velocity limit for one period is then a
// step beyond the samples for the box alone, as the notice says.
TEST(MonitorScene, AHeldObjectMovingFartherInACycleThanItsToleranceIsNamed) {
  const auto wc = LoadBundledWorkcell();
  MonitorOptions options;
  options.swept_check = false;
  options.max_step_m = std::numeric_limits<double>::infinity();
  options.cycle_period_s = 0.005;
  for (;;) {
    try {
      Monitor probe(wc, options);
      break;
    } catch (const LoadError&) {
      options.cycle_period_s *= 0.99;
    }
  }
  const PrimitiveId box = Prim(*wc, "right_box");
  const Eigen::VectorXd q = ArmReachDown(*wc, "right", 0.1, -1.55, 0.95);
  std::string error;
  for (const bool is_swept : {true, false}) {
    options.swept_check = is_swept;
    Monitor monitor(wc, options);
    ASSERT_TRUE(monitor.SetGraspTarget("right_link7", "right_box", true, &error)) << error;
    monitor.Update(q);
    EXPECT_EQ(monitor.DescribeHeldMotionBeyondTolerance("right_box"), "");  // not held
    ASSERT_TRUE(monitor.Attach("right_box", "right_link7", &error)) << error;
    const std::string notice = monitor.DescribeHeldMotionBeyondTolerance("right_box");
    if (is_swept) {
      EXPECT_EQ(notice, "");  // the swept check covers the motion between samples
      continue;
    }
    const std::string says = "held 'right_box' may move ";
    ASSERT_NE(notice.find(says), std::string::npos) << notice;
    const double notice_m = std::atof(notice.c_str() + notice.find(says) + says.size());
    EXPECT_GT(notice_m, monitor.tolerance_m(box)) << notice;
    Eigen::VectorXd q_fast = q;
    for (int k = 1; k <= 7; ++k) {
      const std::string joint = "right_joint" + std::to_string(k);
      const int link = wc->kinematics.FindLink("right_link" + std::to_string(k));
      ASSERT_GE(link, 0) << joint;
      q_fast[test::JointIndex(*wc, joint)] +=
          wc->kinematics.joint(link).max_velocity * options.cycle_period_s;
    }
    const CycleReport& report = monitor.Update(q_fast);
    ASSERT_TRUE(report.beyond_samples.is_beyond);
    EXPECT_EQ(report.beyond_samples.primitive, box);
    EXPECT_NEAR(report.beyond_samples.motion_m, notice_m, 1e-4 * notice_m) << notice;
    EXPECT_TRUE(report.stop);
  }
  // A live 1 cm sphere at the gripper's origin, within every tolerance, held: no notice, and
  // the step bounds are the arm's own (the object's free slots, not carried, widen none).
  Monitor bare(wc, options), holding(wc, options);
  for (Monitor* monitor : {&bare, &holding}) monitor->Update(q);
  const std::vector<Shape> pebble = {Capsule{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                             0.005}};
  holding.SyncShapes();
  const int gripper = wc->kinematics.FindLink("right_link7");
  std::vector<Eigen::Isometry3d> X_WL(wc->kinematics.link_count());
  wc->kinematics.ComputeLinkPoses(q, &X_WL);
  ASSERT_TRUE(holding.AddObject("pebble", pebble, X_WL[gripper], 0.0, true, &error)) << error;
  ASSERT_TRUE(holding.SetGraspTarget("right_link7", "pebble", true, &error)) << error;
  ASSERT_TRUE(holding.Attach("pebble", "right_link7", &error)) << error;
  EXPECT_EQ(holding.DescribeHeldMotionBeyondTolerance("pebble"), "");
  Eigen::VectorXd q_step = q;
  q_step[test::JointIndex(*wc, "right_joint1")] += 0.001;
  EXPECT_EQ(holding.Update(q_step).step_motion_m, bare.Update(q_step).step_motion_m);
}

// A tool point without geometry can hold an object: the kinematics, which skips such a frame
// while nothing hangs from it (KinematicModel::MovingLinksTo), places it at the Attach and
// follows it from then on, with the held box, to the end of the carry and after a Detach and a
// second Attach.
TEST(MonitorScene, ObjectHeldByAFrameWithoutGeometryFollowsIt) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  const PrimitiveId box = Prim(*wc, "right_box");
  const int tool = wc->kinematics.FindLink("right_tool");
  ASSERT_GE(tool, 0);
  for (PrimitiveId id = 0; id < wc->primitives.size(); ++id) {
    ASSERT_NE(wc->primitives[id].link_index, tool) << "right_tool must have no geometry";
  }
  const int joint1 = test::JointIndex(*wc, "right_joint1");
  std::string error;
  Eigen::VectorXd q = ArmReachDown(*wc, "right", 0.1, -1.55, 0.95);
  std::vector<Eigen::Isometry3d> X_WL(wc->kinematics.link_count());
  for (int grasp = 0; grasp < 2; ++grasp) {
    monitor.Update(q);
    const Shape before_W = monitor.shape_W(box);
    ASSERT_TRUE(monitor.Attach("right_box", "right_tool", &error)) << error;
    monitor.SyncShapes();
    EXPECT_TRUE(std::get<Box>(monitor.shape_W(box)).X_WB.isApprox(std::get<Box>(before_W).X_WB,
                                                                   1e-12));
    wc->kinematics.ComputeLinkPoses(q, &X_WL);
    ReferenceScene scene;
    scene.held[box] = {tool, TransformShape(X_WL[tool].inverse(), before_W)};
    const double q1_start = q[joint1];
    for (int k = 1; k <= 20; ++k) {
      q[joint1] = q1_start * (1.0 - k / 20.0);
      const CycleReport& report = monitor.Update(q);
      ExpectSameWarnings(*wc, ReferenceWarnings(*wc, q, scene), report.warnings,
                         "grasp " + std::to_string(grasp) + ", carry step " + std::to_string(k));
      wc->kinematics.ComputeLinkPoses(q, &X_WL);
      const Shape expected = TransformShape(X_WL[tool], scene.held[box].shape_L);
      monitor.SyncShapes();
      EXPECT_TRUE(std::get<Box>(monitor.shape_W(box)).X_WB.isApprox(std::get<Box>(expected).X_WB,
                                                                     1e-12))
          << "grasp " << grasp << ", carry step " << k;
      ExpectValid(monitor);
    }
    // Back where it was picked up, put down, and picked up again.
    for (int k = 1; k <= 20; ++k) {
      q[joint1] = q1_start * (k / 20.0);
      monitor.Update(q);
    }
    ASSERT_TRUE(monitor.Detach("right_box", &error)) << error;
    ExpectValid(monitor);
  }
}

TEST(MonitorScene, ModelSwitchingReplacesTheLinksPrimitives) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  const PrimitiveId coarse = Prim(*wc, "left_link7");
  std::vector<PrimitiveId> detailed;
  for (PrimitiveId id = 0; id < wc->primitives.size(); ++id) {
    if (wc->primitives[id].variant == "grasp" && wc->primitives[id].owner == "left_link7") {
      detailed.push_back(id);
    }
  }
  ASSERT_EQ(detailed.size(), 3u);
  for (const PrimitiveId id : detailed) EXPECT_FALSE(monitor.is_active(id));

  std::string error;
  ASSERT_TRUE(monitor.SwitchModel("left_link7", "grasp", &error)) << error;
  EXPECT_FALSE(monitor.is_active(coarse));
  for (const PrimitiveId id : detailed) EXPECT_TRUE(monitor.is_active(id));
  ExpectValid(monitor);

  ReferenceScene scene;
  scene.variant_of_link[wc->primitives[coarse].link_index] = "grasp";
  std::mt19937_64 rng(test::PrintSeed(77));
  const test::JointLimits limits = test::LimitsOf(*wc);
  for (int k = 0; k < 300; ++k) {
    const Eigen::VectorXd q = test::RandomQ(limits, &rng);
    const CycleReport& report = monitor.Update(q);
    ExpectSameWarnings(*wc, ReferenceWarnings(*wc, q, scene), report.warnings,
                       "grasp model " + std::to_string(k));
    for (const Warning& w : report.warnings) EXPECT_TRUE(w.a != coarse && w.b != coarse);
  }
  // The detailed gripper over the box: fingers warn, the coarse capsule does not exist.
  const Eigen::VectorXd q = ArmReachDown(*wc, "left", 0.95, 0.0, 0.96);
  const CycleReport& report = monitor.Update(q);
  ExpectSameWarnings(*wc, ReferenceWarnings(*wc, q, scene), report.warnings,
                     "grasp model over box");
  for (const Warning& w : report.warnings) EXPECT_TRUE(w.a != coarse && w.b != coarse);

  ASSERT_TRUE(monitor.SwitchModel("left_link7", "", &error)) << error;
  EXPECT_TRUE(monitor.is_active(coarse));
  for (const PrimitiveId id : detailed) EXPECT_FALSE(monitor.is_active(id));
  ExpectSameWarnings(*wc, ReferenceWarnings(*wc, q), monitor.Update(q).warnings, "default again");
  ExpectValid(monitor);

  EXPECT_FALSE(monitor.SwitchModel("left_link7", "no_such_variant", &error));
  EXPECT_FALSE(monitor.SwitchModel("no_such_link", "grasp", &error));
}

TEST(MonitorScene, FrameBoundObjectFollowsItsPose) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  const PrimitiveId camera = Prim(*wc, "camera");
  const Eigen::VectorXd home = MakeQ(*wc, {});
  EXPECT_TRUE(monitor.Update(home).warnings.empty());
  // Move the camera onto the left arm's upper arm.
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() << 0.0, 0.55, 1.6;
  std::string error;
  ASSERT_TRUE(monitor.SetObjectPose("camera", X_WO, &error)) << error;
  ReferenceScene scene;
  const ObjectSpec& spec = wc->objects[wc->FindObject("camera")];
  scene.moved_objects_W[camera] =
      TransformShape(X_WO * spec.X_WO_start.inverse(), wc->primitives[camera].shape_L);
  const CycleReport& report = monitor.Update(home);  // same q, but the scene changed
  ExpectSameWarnings(*wc, ReferenceWarnings(*wc, home, scene), report.warnings, "camera moved");
  EXPECT_TRUE(std::any_of(report.warnings.begin(), report.warnings.end(), [&](const Warning& w) {
    return w.b == camera || w.a == camera;
  }));
  // Driven into the front table top: both tolerances are 0, and the overlap still warns.
  X_WO.translation() << 0.95, 0.5, 0.74;
  ASSERT_TRUE(monitor.SetObjectPose("camera", X_WO, &error)) << error;
  scene.moved_objects_W[camera] =
      TransformShape(X_WO * spec.X_WO_start.inverse(), wc->primitives[camera].shape_L);
  const CycleReport& in_table = monitor.Update(home);
  ExpectSameWarnings(*wc, ReferenceWarnings(*wc, home, scene), in_table.warnings,
                     "camera in the table");
  const PrimitiveId table = Prim(*wc, "front_table_top");
  EXPECT_TRUE(
      std::any_of(in_table.warnings.begin(), in_table.warnings.end(), [&](const Warning& w) {
        return w.a == std::min(camera, table) && w.b == std::max(camera, table) &&
               w.threshold_m == 0.0 && w.distance_m == 0.0;
      }));
  // Next to the back wall (left out as unreachable): the wall joins the checked scene.
  const PrimitiveId wall = Prim(*wc, "back_wall");
  EXPECT_FALSE(monitor.is_active(wall));
  X_WO.translation() << -2.9, 0.0, 1.5;
  ASSERT_TRUE(monitor.SetObjectPose("camera", X_WO, &error)) << error;
  EXPECT_TRUE(monitor.is_active(wall));
  ExpectValid(monitor);
  // A rotation that is not one (scaled by 1.004, as a quaternion off unit norm that TF keeps
  // makes it) or a pose not finite is refused: the shapes would be stretched, or lost.
  Eigen::Isometry3d stretched = X_WO;
  stretched.linear() *= 1.004;
  EXPECT_FALSE(monitor.SetObjectPose("camera", stretched, &error));
  EXPECT_NE(error.find("'camera' not finite or its rotation not orthonormal"), std::string::npos)
      << error;
  Eigen::Isometry3d lost = X_WO;
  lost.translation().x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(monitor.SetObjectPose("camera", lost, &error));
  ExpectValid(monitor);
  EXPECT_FALSE(monitor.SetObjectPose("front_table_top", X_WO, &error));  // static
  EXPECT_FALSE(monitor.SetObjectPose("no_such_object", X_WO, &error));
}

// Validate between a scene change and the next good cycle, a refused one between (red team):
// the kept pairs' bounds are of the scene before, and were checked against the camera moved
// 0.21 m closer to the arm (a false alarm); the next good cycle re-plans them and warns.
TEST(MonitorScene, ValidHoldsWhileASceneChangeWaitsForTheNextCycle) {
  const auto wc = LoadBundledWorkcell();
  MonitorOptions options;
  options.index_slack_m = 0.1;
  Monitor monitor(wc, options);
  const Eigen::VectorXd home = MakeQ(*wc, {});
  monitor.Update(home);
  // Beside the left arm's column (x 0, y 0.55 at home): 0.25 m off, a kept candidate pair.
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() << 0.36, 0.55, 1.5;
  std::string error;
  ASSERT_TRUE(monitor.SetObjectPose("camera", X_WO, &error)) << error;
  EXPECT_TRUE(monitor.Update(home).warnings.empty());
  ASSERT_GT(monitor.report().candidate_pairs, 0u);
  ExpectValid(monitor);
  X_WO.translation().x() = 0.15;  // about 0.02 m from the arm: within its 0.0305 m
  ASSERT_TRUE(monitor.SetObjectPose("camera", X_WO, &error)) << error;
  ExpectValid(monitor);
  Eigen::VectorXd bad = home;
  bad[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(monitor.Update(bad).stop);
  ExpectValid(monitor);
  const CycleReport& report = monitor.Update(home);
  const PrimitiveId camera = Prim(*wc, "camera");
  EXPECT_TRUE(std::any_of(report.warnings.begin(), report.warnings.end(), [&](const Warning& w) {
    return w.a == camera || w.b == camera;
  }));
  ExpectValid(monitor);
  // After a run of bounded cycles, a live ball moved into the left elbow: the bounded cycle's
  // proof is of the scene before ('pair at 0 m'), what the next cycle re-plans and warns of.
  X_WO.translation() << 1.6, 0.0, 2.4;  // the camera back out of the way
  ASSERT_TRUE(monitor.SetObjectPose("camera", X_WO, &error)) << error;
  Eigen::VectorXd q = home;
  q[1] = 0.3;
  monitor.Update(q);
  std::vector<Eigen::Isometry3d> X_WL(wc->kinematics.link_count());
  wc->kinematics.ComputeLinkPoses(q, &X_WL);
  const Eigen::Vector3d elbow = X_WL[wc->kinematics.FindLink("left_link4")].translation();
  Eigen::Isometry3d X_ball = Eigen::Isometry3d::Identity();
  X_ball.translation() = elbow + Eigen::Vector3d(0.0, 0.2, 0.0);  // near: a kept pair
  const std::vector<Shape> ball = {Capsule{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.05}};
  ASSERT_TRUE(monitor.AddObject("ball", ball, X_ball, 0.0, false, &error)) << error;
  std::uint32_t bounded = 0;
  for (int i = 0; i < 20; ++i) {
    q[1] += 1e-6;
    bounded += monitor.Update(q).bounded;
  }
  ASSERT_GT(bounded, 0u);
  X_ball.translation() = elbow;
  ASSERT_TRUE(monitor.MoveObject("ball", X_ball, &error)) << error;
  ExpectValid(monitor);
  EXPECT_FALSE(monitor.Update(q).warnings.empty());
  ExpectValid(monitor);
}

// Each joint's value, in every position of q (CheckInput takes two at a time, an odd last one
// alone): NaN and infinities refused as not finite; a limited joint's value past its limit and
// margin refused as out of limits, one within its margin taken; a continuous joint takes any
// finite value. On the bundled workcell (14 joints), the three-link arm (4, the third
// continuous) and a three-joint arm (the middle one continuous, the last one alone).
TEST(MonitorScene, EveryJointValueIsCheckedInEveryPosition) {
  std::string links = "<link name=\"base\"/>";
  const char* const kJoints[] = {"revolute", "continuous", "revolute"};
  for (int k = 0; k < 3; ++k) {
    const std::string link = "l" + std::to_string(k);
    const std::string parent = k == 0 ? "base" : "l" + std::to_string(k - 1);
    links += "<joint name=\"j" + std::to_string(k) + "\" type=\"" + kJoints[k] +
             "\"><parent link=\"" + parent + "\"/><child link=\"" + link +
             "\"/><origin xyz=\"0 0 0.3\"/><axis xyz=\"0 1 0\"/>"
             "<limit lower=\"-1\" upper=\"1.5\" velocity=\"1\" effort=\"1\"/></joint>"
             "<link name=\"" + link + "\"><collision><geometry>"
             "<cylinder radius=\"0.05\" length=\"0.3\"/></geometry></collision></link>";
  }
  const std::string urdf =
      WriteTempFile("odd_arm.urdf", "<robot name=\"odd_arm\">" + links + "</robot>\n");
  const std::string scene = WriteTempFile("odd_arm.yaml",
                                          "world: {center_m: [0, 0, 0.5], edge_m: 4.0}\n"
                                          "arms:\n  - {name: arm, root_link: l0}\n");
  const std::string data = ACM_SOURCE_DIR "/test/data/";
  const std::vector<std::shared_ptr<const Workcell>> workcells = {
      LoadBundledWorkcell(),
      std::make_shared<const Workcell>(
          LoadWorkcell(data + "three_link_arm.urdf", data + "three_link_scene.yaml")),
      std::make_shared<const Workcell>(LoadWorkcell(urdf, scene))};
  const double inf = std::numeric_limits<double>::infinity();
  for (const auto& wc : workcells) {
    const Monitor monitor(wc, MonitorOptions{});
    const KinematicModel& model = wc->kinematics;
    const Eigen::VectorXd good = Eigen::VectorXd::Zero(model.q_size());
    ASSERT_EQ(monitor.Check(good).input, InputStatus::kOk);
    int continuous = 0;
    for (int link = 1; link < model.link_count(); ++link) {
      const JointSpec& joint = model.joint(link);
      if (joint.q_index < 0) continue;
      auto status_with = [&](double value) {
        Eigen::VectorXd q = good;
        q[joint.q_index] = value;
        return monitor.Check(q).input;
      };
      const std::string what = joint.name;
      for (const double bad : {std::numeric_limits<double>::quiet_NaN(), inf, -inf}) {
        EXPECT_EQ(status_with(bad), InputStatus::kNonFinite) << what << " = " << bad;
      }
      if (joint.type == JointType::kContinuous) {
        // Any number of turns up to kMaxUnlimitedPosition_rad; beyond, a corrupt reading.
        ++continuous;
        EXPECT_EQ(status_with(kMaxUnlimitedPosition_rad), InputStatus::kOk) << what;
        EXPECT_EQ(status_with(-kMaxUnlimitedPosition_rad), InputStatus::kOk) << what;
        for (const double absurd : {1e300, -std::numeric_limits<double>::max()}) {
          EXPECT_EQ(status_with(absurd), InputStatus::kOutOfLimits) << what;
          Eigen::VectorXd q = good;
          q[joint.q_index] = absurd;
          EXPECT_NE(monitor.DescribeRefusal(q).find(
                        "beyond the +/-1e+09 rad a joint may take on a side without a limit"),
                    std::string::npos)
              << monitor.DescribeRefusal(q);
        }
        continue;
      }
      EXPECT_EQ(status_with(joint.upper + 2.0 * kJointLimitMargin), InputStatus::kOutOfLimits)
          << what;
      EXPECT_EQ(status_with(joint.lower - 2.0 * kJointLimitMargin), InputStatus::kOutOfLimits)
          << what;
      EXPECT_EQ(status_with(joint.upper + 0.5 * kJointLimitMargin), InputStatus::kOk) << what;
    }
    EXPECT_EQ(continuous, wc == workcells[0] ? 0 : 1);
  }
}

// A continuous joint with a soft lower limit only: a refusal below it names the limit and no
// upper one; one beyond +/-1e9 above it names the side without a limit.
TEST(MonitorScene, RefusalNamesTheSideWithoutALimit) {
  const std::string data = ACM_SOURCE_DIR "/test/data/";
  const std::string scene =
      WriteTempFile("spin_lower.yaml", ReadTextFile(data + "three_link_scene.yaml") +
                                           "\njoint_limits: {spin: {lower: -4.0}}\n");
  const auto wc =
      std::make_shared<const Workcell>(LoadWorkcell(data + "three_link_arm.urdf", scene));
  const Monitor monitor(wc, MonitorOptions{});
  const int spin = wc->kinematics.joint(wc->kinematics.FindJointChildLink("spin")).q_index;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(wc->kinematics.q_size());
  ASSERT_EQ(monitor.Check(q).input, InputStatus::kOk);
  const std::vector<std::pair<double, std::string>> cases = {
      {-5.0, "joint 'spin' at -5, outside its limits [-4, none] by more than their margin 0.01"},
      {2e9, "joint 'spin' at 2e+09, beyond the +/-1e+09 rad a joint may take on a side without a "
            "limit (a corrupt reading)"}};
  for (const auto& [position, why] : cases) {
    q[spin] = position;
    EXPECT_EQ(monitor.Check(q).input, InputStatus::kOutOfLimits) << position;
    EXPECT_EQ(monitor.DescribeRefusal(q), why);
  }
}

// A mesh object fitted by a chain of capsules, carried: its own capsules, which overlap at their
// joints, never warn against each other (they were checked, so the carried rod warned in every
// cycle).
TEST(MonitorScene, AnObjectOfSeveralPrimitivesNeverWarnsAgainstItself) {
  const std::string data = ACM_SOURCE_DIR "/test/data/";
  const std::string scene = WriteTempFile(
      "rod_scene.yaml", "world: {center_m: [0, 0, 1], edge_m: 4}\nmesh_fit: capsules:4\n"
                        "arms: [{name: arm, root_link: upper_arm}]\n"
                        "objects: [{name: rod, type: mesh, mesh: " +
                            data + "meshes/forearm.stl, pose: {xyz_m: [0.5, 0.0, 0.6]}, "
                                   "attachable: true, tolerance_m: 0.01}]\n");
  const auto wc =
      std::make_shared<const Workcell>(LoadWorkcell(data + "three_link_arm.urdf", scene));
  Monitor monitor(wc, MonitorOptions{});
  Eigen::VectorXd q = Eigen::VectorXd::Zero(wc->kinematics.q_size());
  monitor.Update(q);
  std::string error;
  ASSERT_TRUE(monitor.Attach("rod", "wrist", &error)) << error;
  const ObjectSpec& rod = wc->objects[wc->FindObject("rod")];
  ASSERT_GT(rod.primitive_count, 1);
  const PrimitiveId rod_end = rod.primitive + static_cast<PrimitiveId>(rod.primitive_count);
  auto is_rod = [&](PrimitiveId id) { return id >= rod.primitive && id < rod_end; };
  for (int k = 1; k <= 10; ++k) {
    q[0] = 0.1 * k;  // the shoulder turns, the rod with the arm
    const CycleReport& report = monitor.Update(q);
    ASSERT_EQ(report.input, InputStatus::kOk);
    for (const Warning& w : report.warnings) {
      EXPECT_FALSE(is_rod(w.a) && is_rod(w.b))
          << wc->primitives[w.a].name << " -- " << wc->primitives[w.b].name << " at q0 " << q[0];
    }
  }
  ExpectValid(monitor);
}

// The scene file's soft limits hold for a continuous joint too (the three-link arm's spin).
TEST(MonitorScene, SoftLimitsOfAContinuousJointAreChecked) {
  const std::string data = ACM_SOURCE_DIR "/test/data/";
  const std::string scene = WriteTempFile(
      "soft_spin.yaml", ReadTextFile(data + "three_link_scene.yaml") +
                            "joint_limits: {spin: {lower: -1.0, upper: 1.5}}\n");
  const auto wc =
      std::make_shared<const Workcell>(LoadWorkcell(data + "three_link_arm.urdf", scene));
  const Monitor monitor(wc, MonitorOptions{});
  const int spin = wc->kinematics.joint(wc->kinematics.FindJointChildLink("spin")).q_index;
  ASSERT_GE(spin, 0);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(wc->kinematics.q_size());
  for (const auto& [value, status] : std::vector<std::pair<double, InputStatus>>{
           {1.4, InputStatus::kOk},
           {1.5 + 2.0 * kJointLimitMargin, InputStatus::kOutOfLimits},
           {-1.0 - 2.0 * kJointLimitMargin, InputStatus::kOutOfLimits},
           {-1.0 - 0.5 * kJointLimitMargin, InputStatus::kOk}}) {
    q[spin] = value;
    EXPECT_EQ(monitor.Check(q).input, status) << "spin = " << value;
  }
}

TEST(MonitorScene, BadInputsAreRefusedCountedAndFailSafe) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  const Eigen::VectorXd good = MakeQ(*wc, {{"left_joint2", 0.3}});
  ASSERT_FALSE(monitor.Update(good).stop);
  const Shape before = monitor.shape_W(Prim(*wc, "left_link7"));
  const int j2 = test::JointIndex(*wc, "left_joint2");
  const double upper = test::LimitsOf(*wc).upper[j2];

  Eigen::VectorXd nan = good, inf = good, beyond = good, within = good;
  nan[3] = std::numeric_limits<double>::quiet_NaN();
  inf[5] = -std::numeric_limits<double>::infinity();
  beyond[j2] = upper + 2.0 * kJointLimitMargin;
  within[j2] = upper + 0.5 * kJointLimitMargin;
  const std::vector<std::pair<Eigen::VectorXd, InputStatus>> bad = {
      {Eigen::VectorXd::Zero(good.size() - 1), InputStatus::kWrongSize},
      {Eigen::VectorXd::Zero(good.size() + 1), InputStatus::kWrongSize},
      {nan, InputStatus::kNonFinite},
      {inf, InputStatus::kNonFinite},
      {beyond, InputStatus::kOutOfLimits}};
  std::uint64_t refused = 0;
  for (const auto& [q, status] : bad) {
    const CycleReport& report = monitor.Update(q);
    EXPECT_EQ(report.input, status);
    EXPECT_TRUE(report.stop);
    EXPECT_EQ(monitor.refused_inputs(), ++refused);
    EXPECT_EQ(monitor.Check(q).input, status);
    // The model stays at its last good state.
    const Capsule& now = std::get<Capsule>(monitor.shape_W(Prim(*wc, "left_link7")));
    EXPECT_EQ(now.p1_W, std::get<Capsule>(before).p1_W);
    ExpectValid(monitor);
  }
  EXPECT_EQ(monitor.report().cycle, 1u + bad.size());
  // Good input (even the same q as before the refusals) clears the stop.
  const CycleReport& cleared = monitor.Update(good);
  EXPECT_EQ(cleared.input, InputStatus::kOk);
  EXPECT_FALSE(cleared.stop);
  // Slightly past a limit, within the margin: accepted.
  EXPECT_EQ(monitor.Update(within).input, InputStatus::kOk);
  EXPECT_EQ(monitor.refused_inputs(), refused);
  // Why each was refused, for a person; nothing for acceptable input.
  EXPECT_EQ(monitor.DescribeRefusal(bad[0].first),
            std::to_string(good.size() - 1) + " positions for the model's " +
                std::to_string(good.size()) + " joints");
  EXPECT_EQ(monitor.DescribeRefusal(nan), "joint '" + wc->joint_names[3] + "' at nan");
  EXPECT_EQ(monitor.DescribeRefusal(inf), "joint '" + wc->joint_names[5] + "' at -inf");
  std::ostringstream expected;
  expected << "joint 'left_joint2' at " << beyond[j2] << ", outside its limits ["
           << test::LimitsOf(*wc).lower[j2] << ", " << upper << "] by more than their margin "
           << kJointLimitMargin;
  EXPECT_EQ(monitor.DescribeRefusal(beyond), expected.str());
  EXPECT_EQ(monitor.DescribeRefusal(within), "");
  EXPECT_EQ(monitor.DescribeRefusal(good), "");
}

TEST(MonitorScene, IdleCycleReturnsTheSameReport) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  const Eigen::VectorXd q = MakeQ(*wc, {{"left_joint2", M_PI / 2}, {"left_joint4", M_PI / 2}});
  const CycleReport first = monitor.Update(q);
  ASSERT_FALSE(first.warnings.empty());
  const BroadPhaseCounters total = monitor.total_counters();
  for (int k = 0; k < 5; ++k) {
    const CycleReport& idle = monitor.Update(q);
    EXPECT_EQ(idle.cycle, first.cycle + 1 + k);
    EXPECT_EQ(idle.moved_primitives, 0u);
    EXPECT_EQ(idle.stop, first.stop);
    ASSERT_EQ(idle.warnings.size(), first.warnings.size());
    for (std::size_t i = 0; i < idle.warnings.size(); ++i) {
      EXPECT_EQ(idle.warnings[i].a, first.warnings[i].a);
      EXPECT_EQ(idle.warnings[i].b, first.warnings[i].b);
      EXPECT_EQ(idle.warnings[i].distance_m, first.warnings[i].distance_m);
    }
  }
  // No broad-phase work was done by the idle cycles.
  EXPECT_EQ(monitor.total_counters().object_object_tests, total.object_object_tests);
  EXPECT_EQ(monitor.Check(q).warnings.size(), first.warnings.size());
}

// Speed-scaled tolerance: the same approach of the left forearm to the front table top, slow
// and fast; the fast one warns earlier (farther away). Stopped there (the same q again), it
// is at rest: the base tolerances.
TEST(MonitorScene, SpeedScaledToleranceWarnsLaterWhenSlow) {
  const auto wc = LoadBundledWorkcell();
  MonitorOptions options;
  options.speed_scaled_tolerance = true;
  const PrimitiveId table = Prim(*wc, "front_table_top");
  // Joint 4 sweeps the straight, horizontal forearm down onto the table; returns the angle of
  // the first warning against the table and the threshold it had.
  auto first_warning = [&](double joint4_speed_radps) {
    Monitor monitor(wc, options);
    Eigen::VectorXd q = MakeQ(*wc, {{"left_joint2", M_PI / 2}});
    const int j4 = test::JointIndex(*wc, "left_joint4");
    for (int k = 0; k < 100000; ++k) {
      q[j4] = k * joint4_speed_radps * options.cycle_period_s;
      const CycleReport& report = monitor.Update(q);
      for (const Warning& w : report.warnings) {
        if (w.b != table && w.a != table) continue;
        const Warning first = w;
        // Sampled again where it is, the forearm is at rest: base tolerances (as Check(q), a
        // sample of every joint, says), and the table is warned only within their sum.
        const CycleReport at_rest_check = monitor.Check(q);
        const CycleReport& at_rest = monitor.Update(q);
        EXPECT_EQ(at_rest.moved_primitives, 0u);
        EXPECT_EQ(at_rest.warnings.size(), at_rest_check.warnings.size());
        const double base_m = wc->primitives[first.a].tolerance_m +
                              wc->primitives[first.b].tolerance_m;
        bool is_table_warned = false;
        for (const Warning& r : at_rest.warnings) {
          EXPECT_EQ(r.threshold_m,
                    wc->primitives[r.a].tolerance_m + wc->primitives[r.b].tolerance_m);
          is_table_warned |= r.a == first.a && r.b == first.b;
        }
        EXPECT_EQ(is_table_warned, first.distance_m <= base_m) << first.distance_m;
        return std::make_pair(q[j4], first.threshold_m);
      }
      if (q[j4] > M_PI / 2) break;
    }
    ADD_FAILURE() << "no warning at " << joint4_speed_radps << " rad/s";
    return std::make_pair(0.0, 0.0);
  };
  const auto [slow_angle, slow_threshold] = first_warning(0.05);
  const auto [fast_angle, fast_threshold] = first_warning(0.6);
  std::printf("slow: warns at %.4f rad, threshold %.4f m; fast: %.4f rad, %.4f m\n", slow_angle,
              slow_threshold, fast_angle, fast_threshold);
  EXPECT_GT(slow_angle, fast_angle);
  EXPECT_GT(fast_threshold, slow_threshold);
  const double gain_s = options.reaction_time_s + options.stopping_time_s;
  EXPECT_LE(fast_threshold, 2 * 0.0305 + options.max_speed_mps * gain_s + 1e-12);
}

// Per-joint sample times, one topic per arm: every joint named with `prefix` sampled at time_s.
void SetArmTime(const Workcell& wc, const std::string& prefix, double time_s,
                Eigen::VectorXd* t_s) {
  for (Eigen::Index i = 0; i < t_s->size(); ++i) {
    if (wc.joint_names[static_cast<std::size_t>(i)].rfind(prefix, 0) == 0) (*t_s)[i] = time_s;
  }
}

// With each joint's own sample times (one topic per arm), an unmoved primitive keeps its speed
// while a joint above it moved at its newest sample: the other arm's cycles keep it (they took
// it at rest, its base tolerance, every other cycle), and its joints sampled again unmoved take
// it to rest, in an idle cycle too. A joint sampled apart from the others above it (a torso's)
// takes nothing to rest by its own unmoved sample. With one time for every joint, every joint
// counts as sampled.
TEST(MonitorScene, SpeedScaledToleranceKeepsASpeedUntilItsJointsAreSampledAgain) {
  const auto wc = LoadBundledWorkcell();
  MonitorOptions options;
  options.speed_scaled_tolerance = true;
  const PrimitiveId left = Prim(*wc, "left_link7");
  const PrimitiveId right = Prim(*wc, "right_link7");
  const double base_m = wc->primitives[left].tolerance_m;
  ASSERT_EQ(wc->primitives[right].tolerance_m, base_m);
  const int l1 = test::JointIndex(*wc, "left_joint1");
  const int l4 = test::JointIndex(*wc, "left_joint4");
  const int r1 = test::JointIndex(*wc, "right_joint1");
  Monitor monitor(wc, options);
  Eigen::VectorXd q = MakeQ(*wc, {{"left_joint2", 0.5}, {"right_joint2", 0.5}});
  Eigen::VectorXd t_s = Eigen::VectorXd::Zero(q.size());
  const auto update = [&](const Eigen::VectorXd& times) {
    const CycleReport& report = monitor.Update(q, times);
    ASSERT_EQ(report.input, InputStatus::kOk);
  };
  // The first cycle takes every moving primitive at the largest speed (none known); the right
  // arm's joints never received since (stamped -inf, as the node's defaulted joints) are at rest
  // from the next cycle.
  update(t_s);
  EXPECT_GT(monitor.tolerance_m(right), base_m);
  SetArmTime(*wc, "right_", -std::numeric_limits<double>::infinity(), &t_s);
  q[l1] += 0.02;
  SetArmTime(*wc, "left_", 0.05, &t_s);
  update(t_s);
  const double left_moving_m = monitor.tolerance_m(left);
  EXPECT_GT(left_moving_m, base_m);
  EXPECT_EQ(monitor.tolerance_m(right), base_m);
  // The right arm's message: the left arm keeps its speed.
  q[r1] += 0.03;
  SetArmTime(*wc, "right_", 0.06, &t_s);
  update(t_s);
  EXPECT_EQ(monitor.tolerance_m(left), left_moving_m);
  const double right_moving_m = monitor.tolerance_m(right);
  EXPECT_GT(right_moving_m, left_moving_m);  // a larger move
  // The left arm's message where it was: an idle cycle (the same q), after which the right
  // arm's next message takes the left arm at rest and moves the right one again.
  SetArmTime(*wc, "left_", 0.10, &t_s);
  ASSERT_TRUE(monitor.Update(q, t_s).moved_primitives == 0u);
  EXPECT_EQ(monitor.tolerance_m(left), base_m);
  q[r1] += 0.03;
  SetArmTime(*wc, "right_", 0.11, &t_s);
  update(t_s);
  EXPECT_EQ(monitor.tolerance_m(left), base_m);
  EXPECT_GT(monitor.tolerance_m(right), left_moving_m);
  // The left elbow moves in the left arm's message (the right arm, not sampled, keeps its
  // speed); then the left shoulder alone is sampled again unmoved, with the right arm's next
  // move: the left hand keeps its speed, the elbow's newest sample having moved it.
  q[l4] += 0.02;
  SetArmTime(*wc, "left_", 0.15, &t_s);
  update(t_s);
  const double left_elbow_m = monitor.tolerance_m(left);
  EXPECT_GT(left_elbow_m, base_m);
  EXPECT_GT(monitor.tolerance_m(right), base_m);
  q[r1] += 0.01;
  SetArmTime(*wc, "right_", 0.16, &t_s);
  t_s[l1] = 0.16;
  update(t_s);
  EXPECT_EQ(monitor.tolerance_m(left), left_elbow_m);
  EXPECT_GT(monitor.tolerance_m(right), base_m);
  // One time for every joint: the arm that did not move is at rest.
  q[r1] += 0.02;
  ASSERT_EQ(monitor.Update(q, 0.2).input, InputStatus::kOk);
  EXPECT_EQ(monitor.tolerance_m(left), base_m);
  EXPECT_GT(monitor.tolerance_m(right), base_m);
}

// Speed-scaled tolerances with each joint's own sample times: a primitive moved by a joint
// sampled apart (a torso's, here the left shoulder) while the joints below it move at their
// newest sample adds their step (its speed is not the shoulder's alone); a joint whose value
// changes under the same time (an unstamped message dated by a clock behind) is sampled anew.
TEST(MonitorScene, SpeedScaledToleranceAddsTheStepOfJointsSampledApart) {
  const auto wc = LoadBundledWorkcell();
  MonitorOptions options;
  options.speed_scaled_tolerance = true;
  const PrimitiveId left = Prim(*wc, "left_link7");
  const double base_m = wc->primitives[left].tolerance_m;
  const int l1 = test::JointIndex(*wc, "left_joint1");
  const int l4 = test::JointIndex(*wc, "left_joint4");
  const int r1 = test::JointIndex(*wc, "right_joint1");
  Monitor monitor(wc, options);
  Eigen::VectorXd q = MakeQ(*wc, {{"left_joint2", 0.5}, {"right_joint2", 0.5}});
  Eigen::VectorXd t_s = Eigen::VectorXd::Zero(q.size());
  const auto update = [&]() { ASSERT_EQ(monitor.Update(q, t_s).input, InputStatus::kOk); };
  update();
  t_s.setConstant(0.05);  // every joint sampled where it was: at rest
  update();
  ASSERT_EQ(monitor.tolerance_m(left), base_m);
  // The left arm but its shoulder: the elbow moves.
  const double shoulder_s = t_s[l1];
  SetArmTime(*wc, "left_", 0.10, &t_s);
  t_s[l1] = shoulder_s;
  q[l4] += 0.02;
  update();
  const double elbow_m = monitor.tolerance_m(left);
  EXPECT_GT(elbow_m, base_m);
  // The shoulder alone, a hair: the hand is moved, the elbow's step with it.
  t_s[l1] = 0.11;
  q[l1] += 1e-6;
  update();
  EXPECT_GE(monitor.tolerance_m(left), elbow_m);
  // The whole left arm sampled unmoved (at rest), then the elbow moves under the same times:
  // moving, the right arm's next cycle keeps its speed.
  SetArmTime(*wc, "left_", 0.15, &t_s);
  update();
  ASSERT_EQ(monitor.tolerance_m(left), base_m);
  q[l4] += 0.02;
  update();
  const double same_time_m = monitor.tolerance_m(left);
  EXPECT_GT(same_time_m, base_m);
  q[r1] += 0.01;
  SetArmTime(*wc, "right_", 0.20, &t_s);
  update();
  EXPECT_EQ(monitor.tolerance_m(left), same_time_m);
  ExpectValid(monitor);
}

// Speed-scaled tolerances: an object attached to an arm whose newest sample moved it takes the
// largest speed until the arm is sampled again (the other arm's cycle keeps it), then its own.
TEST(MonitorScene, SpeedScaledToleranceTakesAnObjectAttachedToAMovingArmAtTheLargestSpeed) {
  const auto wc = LoadBundledWorkcell();
  MonitorOptions options;
  options.speed_scaled_tolerance = true;
  const double gain_s = options.reaction_time_s + options.stopping_time_s;
  const PrimitiveId box = Prim(*wc, "right_box");
  const double base_m = wc->primitives[Prim(*wc, "right_link7")].tolerance_m;
  ASSERT_GE(base_m, wc->primitives[box].tolerance_m);  // held, it takes the gripper's
  Monitor monitor(wc, options);
  Eigen::VectorXd q = ArmReachDown(*wc, "right", 0.1, -1.55, 0.95);
  Eigen::VectorXd t_s = Eigen::VectorXd::Zero(q.size());
  std::string error;
  ASSERT_EQ(monitor.Update(q, t_s).input, InputStatus::kOk);
  // The right arm at rest: attached, the box is at rest too.
  SetArmTime(*wc, "right_", 0.05, &t_s);
  ASSERT_EQ(monitor.Update(q, t_s).input, InputStatus::kOk);
  ASSERT_TRUE(monitor.Attach("right_box", "right_link7", &error)) << error;
  EXPECT_EQ(monitor.tolerance_m(box), base_m);
  ASSERT_TRUE(monitor.Detach("right_box", &error)) << error;
  // The right wrist turns; attached then, the box takes the largest speed, kept in the left
  // arm's cycle, until the right arm's next sample moves it (its own speed) or not (at rest).
  q[test::JointIndex(*wc, "right_joint7")] += 0.01;
  SetArmTime(*wc, "right_", 0.10, &t_s);
  ASSERT_EQ(monitor.Update(q, t_s).input, InputStatus::kOk);
  ASSERT_TRUE(monitor.Attach("right_box", "right_link7", &error)) << error;
  const double largest_m = base_m + options.max_speed_mps * gain_s;
  EXPECT_EQ(monitor.tolerance_m(box), largest_m);
  q[test::JointIndex(*wc, "left_joint1")] += 0.01;
  SetArmTime(*wc, "left_", 0.11, &t_s);
  ASSERT_EQ(monitor.Update(q, t_s).input, InputStatus::kOk);
  EXPECT_EQ(monitor.tolerance_m(box), largest_m);
  q[test::JointIndex(*wc, "right_joint7")] += 0.01;
  SetArmTime(*wc, "right_", 0.15, &t_s);
  ASSERT_EQ(monitor.Update(q, t_s).input, InputStatus::kOk);
  const double turning_m = monitor.tolerance_m(box);
  EXPECT_GT(turning_m, base_m);
  EXPECT_LT(turning_m, largest_m);
  SetArmTime(*wc, "right_", 0.20, &t_s);
  ASSERT_EQ(monitor.Update(q, t_s).input, InputStatus::kOk);
  EXPECT_EQ(monitor.tolerance_m(box), base_m);
  ExpectValid(monitor);
}

// The bundled workcell with speed-scaled tolerance, and its tracked box `camera` (a frame-bound
// object): its base tolerance, the tolerance gain of a speed, and its pose moved along x.
class TrackedCamera : public ::testing::Test {
 protected:
  TrackedCamera() { options.speed_scaled_tolerance = true; }
  Eigen::Isometry3d PoseAt(double x_m) const {
    Eigen::Isometry3d X = wc->objects[wc->FindObject("camera")].X_WO_start;
    X.translation().x() += x_m;
    return X;
  }
  // The camera's tolerance at speed `speed_mps`.
  double ToleranceAt(double speed_mps) const {
    return base_m + speed_mps * (options.reaction_time_s + options.stopping_time_s);
  }
  const std::shared_ptr<const Workcell> wc = LoadBundledWorkcell();
  MonitorOptions options;
  const PrimitiveId camera = Prim(*wc, "camera");
  const double base_m = wc->primitives[camera].tolerance_m;
};

// A frame-bound object posed with its sample times (a 10 Hz tracker) in a 20 Hz monitor whose
// arms move every cycle: its speed over the interval between its poses is kept in the cycle
// between them (untimed, it took it at rest: its base tolerance, every other cycle); the same
// pose at a later time takes it to rest, in an idle cycle too; a move at a time not later
// takes the largest speed; an untimed pose gives the speed of its move in the cycle.
TEST_F(TrackedCamera, SpeedScaledToleranceKeepsATimedObjectsSpeedBetweenItsPoses) {
  const int l1 = test::JointIndex(*wc, "left_joint1");
  Monitor monitor(wc, options);
  Eigen::VectorXd q = MakeQ(*wc, {{"left_joint2", 0.5}});
  std::string error;
  const double speed_mps = 0.2;
  std::vector<double> tolerances;
  for (int k = 0; k < 10; ++k) {
    const double t_s = 0.05 * k;
    if (k % 2 == 0) {
      ASSERT_TRUE(monitor.SetObjectPoseAt("camera", PoseAt(speed_mps * t_s), t_s, &error))
          << error;
    }
    q[l1] += 0.01;
    ASSERT_EQ(monitor.Update(q, t_s).input, InputStatus::kOk);
    tolerances.push_back(monitor.tolerance_m(camera));
  }
  // From the second timed pose on, every cycle: 0.2 m/s (0.02 m over 0.1 s, to rounding).
  for (std::size_t k = 2; k < tolerances.size(); ++k) {
    EXPECT_NEAR(tolerances[k], ToleranceAt(speed_mps), 1e-12) << "cycle " << k;
  }
  // Sampled again where it is: at rest, in an idle cycle (the same q) too.
  ASSERT_TRUE(monitor.SetObjectPoseAt("camera", PoseAt(speed_mps * 0.4), 0.5, &error));
  ASSERT_EQ(monitor.Update(q, 0.5).input, InputStatus::kOk);
  EXPECT_EQ(monitor.tolerance_m(camera), base_m);
  // Moved at the same time again: its speed is unknown, the largest, kept the next cycle.
  ASSERT_TRUE(monitor.SetObjectPoseAt("camera", PoseAt(0.1), 0.5, &error));
  q[l1] += 0.01;
  ASSERT_EQ(monitor.Update(q, 0.55).input, InputStatus::kOk);
  EXPECT_EQ(monitor.tolerance_m(camera), ToleranceAt(options.max_speed_mps));
  q[l1] += 0.01;
  ASSERT_EQ(monitor.Update(q, 0.6).input, InputStatus::kOk);
  EXPECT_EQ(monitor.tolerance_m(camera), ToleranceAt(options.max_speed_mps));
  // Untimed: its move in the cycle (0.01 m in 0.05 s), then at rest in the next.
  ASSERT_TRUE(monitor.SetObjectPose("camera", PoseAt(0.11), &error));
  q[l1] += 0.01;
  ASSERT_EQ(monitor.Update(q, 0.65).input, InputStatus::kOk);
  EXPECT_NEAR(monitor.tolerance_m(camera), ToleranceAt(0.01 / options.cycle_period_s), 1e-12);
  q[l1] += 0.01;
  ASSERT_EQ(monitor.Update(q, 0.7).input, InputStatus::kOk);
  EXPECT_EQ(monitor.tolerance_m(camera), base_m);
  EXPECT_FALSE(monitor.SetObjectPoseAt("camera", PoseAt(0.0),
                                       std::numeric_limits<double>::quiet_NaN(), &error));
  ExpectValid(monitor);
}

// A tracker that went silent: a move after more than kObjectSpeedMaxGapCycles cycle periods
// without a timed pose takes the largest speed (averaged over the gap, 0.02 m in 0.55 s would
// read 0.036 m/s); within that gap the measured speed stands, and an unmoved pose after any gap
// is at rest.
TEST_F(TrackedCamera, SpeedScaledToleranceTakesTheLargestSpeedForAMoveAfterALongGap) {
  Monitor monitor(wc, options);
  const Eigen::VectorXd q = MakeQ(*wc, {{"left_joint2", 0.5}});
  std::string error;
  // Posed at `x_m` along x at time `t_s`, then a cycle at that time: the camera's tolerance.
  auto tolerance_after = [&](double x_m, double t_s) {
    EXPECT_TRUE(monitor.SetObjectPoseAt("camera", PoseAt(x_m), t_s, &error)) << error;
    EXPECT_EQ(monitor.Update(q, t_s).input, InputStatus::kOk);
    return monitor.tolerance_m(camera);
  };
  const double gap_s = kObjectSpeedMaxGapCycles * options.cycle_period_s;
  tolerance_after(0.0, 0.0);
  EXPECT_NEAR(tolerance_after(0.02, 0.1), ToleranceAt(0.2), 1e-12);
  EXPECT_EQ(tolerance_after(0.04, 0.1 + gap_s + 0.05), ToleranceAt(options.max_speed_mps));
  EXPECT_NEAR(tolerance_after(0.06, 0.2 + gap_s + 0.05), ToleranceAt(0.2), 1e-12);
  // Just within the gap: 0.09 m over 0.9 of it, the measured speed.
  const double t_s = 0.2 + gap_s + 0.05 + 0.9 * gap_s;
  EXPECT_NEAR(tolerance_after(0.15, t_s), ToleranceAt(0.09 / (0.9 * gap_s)), 1e-9);
  // Unmoved after a long gap: at rest.
  EXPECT_EQ(tolerance_after(0.15, t_s + 3.0 * gap_s), base_m);
  ExpectValid(monitor);
}

TEST(MonitorScene, InconsistentOptionsAreRejected) {
  const auto wc = LoadBundledWorkcell();
  MonitorOptions options;
  options.cycle_period_s = 0.0;
  EXPECT_THROW(Monitor(wc, options), LoadError);
  options = MonitorOptions{};
  options.max_speed_mps = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Monitor(wc, options), LoadError);
}

}  // namespace
}  // namespace arm_collision_monitor
