// The world cube derived when the scene file omits world: (DeriveWorldCube) and the reach
// envelopes it is built from (ComputeWorkcellReach), checked against sampled forward kinematics:
// every primitive of every model, with its tolerance, in the home pose and in seeded random
// configurations within the joint limits (continuous joints over a full turn), and every object
// at its start pose, must lie inside.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <regex>
#include <string>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/scene/workcell_reach.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"
#include "load_error_expect.h"
#include "test_scene_util.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint64_t kSeed = 20261123;
constexpr int kSamples = 2000;
// Rounding of forward kinematics and AABBs over a few metres, m.
constexpr double kRounding_m = 1e-9;

// `scene_path`'s text without its world: line, written to a temporary file.
std::string WithoutWorld(const std::string& name, const std::string& scene_path) {
  const std::string text = ReadTextFile(scene_path);
  const std::string without = std::regex_replace(text, std::regex("\nworld:[^\n]*"), "\n");
  EXPECT_NE(without, text) << scene_path << " has no world: line";
  return WriteTempFile(name, without);
}

// A random q within the joint limits; continuous joints over a full turn.
Eigen::VectorXd RandomConfiguration(const KinematicModel& model, std::mt19937_64* rng) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.q_size());
  for (int link = 1; link < model.link_count(); ++link) {
    const JointSpec& joint = model.joint(link);
    if (joint.q_index < 0) continue;
    const bool is_continuous = joint.type == JointType::kContinuous;
    q[joint.q_index] = std::uniform_real_distribution<double>(
        is_continuous ? -M_PI : joint.lower, is_continuous ? M_PI : joint.upper)(*rng);
  }
  return q;
}

// Expects every primitive of every model (with its tolerance) inside `w.world_W` and every
// link primitive inside its link's reach sphere, at home and in kSamples random configurations.
void ExpectEnclosedInAllConfigurations(const Workcell& w) {
  const WorkcellReach reach = ComputeWorkcellReach(w);
  WorkcellShapes shapes(w, WorkcellShapes::Models::kAll);
  std::mt19937_64 rng(kSeed);
  const Aabb cube = w.world_W.Inflated(kRounding_m);
  int failures = 0;
  for (int sample = 0; sample <= kSamples && failures < 10; ++sample) {
    if (sample > 0) shapes.Evaluate(RandomConfiguration(w.kinematics, &rng));
    for (PrimitiveId id = 0; id < w.primitives.size(); ++id) {
      const PrimitiveSpec& p = w.primitives[id];
      const bool in_cube = cube.Contains(ComputeAabb(shapes.shape_W(id)).Inflated(p.tolerance_m));
      EXPECT_TRUE(in_cube) << "'" << p.name << "' outside the cube in sample " << sample
                           << " (seed " << kSeed << ")";
      failures += in_cube ? 0 : 1;
      if (p.link_index < 0 || !w.kinematics.is_moving(p.link_index)) continue;
      const Capsule& sphere = reach.spheres[p.link_index];
      const double reach_m = MaxDistanceFromPoint_m(shapes.shape_W(id), sphere.p0_W);
      EXPECT_LE(reach_m, sphere.radius_m + kRounding_m)
          << "'" << p.name << "' beyond its link's reach sphere in sample " << sample;
      failures += reach_m <= sphere.radius_m + kRounding_m ? 0 : 1;
    }
  }
}

void ExpectCube(const Aabb& box) {
  const Eigen::Vector3d edges = box.max_W - box.min_W;
  EXPECT_NEAR(edges.x(), edges.y(), kRounding_m);
  EXPECT_NEAR(edges.x(), edges.z(), kRounding_m);
  EXPECT_GT(edges.x(), 0.0);
}

bool HasNotice(const Workcell& w, const std::string& part) {
  for (const std::string& notice : w.notices) {
    if (notice.find(part) != std::string::npos) return true;
  }
  return false;
}

