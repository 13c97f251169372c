// ReadPlanningSceneFile: a whole moveit_msgs/PlanningScene as `rostopic echo` writes it (a shelf
// of boxes, cans, a sphere, a cone, a mesh, an object with its own pose and frame, robot_state
// and an allowed collision matrix) and the compact form of benchmark suites, read field by
// field; every kind of bad input rejected with a message naming the file, the element and what
// was expected.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "arm_collision_monitor/scene/planning_scene_reader.h"
#include "load_error_expect.h"

namespace arm_collision_monitor {
namespace {

const std::string kData = std::string(ACM_SOURCE_DIR) + "/test/data/moveit/";
constexpr double kTight = 1e-12;

using NamePairs = std::vector<std::pair<std::string, std::string>>;

void ExpectPrimitive(const ScenePrimitive& primitive, SolidPrimitiveType type,
                     const std::vector<double>& dimensions_m, const Eigen::Vector3d& p_FP) {
  EXPECT_EQ(primitive.type, type);
  EXPECT_EQ(primitive.dimensions_m, dimensions_m);
  EXPECT_TRUE(primitive.X_FP.translation().isApprox(p_FP, kTight))
      << primitive.X_FP.translation().transpose();
}

TEST(PlanningSceneReader, RostopicEchoDump) {
  const PlanningSceneFile scene = ReadPlanningSceneFile(kData + "workcell_scene.yaml");
  EXPECT_EQ(scene.name, "workcell_shelf");
  EXPECT_TRUE(scene.notices.empty());  // no attached objects, an empty octomap
  EXPECT_TRUE(scene.joint_poses.empty());  // multi_dof_joint_state with no joints
  ASSERT_EQ(scene.objects.size(), 8u);
  const std::vector<std::string> ids = {"shelf", "can_1",  "can_2", "can_3",
                                        "ball",  "funnel", "wedge", "tray"};
  for (std::size_t i = 0; i < ids.size(); ++i) EXPECT_EQ(scene.objects[i].id, ids[i]);

  const SceneCollisionObject& shelf = scene.objects[0];
  EXPECT_EQ(shelf.frame_id, "world");
  EXPECT_EQ(shelf.element, "world.collision_objects[0] 'shelf'");
  EXPECT_EQ(shelf.line, 87);  // its first key
  ASSERT_EQ(shelf.primitives.size(), 5u);
  EXPECT_TRUE(shelf.meshes.empty());
  ExpectPrimitive(shelf.primitives[0], SolidPrimitiveType::kBox, {0.3, 0.8, 0.02}, {1.0, 0, 0.01});
  ExpectPrimitive(shelf.primitives[4], SolidPrimitiveType::kBox, {0.3, 0.02, 1.0},
                  {1.0, 0.39, 0.5});
  EXPECT_TRUE(shelf.primitives[4].X_FP.linear().isIdentity(kTight));

  ExpectPrimitive(scene.objects[2].primitives.at(0), SolidPrimitiveType::kCylinder, {0.12, 0.033},
                  {1.0, 0.0, 0.57});         // [height, radius]
  EXPECT_EQ(scene.objects[4].frame_id, "");  // the planning frame
  ExpectPrimitive(scene.objects[4].primitives.at(0), SolidPrimitiveType::kSphere, {0.05},
                  {0.9, 0.25, 1.05});
  ExpectPrimitive(scene.objects[5].primitives.at(0), SolidPrimitiveType::kCone, {0.1, 0.04},
                  {1.05, -0.25, 1.05});

  const SceneCollisionObject& wedge = scene.objects[6];
  ASSERT_TRUE(wedge.primitives.empty());
  ASSERT_EQ(wedge.meshes.size(), 1u);
  const SceneMesh& mesh = wedge.meshes[0];
  ASSERT_EQ(mesh.vertices_M.size(), 4u);
  EXPECT_EQ(mesh.vertices_M[1], Eigen::Vector3d(0.1, 0, 0));
  EXPECT_EQ(mesh.vertices_M[3], Eigen::Vector3d(0, 0, 0.05));
  ASSERT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.triangles[0], (std::array<std::uint32_t, 3>{0, 2, 1}));
  EXPECT_EQ(mesh.triangles[3], (std::array<std::uint32_t, 3>{1, 2, 3}));
  EXPECT_TRUE(mesh.X_FM.translation().isApprox(Eigen::Vector3d(1.0, 0.1, 0.51), kTight));

