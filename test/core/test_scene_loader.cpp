// LoadWorkcell: the bundled workcell, a third-party-style URDF, and every
// kind of bad input, each rejected with a message naming the file and the element.
#include <console_bridge/console.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/scene/workcell.h"
#include "load_error_expect.h"
#include "test_scene_util.h"

namespace arm_collision_monitor {
namespace {

const std::string kArmUrdf = kData + "three_link_arm.urdf";
const std::string kArmMeshUrdf = kData + "three_link_arm_mesh.urdf";

// A world cube for the small scenes written by the tests.
const std::string kWorldLine = "world: {center_m: [0, 0, 1], edge_m: 4}\n";

// Writes a copy of the three-link arm's URDF with the first `from` replaced by `to`; returns
// its path.
std::string WriteEditedArmUrdf(const std::string& name, const std::string& from,
                               const std::string& to) {
  return WriteEditedFile(kArmUrdf, name, {{from, to}});
}

void ExpectSceneError(const std::string& urdf, const std::string& scene_text,
                      const std::vector<std::string>& parts) {
  const std::string path = WriteTempFile("scene.yaml", scene_text);
  std::vector<std::string> all = parts;
  all.push_back(path);
  ExpectLoadError([&] { LoadWorkcell(urdf, path); }, all);
}

int CountIf(const Workcell& w, bool (*predicate)(const PrimitiveSpec&)) {
  int count = 0;
  for (const PrimitiveSpec& p : w.primitives) count += predicate(p);
  return count;
}

bool IsDefaultCapsule(const PrimitiveSpec& p) {
  return p.variant.empty() && std::holds_alternative<Capsule>(p.shape_L);
}
bool IsDefaultBox(const PrimitiveSpec& p) {
  return p.variant.empty() && std::holds_alternative<Box>(p.shape_L);
}
bool IsVariant(const PrimitiveSpec& p) { return !p.variant.empty(); }

// ------------------------------------------------------------------ the bundled workcell ---

TEST(SceneLoader, BundledWorkcellHasTheSeeds35Primitives) {
  const Workcell w = LoadWorkcell(kUrdf, kScene);
  std::string why;
  EXPECT_TRUE(w.Validate(&why)) << why;
  EXPECT_EQ(CountIf(w, IsDefaultCapsule), 14);
  EXPECT_EQ(CountIf(w, IsDefaultBox), 21);
  EXPECT_EQ(CountIf(w, IsVariant), 6);  // palm + 2 fingers per gripper, inactive at start
  EXPECT_EQ(w.compatible.size(), w.primitives.size());
  EXPECT_TRUE(w.warnings.empty()) << w.warnings.front();
  ASSERT_EQ(w.joint_names.size(), 14u);
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(w.joint_names[i], "left_joint" + std::to_string(i + 1));
    EXPECT_EQ(w.joint_names[7 + i], "right_joint" + std::to_string(i + 1));
  }
  EXPECT_EQ(w.fixed_frame, "world");
  EXPECT_NEAR((w.world_W.max_W - w.world_W.min_W).maxCoeff(), 6.35, 1e-12);
  EXPECT_NEAR((w.world_W.max_W - w.world_W.min_W).minCoeff(), 6.35, 1e-12);
  for (const PrimitiveSpec& p : w.primitives) {
    // Every primitive of a moving link gets its arm's tolerance, everything else 0.
    const bool is_arm = p.group == "left" || p.group == "right";
    EXPECT_EQ(is_arm, std::holds_alternative<Capsule>(p.shape_L)) << p.name;
    EXPECT_EQ(p.tolerance_m, is_arm ? 0.0305 : 0.0) << p.name;
    EXPECT_EQ(p.is_static,
              !is_arm && p.name != "front_box" && p.name != "right_box" && p.name != "camera")
        << p.name;
  }
  ASSERT_EQ(w.arms.size(), 2u);
  EXPECT_EQ(w.grasp_targets.size(), 3u);
  ASSERT_EQ(w.variants.size(), 2u);
  EXPECT_EQ(w.variants[0].primitives.size(), 3u);
  ASSERT_GE(w.FindObject("camera"), 0);
  EXPECT_EQ(w.objects[w.FindObject("camera")].frame, "camera_link");
  EXPECT_TRUE(w.objects[w.FindObject("front_box")].is_attachable);
  EXPECT_FALSE(w.objects[w.FindObject("front_table_top")].is_attachable);
  for (const ObjectSpec& o : w.objects) {
    EXPECT_EQ(w.primitives[o.primitive].name, o.name);
    EXPECT_EQ(w.primitives[o.primitive].object_index, w.FindObject(o.name));
  }
}

TEST(SceneLoader, BundledGripperIsOneCapsuleEndingAtTheToolTip) {
  const Workcell w = LoadWorkcell(kUrdf, kScene);
  // The "cylinder plus two end spheres" idiom became one capsule named after its link.
  ASSERT_GE(w.FindPrimitive("left_link7"), 0);
  EXPECT_LT(w.FindPrimitive("left_link7/0"), 0);
  const Capsule& c = std::get<Capsule>(w.primitives[w.FindPrimitive("left_link7")].shape_L);
  EXPECT_NEAR(c.radius_m, 0.06, 1e-12);
  EXPECT_NEAR(c.p0_W.z(), 0.06, 1e-12);
  EXPECT_NEAR(c.p1_W.z(), 0.145, 1e-12);
  // Home pose: the capsule's top is the tool tip, 0.8 m pedestal + 1.905 m reach.
  std::vector<Eigen::Isometry3d> X_WL(w.kinematics.link_count());
  w.kinematics.ComputeLinkPoses(Eigen::VectorXd::Zero(14), &X_WL);
  const Shape tip_W = TransformShape(X_WL[w.kinematics.FindLink("left_link7")],
                                     w.primitives[w.FindPrimitive("left_link7")].shape_L);
  EXPECT_NEAR(ComputeAabb(tip_W).max_W.z(), 0.8 + 1.905, 1e-12);
}

TEST(SceneLoader, BundledCompatibility) {
  const Workcell w = LoadWorkcell(kUrdf, kScene);
  for (const std::string side : {"left", "right"}) {
    EXPECT_TRUE(Compatible(w, side + "_pedestal", side + "_link1"));  // through fixed base
    EXPECT_FALSE(Compatible(w, side + "_pedestal", side + "_link2"));
    for (int i = 1; i < 7; ++i) {
      const std::string a = side + "_link" + std::to_string(i);
      EXPECT_TRUE(Compatible(w, a, side + "_link" + std::to_string(i + 1)));
      if (i < 6) {
        EXPECT_FALSE(Compatible(w, a, side + "_link" + std::to_string(i + 2)));
      }
    }
    EXPECT_TRUE(Compatible(w, side + "_link6", side + "_link7/palm"));
    EXPECT_TRUE(Compatible(w, side + "_link7", side + "_link7/finger1"));
    EXPECT_FALSE(Compatible(w, side + "_link7", "front_box"));  // only while grasping
  }
  // Both pedestals are fixed to the world frame, yet they are separate parts.
  EXPECT_FALSE(Compatible(w, "left_pedestal", "right_link1"));
  EXPECT_FALSE(Compatible(w, "left_link1", "right_link1"));
  EXPECT_FALSE(Compatible(w, "left_link7", "right_link7"));
  EXPECT_TRUE(Compatible(w, "front_box", "front_table_top"));  // listed in the scene file
  EXPECT_TRUE(Compatible(w, "right_box", "right_table_top"));
  EXPECT_FALSE(Compatible(w, "front_box", "right_table_top"));
  EXPECT_FALSE(Compatible(w, "left_link7", "front_table_top"));
}

// ------------------------------------------------------------------ third-party URDFs ------

TEST(SceneLoader, ThirdPartyCylinderArmLoads) {
  const Workcell w = LoadWorkcell(kArmUrdf, kData + "three_link_scene.yaml");
  std::string why;
  EXPECT_TRUE(w.Validate(&why)) << why;
  EXPECT_EQ(w.joint_names, (std::vector<std::string>{"shoulder", "elbow", "spin", "slide"}));
  // base box, upper_arm, forearm, wrist sphere, two finger boxes, the table.
  ASSERT_EQ(w.primitives.size(), 7u);
  const PrimitiveSpec& base = w.primitives[w.FindPrimitive("base_link")];
  EXPECT_TRUE(std::holds_alternative<Box>(base.shape_L));
  EXPECT_TRUE(base.is_static);
  EXPECT_EQ(base.tolerance_m, 0.0);
  const PrimitiveSpec& upper = w.primitives[w.FindPrimitive("upper_arm")];
  const Capsule& upper_capsule = std::get<Capsule>(upper.shape_L);
  EXPECT_TRUE(upper_capsule.p0_W.isApprox(Eigen::Vector3d(0, 0, 0), 1e-15));
  EXPECT_NEAR((upper_capsule.p1_W - Eigen::Vector3d(0, 0, 0.4)).norm(), 0.0, 1e-15);
  EXPECT_EQ(upper_capsule.radius_m, 0.05);
  EXPECT_EQ(upper.tolerance_m, 0.0305);
  EXPECT_EQ(upper.group, "arm");
  // The forearm cylinder is rotated onto x by its origin: the capsule follows.
  const Capsule& forearm = std::get<Capsule>(w.primitives[w.FindPrimitive("forearm")].shape_L);
  EXPECT_NEAR((forearm.p0_W - Eigen::Vector3d(0, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((forearm.p1_W - Eigen::Vector3d(0.35, 0, 0)).norm(), 0.0, 1e-12);
  const Capsule& wrist = std::get<Capsule>(w.primitives[w.FindPrimitive("wrist")].shape_L);
  EXPECT_EQ(wrist.p0_W, wrist.p1_W);  // a sphere: zero-length capsule
  EXPECT_EQ(wrist.radius_m, 0.045);
  EXPECT_TRUE(Compatible(w, "base_link", "upper_arm"));
  EXPECT_TRUE(Compatible(w, "wrist", "finger_a"));
  EXPECT_FALSE(Compatible(w, "finger_a", "finger_b"));  // siblings
  EXPECT_FALSE(Compatible(w, "upper_arm", "wrist"));
  EXPECT_FALSE(Compatible(w, "base_link", "forearm"));
}

// A joint with velocity 0 (a MOVO and a Techman user's URDFs: accepted without a word) or a
// continuous joint without <limit> is named in a start-up notice, with what it means and the
// remedy; the scene file's joint_limits: velocity silences it.
TEST(SceneLoader, JointsWithoutAVelocityLimitAreNoticed) {
  auto has_notice = [](const Workcell& w, const std::string& part) {
    for (const std::string& notice : w.notices) {
      if (notice.find(part) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_FALSE(has_notice(LoadWorkcell(kArmUrdf, kData + "three_link_scene.yaml"),
                          "without a velocity limit"));
  const std::string urdf = WriteEditedArmUrdf("no_velocity.urdf", "<limit velocity=\"2.0\" "
                                              "effort=\"10\"/>", "");
  const std::string scene = WriteTempFile("no_velocity.yaml", kWorldLine);
  const Workcell w = LoadWorkcell(urdf, scene);
  EXPECT_TRUE(has_notice(w, urdf + ": joint 'spin' without a velocity limit (velocity 0, or no "
                              "<limit>): the start-up check"))
      << ::testing::PrintToString(w.notices);
  EXPECT_TRUE(has_notice(w, "joint_limits: {<joint>: {velocity: v}}"));
  const Workcell given = LoadWorkcell(
      urdf, WriteTempFile("velocity_given.yaml",
                          kWorldLine + "joint_limits: {spin: {velocity: 2.0}}\n"));
  EXPECT_FALSE(has_notice(given, "without a velocity limit")) << ::testing::PrintToString(
      given.notices);
}

// ... and a scene file without arms (an empty one too, or arms: []) says so at start-up; one
// with an arm does not.
TEST(SceneLoader, MovingLinksOutsideEveryArmKeepTheDefaultTolerance) {
  const auto has_no_arms_warning = [](const Workcell& w) {
    return std::any_of(w.warnings.begin(), w.warnings.end(), [&](const std::string& warning) {
      return warning.rfind(w.scene_path + ": arms: not given or empty", 0) == 0 &&
             warning.find("default tolerance (0.04 m)") != std::string::npos;
    });
  };
  const Workcell w = LoadWorkcell(kArmUrdf, WriteTempFile("no_arms.yaml", kWorldLine),
                                  /*default_arm_tolerance_m=*/0.04);
  EXPECT_EQ(w.primitives[w.FindPrimitive("base_link")].tolerance_m, 0.0);  // fixed to the root
  EXPECT_EQ(w.primitives[w.FindPrimitive("upper_arm")].tolerance_m, 0.04);
  EXPECT_EQ(w.primitives[w.FindPrimitive("upper_arm")].group, "");
  EXPECT_TRUE(has_no_arms_warning(w)) << ::testing::PrintToString(w.warnings);
  for (const std::string& text : {std::string(), kWorldLine + "arms: []\n"}) {
    const Workcell empty =
        LoadWorkcell(kArmUrdf, WriteTempFile("empty.yaml", text), /*default_arm_tolerance_m=*/0.04);
    EXPECT_TRUE(has_no_arms_warning(empty)) << text << ::testing::PrintToString(empty.warnings);
  }
  const Workcell one_arm = LoadWorkcell(kArmUrdf, kData + "three_link_scene.yaml", 0.04);
  EXPECT_FALSE(has_no_arms_warning(one_arm));
  EXPECT_EQ(one_arm.primitives[one_arm.FindPrimitive("upper_arm")].group, "arm");
}

// The plain loader resolves no package:// URL (the ROS programs' fetcher does: test/node).
TEST(SceneLoader, PackageMeshWithoutRosFetcherFailsNamingLinkAndFile) {
  ExpectLoadError([&] { LoadWorkcell(kArmMeshUrdf, kData + "three_link_scene.yaml"); },
                  {kArmMeshUrdf, "link 'forearm'",
                   "package://arm_collision_monitor/test/data/meshes/forearm.stl",
                   "package:// URLs are not resolved", "give a file path"});
}

TEST(SceneLoader, MeshWorksThroughAnOverride) {
  const Workcell w = LoadWorkcell(kArmMeshUrdf, kData + "three_link_mesh_override.yaml");
  const PrimitiveSpec& forearm = w.primitives[w.FindPrimitive("forearm")];
  const Capsule& c = std::get<Capsule>(forearm.shape_L);
  EXPECT_EQ(c.p1_W, Eigen::Vector3d(0.35, 0, 0));
  EXPECT_EQ(c.radius_m, 0.045);
  EXPECT_EQ(forearm.tolerance_m, 0.02);  // the arm's tolerance from the scene
  std::string why;
  EXPECT_TRUE(w.Validate(&why)) << why;
  // Ignoring the link works as well.
  const std::string ignore =
      WriteTempFile("ignore.yaml", kWorldLine + "links:\n  forearm: {ignore: true}\n");
  EXPECT_LT(LoadWorkcell(kArmMeshUrdf, ignore).FindPrimitive("forearm"), 0);
}

TEST(SceneLoader, LinkOverridesRadiusEndpointsAndTolerance) {
  const Workcell w = LoadWorkcell(
      kArmUrdf,
      WriteTempFile("overrides.yaml", kWorldLine + "arms: [{name: arm, root_link: upper_arm}]\n"
                                               "links:\n"
                                               "  upper_arm: {radius_m: 0.07, tolerance_m: 0.05}\n"
                                               "  wrist: {p0_m: [0, 0, 0], p1_m: [0.1, 0, 0]}\n"));
  const PrimitiveSpec& upper = w.primitives[w.FindPrimitive("upper_arm")];
  EXPECT_EQ(std::get<Capsule>(upper.shape_L).radius_m, 0.07);
  EXPECT_EQ(upper.tolerance_m, 0.05);
  EXPECT_EQ(w.primitives[w.FindPrimitive("forearm")].tolerance_m, 0.0305);
  // Endpoints without a radius keep the link's single capsule's radius.
  const Capsule& wrist = std::get<Capsule>(w.primitives[w.FindPrimitive("wrist")].shape_L);
  EXPECT_EQ(wrist.p1_W, Eigen::Vector3d(0.1, 0, 0));
  EXPECT_EQ(wrist.radius_m, 0.045);
  // A radius below the link's own (0.05 m) is warned of; the wider one above is not.
  const auto narrowing = [](const Workcell& x) {
    const std::string start = x.scene_path + ": links.upper_arm: radius_m 0.03 m is below the ";
    return std::count_if(x.warnings.begin(), x.warnings.end(), [&](const std::string& warning) {
      return warning.rfind(start + "0.05 m", 0) == 0;
    });
  };
  EXPECT_EQ(narrowing(w), 0) << ::testing::PrintToString(w.warnings);
  const std::string narrow_scene = kWorldLine + "links: {upper_arm: {radius_m: 0.03}}\n";
  const Workcell narrow = LoadWorkcell(kArmUrdf, WriteTempFile("narrow.yaml", narrow_scene));
  const PrimitiveSpec& narrow_upper = narrow.primitives[narrow.FindPrimitive("upper_arm")];
  EXPECT_EQ(std::get<Capsule>(narrow_upper.shape_L).radius_m, 0.03);
  EXPECT_EQ(narrowing(narrow), 1) << ::testing::PrintToString(narrow.warnings);
}

TEST(SceneLoader, CapsuleIdiomNeedsMatchingSpheres) {
  const std::string link_template =
      "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <link name=\"base\">\n"
      "    <collision><origin xyz=\"0 0 0.5\"/><geometry><cylinder radius=\"0.1\" "
      "length=\"1\"/></geometry></collision>\n"
      "    <collision><origin xyz=\"0 0 0\"/><geometry><sphere radius=\"RADIUS\"/></geometry>"
      "</collision>\n"
      "    <collision><origin xyz=\"0 0 1\"/><geometry><sphere radius=\"0.1\"/></geometry>"
      "</collision>\n  </link>\n</robot>\n";
  const std::string scene = WriteTempFile("idiom.yaml", kWorldLine);
  auto with_radius = [&](const std::string& radius) {
    std::string text = link_template;
    text.replace(text.find("RADIUS"), 6, radius);
    return LoadWorkcell(WriteTempFile("idiom_" + radius + ".urdf", text), scene);
  };
  const Workcell merged = with_radius("0.1");
  ASSERT_EQ(merged.primitives.size(), 1u);
  const Capsule& c = std::get<Capsule>(merged.primitives[0].shape_L);
  EXPECT_NEAR((c.p0_W - Eigen::Vector3d(0, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((c.p1_W - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, 1e-15);
  // A larger end sphere is not a cap: three primitives named by their index in the link.
  const Workcell separate = with_radius("0.2");
  ASSERT_EQ(separate.primitives.size(), 3u);
  EXPECT_EQ(separate.primitives[1].name, "base/1");
}

// Drake's <capsule radius length> URDF extension, which urdfdom cannot parse (it drops the
// link's collision elements from there on: an iiwa user's Drake URDF was refused, "has 1
// <collision> elements but urdfdom read 0"): the capsule along z of its origin, `length`
// between its end spheres' centres, beside the link's other elements, which keep their names.
TEST(SceneLoader, DrakeCapsuleElementIsACapsule) {
  const std::string urdf = WriteTempFile(
      "drake_capsule.urdf",
      "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <link name=\"base\">\n"
      "    <collision name=\"body\"><origin xyz=\"0.1 0.2 0.3\" rpy=\"1.5707963267948966 0 0\"/>"
      "<geometry><capsule radius=\"0.05\" length=\"0.4\"/></geometry></collision>\n"
      "    <collision><origin xyz=\"0 0 1\"/><geometry><box size=\"0.1 0.1 0.1\"/></geometry>"
      "</collision>\n  </link>\n</robot>\n");
  const Workcell w = LoadWorkcell(urdf, WriteTempFile("drake_capsule.yaml", kWorldLine));
  ASSERT_EQ(w.primitives.size(), 2u);
  const int body = w.FindPrimitive("base/body");
  ASSERT_GE(body, 0);
  const Capsule& c = std::get<Capsule>(w.primitives[body].shape_L);
  // rpy (pi/2, 0, 0) turns z onto the y axis.
  const Eigen::Vector3d a(0.1, 0.2 + 0.2, 0.3), b(0.1, 0.2 - 0.2, 0.3);
  EXPECT_NEAR(std::min((c.p0_W - a).norm(), (c.p0_W - b).norm()), 0.0, 1e-12);
  EXPECT_NEAR(std::min((c.p1_W - a).norm(), (c.p1_W - b).norm()), 0.0, 1e-12);
  EXPECT_NEAR((c.p0_W - c.p1_W).norm(), 0.4, 1e-12);
  EXPECT_EQ(c.radius_m, 0.05);
  const Box& box = std::get<Box>(w.primitives[1 - body].shape_L);
  EXPECT_EQ(box.X_WB.translation(), Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(w.primitives[1 - body].name, "base/1");
}

// A box of size 0 0 0 (kinova-ros's end-effector links) is a point at its origin, as a sphere
// of radius 0 is; a box with one size 0 stays refused (BadCollisionGeometryNamesTheElement).
TEST(SceneLoader, BoxOfSizeZeroIsAPoint) {
  const std::string urdf = WriteTempFile(
      "zero_box.urdf",
      "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <link name=\"base\">\n"
      "    <collision><origin xyz=\"0.1 0.2 0.3\" rpy=\"0 0 0\"/><geometry><box size=\"0 0 0\"/>"
      "</geometry></collision>\n  </link>\n</robot>\n");
  const Workcell w = LoadWorkcell(urdf, WriteTempFile("zero_box.yaml", kWorldLine));
  ASSERT_EQ(w.primitives.size(), 1u);
  const Capsule& point = std::get<Capsule>(w.primitives[0].shape_L);
  EXPECT_EQ(point.p0_W, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(point.p1_W, point.p0_W);
  EXPECT_EQ(point.radius_m, 0.0);
}

// A bad size in a <collision> element stops start-up with a message naming the file, the link,
// the element's index in the link and what was expected (ReadCollisionElement; urdfdom itself
// drops an element whose numbers do not parse, which CheckEveryCollisionRead reports).
TEST(SceneLoader, BadCollisionGeometryNamesTheElement) {
  const std::string scene = WriteTempFile("bad_geometry.yaml", kWorldLine);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"<origin xyz=\"0 0 0\"/><geometry><box size=\"0 1 1\"/></geometry>",
       "<box size> must be 3 finite numbers > 0, or all 0 (a point)"},
      {"<origin xyz=\"0 0 0\"/><geometry><sphere radius=\"-0.1\"/></geometry>",
       "<sphere radius> must be a finite number >= 0"},
      {"<origin xyz=\"0 0 0\"/><geometry><cylinder radius=\"0.1\" length=\"-1\"/></geometry>",
       "<cylinder radius, length> must be finite numbers >= 0"},
      {"<origin xyz=\"0 0 0\"/><geometry><capsule radius=\"0.1\" length=\"x\"/></geometry>",
       "<capsule>: <capsule radius, length> must be finite numbers >= 0"},
      {"<origin xyz=\"0 0\"/><geometry><capsule radius=\"0.1\" length=\"1\"/></geometry>",
       "<capsule>: <origin>:"},
      // urdfdom keeps the first shape of a <geometry> only (a red team's sphere went unseen).
      {"<geometry><cylinder radius=\"0.1\" length=\"1\"/><sphere radius=\"0.5\"/></geometry>",
       "link 'base': its <collision> element 1 (from 0) in the file holds a <geometry> of 2 "
       "shapes; urdfdom reads only the first: give each shape a <collision> of its own"},
      {"<geometry><cylinder radius=\"0.1\" length=\"1\"/></geometry>"
       "<geometry><sphere radius=\"0.5\"/></geometry>",
       "link 'base': its <collision> element 1 (from 0) in the file holds 2 <geometry> elements; "
       "urdfdom reads only the first"},
  };
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::string urdf = WriteTempFile(
        "bad_geometry_" + std::to_string(k) + ".urdf",
        "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <link name=\"base\">\n"
        "    <collision><geometry><sphere radius=\"0.1\"/></geometry></collision>\n"
        "    <collision>" + cases[k].first + "</collision>\n  </link>\n</robot>\n");
    // urdfdom's elements are numbered where ReadCollisionElement refuses one, the file's where
    // urdfdom drops shapes.
    const bool is_dropped = cases[k].second.rfind("link 'base': ", 0) == 0;
    ExpectLoadError([&] { LoadWorkcell(urdf, scene); },
                    {urdf, is_dropped ? cases[k].second : "link 'base' <collision> 1 (from 0)",
                     cases[k].second});
  }
}

TEST(SceneLoader, PairsOverlappingInEveryConfigurationAreReported) {
  const std::string scene_text = kWorldLine +
                                 "arms: [{name: arm, root_link: upper_arm}]\n"
                                 "links: {upper_arm: {radius_m: 0.5}}\n";
  const Workcell w = LoadWorkcell(kArmUrdf, WriteTempFile("always.yaml", scene_text));
  ASSERT_FALSE(w.warnings.empty());
  bool found = false;
  for (const std::string& warning : w.warnings) {
    found |= warning.find("'upper_arm' and 'wrist'") != std::string::npos;
    EXPECT_NE(warning.find("seed"), std::string::npos) << warning;
  }
  EXPECT_TRUE(found) << w.warnings.front();
  // Declaring them compatible silences it.
  const Workcell excused = LoadWorkcell(
      kArmUrdf, WriteTempFile("always_excused.yaml",
                          scene_text + "compatible: [[upper_arm, wrist], [upper_arm, finger_a], "
                                       "[upper_arm, finger_b]]\n"));
  for (const std::string& warning : excused.warnings) {
    EXPECT_EQ(warning.find("'upper_arm' and"), std::string::npos) << warning;
  }
  // A wrist of two primitives: one finding for the two links, named as compatible: takes them
  // (a Sawyer user read 20 findings of primitives where 4 pairs of links excused them all).
  const std::string two = WriteEditedArmUrdf(
      "two_wrist.urdf", "<geometry><sphere radius=\"0.045\"/></geometry>\n    </collision>",
      "<geometry><sphere radius=\"0.045\"/></geometry>\n    </collision>\n    <collision>\n"
      "      <origin xyz=\"0.02 0 0\"/>\n      <geometry><sphere radius=\"0.03\"/></geometry>\n"
      "    </collision>");
  int wrist_findings = 0;
  for (const std::string& warning :
       LoadWorkcell(two, WriteTempFile("always_two.yaml", scene_text)).warnings) {
    if (warning.find("'upper_arm' and 'wrist") == std::string::npos) continue;
    ++wrist_findings;
    EXPECT_NE(warning.find("'upper_arm' and 'wrist' (2 pairs of their primitives: 'upper_arm' "
                           "and 'wrist/0', 'upper_arm' and 'wrist/1') are within their "
                           "tolerances in the home pose and in all 256 sampled configurations"),
              std::string::npos)
        << warning;
    EXPECT_NE(warning.find("list them under compatible: ([upper_arm, wrist])"),
              std::string::npos)
        << warning;
  }
  EXPECT_EQ(wrist_findings, 1);
}

// The findings of pairs that touch in every configuration name the two links or objects only
// where excusing them excuses no other pair.
TEST(SceneLoader, PairsOverlappingEverywhereAreGroupedOnlyWhereExcusingTheOwnersIsSafe) {
  auto findings_of = [](const Workcell& w, const std::string& part) {
    std::vector<std::string> found;
    for (const std::string& warning : w.warnings) {
      if (warning.find(part) != std::string::npos) found.push_back(warning);
    }
    return found;
  };
  // A post in the upper arm's axis, touched by its capsule and by a model variant's: both pairs
  // of the two owners, one finding (the variant's primitives come after the objects, in the
  // other order) with the entry that excuses them.
  const std::string post = kWorldLine + "arms: [{name: arm, root_link: upper_arm}]\n"
                           "objects: [{name: post, size_m: [0.02, 0.02, 0.02], "
                           "pose: {xyz_m: [0, 0, 0.35]}}]\n";
  // The findings naming the post, with the upper arm's variant of one capsule (x, r).
  auto with_variant = [&](const std::string& x, const std::string& r) {
    return findings_of(
        LoadWorkcell(kArmUrdf, WriteTempFile("variant_post.yaml",
                                             post + "variants: [{link: upper_arm, name: v, "
                                                    "capsules: [{name: c, p0_m: [" + x +
                                                    ", 0, 0.1], p1_m: [" + x +
                                                    ", 0, 0.3], radius_m: " + r + "}]}]\n")),
        "'post'");
  };
  const std::vector<std::string> grouped = with_variant("0", "0.05");
  ASSERT_EQ(grouped.size(), 1u);
  EXPECT_NE(grouped[0].find("'upper_arm' and 'post' (2 pairs of their primitives: 'upper_arm' "
                            "and 'post', '"),
            std::string::npos)
      << grouped[0];
  EXPECT_NE(grouped[0].find("compatible: ([upper_arm, post])"), std::string::npos) << grouped[0];
  // A variant's capsule far off the post: 'upper_arm', the name of the link's one default
  // primitive, stands for the variant's too, so no entry can excuse the default's pair alone.
  const std::vector<std::string> no_entry = with_variant("0.4", "0.01");
  ASSERT_EQ(no_entry.size(), 1u);
  EXPECT_NE(no_entry[0].find("'upper_arm' and 'post' are within their tolerances in the home "
                             "pose and in all 256"),
            std::string::npos)
      << no_entry[0];
  EXPECT_NE(no_entry[0].find("they would warn in every cycle; 1 of them compatible: cannot "
                             "excuse alone (their names stand for a link or object, all of "
                             "whose primitives an entry would excuse, model variants' too)"),
            std::string::npos)
      << no_entry[0];
  // The upper arm with a collar around its base, which holds a post beside the axis in every
  // configuration, and a knob that meets the post at one shoulder angle: excusing the two
  // links would excuse the knob, so the collar's pair alone is named.
  const std::string arm = WriteEditedArmUrdf(
      "collar_knob.urdf", "<geometry><cylinder radius=\"0.05\" length=\"0.4\"/></geometry>\n"
                          "    </collision>",
      "<geometry><cylinder radius=\"0.05\" length=\"0.4\"/></geometry>\n    </collision>\n"
      "    <collision name=\"collar\">\n      <origin xyz=\"0 0 0.1\"/>\n"
      "      <geometry><cylinder radius=\"0.35\" length=\"0.1\"/></geometry>\n"
      "    </collision>\n    <collision name=\"knob\">\n      <origin xyz=\"0 0.3 0.3\"/>\n"
      "      <geometry><sphere radius=\"0.03\"/></geometry>\n    </collision>");
  const std::string beside = kWorldLine + "arms: [{name: arm, root_link: upper_arm}]\n"
                             "objects: [{name: post, size_m: [0.02, 0.02, 0.5], "
                             "pose: {xyz_m: [0.3, 0, 0.35]}}]\n";
  const Workcell collar = LoadWorkcell(arm, WriteTempFile("collar_post.yaml", beside));
  const std::vector<std::string> alone = findings_of(collar, "'post'");
  ASSERT_EQ(alone.size(), 1u);
  EXPECT_NE(alone[0].find("'upper_arm' and 'post' (1 pair of their primitives: 'upper_arm/collar' "
                          "and 'post') are within their tolerances in the home pose and in all "
                          "256"),
            std::string::npos)
      << alone[0];
  EXPECT_NE(alone[0].find("compatible: ([upper_arm/collar, post])"), std::string::npos)
      << alone[0];
  // The entry shown silences the finding and leaves the knob's pair checked.
  const Workcell excused = LoadWorkcell(
      arm, WriteTempFile("collar_post_excused.yaml",
                         beside + "compatible: [[upper_arm/collar, post]]\n"));
  EXPECT_TRUE(findings_of(excused, "'post'").empty()) << findings_of(excused, "'post'").front();
  EXPECT_FALSE(excused.compatible.AreCompatible(excused.FindPrimitive("upper_arm/knob"),
                                                excused.FindPrimitive("post")));
}

// The entry a finding shows reads back as the names it holds, however odd (a planning scene's
// object ids are free text): appended to the scene, it silences the finding.
TEST(SceneLoader, TheEntryAFindingShowsExcusesItsPair) {
  for (const std::string& name :
       {std::string("post #1"), std::string("null"), std::string("say \"hi\" \\ now"),
        std::string("two\nlines")}) {
    std::string quoted = "\"";  // the name in the scene file, YAML double-quoted
    for (const char c : name) {
      if (c == '"' || c == '\\') quoted += '\\';
      quoted += c == '\n' ? std::string("\\n") : std::string(1, c);
    }
    const std::string scene = kWorldLine + "arms: [{name: arm, root_link: upper_arm}]\n"
                              "objects: [{name: " + quoted + "\", size_m: [0.02, 0.02, 0.02], "
                              "pose: {xyz_m: [0, 0, 0.35]}}]\n";
    const Workcell w = LoadWorkcell(kArmUrdf, WriteTempFile("odd_name.yaml", scene));
    std::string entry;
    for (const std::string& warning : w.warnings) {
      const std::size_t at = warning.find("list them under compatible: (");
      if (warning.find("'" + name + "'") == std::string::npos || at == std::string::npos) continue;
      const std::size_t from = at + std::string("list them under compatible: (").size();
      entry = warning.substr(from, warning.rfind(')') - from);
    }
    ASSERT_FALSE(entry.empty()) << name;
    const Workcell excused =
        LoadWorkcell(kArmUrdf, WriteTempFile("odd_name_excused.yaml",
                                             scene + "compatible: [" + entry + "]\n"));
    EXPECT_TRUE(excused.compatible.AreCompatible(excused.FindPrimitive("upper_arm"),
                                                 excused.FindPrimitive(name)))
        << name << ": " << entry;
  }
}

TEST(SceneLoader, PairsOverlappingInMostConfigurationsAreReported) {
  // The upper arm's capsule set 0.3 m off the shoulder's axis: at shoulder angle t (uniform in
  // its limits [-2.5, 2.5]) its axis is at x = 0.3 cos(t + 0.3) (the joint's yaw 0.3). The slab
  // from x = -0.05 on is within the threshold (0.05, the arm's tolerance) of the capsule (radius
  // 0.05) while cos(t + 0.3) >= -0.5: in 4.19 rad of the 5 (84 %: about 214 of 256 samples),
  // the home pose too, not in all (a Flexiv Rizon user's link5 and link7 warned in every cycle
  // of a path, with no finding).
  const std::string scene_text =
      kWorldLine +
      "arms: [{name: arm, root_link: upper_arm, tolerance_m: 0.05}]\n"
      "links: {upper_arm: {p0_m: [0.3, 0, 0], p1_m: [0.3, 0, 0.4]}}\n"
      "objects: [{name: slab, size_m: [1.0, 3.0, 0.4], pose: {xyz_m: [0.45, 0, 0.3]}}]\n";
  const Workcell w = LoadWorkcell(kArmUrdf, WriteTempFile("most.yaml", scene_text));
  const std::string pair = "'upper_arm' and 'slab' are within their tolerances in the home pose "
                           "and in ";
  int found = 0;
  for (const std::string& warning : w.warnings) {
    const std::size_t at = warning.find(pair);
    if (at == std::string::npos) continue;
    ++found;
    const int within = std::atoi(warning.c_str() + at + pair.size());
    EXPECT_GE(within, kMostlyOverlappingSamples) << warning;
    EXPECT_LT(within, kAlwaysOverlappingSamples) << warning;
    EXPECT_NEAR(within, 0.84 * kAlwaysOverlappingSamples, 40) << warning;  // > 6 binomial sd
    EXPECT_NE(warning.find(" of 256 sampled configurations (seed "), std::string::npos);
    // A link and an object: no advice to excuse them.
    EXPECT_NE(warning.find(" (half or more): they would warn in most cycles; a lower tolerance, "
                           "another fit of the link's geometry (mesh_fit:, links:) or the "
                           "object placed farther may clear them"),
              std::string::npos)
        << warning;
  }
  EXPECT_EQ(found, 1);
  // Farther off (the slab from x = 0.1 on: cos(t + 0.3) >= 0, 3.14 rad of 5, 63 %) it is still
  // reported; from x = 0.35 on (cos >= 0.833: 1.17 of 5, 23 %, still within in the home pose,
  // cos 0.3 = 0.955), no longer.
  for (const auto& [x_m, is_reported] : {std::pair{0.6, true}, std::pair{0.85, false}}) {
    const std::string moved = kWorldLine +
                              "arms: [{name: arm, root_link: upper_arm, tolerance_m: 0.05}]\n"
                              "links: {upper_arm: {p0_m: [0.3, 0, 0], p1_m: [0.3, 0, 0.4]}}\n"
                              "objects: [{name: slab, size_m: [1.0, 3.0, 0.4], pose: {xyz_m: [" +
                              std::to_string(x_m) + ", 0, 0.3]}}]\n";
    bool reported = false;
    for (const std::string& warning :
         LoadWorkcell(kArmUrdf, WriteTempFile("most_moved.yaml", moved)).warnings) {
      reported |= warning.find(pair) != std::string::npos;
    }
    EXPECT_EQ(reported, is_reported) << "slab centre at x = " << x_m;
  }
}

TEST(SceneLoader, PrimitivesOfOneObjectAreCompatible) {
  // A mesh object fitted by a chain of capsules that overlap at their joints: one rigid body,
  // never checked against itself (the start-up check called the attachable rod's own pairs
  // "'rod' and 'rod'", and, carried, they would have warned in every cycle).
  const Workcell w = LoadWorkcell(
      kArmUrdf, WriteTempFile("rod.yaml", kWorldLine + "mesh_fit: capsules:4\n"
                                              "objects: [{name: rod, type: mesh, mesh: " +
                                              kData + "meshes/forearm.stl, pose: {xyz_m: [1, 1, "
                                              "1]}, attachable: true, tolerance_m: 0.01}]\n"));
  const ObjectSpec& rod = w.objects[w.FindObject("rod")];
  ASSERT_GT(rod.primitive_count, 1);
  for (int i = 0; i < rod.primitive_count; ++i) {
    for (int j = i + 1; j < rod.primitive_count; ++j) {
      EXPECT_TRUE(w.compatible.AreCompatible(rod.primitive + i, rod.primitive + j)) << i << j;
    }
  }
  for (const std::string& warning : w.warnings) {
    EXPECT_EQ(warning.find("'rod/"), std::string::npos) << warning;
  }
}

TEST(SceneLoader, PrimitivesOutsideTheWorldInTheHomePoseAreReported) {
  const Workcell w = LoadWorkcell(
      kArmUrdf, WriteTempFile("small_world.yaml", "world: {center_m: [0, 0, 0.2], edge_m: 0.6}\n"));
  bool found = false;
  for (const std::string& warning : w.warnings) {
    found |= warning.find("'upper_arm' with its tolerance is not inside the world cube") !=
             std::string::npos;
    EXPECT_EQ(warning.find("unit error"), std::string::npos) << warning;  // 0.5 m wide
  }
  EXPECT_TRUE(found);
}

// A link in millimetres (a mesh without scale: here its cylinder, 350 m long) is outside a given
// world cube, and the warning says why it most likely is.
TEST(SceneLoader, ALinkWiderThanAWorkcellIsNamedAUnitError) {
  const std::string urdf = WriteEditedArmUrdf(
      "mm_arm.urdf", "<cylinder radius=\"0.04\" length=\"0.35\"/>",
      "<cylinder radius=\"40\" length=\"350\"/>");
  const Workcell w = LoadWorkcell(urdf, kData + "three_link_scene.yaml");
  bool found = false;
  for (const std::string& warning : w.warnings) {
    found |= warning.find("'forearm' with its tolerance is not inside the world cube") !=
                 std::string::npos &&
             warning.find("unit error in link 'forearm' (a mesh in millimetres without scale") !=
                 std::string::npos;
  }
  EXPECT_TRUE(found) << ::testing::PrintToString(w.warnings);
}

// Without world: (the derived cube holds every link) a link in millimetres is named a unit error
// first among the warnings, before the pairs it makes warn in every cycle.
TEST(SceneLoader, AWideLinkInADerivedWorldIsNamedAUnitErrorFirst) {
  const std::string urdf = WriteEditedArmUrdf(
      "mm_arm_derived.urdf", "<cylinder radius=\"0.04\" length=\"0.35\"/>",
      "<cylinder radius=\"40\" length=\"350\"/>");
  const Workcell w = LoadWorkcell(urdf, WriteTempFile("no_world.yaml", "{}\n"));
  ASSERT_FALSE(w.warnings.empty());
  EXPECT_NE(w.warnings[0].find("'forearm' with its tolerance, in the home pose: it is "),
            std::string::npos) << w.warnings[0];
  EXPECT_NE(w.warnings[0].find("unit error in link 'forearm' (a mesh in millimetres without "
                               "scale"), std::string::npos) << w.warnings[0];
  int unit_errors = 0;
  for (const std::string& warning : w.warnings) {
    unit_errors += warning.find("unit error") != std::string::npos;
  }
  EXPECT_EQ(unit_errors, 1) << ::testing::PrintToString(w.warnings);
  // The workcell as it should be: no such warning.
  for (const std::string& warning : LoadWorkcell(kArmUrdf, WriteTempFile("no_world.yaml",
                                                                         "{}\n")).warnings) {
    EXPECT_EQ(warning.find("unit error"), std::string::npos) << warning;
  }
}

// A link wider than 20 m (a gantry's rail) outside a given world cube of 100 m that could hold
// it: misplaced, not a unit error; wider than the cube itself, it is named one.
TEST(SceneLoader, ALinkTheWorldCouldHoldIsNotNamedAUnitError) {
  for (const int length_m : {30, 150}) {
    const std::string urdf = WriteEditedArmUrdf(
        "long_arm.urdf", "<cylinder radius=\"0.04\" length=\"0.35\"/>",
        "<cylinder radius=\"0.04\" length=\"" + std::to_string(length_m) + "\"/>");
    const Workcell w = LoadWorkcell(
        urdf, WriteTempFile("far_world.yaml", "world: {center_m: [60, 0, 0], edge_m: 100}\n"));
    bool is_outside = false, is_unit_error = false;
    for (const std::string& warning : w.warnings) {
      is_outside |= warning.find("'forearm' with its tolerance is not inside the world cube") !=
                    std::string::npos;
      is_unit_error |= warning.find("unit error in link 'forearm'") != std::string::npos;
    }
    EXPECT_TRUE(is_outside) << length_m << ::testing::PrintToString(w.warnings);
    EXPECT_EQ(is_unit_error, length_m > 100) << length_m << ::testing::PrintToString(w.warnings);
  }
}

TEST(SceneLoader, JointLimitOverrides) {
  const Workcell w = LoadWorkcell(
      kArmUrdf,
      WriteTempFile("limits.yaml", kWorldLine + "joint_limits: {elbow: {lower: -1.0}}\n"));
  const JointSpec& elbow = w.kinematics.joint(w.kinematics.FindJointChildLink("elbow"));
  EXPECT_EQ(elbow.lower, -1.0);
  EXPECT_EQ(elbow.upper, 2.0);
  ExpectSceneError(kArmUrdf, kWorldLine + "joint_limits: {elbow: {upper: 3.0}}\n",
                   {"joint_limits.elbow", "URDF upper"});
  ExpectSceneError(kArmUrdf, kWorldLine + "joint_limits: {knee: {upper: 1.0}}\n",
                   {"joint_limits.knee", "unknown joint"});
  ExpectSceneError(kArmUrdf, kWorldLine + "joint_limits: {finger_mimic: {upper: 0.0}}\n",
                   {"joint_limits.finger_mimic", "a mimic joint of 'slide'"});
  // The continuous wrist's soft limits lie within kMaxUnlimitedPosition_rad (beyond it, no
  // position would be accepted).
  ExpectSceneError(kArmUrdf, kWorldLine + "joint_limits: {spin: {lower: 2e9}}\n",
                   {"joint_limits.spin", "expected URDF lower (none: -1e+09) <= lower <= upper "
                                         "<= URDF upper (none: 1e+09)"});
  ExpectSceneError(kArmUrdf, kWorldLine + "joint_limits: {elbow: {upper: 3.0}}\n",
                   {"expected URDF lower (-2) <= lower <= upper <= URDF upper (2)"});
  // A velocity limit below the URDF's (its motor's, say) replaces it; above it, or not positive,
  // is an error naming the key.
  const Workcell slow = LoadWorkcell(
      kArmUrdf, WriteTempFile("velocity.yaml",
                              kWorldLine + "joint_limits: {elbow: {velocity: 0.25}}\n"));
  const JointSpec& slow_elbow = slow.kinematics.joint(slow.kinematics.FindJointChildLink("elbow"));
  EXPECT_EQ(slow_elbow.max_velocity, 0.25);
  EXPECT_EQ(slow_elbow.lower, -2.0);  // the URDF's, untouched
  EXPECT_GT(elbow.max_velocity, 0.25);
  ExpectSceneError(kArmUrdf,
                   kWorldLine + "joint_limits: {elbow: {velocity: " +
                       std::to_string(2.0 * elbow.max_velocity) + "}}\n",
                   {"joint_limits.elbow.velocity", "<= URDF velocity"});
  ExpectSceneError(kArmUrdf, kWorldLine + "joint_limits: {elbow: {velocity: 0}}\n",
                   {"joint_limits.elbow.velocity"});
  ExpectSceneError(kArmUrdf, kWorldLine + "joint_limits: {elbow: {speed: 1}}\n",
                   {"joint_limits.elbow", "unknown key 'speed'"});
}

TEST(SceneLoader, JointDefaults) {
  const Workcell w = LoadWorkcell(
      kArmUrdf, WriteTempFile("defaults.yaml", kWorldLine +
                                                   "joint_limits: {elbow: {lower: -1.0}}\n"
                                                   "joint_defaults: {slide: 0.05, spin: -7.5}\n"));
  const auto q_index = [&](const char* joint) {
    return w.kinematics.joint(w.kinematics.FindJointChildLink(joint)).q_index;
  };
  const std::vector<std::pair<int, double>> expected = {{q_index("slide"), 0.05},
                                                        {q_index("spin"), -7.5}};
  EXPECT_EQ(w.joint_defaults, expected);
  EXPECT_TRUE(LoadWorkcell(kArmUrdf, WriteTempFile("no_defaults.yaml", kWorldLine))
                  .joint_defaults.empty());
  // Within the limits, the soft ones included; an actuated joint (a mimic joint follows its
  // target); a number.
  const std::vector<std::pair<std::string, std::vector<std::string>>> bad = {
      {"joint_defaults: {slide: 0.3}\n", {"joint_defaults.slide", "within the joint's limits"}},
      {"joint_limits: {elbow: {lower: -1.0}}\njoint_defaults: {elbow: -1.5}\n",
       {"joint_defaults.elbow", "within the joint's limits"}},
      {"joint_defaults: {finger_mimic: 0}\n",
       {"joint_defaults.finger_mimic",
        "a mimic joint of 'slide' (its position follows that joint's: give that joint's)"}},
      {"joint_defaults: {tool_joint: 0}\n",
       {"joint_defaults.tool_joint", "a fixed joint of the URDF (expected an actuated joint)"}},
      {"joint_defaults: {knee: 0}\n", {"joint_defaults.knee", "unknown joint"}},
      {"joint_defaults: {elbow: open}\n", {"joint_defaults.elbow"}},
      {"joint_defaults: {elbow: .nan}\n", {"joint_defaults.elbow"}},
      // The continuous wrist: within kMaxUnlimitedPosition_rad (beyond, every cycle is refused).
      {"joint_defaults: {spin: 2e9}\n",
       {"joint_defaults.spin", "within the joint's limits [none: -1e+09, none: 1e+09]"}},
  };
  for (const auto& [scene, parts] : bad) ExpectSceneError(kArmUrdf, kWorldLine + scene, parts);
  ExpectSceneError(kArmUrdf, kWorldLine + "joint_defaults: [elbow, 0]\n", {"joint_defaults"});
}

TEST(SceneLoader, ValidateCatchesBrokenInvariants) {
  Workcell w = LoadWorkcell(kUrdf, kScene);
  std::string why;
  ASSERT_TRUE(w.Validate(&why)) << why;
  Workcell renamed = w;
  renamed.primitives[3].name = renamed.primitives[2].name;
  EXPECT_FALSE(renamed.Validate(&why));
  EXPECT_NE(why.find("duplicate name"), std::string::npos) << why;
  for (const std::pair<int, double>& bad : {std::pair<int, double>{14, 0.0}, {-1, 0.0},
                                            {0, std::numeric_limits<double>::quiet_NaN()}}) {
    Workcell defaulted = w;
    defaulted.joint_defaults = {{1, 0.0}};
    EXPECT_TRUE(defaulted.Validate(&why)) << why;
    defaulted.joint_defaults.push_back(bad);
    EXPECT_FALSE(defaulted.Validate(&why)) << bad.first;
    EXPECT_NE(why.find("joint default"), std::string::npos) << why;
  }
  Workcell orphan = w;
  orphan.objects[0].primitive = 0;
  EXPECT_FALSE(orphan.Validate(&why));
  Workcell negative = w;
  std::get<Capsule>(negative.primitives[w.FindPrimitive("left_link2")].shape_L).radius_m = -1.0;
  EXPECT_FALSE(negative.Validate(&why));
  Workcell resized = w;
  resized.compatible = CompatibilityMatrix(3);
  EXPECT_FALSE(resized.Validate(&why));
}

// ------------------------------------------------------------------ bad input --------------

TEST(SceneLoader, MissingFilesAreRejected) {
  ExpectLoadError([&] { LoadWorkcell(kUrdf, kData + "no_such_scene.yaml"); },
                  {"no_such_scene.yaml", "cannot open"});
  ExpectLoadError([&] { LoadWorkcell(kData + "no_such.urdf", kScene); },
                  {"no_such.urdf", "cannot open"});
  // A relative path says where it was looked for (roslaunch runs nodes in ROS_HOME).
  const std::string cwd = std::filesystem::current_path().string();
  ExpectLoadError([&] { LoadWorkcell("no_such_relative.urdf", kScene); },
                  {"no_such_relative.urdf", "working directory '" + cwd + "'", "ROS_HOME"});
  ExpectLoadError([&] { LoadWorkcell(kUrdf, "no_such_relative.yaml"); },
                  {"no_such_relative.yaml", "working directory '" + cwd + "'"});
}

// Xacro left in a file, which urdfdom ignores: refused naming the element when it changes the
// model (in a link or joint, a condition, a call of a macro that writes a link or that the file
// does not define), else loaded with one warning that counts it and names included files. An
// expanded file keeping xacro's namespace attribute on <robot> gets urdfdom's verdict alone.
TEST(SceneLoader, XacroLeftIsRefusedWhereItChangesTheModel) {
  const std::string robot = "<robot name='r' xmlns:xacro='http://www.ros.org/wiki/xacro'>";
  const std::string expanded = WriteTempFile(
      "expanded.urdf", robot + "<link name='a'/><joint name='j' type='fixed'><parent link='a'/>"
                               "<child link='b'/></joint></robot>");
  try {
    LoadWorkcell(expanded, kScene);
    ADD_FAILURE() << "a joint to a missing link loaded";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("not a valid URDF"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("xacro"), std::string::npos) << e.what();
  }
  const std::string expand = "expand it with xacro first";
  const std::string unexpanded = WriteTempFile(
      "unexpanded.urdf", robot + "<xacro:property name='r' value='0.1'/><link name='a'><collision>"
                                 "<geometry><sphere radius='${r}'/></geometry></collision></link>"
                                 "</robot>");
  ExpectLoadError([&] { LoadWorkcell(unexpanded, kScene); },
                  {"unexpanded.urdf:1: link 'a': <sphere radius='${r}'>", "changes the model",
                   expand, "(Debian's ROS has none)"});
  const std::string scene = kData + "three_link_scene.yaml";
  // The three-link arm with `xacro` after its <robot> tag.
  auto with_xacro = [&](const std::string& xacro) {
    return WriteEditedArmUrdf("xacro.urdf", "<robot name=\"three_link_arm\">",
                              "<robot name=\"three_link_arm\">" + xacro);
  };
  const std::string gazebo_macro =
      "<xacro:macro name='paint' params='link'><gazebo reference='${link}'/></xacro:macro>";
  const std::string harmless = with_xacro(
      "<xacro:include filename='$(find arm)/urdf/materials.xacro'/>" + gazebo_macro +
      "<xacro:macro name='paint_twice' params='link'><xacro:paint link='${link}'/>"
      "<xacro:property name='unused' value='1'/></xacro:macro>"
      "<xacro:paint link='base_link'/><xacro:paint_twice link='wrist'/>");
  const Workcell plain = LoadWorkcell(kArmUrdf, scene);
  const Workcell w = LoadWorkcell(harmless, scene);
  ASSERT_EQ(w.primitives.size(), plain.primitives.size());
  ASSERT_EQ(w.warnings.size(), plain.warnings.size() + 1);
  EXPECT_EQ(w.warnings.front(),
            harmless + ": xacro left in the file, ignored as urdfdom ignores it: 2 macro, "
                       "property or arg definition(s); 2 call(s) of its macros that write no "
                       "link or joint; 1 <xacro:include> not read ('$(find arm)/urdf/"
                       "materials.xacro'): links or collision geometry an included file adds are "
                       "not in the model (expand the file with xacro if it adds any)");
  // A chain of macros past kXacroMaxMacroDepth, each calling the next.
  std::string chain;
  for (int k = 0; k <= kXacroMaxMacroDepth + 1; ++k) {
    chain += "<xacro:macro name='m" + std::to_string(k) + "'><xacro:m" + std::to_string(k + 1) +
             "/></xacro:macro>";
  }
  chain += "<xacro:macro name='m" + std::to_string(kXacroMaxMacroDepth + 2) +
           "'><gazebo/></xacro:macro><xacro:m0/>";
  for (const auto& [xacro, parts] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"<xacro:ur5 prefix='left_'/>", {"<xacro:ur5>", "a macro this file does not define"}},
           {gazebo_macro + "<xacro:macro name='arm'><xacro:paint link='a'/><link name='extra'/>"
                           "</xacro:macro><xacro:arm/>",
            {"<xacro:arm>", "its macro 'arm' writes a <link>"}},
           {"<xacro:macro name='loop'><xacro:paint link='a'/><xacro:loop/></xacro:macro>"
            "<xacro:loop/>" + gazebo_macro,
            {"<xacro:loop>", "its macro 'loop' calls itself"}},
           {chain, {"<xacro:m0>", "macros calling each other too deep"}},
           {"<xacro:macro name='maybe'><xacro:if value='1'><gazebo/></xacro:if></xacro:macro>"
            "<xacro:maybe/>",
            {"<xacro:maybe>", "its macro 'maybe' holds <xacro:if>"}},
           {"<xacro:if value='true'><link name='extra'/></xacro:if>", {"<xacro:if>"}},
           {"<link name='extra'><xacro:paint link='extra'/></link>",
            {"link 'extra': <xacro:paint>"}}}) {
    const std::string urdf = with_xacro(xacro);
    std::vector<std::string> all = parts;
    all.insert(all.end(), {urdf, "changes the model", expand});
    ExpectLoadError([&] { LoadWorkcell(urdf, scene); }, all);
  }
  const std::string named = WriteTempFile("named.urdf", "<robot name='${name}'/>");
  ExpectLoadError([&] { LoadWorkcell(named, scene); }, {"<robot name='${name}'>", expand});
}

TEST(SceneLoader, MalformedFilesAreRejected) {
  ExpectSceneError(kUrdf, "world: {center_m: [0, 0, 1], edge_m: 4\narms: [\n", {"malformed YAML"});
  ExpectSceneError(kUrdf, "- just\n- a list\n", {"expected a map"});
  // Its <link> is never closed: the element and its line, which urdfdom's own message ("Error
  // reading end tag") does not give.
  ExpectLoadError([&] { LoadWorkcell(kData + "malformed.urdf", kScene); },
                  {"malformed.urdf:4: malformed XML", "<link>, which begins on line 4,",
                   "expected a well-formed URDF"});
  // An empty file has no line to name.
  const std::string empty = WriteTempFile("empty.urdf", "  \n");
  ExpectLoadError([&] { LoadWorkcell(empty, kScene); },
                  {empty + ": malformed XML (XML_ERROR_EMPTY_DOCUMENT): the file holds no element "
                           "(expected a well-formed URDF)"});
  ExpectLoadError([&] { LoadWorkcell(kData + "floating_joint.urdf", kScene); },
                  {"floating_joint.urdf", "joint 'free'", "floating", "make it type='fixed'"});
  // What urdfdom rejects: its reasons (logged through console_bridge alone) in the error, with
  // the line of the element they name.
  const std::string head = "<robot name='r'>\n<link name='a'/>\n<link name='b'/>\n";
  for (const auto& [body, parts] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"<joint name='j' type='revolut'>\n<parent link='a'/><child link='b'/></joint>\n",
            {":4: joint 'j': not a valid URDF", "[j] has no known type [revolut]"}},
           {"<joint name='j' type='fixed'>\n<parent link='c'/><child link='b'/></joint>\n",
            {":4: joint 'j': not a valid URDF", "parent link [c] of joint [j] not found"}},
           {"<link name='a'/>\n", {":4: link 'a': not a valid URDF", "'a' is not unique"}}}) {
    const std::string urdf = WriteTempFile("rejected.urdf", head + body + "</robot>\n");
    std::vector<std::string> all = parts;
    all.insert(all.end(), {urdf, "urdfdom rejected it"});
    ExpectLoadError([&] { LoadWorkcell(urdf, kScene); }, all);
  }
  // With console_bridge silenced (as a process may set it), urdfdom's reasons still reach the
  // error, and the level is back after.
  const console_bridge::LogLevel level = console_bridge::getLogLevel();
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  const std::string silenced = WriteTempFile(
      "silenced.urdf", head + "<joint name='j' type='revolut'>\n<parent link='a'/><child "
                              "link='b'/></joint>\n</robot>\n");
  ExpectLoadError([&] { LoadWorkcell(silenced, kScene); },
                  {":4: joint 'j': not a valid URDF", "[j] has no known type [revolut]"});
  EXPECT_EQ(console_bridge::getLogLevel(), console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  console_bridge::setLogLevel(level);
  // A package's unexpanded xacro that only defines a macro (Interbotix ships its arms so): said.
  const std::string xacro = WriteTempFile(
      "macro_only.urdf.xacro",
      "<robot name='r' xmlns:xacro='http://ros.org/wiki/xacro'>\n<xacro:macro name='arm'>\n"
      "<link name='a'/>\n</xacro:macro>\n</robot>\n");
  ExpectLoadError([&] { LoadWorkcell(xacro, kScene); },
                  {xacro, "urdfdom rejected it", "it is xacro, not expanded (1 <xacro:...> "
                   "element(s), the first <xacro:macro name='arm'> at line 2): expand it"});
}

// The handler that keeps urdfdom's messages stays console_bridge's "previous" one after a parse,
// and rosconsole_bridge reinstates that one at exit: made current so, it must still be there (a
// handler on the stack was not), write what is logged, and serve the next parse.
TEST(SceneLoader, UrdfdomLogHandlerReinstatedStillWorks) {
  const std::string urdf = WriteTempFile(
      "reinstated.urdf", "<robot name='r'>\n<link name='a'/>\n<link name='b'/>\n<joint "
                         "name='j' type='revolut'>\n<parent link='a'/><child link='b'/></joint>"
                         "\n</robot>\n");
  ExpectLoadError([&] { LoadWorkcell(urdf, kScene); }, {"[j] has no known type [revolut]"});
  console_bridge::OutputHandler* const before = console_bridge::getOutputHandler();
  console_bridge::restorePreviousOutputHandler();  // as rosconsole_bridge's proxy does at exit
  ASSERT_NE(console_bridge::getOutputHandler(), before);
  CONSOLE_BRIDGE_logError("logged through the reinstated handler");
  ExpectLoadError([&] { LoadWorkcell(urdf, kScene); }, {":4: joint 'j'", "[revolut]"});
  CONSOLE_BRIDGE_logError("and after the next parse");
}

TEST(SceneLoader, UnknownNamesAreRejected) {
  ExpectSceneError(kUrdf, kWorldLine + "links: {left_link9: {ignore: true}}\n",
                   {"links.left_link9", "unknown link"});
  ExpectSceneError(kUrdf, kWorldLine + "arms: [{name: left, root_link: left_shoulder}]\n",
                   {"arms[0] 'left'", "unknown link 'left_shoulder'"});
  ExpectSceneError(kUrdf, kWorldLine + "joint_limits: {left_joint8: {lower: 0}}\n",
                   {"joint_limits.left_joint8", "unknown joint"});
  ExpectSceneError(kUrdf, kWorldLine + "compatible: [[left_link1, teapot]]\n",
                   {"compatible[0]", "unknown name 'teapot'"});
  ExpectSceneError(kUrdf, kWorldLine + "grasp_targets: [{link: left_link7, object: teapot}]\n",
                   {"grasp_targets[0]", "unknown object 'teapot'"});
  ExpectSceneError(kUrdf,
                   kWorldLine +
                       "variants: [{link: left_hand, name: grasp, capsules: "
                       "[{name: palm, p0_m: [0,0,0], p1_m: [0,0,1], radius_m: 0.1}]}]\n",
                   {"variants[0]", "unknown link 'left_hand'"});
  // A variant without capsules: yaml-cpp throws for the kind of the missing key's node, which
  // crashed the loader (a fuzzer's); the key is named.
  ExpectSceneError(kUrdf, kWorldLine + "variants: [{link: left_link7, name: grasp}]\n",
                   {"variants[0] 'left_link7/grasp'.capsules", "expected a list"});
  ExpectSceneError(kUrdf, kWorldLine + "objetcs: []\n", {"unknown key 'objetcs'"});
  ExpectSceneError(
      kUrdf, kWorldLine + "links:\n  left_link3: {radius_m: 0.1}\n  left_link3: {ignore: true}\n",
      {"links", "duplicate key 'left_link3'"});
  // world: may be omitted (test_scene_world_cube), not malformed.
  ExpectSceneError(kUrdf, "world: [0, 0, 3]\narms: []\n", {"world", "expected a map"});
}

TEST(SceneLoader, BadRadiiAreRejected) {
  ExpectSceneError(kUrdf, kWorldLine + "links: {left_link3: {radius_m: -0.1}}\n",
                   {"links.left_link3.radius_m", ">= 0"});
  ExpectSceneError(kUrdf, kWorldLine + "links: {left_link3: {radius_m: .nan}}\n",
                   {"links.left_link3.radius_m", "finite"});
  ExpectSceneError(kUrdf,
                   kWorldLine +
                       "variants: [{link: left_link7, name: grasp, capsules: "
                       "[{name: palm, p0_m: [0,0,0], p1_m: [0,0,1], radius_m: -1}]}]\n",
                   {"capsules[0].radius_m", ">= 0"});
  ExpectSceneError(kUrdf, kWorldLine + "links: {left_link3: {p0_m: [0, 0, 0]}}\n",
                   {"links.left_link3", "p0_m and p1_m"});
  // A negative radius in the URDF itself.
  const std::string bad_urdf =
      WriteEditedArmUrdf("negative_radius.urdf", "radius=\"0.05\"", "radius=\"-0.05\"");
  ExpectLoadError([&] { LoadWorkcell(bad_urdf, kData + "three_link_scene.yaml"); },
                  {bad_urdf, "link 'upper_arm'", "cylinder"});
}

TEST(SceneLoader, DuplicateNamesAreRejected) {
  ExpectSceneError(kUrdf,
                   kWorldLine +
                       "objects:\n"
                       "  - {name: crate, size_m: [1, 1, 1], pose: {xyz_m: [1, 1, 1]}}\n"
                       "  - {name: crate, size_m: [1, 1, 1], pose: {xyz_m: [1, 1, 1]}}\n",
                   {"objects[1] 'crate'", "duplicate name 'crate'", "objects[0]"});
  ExpectSceneError(kUrdf,
                   kWorldLine +
                       "objects:\n"
                       "  - {name: left_link2, size_m: [1, 1, 1], pose: {xyz_m: [1, 1, 1]}}\n",
                   {"duplicate name 'left_link2'", "link 'left_link2'"});
  ExpectSceneError(kUrdf,
                   kWorldLine +
                       "arms: [{name: a, root_link: left_base_link}, "
                       "{name: a, root_link: right_base_link}]\n",
                   {"arms[1]", "duplicate arm name 'a'"});
  ExpectSceneError(kUrdf,
                   kWorldLine +
                       "arms: [{name: a, root_link: left_base_link}, "
                       "{name: b, root_link: left_link3}]\n",
                   {"both contain link 'left_link3'"});
}

TEST(SceneLoader, BadBoxesAreRejected) {
  ExpectSceneError(
      kUrdf, kWorldLine + "objects: [{name: crate, size_m: [1, 0, 1], pose: {xyz_m: [1, 1, 1]}}]\n",
      {"objects[0] 'crate'", "size_m", "> 0"});
  ExpectSceneError(
      kUrdf,
      kWorldLine + "objects: [{name: crate, size_m: [1, -1, 1], pose: {xyz_m: [1, 1, 1]}}]\n",
      {"objects[0] 'crate'", "size_m"});
  ExpectSceneError(
      kUrdf, kWorldLine + "objects: [{name: crate, size_m: [1, 1], pose: {xyz_m: [1, 1, 1]}}]\n",
      {"objects[0] 'crate'.size_m", "3 numbers"});
  ExpectSceneError(kUrdf, kWorldLine + "objects: [{name: crate, size_m: [1, 1, 1]}]\n",
                   {"objects[0] 'crate'", "missing pose"});
  ExpectSceneError(
      kUrdf, kWorldLine + "objects: [{name: crate, size_m: [1, 1, 1], pose: {xyz_m: [9, 0, 1]}}]\n",
      {"objects[0] 'crate'", "world cube"});
  const std::string bad_urdf =
      WriteEditedArmUrdf("zero_box.urdf", "size=\"0.3 0.3 0.1\"", "size=\"0.3 0 0.1\"");
  ExpectLoadError([&] { LoadWorkcell(bad_urdf, kData + "three_link_scene.yaml"); },
                  {bad_urdf, "link 'base_link'", "box size"});
}

}  // namespace
}  // namespace arm_collision_monitor