TEST(SceneWorldCube, ThreeLinkArmWithoutWorldEnclosesEveryConfiguration) {
  // Offset and rotated joint origins, a continuous wrist, a prismatic joint and its mimic.
  const std::string scene =
      WithoutWorld("three_link_no_world.yaml", kData + "three_link_scene.yaml");
  const Workcell w = LoadWorkcell(kData + "three_link_arm.urdf", scene);
  std::string why;
  EXPECT_TRUE(w.Validate(&why)) << why;
  ExpectCube(w.world_W);
  EXPECT_TRUE(HasNotice(w, "world: not given; derived")) << ::testing::PrintToString(w.notices);
  ExpectEnclosedInAllConfigurations(w);
  // A mimic joint slides as far as the joint it mimics puts it, past its own <limit> (three
  // times the slide here, 0.63 m at the end of its accepted range, the limit widened by its
  // margin, against the limit's 0.2 m): the reach takes that in.
  const std::string urdf = std::regex_replace(ReadTextFile(kData + "three_link_arm.urdf"),
                                              std::regex("multiplier=\"-1\""),
                                              "multiplier=\"-3\"");
  ASSERT_NE(urdf, ReadTextFile(kData + "three_link_arm.urdf"));
  const Workcell far = LoadWorkcell(WriteTempFile("mimic_times_3.urdf", urdf), scene);
  EXPECT_DOUBLE_EQ(far.kinematics.Travel_m(
                far.kinematics.joint(far.kinematics.FindJointChildLink("finger_mimic"))),
            3.0 * (0.2 + kJointLimitMargin));
  ExpectEnclosedInAllConfigurations(far);
}

TEST(SceneWorldCube, BundledSceneWithoutWorldContainsTheStatedCubesContents) {
  const Workcell stated = LoadWorkcell(kUrdf, kScene);
  const Workcell w = LoadWorkcell(kUrdf, WithoutWorld("bundled_no_world.yaml", kScene));
  ASSERT_EQ(w.primitives.size(), stated.primitives.size());
  ExpectCube(w.world_W);
  // Every object (attachable and frame-bound ones at their start poses) of the stated cube.
  ASSERT_FALSE(w.objects.empty());
  for (const ObjectSpec& object : w.objects) {
    for (int k = 0; k < object.primitive_count; ++k) {
      const PrimitiveSpec& p = w.primitives[object.primitive + k];
      const Aabb box = ComputeAabb(p.shape_L).Inflated(p.tolerance_m);
      ASSERT_TRUE(stated.world_W.Contains(box)) << p.name;  // the stated cube's contents
      EXPECT_TRUE(w.world_W.Contains(box)) << p.name;
    }
  }
  ExpectEnclosedInAllConfigurations(w);
  const double edge_m = (w.world_W.max_W - w.world_W.min_W).x();
  std::printf("derived world cube: edge %.3f m (stated %.3f m), centre %s\n", edge_m,
              (stated.world_W.max_W - stated.world_W.min_W).x(),
              ::testing::PrintToString(0.5 * (w.world_W.min_W + w.world_W.max_W)).c_str());
}

// A derived cube over kLargeDerivedWorldEdge_m names the primitive that reaches farthest (here an
// object put 80 m away, as a link in millimetres or with a stray origin would be); the bundled
// workcell's cube names none.
TEST(SceneWorldCube, LargeDerivedWorldNamesItsFarthestPrimitive) {
  const Workcell plain = LoadWorkcell(kUrdf, WithoutWorld("plain_no_world.yaml", kScene));
  EXPECT_TRUE(HasNotice(plain, "world: not given; derived"));
  EXPECT_FALSE(HasNotice(plain, "from the origin in the home pose"));
  const std::string objects = "\nobjects:\n";
  const Workcell w = LoadWorkcell(
      kUrdf, WriteEditedFile(WithoutWorld("far_no_world.yaml", kScene), "far.yaml",
                             {{objects, objects + "  - {name: far_crate, size_m: [1, 1, 1], "
                                                  "pose: {xyz_m: [80, 0, 0.5]}}\n"}}));
  EXPECT_GT((w.world_W.max_W - w.world_W.min_W).x(), kLargeDerivedWorldEdge_m);
  EXPECT_TRUE(HasNotice(w, "'far_crate' reaches 80.5"))
      << ::testing::PrintToString(w.notices);
}

TEST(SceneWorldCube, ExplicitWorldWins) {
  const Workcell w = LoadWorkcell(kUrdf, kScene);
  const Aabb stated = Aabb::Cube(Eigen::Vector3d(0.0, 0.0, 3.0), 6.35);
  EXPECT_EQ(w.world_W.min_W, stated.min_W);
  EXPECT_EQ(w.world_W.max_W, stated.max_W);
  EXPECT_FALSE(HasNotice(w, "world: not given"));
  // ... and an object outside a stated cube is still an error.
  ExpectLoadError(
      [&] {
        LoadWorkcell(kData + "three_link_arm.urdf",
                     WriteTempFile("small_world.yaml",
                                   std::regex_replace(ReadTextFile(kData + "three_link_scene.yaml"),
                                                      std::regex("edge_m: 4.0"), "edge_m: 0.5")));
      },
      {"'table'", "not inside the world cube"});
}