  // The tray: object pose (0.4, 0.2, 0.8), 90 deg about z; its board 0.1 along the object's x
  // and 0.02 up, turned 90 deg about x; so in F the board sits at (0.4, 0.3, 0.82) and its
  // axes are x_P = y_F, y_P = z_F, z_P = x_F.
  const SceneCollisionObject& tray = scene.objects[7];
  EXPECT_EQ(tray.frame_id, "left_base_link");
  ASSERT_EQ(tray.primitives.size(), 2u);
  const Eigen::Isometry3d& X_FP = tray.primitives[0].X_FP;
  EXPECT_TRUE(X_FP.translation().isApprox(Eigen::Vector3d(0.4, 0.3, 0.82), kTight));
  Eigen::Matrix3d R_FP_expected;
  R_FP_expected << 0, 0, 1,  //
      1, 0, 0,               //
      0, 1, 0;
  EXPECT_TRUE(X_FP.linear().isApprox(R_FP_expected, kTight)) << X_FP.linear();
  // The can's (0, 0.71, 0, 0.71) is normalised: 90 deg about y, then the object's 90 about z.
  const Eigen::Matrix3d R_FC = tray.primitives[1].X_FP.linear();
  EXPECT_TRUE(R_FC.isUnitary(kTight));
  EXPECT_TRUE(R_FC.col(2).isApprox(Eigen::Vector3d(0, 1, 0), kTight)) << R_FC;
  EXPECT_TRUE(tray.primitives[1].X_FP.translation().isApprox(Eigen::Vector3d(0.4, 0.2, 0.8)));