// A world cube over kMaxWorldEdge_m would make the monitor's rounding margin metres long. A
// prismatic joint sliding further than that within its limits (+/-1e9 m: a MOVO user's "no
// limits") is refused whatever the world, naming the joint, the URDF and joint_limits: (with an
// explicit world its lever arms made cycles take seconds); joint_limits: narrowing it loads. A
// derived cube over the edge for an object far off names the object; a world: of such an edge
// is refused naming edge_m, one of just that edge loads.
TEST(SceneWorldCube, WorldOverTheLargestEdgeIsRefused) {
  const std::string urdf = std::regex_replace(
      ReadTextFile(kData + "three_link_arm.urdf"),
      std::regex("<limit lower=\"0\" upper=\"0.2\" velocity=\"0.1\""),
      "<limit lower=\"-1e9\" upper=\"1e9\" velocity=\"0.1\"");
  const std::string huge = WriteTempFile("huge_slide.urdf", urdf);
  ASSERT_NE(urdf, ReadTextFile(kData + "three_link_arm.urdf"));
  const std::string stated = kData + "three_link_scene.yaml";
  const std::string derived = WithoutWorld("huge_slide_no_world.yaml", stated);
  for (const std::string& scene : {stated, derived}) {
    ExpectLoadError([&] { LoadWorkcell(huge, scene); },
                    {huge + ": prismatic joint 'slide' slides up to 1e+09 m, over the 10000 m",
                     "'slide' is limited to [-1e+09, 1e+09]",
                     "joint_limits: {slide: {lower: l, upper: u}}"});
  }
  // A prismatic joint mimicking the continuous wrist (no limits) slides as far as the wrist's
  // accepted positions take it, +/-kMaxUnlimitedPosition_rad: the joint it mimics is named, with
  // the remedy.
  const std::string spun = WriteTempFile(
      "mimic_of_spin.urdf", std::regex_replace(ReadTextFile(kData + "three_link_arm.urdf"),
                                               std::regex("<mimic joint=\"slide\""),
                                               "<mimic joint=\"spin\""));
  ExpectLoadError([&] { LoadWorkcell(spun, stated); },
                  {spun + ": prismatic joint 'finger_mimic' mimics 'spin' (multiplier -1, "
                          "offset 0) slides up to 1e+09 m with it",
                   "'spin' is limited to [-inf, inf]", "joint_limits: {spin: {lower: l"});
  const std::string narrowed = WriteTempFile(
      "huge_slide_narrowed.yaml",
      ReadTextFile(derived) + "joint_limits: {slide: {lower: 0.0, upper: 0.2}}\n");
  const Workcell w = LoadWorkcell(huge, narrowed);
  EXPECT_LT((w.world_W.max_W - w.world_W.min_W).x(), kLargeDerivedWorldEdge_m);
  const std::string objects = "\nobjects:\n";
  const std::string far_scene = WriteEditedFile(
      derived, "far_marker.yaml",
      {{objects,
        objects + "  - {name: far_marker, size_m: [1, 1, 1], pose: {xyz_m: [2e4, 0, 0]}}\n"}});
  ExpectLoadError([&] { LoadWorkcell(kData + "three_link_arm.urdf", far_scene); },
                  {far_scene + ": world: missing", "over the 10000 m",
                   "'far_marker' reaches 200", "from the middle of the arms' reach"});
  // A slide of 9 km within the limit, whose reach makes the derived cube 18 km: named.
  const std::string long_slide = WriteTempFile(
      "long_slide.urdf",
      std::regex_replace(ReadTextFile(kData + "three_link_arm.urdf"),
                         std::regex("<limit lower=\"0\" upper=\"0.2\" velocity=\"0.1\""),
                         "<limit lower=\"-9000\" upper=\"9000\" velocity=\"0.1\""));
  ExpectLoadError([&] { LoadWorkcell(long_slide, derived); },
                  {derived + ": world: missing", "link 'finger_", "' reaches 900",
                   "prismatic joints of " + long_slide + " above it: '", "up to 9000.01 m)",
                   "give world: {center_m"});
  auto with_edge = [&](const std::string& name, const std::string& edge) {
    return WriteTempFile(name, std::regex_replace(ReadTextFile(stated), std::regex("edge_m: 4.0"),
                                                  "edge_m: " + edge));
  };
  ExpectLoadError(
      [&] { LoadWorkcell(kData + "three_link_arm.urdf", with_edge("huge_world.yaml", "2e4")); },
      {"huge_world.yaml", "world.edge_m", "expected at most 10000 m", "got 2e4"});
  EXPECT_EQ(LoadWorkcell(kData + "three_link_arm.urdf", with_edge("edge_world.yaml", "1e4"))
                .world_W.max_W.x(),
            5e3);
}