  const SceneAllowedCollisions& acm = scene.allowed_collisions;
  EXPECT_EQ(acm.allowed_pairs, (NamePairs{{"left_link7", "left_tool"}, {"left_tool", "can_1"}}));
  EXPECT_EQ(acm.disallowed_pairs.size(), 10u - 2u);  // 5 names: 10 pairs above the diagonal
  EXPECT_EQ(acm.disallowed_pairs.front(),
            (std::pair<std::string, std::string>{"left_link7", "right_tool"}));
  EXPECT_EQ(acm.default_allowed_names, std::vector<std::string>{"world"});
}

TEST(PlanningSceneReader, CompactBenchmarkForm) {
  const PlanningSceneFile scene = ReadPlanningSceneFile(kData + "bookshelf_compact.yaml");
  EXPECT_EQ(scene.name, "");
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_EQ(scene.objects[0].id, "Can1");
  EXPECT_EQ(scene.objects[0].frame_id, "base_link");
  EXPECT_EQ(scene.objects[0].line, 3);
  ExpectPrimitive(scene.objects[0].primitives.at(0), SolidPrimitiveType::kCylinder, {0.14, 0.03},
                  {0.9, 0, 1.08});
  ExpectPrimitive(scene.objects[1].primitives.at(0), SolidPrimitiveType::kBox, {1.2, 1, 0.04},
                  {1, 0, 1});
  EXPECT_EQ(scene.objects[2].frame_id, "");  // no header
  ExpectPrimitive(scene.objects[2].primitives.at(0), SolidPrimitiveType::kSphere, {0.05},
                  {0.7, 0.2, 1.1});
  EXPECT_TRUE(scene.objects[2].primitives[0].X_FP.linear().isIdentity(kTight));
  const SceneMesh& mesh = scene.objects[3].meshes.at(0);
  EXPECT_EQ(mesh.vertices_M.size(), 4u);
  EXPECT_EQ(mesh.triangles.at(1), (std::array<std::uint32_t, 3>{0, 1, 3}));
  EXPECT_EQ(scene.allowed_collisions.allowed_pairs, (NamePairs{{"Can1", "shelf_bottom"}}));
  EXPECT_TRUE(scene.allowed_collisions.disallowed_pairs.empty());
}

// The bookshelf of bookshelf_compact.yaml as MoveIt's scene geometry text (newer format: object
// poses, one of them rotated with its shape rotated back, and a subframe) reads as the same
// shapes, in the planning frame.
TEST(PlanningSceneReader, SceneGeometryTextMatchesTheYamlForm) {
  const PlanningSceneFile text = ReadPlanningSceneFile(kData + "bookshelf.scene");
  const PlanningSceneFile yaml = ReadPlanningSceneFile(kData + "bookshelf_compact.yaml");
  EXPECT_EQ(text.name, "bookshelf");
  EXPECT_EQ(text.objects.at(0).line, 2);
  EXPECT_EQ(text.objects.at(3).line, 35);
  EXPECT_EQ(text.objects.at(3).element, "object 'Tetra'");
  EXPECT_TRUE(text.allowed_collisions.allowed_pairs.empty());
  ASSERT_EQ(text.objects.size(), yaml.objects.size());
  for (std::size_t i = 0; i < text.objects.size(); ++i) {
    const SceneCollisionObject& t = text.objects[i];
    const SceneCollisionObject& y = yaml.objects[i];
    EXPECT_EQ(t.id, y.id);
    EXPECT_EQ(t.frame_id, "");
    ASSERT_EQ(t.primitives.size(), y.primitives.size()) << t.id;
    for (std::size_t k = 0; k < t.primitives.size(); ++k) {
      EXPECT_EQ(t.primitives[k].type, y.primitives[k].type) << t.id;
      EXPECT_EQ(t.primitives[k].dimensions_m, y.primitives[k].dimensions_m) << t.id;
      EXPECT_TRUE(t.primitives[k].X_FP.isApprox(y.primitives[k].X_FP, 1e-9))
          << t.id << "\n" << t.primitives[k].X_FP.matrix();
    }
    ASSERT_EQ(t.meshes.size(), y.meshes.size()) << t.id;
    for (std::size_t k = 0; k < t.meshes.size(); ++k) {
      EXPECT_EQ(t.meshes[k].vertices_M, y.meshes[k].vertices_M) << t.id;
      EXPECT_EQ(t.meshes[k].triangles, y.meshes[k].triangles) << t.id;
      EXPECT_TRUE(t.meshes[k].X_FM.isApprox(y.meshes[k].X_FM, 1e-12)) << t.id;
    }
  }
}

// The older format (MoveIt before 1.1): no object pose, shape poses in the planning frame, no
// subframes; a cone's "radius length" in shape_msgs' order, and a quaternion a little off unit
// norm normalised.
TEST(PlanningSceneReader, OlderSceneGeometryText) {
  const PlanningSceneFile scene = ReadPlanningSceneFile(WriteTempFile(
      "older.scene",
      "* (noname)\n* funnel\n1\ncone\n0.1 0.3\n1 2 3\n0 0 0.7072 0.7072\n0 0 0 0\n"
      "* post one\n1\nbox\n0.1 0.2 0.3\n0 0 0\n0 0 0 1\n0 0 0 0\n.\n"));
  EXPECT_EQ(scene.name, "* (noname)");  // the first line, whatever it holds
  ASSERT_EQ(scene.objects.size(), 2u);
  const ScenePrimitive& cone = scene.objects[0].primitives.at(0);
  ExpectPrimitive(cone, SolidPrimitiveType::kCone, {0.3, 0.1}, {1, 2, 3});
  EXPECT_TRUE((cone.X_FP.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(),
                                                                       1e-12));
  EXPECT_EQ(scene.objects[1].id, "post one");
  EXPECT_EQ(scene.objects[1].line, 9);
  ExpectPrimitive(scene.objects[1].primitives.at(0), SolidPrimitiveType::kBox, {0.1, 0.2, 0.3},
                  {0, 0, 0});
}

/// MoveIt's scene geometry text of one object "a" (newer format) whose shape lines are `shape`.
std::string OneTextObject(const std::string& shape) {
  return "s\n* a\n0 0 0\n0 0 0 1\n1\n" + shape + "\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n";
}

TEST(PlanningSceneReader, BadSceneGeometryTextNamesLineObjectAndExpectation) {
  EXPECT_EQ(ReadPlanningSceneFile(WriteTempFile("good.scene", OneTextObject("sphere\n1")))
                .objects.size(),
            1u);
  ExpectBadInputFilesRejected(
      "bad.scene",
      {
          {"s\n* a\n0 0 0\n0 0 0 1\n1\nsphere\n1\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n",
           {":12:", "after object 'a'", "the file ends", "'.' for the end of the scene"}},
          {"s\n+ a\n.\n", {":2:", "scene: '+'", "'* ID' for an object"}},
          {"s\n*\n1\n.\n", {":2:", "object ''", "without id"}},
          {OneTextObject("plane\n0 0 1 0"),
           {":6:", "object 'a' shape 0", "planes are not supported"}},
          {OneTextObject("prism\n1"),
           {":6:", "object 'a' shape 0", "unknown shape type 'prism'", "box, sphere"}},
          {"s\n* a\n0 0 0\n0 0 0 1\n2\nsphere\n1\n0 0 0\n0 0 0 1\n0 0 0 0\n",  // cut short
           {"object 'a' shape 1: the file ends (expected box, sphere"}},
          {OneTextObject("cylinder\n0.1 -2"),
           {":7:", "object 'a' shape 0", "the cylinder's length -2", "a number > 0"}},
          {OneTextObject("cylinder\n0.025"),
           {":8:", "object 'a' shape 0", "line 7 holds 1 of the 2 dimensions, and the "
            "cylinder's length would be this line's first number (expected a shape's dimensions "
            "on one line, as MoveIt writes them)"}},
          {OneTextObject("box\n1 nan 1"),
           {":7:", "'nan'", "the box's size y, a finite number"}},
          {OneTextObject("mesh\n3 1\n0 0 0\n1 0 0\n0 1 0\n0 1 3"),
           {":11:", "object 'a' shape 0", "'3'", "a vertex index, an integer from 0 to 2"}},
          {OneTextObject("mesh\n2 1\n0 0 0\n1 0 0\n0 1 1"),
           {":7:", "2 vertices and 1 triangles", "at least 3 vertices"}},
          {"s\n* a\n0 0 0\n0 0 0 0\n1\nsphere\n1\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n",
           {":4:", "object 'a'", "the object's pose", "zero quaternion"}},
          {"s\n* a\n0 0 0\n0 0 0 1\n1\nsphere\n1\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n"
           "* a\n0 0 0\n0 0 0 1\n1\nsphere\n1\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n.\n",
           {":12:", "object 'a'", "id repeated", "unique ids"}},
          {"s\n* a\n0 0 0\n0 0 0 1\n-1\n.\n",
           {":5:", "'-1'", "the object's shape count, an integer from 0"}},
      },
      [](const std::string& path) { ReadPlanningSceneFile(path); });
}

// An object of no shapes (subframes only, as MoveIt can save one) has nothing to check: it is
// skipped with a notice; the next object's messages still name the skipped one.
TEST(PlanningSceneReader, SceneGeometryTextObjectWithoutShapesIsSkipped) {
  const std::string held = "* held\n0 0 0\n0 0 0 1\n1\nsphere\n1\n0 0 0\n0 0 0 1\n0 0 0 0\n0\n";
  const std::string marks = "* marks\n0 0 0\n0 0 0 1\n0\n1\ntip 0 0 0.1 0 0 0 1\n";
  const PlanningSceneFile scene =
      ReadPlanningSceneFile(WriteTempFile("shapeless.scene", "s\n" + marks + held + "."));
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].id, "held");
  ASSERT_EQ(scene.notices.size(), 1u);
  EXPECT_EQ(scene.notices[0], "object 'marks' (line 2): no shapes (subframes only, or none): "
                              "nothing to check; skipped");

  ExpectBadInputFilesRejected(
      "shapeless_bad.scene",
      {{"s\n" + marks + "+\n.\n", {":8:", "after object 'marks': '+'"}},
       {"s\n" + marks + "* marks\n.\n", {":8:", "object 'marks'", "id repeated"}}},
      [](const std::string& path) { ReadPlanningSceneFile(path); });
}

TEST(PlanningSceneReader, NoticesForIgnoredGeometry) {
  const PlanningSceneFile scene = ReadPlanningSceneFile(WriteTempFile(
      "notices.yaml",
      "robot_state: {attached_collision_objects: [{link_name: tool, object: {id: held}}]}\n"
      "world: {octomap: {octomap: {binary: true, data: [1, 2, 3]}}}\n"));
  EXPECT_TRUE(scene.objects.empty());
  ASSERT_EQ(scene.notices.size(), 2u);
  EXPECT_NE(scene.notices[0].find("1 objects attached"), std::string::npos) << scene.notices[0];
  EXPECT_NE(scene.notices[1].find("octomap of 3 bytes"), std::string::npos) << scene.notices[1];
  // MoveIt's link padding and scale: only entries other than 0 and 1 are told of.
  const PlanningSceneFile padded = ReadPlanningSceneFile(WriteTempFile(
      "padded.yaml",
      "link_padding: [{link_name: a, padding: 0.0}, {link_name: b, padding: 0.02}]\n"
      "link_scale: [{link_name: a, scale: 1.0}, {link_name: b, scale: 1.5}, "
      "{link_name: c, scale: 1.2}]\n"));
  ASSERT_EQ(padded.notices.size(), 2u) << ::testing::PrintToString(padded.notices);
  EXPECT_EQ(padded.notices[0].rfind("link_padding: MoveIt's padding of 1 links is ignored", 0), 0u)
      << padded.notices[0];
  EXPECT_EQ(padded.notices[1].rfind("link_scale: MoveIt's scale of 2 links is ignored", 0), 0u)
      << padded.notices[1];
  const PlanningSceneFile neutral = ReadPlanningSceneFile(WriteTempFile(
      "neutral.yaml", "link_padding: [{link_name: a, padding: 0}]\n"
                      "link_scale: [{link_name: a, scale: 1}]\n"));
  EXPECT_TRUE(neutral.notices.empty()) << ::testing::PrintToString(neutral.notices);
  // A value that is no number is told of too, not thrown as yaml-cpp's own exception (fuzz
  // finding: scale "1..0" ended the reader with YAML::BadConversion).
  const PlanningSceneFile garbled = ReadPlanningSceneFile(WriteTempFile(
      "garbled.yaml", "link_scale: [{link_name: a, scale: 1..0}, {link_name: b, scale: x}]\n"));
  ASSERT_EQ(garbled.notices.size(), 1u) << ::testing::PrintToString(garbled.notices);
  EXPECT_EQ(garbled.notices[0].rfind("link_scale: MoveIt's scale of 2 links is ignored", 0), 0u)
      << garbled.notices[0];
}