// A revolute mimic joint whose position over the accepted positions of the joint it mimics
// passes kMaxMimicPosition (an absurd multiplier: its poses lose all precision, then overflow
// to NaN, which warned of nothing) is refused, naming it.
TEST(SceneWorldCube, MimicJointsOfAbsurdRangeAreRefused) {
  const std::string scene = kData + "three_link_scene.yaml";
  const auto revolute_mimic = [](const std::string& name, const std::string& mimic) {
    return WriteEditedFile(kData + "three_link_arm.urdf", name,
                           {{"<joint name=\"finger_mimic\" type=\"prismatic\">",
                             "<joint name=\"finger_mimic\" type=\"revolute\">"},
                            {"<mimic joint=\"slide\" multiplier=\"-1\" offset=\"0\"/>", mimic}});
  };
  const std::string absurd =
      revolute_mimic("mimic_1e308.urdf", "<mimic joint=\"slide\" multiplier=\"1e308\"/>");
  ExpectLoadError([&] { LoadWorkcell(absurd, scene); },
                  {absurd + ": mimic joint 'finger_mimic' (multiplier 1e+308, offset 0) reaches "
                            "2.1e+307 rad over the positions of 'slide' the monitor accepts "
                            "([-0.01, 0.21]), over the 1.6e+10 rad a mimic joint may take"});
  // A x10 mimic of the continuous wrist with an offset (up to 1e10 + 0.5 rad) loads; a x20 one
  // does not.
  const std::string tenfold = revolute_mimic(
      "mimic_spin_x10.urdf", "<mimic joint=\"spin\" multiplier=\"10\" offset=\"0.5\"/>");
  EXPECT_EQ(LoadWorkcell(tenfold, scene).kinematics.MimicJointNames(),
            std::vector<std::string>{"finger_mimic"});
  const std::string twentyfold =
      revolute_mimic("mimic_spin_x20.urdf", "<mimic joint=\"spin\" multiplier=\"20\"/>");
  ExpectLoadError([&] { LoadWorkcell(twentyfold, scene); },
                  {"mimic joint 'finger_mimic' (multiplier 20, offset 0) reaches 2e+10 rad"});
  const std::string geared = revolute_mimic(
      "mimic_spin_x2000.urdf", "<mimic joint=\"spin\" multiplier=\"2000\" offset=\"1\"/>");
  ExpectLoadError([&] { LoadWorkcell(geared, scene); },
                  {"mimic joint 'finger_mimic' (multiplier 2000, offset 1) reaches 2e+12 rad "
                   "over the positions of 'spin' the monitor accepts ([-1e+09, 1e+09])"});
}

TEST(SceneWorldCube, ReachSpheresOnlyForLinksBelowAMovingJoint) {
  const Workcell w = LoadWorkcell(kData + "three_link_arm.urdf", kData + "three_link_scene.yaml");
  const WorkcellReach reach = ComputeWorkcellReach(w);
  ASSERT_EQ(reach.spheres.size(), static_cast<std::size_t>(w.kinematics.link_count()));
  for (int link = 0; link < w.kinematics.link_count(); ++link) {
    const bool moves = w.kinematics.is_moving(link);
    EXPECT_EQ(reach.hold_radius_m[link] >= 0.0, moves) << w.kinematics.link_name(link);
    if (!moves) {
      EXPECT_LT(reach.spheres[link].radius_m, 0.0) << w.kinematics.link_name(link);
    }
  }
}

TEST(SceneWorldCube, NothingToDeriveFromIsAnError) {
  const std::string urdf = WriteTempFile("bare.urdf", "<robot name='r'><link name='a'/></robot>\n");
  const std::string scene = WriteTempFile("bare.yaml", "arms: []\n");
  ExpectLoadError([&] { LoadWorkcell(urdf, scene); },
                  {scene, "world: missing", "no primitive", "edge_m"});
}

}  // namespace
}  // namespace arm_collision_monitor