// robot_state.multi_dof_joint_state, where MoveIt's dumps say where a floating virtual joint
// puts the robot: each joint's transform, in the message's form and the compact one.
TEST(PlanningSceneReader, MultiDofJointStateGivesJointPoses) {
  const PlanningSceneFile scene = ReadPlanningSceneFile(WriteTempFile(
      "multi_dof.yaml",
      "robot_state:\n  joint_state: {name: [j1], position: [0.5]}\n"
      "  multi_dof_joint_state:\n"
      "    header: {frame_id: world}\n"
      "    joint_names: [virtual_joint, base_joint]\n"
      "    transforms:\n"
      "      - translation: {x: 1.0, y: -2.0, z: 0.5}\n"
      "        rotation: {x: 0.0, y: 0.0, z: 0.7071067811865476, w: 0.7071067811865476}\n"
      "      - {translation: [0.1, 0.2, 0.3]}\n"
      "    twist: []\n    wrench: []\n"));
  ASSERT_EQ(scene.joint_poses.size(), 2u);
  const SceneJointPose& vj = scene.joint_poses[0];
  EXPECT_EQ(vj.joint, "virtual_joint");
  EXPECT_EQ(vj.line, 7);  // its entry of transforms
  EXPECT_TRUE(vj.X_PC.translation().isApprox(Eigen::Vector3d(1.0, -2.0, 0.5), kTight));
  // A quarter turn about z: x onto y.
  EXPECT_TRUE((vj.X_PC.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(),
                                                                    kTight));
  EXPECT_EQ(scene.joint_poses[1].joint, "base_joint");
  EXPECT_TRUE(scene.joint_poses[1].X_PC.translation().isApprox(Eigen::Vector3d(0.1, 0.2, 0.3)));
  EXPECT_TRUE(scene.joint_poses[1].X_PC.linear().isIdentity());
}

TEST(PlanningSceneReader, BadMultiDofJointStateNamesFileElementAndExpectation) {
  const std::string state = "robot_state.multi_dof_joint_state";
  auto scene_with = [](const std::string& fields) {
    return "robot_state:\n  multi_dof_joint_state: {" + fields + "}\n";
  };
  ExpectBadInputFilesRejected(
      "bad_multi_dof.yaml",
      {
          {scene_with("joint_names: [a, b], transforms: [{}]"),
           {state + ".transforms", "1 transforms for 2 joint_names", "one per joint name"}},
          {scene_with("joint_names: [a], transforms: [{}, {}]"),
           {state + ".transforms", "2 transforms for 1 joint_names"}},
          {scene_with("joint_names: [a, a], transforms: [{}, {}]"),
           {state + ".joint_names[1]", "'a' repeated"}},
          {scene_with("joint_names: [a], transforms: [{rotation: [0, 0, 0, 0]}]"),
           {state + ".transforms[0].rotation"}},
          {scene_with("joint_names: [a], transforms: [{translaton: [0, 0, 0]}]"),
           {state + ".transforms[0]", "unknown key 'translaton'"}},
          {scene_with("joint_names: [a], transforms: {a: 1}"),
           {state + ".transforms"}},
      },
      [](const std::string& path) { ReadPlanningSceneFile(path); });
}

TEST(PlanningSceneReader, MissingOrMalformedFile) {
  const std::string missing = ::testing::TempDir() + "acm_test_no_such_scene.yaml";
  ExpectLoadError([&] { ReadPlanningSceneFile(missing); },
                  {missing, "cannot open", "readable planning-scene file"});
  const std::string malformed = WriteTempFile("malformed_scene.yaml", "world: [\n");
  ExpectLoadError([&] { ReadPlanningSceneFile(malformed); }, {malformed + ":2:", "malformed YAML"});
}

/// A scene of one collision object whose fields are `fields` (YAML flow-map entries).
std::string OneObject(const std::string& fields) {
  return "world:\n  collision_objects:\n    - {" + fields + "}\n";
}

const std::string kBox = "primitives: [{type: 1, dimensions: [1, 1, 1]}], primitive_poses: [{}]";
const std::string kObject = "world.collision_objects[0] 'a'";

void ReadScene(const std::string& path) { ReadPlanningSceneFile(path); }

// The same of a planning scene's object with subframes only, as rostopic echo writes it.
TEST(PlanningSceneReader, ObjectWithoutShapesIsSkipped) {
  const PlanningSceneFile scene = ReadPlanningSceneFile(WriteTempFile(
      "shapeless.yaml", OneObject("id: a, subframe_names: [tip], subframe_poses: [{}]") +
                            "    - {id: b, " + kBox + "}\n"));
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].id, "b");
  ASSERT_EQ(scene.notices.size(), 1u);
  EXPECT_EQ(scene.notices[0], kObject + " (line 3): no shapes (subframes only, or none): "
                                        "nothing to check; skipped");
  ExpectBadInputFilesRejected(
      "shapeless_repeated.yaml", {{OneObject("id: a") + "    - {id: a, " + kBox + "}\n",
                                   {"world.collision_objects[1]", "id 'a' repeated"}}},
      ReadScene);
}

TEST(PlanningSceneReader, BadObjectsNameFileElementAndExpectation) {
  // The valid base case of the bad objects below.
  EXPECT_EQ(ReadPlanningSceneFile(WriteTempFile("good_scene.yaml", OneObject("id: a, " + kBox)))
                .objects.size(),
            1u);
  ExpectBadInputFilesRejected(
      "bad_scene.yaml",
      {
          {OneObject("primitives: [{type: 1, dimensions: [1, 1, 1]}], primitive_poses: [{}]"),
           {"world.collision_objects[0]", "without id", "id: NAME"}},
          {OneObject("id: a, " + kBox) + "    - {id: a, " + kBox + "}\n",
           {":4:", "world.collision_objects[1]", "id 'a' repeated", "unique ids"}},
          {OneObject("id: a, primitives: [{type: 7, dimensions: [1]}], primitive_poses: [{}]"),
           {kObject + ".primitives[0].type", "unknown value '7'", "1 BOX, 2 SPHERE"}},
          {OneObject("id: a, primitives: [{type: prism, dimensions: [1]}], primitive_poses: [{}]"),
           {kObject + ".primitives[0].type", "unknown value 'prism'", "4 CONE"}},
          {OneObject("id: a, primitives: [{type: 3, dimensions: [0.1]}], primitive_poses: [{}]"),
           {kObject + ".primitives[0].dimensions", "expected 2 dimensions",
            "cylinder: [height, radius]"}},
          {OneObject("id: a, primitives: [{type: box, dimensions: [1, -2, 1]}], "
                     "primitive_poses: [{}]"),
           {kObject + ".primitives[0].dimensions[1]", "expected a number > 0"}},
          {OneObject("id: a, primitives: [{type: 2, dimensions: [.nan]}], primitive_poses: [{}]"),
           {kObject + ".primitives[0].dimensions[0]", "expected a finite number"}},
          {OneObject("id: a, primitives: [{type: 2, dimensions: [1]}, {type: 2, dimensions: [1]}], "
                     "primitive_poses: [{}]"),
           {kObject + ".primitive_poses", "1 poses for 2 primitives", "one pose per entry"}},
          {OneObject("id: a, " + kBox + ", pose: {orientation: {x: 0, y: 0, z: 0, w: 0}}"),
           {kObject + ".pose.orientation", "zero quaternion", "w = 1"}},
          {OneObject("id: a, primitives: [{type: 1, dimensions: [1, 1, 1]}], "
                     "primitive_poses: [{orientation: [0, 0, 1, 1]}]"),
           {kObject + ".primitive_poses[0].orientation", "norm 1.41", "unit quaternion"}},
          {OneObject("id: a, meshes: [{vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "
                     "triangles: [{vertex_indices: [0, 1, 3]}]}], mesh_poses: [{}]"),
           {kObject + ".meshes[0].triangles[0].vertex_indices[2]", "bad vertex index '3'",
            "from 0 to 2: the mesh has 3 vertices"}},
          {OneObject("id: a, meshes: [{vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "
                     "triangles: [[0, -1, 2]]}], mesh_poses: [{}]"),
           {kObject + ".meshes[0].triangles[0][1]", "bad vertex index '-1'"}},
          {OneObject("id: a, meshes: [{vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "
                     "triangles: [[0, 1]]}], mesh_poses: [{}]"),
           {kObject + ".meshes[0].triangles[0]", "3 vertex indices"}},
          {OneObject("id: a, meshes: [{vertices: [], triangles: []}], mesh_poses: [{}]"),
           {kObject + ".meshes[0]", "both non-empty"}},
          {OneObject("id: a, meshes: [{resource: 'package://p/m.stl'}], mesh_poses: [{}]"),
           {kObject + ".meshes[0].resource", "not read", "vertices and triangles"}},
          {OneObject("id: a, " + kBox + ", operation: 1"),
           {kObject + ".operation", "only ADD (0)", "operation: 0 or none"}},
          {OneObject("id: a, " + kBox + ", operation: move"),
           {kObject + ".operation", "only ADD", "operation: 0 or none"}},
          {OneObject("id: a, " + kBox + ", operation: 9"),
           {kObject + ".operation", "unknown value '9'", "0 ADD, 1 REMOVE"}},
          {OneObject("id: a, " + kBox + ", planes: [{coef: [0, 0, 1, 0]}], plane_poses: [{}]"),
           {kObject + ".planes", "not supported", "expected primitives or meshes"}},
          {OneObject("id: a, " + kBox + ", primitve_poses: []"),
           {kObject, "unknown key 'primitve_poses'", "primitive_poses"}},
      },
      ReadScene);
}

const std::string kTriangle =
    "{vertices: [[0, 0, 0], [1, 0, 0], [0, 1, 0]], triangles: [[0, 1, 2]]}";

TEST(PlanningSceneReader, MissingPosesAndNonFiniteNumbersNameFileAndObject) {
  ExpectBadInputFilesRejected(
      "bad_poses.yaml",
      {
          // Poses missing or not one per shape.
          {OneObject("id: a, primitives: [{type: 2, dimensions: [0.1]}]"),
           {kObject + ".primitive_poses", "0 poses for 1 primitives", "one pose per entry"}},
          {OneObject("id: a, meshes: [" + kTriangle + "]"),
           {kObject + ".mesh_poses", "0 poses for 1 meshes", "one pose per entry of meshes"}},
          {OneObject("id: a, meshes: [" + kTriangle + "], mesh_poses: [{}, {}]"),
           {kObject + ".mesh_poses", "2 poses for 1 meshes"}},
          {OneObject("id: a, " + kBox + ", meshes: [" + kTriangle + "], mesh_poses: []"),
           {kObject + ".mesh_poses", "0 poses for 1 meshes"}},
          {OneObject("id: a, primitives: [{type: 1, dimensions: [1, 1, 1]}], "
                     "primitive_poses: [7]"),
           {kObject + ".primitive_poses[0]", "expected a map"}},
          // Non-finite numbers, wherever they are.
          {OneObject("id: a, primitives: [{type: 1, dimensions: [1, 1, 1]}], "
                     "primitive_poses: [{position: {x: 0, y: .inf, z: 0}}]"),
           {kObject + ".primitive_poses[0].position.y", "expected a finite number"}},
          {OneObject("id: a, " + kBox + ", pose: {position: [0, .nan, 0]}"),
           {kObject + ".pose.position[1]", "expected a finite number"}},
          {OneObject("id: a, " + kBox + ", pose: {orientation: [0, 0, -.inf, 1]}"),
           {kObject + ".pose.orientation[2]", "expected a finite number"}},
          {OneObject("id: a, primitives: [{type: 1, dimensions: [1, 1, 1]}], "
                     "primitive_poses: [{orientation: {x: 0, y: 0, z: 0, w: .nan}}]"),
           {kObject + ".primitive_poses[0].orientation.w", "expected a finite number"}},
          {OneObject("id: a, meshes: [{vertices: [[0, 0, 0], [1, 0, .inf], [0, 1, 0]], "
                     "triangles: [[0, 1, 2]]}], mesh_poses: [{}]"),
           {kObject + ".meshes[0].vertices[1][2]", "expected a finite number"}},
          {OneObject("id: a, primitives: [{type: cylinder, dimensions: [.inf, 0.1]}], "
                     "primitive_poses: [{}]"),
           {kObject + ".primitives[0].dimensions[0]", "expected a finite number"}},
          {OneObject("id: a, primitives: [{type: box, dimensions: [1, 1e999, 1]}], "
                     "primitive_poses: [{}]"),
           {kObject + ".primitives[0].dimensions[1]", "expected a number, got '1e999'"}},
      },
      ReadScene);
}

TEST(PlanningSceneReader, BadMatricesNameFileElementAndExpectation) {
  const std::string acm = "allowed_collision_matrix";
  ExpectBadInputFilesRejected(
      "bad_acm.yaml",
      {
          {"allowed_collision_matrix:\n  entry_names: [a, b]\n  entry_values:\n"
           "    - enabled: [false, true]\n    - enabled: [false, false]\n",
           {":5:", acm + ".entry_values[1]", "(b, a) differs from (a, b)", "symmetric"}},
          {"allowed_collision_matrix: {entry_names: [a, b], entry_values: [[false, true]]}\n",
           {acm + ".entry_values", "expected 2 rows"}},
          {"allowed_collision_matrix: {entry_names: [a, b], entry_values: [[false], [true, "
           "false]]}\n",
           {acm + ".entry_values[0]", "expected 2 booleans, one per entry_names entry"}},
          {"allowed_collision_matrix: {entry_names: [a, a], entry_values: [[0, 0], [0, 0]]}\n",
           {acm + ".entry_names[1]", "'a' repeated", "unique names"}},
          {"allowed_collision_matrix: {entry_names: [a], entry_values: [[maybe]]}\n",
           {acm + ".entry_values[0][0]", "true or false"}},
          {"allowed_collision_matrix: {default_entry_names: [a, b], default_entry_values: "
           "[true]}\n",
           {acm + ".default_entry_values", "one per default_entry_names entry"}},
          {"allowed_colision_matrix: {}\n", {"unknown key 'allowed_colision_matrix'"}},
      },
      ReadScene);
}

}  // namespace
}  // namespace arm_collision_monitor
