// LoadWorkcell with MoveIt inputs: srdf: (collision rules as compatible pairs), planning_scene:
// (world collision objects as static objects, its allowed collision matrix with
// planning_scene_acm), the shape options (cylinder_model, mesh_fit) and typed objects:. The
// shapes must enclose the solids they model: sampled points of each exact solid are checked
// with geometry/distance.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "load_error_expect.h"
#include "test_scene_util.h"

namespace arm_collision_monitor {
namespace {

const std::string kMoveit = kData + "moveit/";
const std::string kSrdf = kMoveit + "workcell.srdf";
const std::string kPlanningScene = kMoveit + "workcell_scene.yaml";

// Rounding allowed for a point on the surface of a solid and its enclosing shape, m.
constexpr double kSurfaceRounding_m = 1e-12;

// The bundled scene file with `extra` top-level lines appended, written to a temporary file.
std::string BundledSceneWith(const std::string& name, const std::string& extra) {
  return WriteTempFile(name, ReadTextFile(kScene) + "\n" + extra);
}

using PairSet = std::set<std::pair<std::string, std::string>>;

// Every compatible pair of `w` by primitive names (each pair ordered by name).
PairSet CompatibleNames(const Workcell& w) {
  PairSet pairs;
  for (PrimitiveId a = 0; a < w.primitives.size(); ++a) {
    for (PrimitiveId b = a + 1; b < w.primitives.size(); ++b) {
      if (!w.compatible.AreCompatible(a, b)) continue;
      pairs.insert(std::minmax(w.primitives[a].name, w.primitives[b].name));
    }
  }
  return pairs;
}

PairSet Difference(const PairSet& more, const PairSet& fewer) {
  PairSet diff;
  std::set_difference(more.begin(), more.end(), fewer.begin(), fewer.end(),
                      std::inserter(diff, diff.end()));
  return diff;
}

// The warning containing `part`, "" if none.
std::string FindWarning(const Workcell& w, const std::string& part) {
  for (const std::string& warning : w.warnings) {
    if (warning.find(part) != std::string::npos) return warning;
  }
  return "";
}

const Shape& ShapeOf(const Workcell& w, const std::string& name) {
  const int id = w.FindPrimitive(name);
  EXPECT_GE(id, 0) << name;
  return w.primitives.at(std::max(id, 0)).shape_L;
}

// Expects the point to be inside (or on, within rounding) `shape`.
void ExpectInside(const Eigen::Vector3d& p_W, const Shape& shape, const std::string& what) {
  const double d_m = ShapeDistance(Capsule{p_W, p_W, 0.0}, shape).distance_m;
  EXPECT_LE(d_m, kSurfaceRounding_m) << what << " point " << p_W.transpose();
}

// Seeded points of the solid cylinder (radius r, length h, axis along X_WC's z, centred on its
// origin), its rims included; for a cone (tip towards +z) when `is_cone`.
std::vector<Eigen::Vector3d> SolidPoints_W(const Eigen::Isometry3d& X_WC, double r_m, double h_m,
                                           bool is_cone, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 2000; ++i) {
    const double z = (i < 4 ? (i % 2) : unit(rng)) - 0.5;  // the first points on the end faces
    const double max_r = is_cone ? r_m * (0.5 - z) : r_m;
    const double rho = (i % 3 == 0) ? max_r : max_r * std::sqrt(unit(rng));  // a third on the rim
    const double phi = 2.0 * M_PI * unit(rng);
    points.push_back(X_WC * Eigen::Vector3d(rho * std::cos(phi), rho * std::sin(phi), z * h_m));
  }
  return points;
}

void ExpectCapsule(const Shape& shape, const Eigen::Vector3d& end0, const Eigen::Vector3d& end1,
                   double radius_m, const std::string& what) {
  ASSERT_TRUE(std::holds_alternative<Capsule>(shape)) << what;
  const Capsule& c = std::get<Capsule>(shape);
  const bool same = (c.p0_W - end0).norm() < 1e-12 && (c.p1_W - end1).norm() < 1e-12;
  const bool swapped = (c.p0_W - end1).norm() < 1e-12 && (c.p1_W - end0).norm() < 1e-12;
  EXPECT_TRUE(same || swapped) << what << ": " << c.p0_W.transpose() << " -- "
                               << c.p1_W.transpose();
  EXPECT_DOUBLE_EQ(c.radius_m, radius_m) << what;
}

void ExpectValid(const Workcell& w) {
  std::string why;
  EXPECT_TRUE(w.Validate(&why)) << why;
}

// ---------------------------------------------------------------------------------------------
// srdf:

TEST(SceneMoveitInputs, SrdfDisabledPairsBecomeCompatible) {
  const Workcell base = LoadWorkcell(kUrdf, kScene);
  const Workcell w = LoadWorkcell(kUrdf, BundledSceneWith("srdf.yaml", "srdf: " + kSrdf + "\n"));
  ExpectValid(w);
  ASSERT_EQ(w.primitives.size(), base.primitives.size());
  // The SRDF's pairs not already automatic (adjacent links are): the rest are links without
  // primitives (base links are ignored, tools and world have no geometry).
  const PairSet expected = {{"left_link1", "left_link3"}, {"left_pedestal", "right_pedestal"}};
  EXPECT_EQ(Difference(CompatibleNames(w), CompatibleNames(base)), expected);
  EXPECT_TRUE(Difference(CompatibleNames(base), CompatibleNames(w)).empty());
  EXPECT_TRUE(Compatible(w, "left_link1", "left_link3"));
  EXPECT_FALSE(Compatible(w, "right_link1", "right_link3"));
  EXPECT_FALSE(Compatible(w, "left_link7", "right_link7"));
  EXPECT_FALSE(Compatible(w, "left_link2", "left_link4"));

  const std::string notice = FindWarning(w, "skipped 5 link(s) without primitives");
  ASSERT_FALSE(notice.empty());
  EXPECT_NE(notice.find(kSrdf), std::string::npos) << notice;
  for (const char* name : {"'left_base_link'", "'right_base_link'", "'left_tool'",
                           "'right_tool'", "'world'"}) {
    EXPECT_NE(notice.find(name), std::string::npos) << name << " not in " << notice;
  }
  // A bare link's fixed children with geometry are named (franka_description's with_sc URDF keeps
  // the shapes on such children, which the stock SRDF does not name: a dual FR3 user).
  EXPECT_NE(notice.find("; 'world' has geometry on its fixed children 'left_pedestal', "
                        "'right_pedestal' (a rule holds for a link's own geometry: name the "
                        "children)"),
            std::string::npos)
      << notice;
  EXPECT_EQ(notice.find("'left_base_link' has"), std::string::npos) << notice;
  // srdfdom's warning too: this SRDF names robot 'workcell', the URDF 'dual_arm_workcell'.
  EXPECT_FALSE(FindWarning(w, "<robot name='workcell'> differs").empty());
  EXPECT_EQ(w.warnings.size(), base.warnings.size() + 2);
}

TEST(SceneMoveitInputs, SrdfPathsResolveRelativeToTheSceneAndAsFileUrls) {
  const Workcell base = LoadWorkcell(kUrdf, BundledSceneWith("srdf_abs.yaml", "srdf: " + kSrdf));
  WriteTempFile("copy.srdf", ReadTextFile(kSrdf));  // beside the scene files written below
  for (const std::string& value : {std::string("acm_test_copy.srdf"), "file://" + kSrdf}) {
    const Workcell w = LoadWorkcell(kUrdf, BundledSceneWith("srdf_rel.yaml", "srdf: " + value));
    EXPECT_EQ(CompatibleNames(w), CompatibleNames(base)) << value;
  }
}

TEST(SceneMoveitInputs, SrdfDefaultDisabledLinkIsCompatibleWithAllButItsEnabledPairs) {
  const std::string srdf = WriteTempFile(
      "default.srdf",
      "<robot name='workcell'>\n"
      "  <enable_collisions link1='ink7' link2='floor'/>\n"
      "  <disable_default_collisions link='left_link7'/>\n"
      "  <enable_collisions link1='front_box' link2='left_link7'/>\n"
      "  <enable_collisions link1='left_link7' link2='floor'/>\n"
      "  <disable_collisions link1='left_link7' link2='floor'/>\n"
      "  <disable_collisions link1='right_link7' link2='no_such_link'/>\n"
      "  <disable_collisions link1='link7' link2='right_link6'/>\n"
      "  <disable_collisions link1='ink7' link2='right_link6'/>\n"
      "  <enable_collisions link1='floor' link2='flor'/>\n"
      "</robot>\n");
  const Workcell w = LoadWorkcell(kUrdf, BundledSceneWith("default.yaml", "srdf: " + srdf));
  ExpectValid(w);
  EXPECT_TRUE(Compatible(w, "left_link7", "right_link7"));
  EXPECT_TRUE(Compatible(w, "left_link7", "camera"));
  EXPECT_TRUE(Compatible(w, "left_link7/finger1", "right_link2"));  // a variant of the link
  EXPECT_FALSE(Compatible(w, "left_link7", "front_box"));           // enabled again
  EXPECT_FALSE(Compatible(w, "left_link7/palm", "front_box"));
  EXPECT_TRUE(Compatible(w, "left_link7", "floor"));  // disabled wins over enabled
  EXPECT_FALSE(Compatible(w, "right_link7", "left_link6"));
  // A name the URDF and the scene do not know is told apart from a link without geometry.
  // A name the URDF has with a prefix (an SRDF of one arm) is shown with the links that carry
  // it; the end of a name without a separator before it is not ('ink7'). Each is named with the
  // line where it first appears, whatever the element ('ink7' in lines 2 and 9), also one in
  // an enabled pair that limits no default ('flor').
  const std::string unknown = FindWarning(w, "skipped 4 unknown name(s), neither a URDF link");
  EXPECT_NE(unknown.find("(a typo, or a file of another robot?): 'no_such_link' (line 7), "
                         "'link7' (line 8), 'ink7' (line 2), 'flor' (line 10); "
                         "the URDF has 'link7' as 'left_link7', 'right_link7'"),
            std::string::npos)
      << unknown;
  EXPECT_EQ(unknown.find("' as", unknown.find("right_link7'") + 12), std::string::npos) << unknown;
  EXPECT_TRUE(FindWarning(w, "without primitives").empty());
}

// A Setup Assistant "Never" pair between two arms is a sampled claim: checked unless trusted.
TEST(SceneMoveitInputs, SrdfNeverPairsBetweenArmsStayCheckedUnlessTrusted) {
  const std::string srdf = WriteTempFile(
      "never.srdf",
      "<robot name='dual_arm_workcell'>\n"
      "  <disable_collisions link1='left_link7' link2='right_link7' reason='Never'/>\n"
      "  <disable_collisions link1='right_link6' link2='left_link5' reason='Never'/>\n"
      "  <disable_collisions link1='left_link6' link2='right_link6' reason='User'/>\n"
      "  <disable_collisions link1='left_link5' link2='right_link5'/>\n"
      "  <disable_collisions link1='left_link3' link2='left_link7' reason='Never'/>\n"
      "  <disable_collisions link1='right_link7' link2='front_box' reason='Never'/>\n"
      "</robot>\n");
  const Workcell w = LoadWorkcell(kUrdf, BundledSceneWith("never.yaml", "srdf: " + srdf));
  ExpectValid(w);
  EXPECT_FALSE(Compatible(w, "left_link7", "right_link7"));
  EXPECT_FALSE(Compatible(w, "left_link5", "right_link6"));
  EXPECT_TRUE(Compatible(w, "left_link6", "right_link6"));   // another reason
  EXPECT_TRUE(Compatible(w, "left_link5", "right_link5"));   // no reason
  EXPECT_TRUE(Compatible(w, "left_link3", "left_link7"));    // one arm
  EXPECT_TRUE(Compatible(w, "right_link7", "front_box"));    // an arm and the environment
  const std::string kept = "2 <disable_collisions> pair(s) of reason 'Never' between links of two"
                           " arms stay checked";
  std::string notice;
  for (const std::string& line : w.notices) {
    if (line.find(kept) != std::string::npos) notice = line;
  }
  ASSERT_FALSE(notice.empty());
  EXPECT_EQ(notice.find(srdf + ": "), 0u) << notice;
  EXPECT_NE(notice.find("'left_link7' and 'right_link7', 'right_link6' and 'left_link5'"),
            std::string::npos)
      << notice;

  const Workcell trusted = LoadWorkcell(
      kUrdf, BundledSceneWith("never_trusted.yaml",
                              "srdf: " + srdf + "\nsrdf_trust_never_between_arms: true\n"));
  EXPECT_TRUE(Compatible(trusted, "left_link7", "right_link7"));
  EXPECT_TRUE(Compatible(trusted, "left_link5", "right_link6"));
  for (const std::string& line : trusted.notices) EXPECT_EQ(line.find(kept), std::string::npos);

  const std::string alone =
      BundledSceneWith("never_alone.yaml", "srdf_trust_never_between_arms: true\n");
  ExpectLoadError([&] { LoadWorkcell(kUrdf, alone); },
                  {alone, "srdf_trust_never_between_arms", "given without srdf:"});
}

TEST(SceneMoveitInputs, SrdfOfAnotherRobotIsNoticed) {
  const std::string srdf = WriteTempFile("other.srdf", "<robot name='panda'/>\n");
  const Workcell w = LoadWorkcell(kUrdf, BundledSceneWith("other.yaml", "srdf: " + srdf));
  EXPECT_FALSE(FindWarning(w, "'panda'").empty());
}

// ---------------------------------------------------------------------------------------------
// planning_scene:

TEST(SceneMoveitInputs, PlanningSceneObjectsBecomeStaticObjects) {
  const Workcell base = LoadWorkcell(kUrdf, kScene);
  const Workcell w =
      LoadWorkcell(kUrdf, BundledSceneWith("ps.yaml", "planning_scene: " + kPlanningScene));
  ExpectValid(w);
  // shelf: 5 boxes; three cans, ball, funnel, wedge (one capsule), tray: 2.
  EXPECT_EQ(w.primitives.size(), base.primitives.size() + 5 + 3 + 1 + 1 + 1 + 2);
  EXPECT_EQ(w.objects.size(), base.objects.size() + 8);
  for (const char* id : {"shelf", "can_1", "can_2", "can_3", "ball", "funnel", "wedge", "tray"}) {
    const int o = w.FindObject(id);
    ASSERT_GE(o, 0) << id;
    EXPECT_FALSE(w.objects[o].is_attachable);
    EXPECT_TRUE(w.objects[o].frame.empty());
    for (int k = 0; k < w.objects[o].primitive_count; ++k) {
      const PrimitiveSpec& p = w.primitives[w.objects[o].primitive + k];
      EXPECT_EQ(p.owner, id);
      EXPECT_EQ(p.object_index, o);
      EXPECT_TRUE(p.is_static);
      EXPECT_EQ(p.tolerance_m, 0.0);
      EXPECT_EQ(p.name, w.objects[o].primitive_count == 1 ? id : id + ("/" + std::to_string(k)));
    }
  }
  EXPECT_EQ(w.objects[w.FindObject("shelf")].primitive_count, 5);
  EXPECT_EQ(w.objects[w.FindObject("tray")].primitive_count, 2);

  ASSERT_TRUE(std::holds_alternative<Box>(ShapeOf(w, "shelf/3")));
  const Box& side = std::get<Box>(ShapeOf(w, "shelf/3"));
  EXPECT_TRUE(side.X_WB.isApprox(Eigen::Isometry3d(Eigen::Translation3d(1.0, -0.39, 0.5)), 1e-15));
  EXPECT_TRUE(side.half_extents_m.isApprox(Eigen::Vector3d(0.15, 0.01, 0.5), 1e-15));

  ExpectCapsule(ShapeOf(w, "ball"), {0.9, 0.25, 1.05}, {0.9, 0.25, 1.05}, 0.05, "ball");
  ExpectCapsule(ShapeOf(w, "can_1"), {1.0, -0.2, 0.51}, {1.0, -0.2, 0.63}, 0.033, "can_1");
  const Eigen::Isometry3d X_WCan(Eigen::Translation3d(1.0, -0.2, 0.57));
  for (const Eigen::Vector3d& p_W : SolidPoints_W(X_WCan, 0.033, 0.12, false, 1)) {
    ExpectInside(p_W, ShapeOf(w, "can_1"), "can_1 (seed 1)");
  }
  const Eigen::Isometry3d X_WFunnel(Eigen::Translation3d(1.05, -0.25, 1.05));
  for (const Eigen::Vector3d& p_W : SolidPoints_W(X_WFunnel, 0.04, 0.1, true, 2)) {
    ExpectInside(p_W, ShapeOf(w, "funnel"), "funnel (seed 2)");
  }
  const Eigen::Vector3d p_WWedge(1.0, 0.1, 0.51);
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0, 0),
                                   Eigen::Vector3d(0, 0.1, 0), Eigen::Vector3d(0, 0, 0.05)}) {
    ExpectInside(p_WWedge + v, ShapeOf(w, "wedge"), "wedge vertex");
  }
  EXPECT_TRUE(std::holds_alternative<Capsule>(ShapeOf(w, "wedge")));

  // tray: in left_base_link (0, 0.55, 0.8 in W), at (0.4, 0.2, 0.8) turned 90 deg about z.
  ASSERT_TRUE(std::holds_alternative<Box>(ShapeOf(w, "tray/0")));
  const Box& tray = std::get<Box>(ShapeOf(w, "tray/0"));
  EXPECT_TRUE(tray.X_WB.translation().isApprox(Eigen::Vector3d(0.4, 0.85, 1.62), 1e-12))
      << tray.X_WB.translation().transpose();
  // Box x along W y; box y (turned about x by 90 deg) along W z.
  EXPECT_TRUE(tray.X_WB.linear().col(0).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_TRUE(tray.X_WB.linear().col(1).isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
  ExpectCapsule(ShapeOf(w, "tray/1"), {0.4, 0.725, 1.6}, {0.4, 0.775, 1.6}, 0.02, "tray/1");
}

TEST(SceneMoveitInputs, ShapeOptionsAndTolerance) {
  const Workcell boxes = LoadWorkcell(
      kUrdf, BundledSceneWith("ps_box.yaml", "planning_scene: " + kPlanningScene +
                                                 "\ncylinder_model: box\nmesh_fit: box\n"
                                                 "planning_scene_tolerance_m: 0.01\n"));
  ExpectValid(boxes);
  ASSERT_TRUE(std::holds_alternative<Box>(ShapeOf(boxes, "can_1")));
  EXPECT_TRUE(std::get<Box>(ShapeOf(boxes, "can_1"))
                  .half_extents_m.isApprox(Eigen::Vector3d(0.033, 0.033, 0.06), 1e-15));
  const Eigen::Isometry3d X_WFunnel(Eigen::Translation3d(1.05, -0.25, 1.05));
  for (const Eigen::Vector3d& p_W : SolidPoints_W(X_WFunnel, 0.04, 0.1, true, 3)) {
    ExpectInside(p_W, ShapeOf(boxes, "funnel"), "funnel box (seed 3)");
  }
  EXPECT_TRUE(std::holds_alternative<Box>(ShapeOf(boxes, "wedge")));
  EXPECT_EQ(boxes.primitives[boxes.FindPrimitive("wedge")].tolerance_m, 0.01);
  EXPECT_EQ(boxes.primitives[boxes.FindPrimitive("floor")].tolerance_m, 0.0);

  const Workcell chain = LoadWorkcell(
      kUrdf, BundledSceneWith("ps_chain.yaml",
                              "planning_scene: " + kPlanningScene + "\nmesh_fit: capsules:2\n"));
  ExpectValid(chain);
  const ObjectSpec& wedge = chain.objects[chain.FindObject("wedge")];
  EXPECT_EQ(wedge.primitive_count, 2);
  const Eigen::Vector3d p_WWedge(1.0, 0.1, 0.51);
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0, 0),
                                   Eigen::Vector3d(0, 0.1, 0), Eigen::Vector3d(0, 0, 0.05)}) {
    double d_m = 1.0;
    for (int k = 0; k < wedge.primitive_count; ++k) {
      const Eigen::Vector3d p_W = p_WWedge + v;
      d_m = std::min(d_m, ShapeDistance(Capsule{p_W, p_W, 0.0},
                                        chain.primitives[wedge.primitive + k].shape_L)
                              .distance_m);
    }
    EXPECT_LE(d_m, kSurfaceRounding_m) << v.transpose();
  }
}

const char* const kAcmScene =
    "world:\n"
    "  collision_objects:\n"
    "    - id: crate\n"
    "      primitives: [{type: box, dimensions: [0.2, 0.2, 0.2]}]\n"
    "      primitive_poses: [{position: [0.5, 0, 1.5]}]\n"
    "allowed_collision_matrix:\n"
    "  entry_names: [left_link7, crate, right_link7, left_tool]\n"
    "  entry_values:\n"
    "    - [false, true, false, true]\n"
    "    - [true, false, false, false]\n"
    "    - [false, false, false, false]\n"
    "    - [true, false, false, false]\n"
    "  default_entry_names: [right_link6, ghost]\n"
    "  default_entry_values: [true, true]\n";

TEST(SceneMoveitInputs, PlanningSceneAcmIsImportedOnRequest) {
  const std::string ps = WriteTempFile("acm_ps.yaml", kAcmScene);
  const Workcell plain =
      LoadWorkcell(kUrdf, BundledSceneWith("acm0.yaml", "planning_scene: " + ps));
  const Workcell w = LoadWorkcell(
      kUrdf, BundledSceneWith("acm1.yaml", "planning_scene: " + ps + "\nplanning_scene_acm: true"));
  ExpectValid(w);
  EXPECT_FALSE(Compatible(plain, "left_link7", "crate"));
  EXPECT_TRUE(Compatible(w, "left_link7", "crate"));
  EXPECT_TRUE(Compatible(w, "left_link7/palm", "crate"));
  EXPECT_FALSE(Compatible(w, "right_link7", "crate"));
  EXPECT_TRUE(Compatible(w, "right_link6", "crate"));  // a default entry
  EXPECT_TRUE(Compatible(w, "right_link6", "left_link2"));
  EXPECT_FALSE(Compatible(w, "left_link2", "left_link5"));
  EXPECT_NE(FindWarning(w, "allowed_collision_matrix: skipped 1 link(s) without primitives")
                .find("'left_tool'"),
            std::string::npos);
  EXPECT_NE(FindWarning(w, "allowed_collision_matrix: skipped 1 unknown name(s)").find("'ghost'"),
            std::string::npos);
  EXPECT_TRUE(FindWarning(plain, "allowed_collision_matrix").empty());
}

// An object of no shapes (subframes only) is skipped, and the matrix's entries naming it are no
// unknown names: it is in the file, with nothing to excuse.
TEST(SceneMoveitInputs, PlanningSceneAcmNamingAShapelessObjectIsNoUnknownName) {
  std::string scene = kAcmScene;
  const std::string objects = "  collision_objects:\n";
  scene.insert(scene.find(objects) + objects.size(),
               "    - {id: marks, subframe_names: [tip], subframe_poses: [{}]}\n");
  const std::string defaults = "  default_entry_names: [right_link6, ghost]\n"
                               "  default_entry_values: [true, true]\n";
  ASSERT_NE(scene.find(defaults), std::string::npos);
  scene.replace(scene.find(defaults), defaults.size(),
                "  default_entry_names: [right_link6, ghost, marks]\n"
                "  default_entry_values: [true, true, true]\n");
  const std::string ps = WriteTempFile("acm_shapeless_ps.yaml", scene);
  const Workcell w = LoadWorkcell(
      kUrdf, BundledSceneWith("acm2.yaml", "planning_scene: " + ps + "\nplanning_scene_acm: true"));
  ExpectValid(w);
  EXPECT_TRUE(Compatible(w, "right_link6", "crate"));
  const std::string unknown = FindWarning(w, "allowed_collision_matrix: skipped 1 unknown name(s)");
  EXPECT_NE(unknown.find("'ghost'"), std::string::npos) << unknown;
  EXPECT_EQ(unknown.find("'marks'"), std::string::npos) << unknown;
  EXPECT_FALSE(FindWarning(w, "'marks' (line 3): no shapes").empty());
}

// ---------------------------------------------------------------------------------------------
// Typed objects:

TEST(SceneMoveitInputs, TypedObjectsLoadWithTheirShapes) {
  const std::string objects =
      "objects:\n"
      "  - {name: ball, type: sphere, radius_m: 0.1, pose: {xyz_m: [1, 1, 1]}}\n"
      "  - {name: can, type: cylinder, radius_m: 0.05, length_m: 0.2, pose: {xyz_m: [1, -1, 1]},"
      " tolerance_m: 0.02}\n"
      "  - {name: rod, type: capsule, radius_m: 0.03, length_m: 0.4,"
      " pose: {xyz_m: [-1, 1, 1], rpy: [1.5707963267948966, 0, 0]}, attachable: true}\n"
      "  - {name: crate, type: box, size_m: [0.2, 0.4, 0.6], pose: {xyz_m: [-1, -1, 1]}}\n"
      "  - {name: pipe, type: cylinder, radius_m: 0.02, length_m: 0.4, pose: {xyz_m: [0, 1, 1]}}\n";
  const std::string world = "world: {center_m: [0, 0, 1], edge_m: 4}\n";
  for (const std::string model : {"capsule", "box", "tighter"}) {
    const Workcell w = LoadWorkcell(
        kUrdf, WriteTempFile("typed.yaml", world + "cylinder_model: " + model + "\n" + objects));
    ExpectValid(w);
    ExpectCapsule(ShapeOf(w, "ball"), {1, 1, 1}, {1, 1, 1}, 0.1, "ball");
    ExpectCapsule(ShapeOf(w, "rod"), {-1, 1.2, 1}, {-1, 0.8, 1}, 0.03, "rod");
    EXPECT_FALSE(w.primitives[w.FindPrimitive("rod")].is_static);
    EXPECT_EQ(w.primitives[w.FindPrimitive("can")].tolerance_m, 0.02);
    ASSERT_TRUE(std::holds_alternative<Box>(ShapeOf(w, "crate")));
    EXPECT_EQ(std::get<Box>(ShapeOf(w, "crate")).half_extents_m, Eigen::Vector3d(0.1, 0.2, 0.3));
    // tighter: the can (length 4 radii) gets its box, 0.002 m^3 against the capsule's 0.0021;
    // the pipe (20 radii) its capsule, 0.00054 m^3 against the box's 0.00064.
    if (model == "capsule") {
      ExpectCapsule(ShapeOf(w, "can"), {1, -1, 0.9}, {1, -1, 1.1}, 0.05, "can");
    } else {
      ASSERT_TRUE(std::holds_alternative<Box>(ShapeOf(w, "can")));
      EXPECT_EQ(std::get<Box>(ShapeOf(w, "can")).half_extents_m, Eigen::Vector3d(0.05, 0.05, 0.1));
    }
    if (model == "box") {
      ASSERT_TRUE(std::holds_alternative<Box>(ShapeOf(w, "pipe")));
      EXPECT_EQ(std::get<Box>(ShapeOf(w, "pipe")).half_extents_m,
                Eigen::Vector3d(0.02, 0.02, 0.2));
    } else {
      ExpectCapsule(ShapeOf(w, "pipe"), {0, 1, 0.8}, {0, 1, 1.2}, 0.02, "pipe");
    }
    const Eigen::Isometry3d X_WCan(Eigen::Translation3d(1, -1, 1));
    for (const Eigen::Vector3d& p_W : SolidPoints_W(X_WCan, 0.05, 0.2, false, 4)) {
      ExpectInside(p_W, ShapeOf(w, "can"), "can " + model + " (seed 4)");
    }
  }
}

// urdf_cylinder_model: the URDF's bare cylinders become the capsule (default), the box or the
// smaller of the two; a capsule written as a cylinder with two end spheres stays that capsule,
// and a link with a radius_m override keeps its capsule, which the override widens.
TEST(SceneMoveitInputs, UrdfCylindersFollowUrdfCylinderModel) {
  const Workcell plain = LoadWorkcell(kUrdf, kScene);
  const std::string links = "\nlinks:\n";
  const std::string scene =
      EditedText(ReadTextFile(kScene), {{links, links + "  left_link2: {radius_m: 0.1}\n"}});
  for (const std::string model : {"box", "tighter"}) {
    const Workcell w =
        LoadWorkcell(kUrdf, WriteTempFile("urdf_cylinders.yaml",
                                          scene + "\nurdf_cylinder_model: " + model + "\n"));
    ExpectValid(w);
    // left_link1: radius 0.09, length 0.3 (3.3 radii: the box is the smaller).
    const Capsule& capsule = std::get<Capsule>(ShapeOf(plain, "left_link1"));
    ASSERT_TRUE(std::holds_alternative<Box>(ShapeOf(w, "left_link1"))) << model;
    const Box& box = std::get<Box>(ShapeOf(w, "left_link1"));
    EXPECT_EQ(box.half_extents_m, Eigen::Vector3d(0.09, 0.09, 0.15)) << model;
    EXPECT_TRUE(box.X_WB.translation().isApprox(0.5 * (capsule.p0_W + capsule.p1_W), 1e-12));
    EXPECT_TRUE(box.X_WB.linear().col(2).isApprox((capsule.p1_W - capsule.p0_W).normalized(),
                                                  1e-12));
    // The gripper's capsule idiom, exact as it is.
    const Capsule& gripper = std::get<Capsule>(ShapeOf(plain, "left_link7"));
    ASSERT_TRUE(std::holds_alternative<Capsule>(ShapeOf(w, "left_link7"))) << model;
    EXPECT_EQ(std::get<Capsule>(ShapeOf(w, "left_link7")).p0_W, gripper.p0_W);
    ASSERT_TRUE(std::holds_alternative<Capsule>(ShapeOf(w, "left_link2"))) << model;
    EXPECT_EQ(std::get<Capsule>(ShapeOf(w, "left_link2")).radius_m, 0.1);
    ASSERT_TRUE(std::holds_alternative<Box>(ShapeOf(w, "right_link2"))) << model;
  }
  ExpectValid(plain);
  EXPECT_TRUE(std::holds_alternative<Capsule>(ShapeOf(plain, "left_link1")));
}

// ---------------------------------------------------------------------------------------------
// Errors: each names the file and the element.

void ExpectBundledSceneError(const std::string& extra, std::vector<std::string> parts) {
  const std::string scene = BundledSceneWith("bad.yaml", extra);
  parts.push_back(scene);
  ExpectLoadError([&] { LoadWorkcell(kUrdf, scene); }, parts);
}

TEST(SceneMoveitInputs, BadSceneKeysAreRejected) {
  ExpectBundledSceneError("srdf: package://workcell_moveit/config/workcell.srdf",
                          {"srdf", "package://", "give a file path"});
  ExpectBundledSceneError("planning_scene: package://x/scene.yaml",
                          {"planning_scene", "package://"});
  ExpectBundledSceneError("srdf: no_such_file.srdf", {"srdf", "no_such_file.srdf"});
  ExpectBundledSceneError("planning_scene_acm: true", {"planning_scene_acm", "without"});
  ExpectBundledSceneError("planning_scene_tolerance_m: 0.1",
                          {"planning_scene_tolerance_m", "without"});
  ExpectBundledSceneError("cylinder_model: cone",
                          {"cylinder_model", "'cone'", "capsule, box or tighter"});
  ExpectBundledSceneError("urdf_cylinder_model: disc",
                          {"urdf_cylinder_model", "'disc'", "capsule, box or tighter"});
  ExpectBundledSceneError("mesh_fit: capsules:0", {"mesh_fit", "capsules:K", "'capsules:0'"});
  ExpectBundledSceneError("mesh_fit: capsules:x", {"mesh_fit", "capsules:K"});
  ExpectBundledSceneError("mesh_fit: hull", {"mesh_fit", "'hull'"});
}

TEST(SceneMoveitInputs, MalformedSrdfNamesItsFileAndLine) {
  const std::string srdf = WriteTempFile(
      "malformed.srdf",
      "<robot name='workcell'>\n  <disable_collisions link1='left_link1' link2='left_link3'/>\n"
      "  <group name='arm'>\n</robot>\n");
  ExpectBundledSceneError("srdf: " + srdf, {srdf + ":3:", "malformed XML", "<group>"});
  const std::string unknown =
      WriteTempFile("unknown_element.srdf",
                    "<robot name='workcell'>\n  <disable_colisions link1='a'/>\n</robot>\n");
  ExpectBundledSceneError("srdf: " + unknown,
                          {unknown + ":2:", "unknown element <disable_colisions>"});
}

std::string PlanningSceneWithObject(const std::string& name, const std::string& object) {
  return WriteTempFile(name, "world:\n  collision_objects:\n" + object);
}

// MoveIt's scene geometry text (a .scene file) loads as the YAML forms do: its objects static, in
// the fixed frame; a bad one stops the load naming the .scene file, its line and the object.
TEST(SceneMoveitInputs, SceneGeometryTextObjectsBecomeStaticObjects) {
  const Workcell base = LoadWorkcell(kUrdf, kScene);
  const Workcell w = LoadWorkcell(
      kUrdf, BundledSceneWith("ps_text.yaml", "planning_scene: " + kMoveit + "bookshelf.scene"));
  ExpectValid(w);
  EXPECT_EQ(w.primitives.size(), base.primitives.size() + 4);
  for (const char* id : {"Can1", "shelf_bottom", "Ball", "Tetra"}) {
    const int o = w.FindObject(id);
    ASSERT_GE(o, 0) << id;
    EXPECT_TRUE(w.objects[o].frame.empty()) << id;
    EXPECT_TRUE(w.primitives[w.objects[o].primitive].is_static) << id;
  }
  ExpectCapsule(ShapeOf(w, "Can1"), {0.9, 0.0, 1.01}, {0.9, 0.0, 1.15}, 0.03, "Can1");
  ExpectCapsule(ShapeOf(w, "Ball"), {0.7, 0.2, 1.1}, {0.7, 0.2, 1.1}, 0.05, "Ball");
  ASSERT_TRUE(std::holds_alternative<Box>(ShapeOf(w, "shelf_bottom")));
  EXPECT_TRUE(std::get<Box>(ShapeOf(w, "shelf_bottom"))
                  .half_extents_m.isApprox(Eigen::Vector3d(0.6, 0.5, 0.02), 1e-15));

  // Scene geometry text has no allowed collision matrix: asking for it imports none, and says so.
  const Workcell acm = LoadWorkcell(
      kUrdf, BundledSceneWith("ps_text_acm.yaml", "planning_scene: " + kMoveit +
                                                      "bookshelf.scene\nplanning_scene_acm: true"));
  const std::string notice = FindWarning(acm, "planning_scene_acm: true");
  EXPECT_NE(notice.find(kMoveit + "bookshelf.scene"), std::string::npos) << notice;
  EXPECT_NE(notice.find("none imported"), std::string::npos) << notice;
  EXPECT_EQ(acm.warnings.size(), w.warnings.size() + 1);

  const std::string bad = WriteTempFile(
      "bad_text.scene", "s\n* cup\n0.5 0 1\n0 0 0 1\n1\ntorus\n0.1 0.02\n");
  ExpectBundledSceneError("planning_scene: " + bad,
                          {bad + ":6:", "object 'cup' shape 0", "unknown shape type 'torus'"});
}

TEST(SceneMoveitInputs, BadPlanningSceneObjectsAreRejected) {
  const std::string box = "      primitives: [{type: box, dimensions: [0.1, 0.1, 0.1]}]\n"
                          "      primitive_poses: [{position: [0.5, 0, 1]}]\n";
  struct Case {
    std::string object;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {"    - id: lid\n      header: {frame_id: left_link3}\n" + box,
       {"'lid'", "frame_id 'left_link3'", "moving link"}},
      {"    - id: lid\n      header: {frame_id: base_link}\n" + box,
       {"'lid'", "frame_id 'base_link'", "not a URDF link"}},
      {"    - id: floor\n" + box, {"duplicate name 'floor'"}},
      {"    - id: far\n      primitives: [{type: sphere, dimensions: [0.1]}]\n"
       "      primitive_poses: [{position: [9, 0, 1]}]\n",
       {"'far'", "world cube"}},
      {"    - id: sheet\n      meshes:\n"
       "        - triangles: [[0, 1, 2], [0, 2, 3]]\n"
       "          vertices: [[0, 0, 0], [0.1, 0, 0], [0.1, 0.1, 0], [0, 0.1, 0]]\n"
       "      mesh_poses: [{position: [0.5, 0, 1]}]\n",
       {"'sheet'", "meshes[0]", "no volume"}},
      {"    - id: torus\n      primitives: [{type: torus, dimensions: [0.1, 0.02]}]\n"
       "      primitive_poses: [{position: [0.5, 0, 1]}]\n",
       {"'torus'", "primitives[0].type", "unknown value 'torus'", "4 CONE"}},
      {"    - id: lid\n      header: {frame_id: no_such_frame}\n" + box,
       {"'lid'", "frame_id 'no_such_frame'", "not a URDF link"}},
  };
  for (const Case& c : cases) {
    const std::string ps = PlanningSceneWithObject("bad_ps.yaml", c.object);
    std::vector<std::string> parts = c.parts;
    parts.push_back(ps);
    ExpectBundledSceneError("planning_scene: " + ps, parts);
  }
}

// A Setup Assistant SRDF hangs the URDF root from another frame by a fixed virtual joint, and
// MoveIt's planning-scene dumps then name that frame: it means the fixed frame. A non-fixed
// virtual joint does not make an alias (the root moves in that frame): without the scene's
// pose of the joint (next test) the root stands at its origin, MoveIt's default, with a notice.
TEST(SceneMoveitInputs, FixedVirtualJointParentFrameNamesTheFixedFrame) {
  const std::string object =
      "    - id: lid\n      header: {frame_id: map}\n"
      "      primitives: [{type: box, dimensions: [0.1, 0.1, 0.1]}]\n"
      "      primitive_poses: [{position: [0.5, 0, 1]}]\n";
  const std::string ps = PlanningSceneWithObject("alias_ps.yaml", object);
  auto srdf_with = [](const std::string& type) {
    return WriteTempFile("alias_" + type + ".srdf",
                         "<robot name='workcell'>\n  <virtual_joint name='vj' type='" + type +
                             "' parent_frame='map' child_link='world'/>\n</robot>\n");
  };
  const Workcell w = LoadWorkcell(
      kUrdf, BundledSceneWith("alias.yaml",
                              "srdf: " + srdf_with("fixed") + "\nplanning_scene: " + ps + "\n"));
  const Shape& lid = ShapeOf(w, "lid");
  ASSERT_TRUE(std::holds_alternative<Box>(lid));
  EXPECT_TRUE(std::get<Box>(lid).X_WB.translation().isApprox(Eigen::Vector3d(0.5, 0, 1)));
  ExpectBundledSceneError("planning_scene: " + ps,
                          {ps, "'lid'", "frame_id 'map'", "not a URDF link"});
  const std::string floating = srdf_with("floating");
  const Workcell moving = LoadWorkcell(
      kUrdf, BundledSceneWith("floating.yaml",
                              "srdf: " + floating + "\nplanning_scene: " + ps + "\n"));
  EXPECT_NE(FindWarning(moving, "type='floating'>: the root link moves in 'map'"), "");
  EXPECT_TRUE(std::get<Box>(ShapeOf(moving, "lid")).X_WB.isApprox(std::get<Box>(lid).X_WB));
  const std::string notice = FindWarning(moving, "the objects in 'map'");
  EXPECT_NE(notice.find(ps + ": "), std::string::npos) << notice;
  EXPECT_NE(notice.find("at its origin, MoveIt's default"), std::string::npos) << notice;
  EXPECT_NE(notice.find("floating virtual joint 'vj' (" + floating + ":2)"), std::string::npos)
      << notice;
}

// A floating (or planar) virtual joint onto the root, as a stock Panda SRDF has: MoveIt's dump
// says in robot_state.multi_dof_joint_state where the joint puts the robot, and the objects in
// its parent frame, MoveIt's planning frame (so also those without a frame), are placed
// relative to that pose (the robot taken to stay there, with a notice). The pose of another
// joint does not place it.
TEST(SceneMoveitInputs, FloatingVirtualJointFrameIsPlacedByTheScenesRobotState) {
  const std::string srdf = WriteTempFile(
      "placed.srdf", "<robot name='workcell'>\n  <virtual_joint name='vj' type='floating' "
                     "parent_frame='map' child_link='world'/>\n</robot>\n");
  // The root 'world' stands at (1, 2, 0) in 'map', turned a quarter about z.
  auto scene_with_joint = [](const std::string& name, const std::string& joint) {
    return PlanningSceneWithObject(
        name,
        "    - id: lid\n      header: {frame_id: map}\n"
        "      primitives: [{type: box, dimensions: [0.1, 0.2, 0.3]}]\n"
        "      primitive_poses: [{position: [1.5, 2, 1]}]\n"
        "    - id: pan\n"
        "      primitives: [{type: box, dimensions: [0.1, 0.2, 0.3]}]\n"
        "      primitive_poses: [{position: [1.5, 2, 1]}]\n"
        "robot_state:\n  multi_dof_joint_state:\n    joint_names: [" + joint + "]\n"
        "    transforms:\n      - translation: {x: 1, y: 2, z: 0}\n"
        "        rotation: {x: 0, y: 0, z: 0.7071067811865476, w: 0.7071067811865476}\n");
  };
  const std::string ps = scene_with_joint("placed_ps.yaml", "vj");
  const Workcell w = LoadWorkcell(
      kUrdf, BundledSceneWith("placed.yaml", "srdf: " + srdf + "\nplanning_scene: " + ps + "\n"));
  const Shape& lid = ShapeOf(w, "lid");
  ASSERT_TRUE(std::holds_alternative<Box>(lid));
  const Box& box = std::get<Box>(lid);
  // Its offset (0.5, 0, 1) in 'map' from the root's origin is (0, -0.5, 1) in the root's frame
  // (the root's x is map's y).
  EXPECT_TRUE(box.X_WB.translation().isApprox(Eigen::Vector3d(0, -0.5, 1), 1e-12))
      << box.X_WB.translation().transpose();
  // The box's x edge (along map's x) lies along the root's -y.
  EXPECT_TRUE((box.X_WB.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY(),
                                                                      1e-12));
  EXPECT_TRUE(std::get<Box>(ShapeOf(w, "pan")).X_WB.isApprox(box.X_WB));
  const std::string notice = FindWarning(w, "the objects in 'map'");
  EXPECT_NE(notice.find(ps + ": "), std::string::npos) << notice;
  EXPECT_NE(notice.find("translation [1, 2, 0] m"), std::string::npos) << notice;
  EXPECT_NE(notice.find("gives (line 14) of the SRDF's floating virtual joint 'vj'"),
            std::string::npos)
      << notice;
  EXPECT_NE(notice.find("takes the robot to stay there"), std::string::npos) << notice;
  const std::string other = scene_with_joint("other_joint_ps.yaml", "base_joint");
  const Workcell at_origin = LoadWorkcell(
      kUrdf,
      BundledSceneWith("other_joint.yaml", "srdf: " + srdf + "\nplanning_scene: " + other + "\n"));
  EXPECT_TRUE(std::get<Box>(ShapeOf(at_origin, "lid"))
                  .X_WB.translation()
                  .isApprox(Eigen::Vector3d(1.5, 2, 1), 1e-12));
  EXPECT_NE(FindWarning(at_origin, "its origin, MoveIt's default"), "");
}

TEST(SceneMoveitInputs, BadTypedObjectsAreRejected) {
  const std::string world = "world: {center_m: [0, 0, 1], edge_m: 4}\nobjects:\n";
  const std::string pose = "pose: {xyz_m: [1, 1, 1]}";
  const std::vector<BadInputFile> cases = {
      {world + "  - {name: ball, type: sphere, " + pose + "}\n",
       {"objects[0] 'ball'", "a sphere needs radius_m"}},
      {world + "  - {name: ball, type: sphere, radius_m: 0.1, size_m: [1, 1, 1], " + pose + "}\n",
       {"objects[0] 'ball'.size_m", "not a key of a sphere"}},
      {world + "  - {name: can, type: cylinder, radius_m: 0.1, " + pose + "}\n",
       {"objects[0] 'can'", "a cylinder needs length_m"}},
      {world + "  - {name: can, type: cylinder, radius_m: 0, length_m: 1, " + pose + "}\n",
       {"objects[0] 'can'.radius_m"}},
      {world + "  - {name: rod, type: capsule, radius_m: 0.1, length_m: -1, " + pose + "}\n",
       {"objects[0] 'rod'.length_m"}},
      {world + "  - {name: crate, radius_m: 0.1, " + pose + "}\n",
       {"objects[0] 'crate'", "a box needs size_m"}},
      {world + "  - {name: cone, type: cone, radius_m: 0.1, " + pose + "}\n",
       {"objects[0] 'cone'.type", "unknown type 'cone'"}},
      {world + "  - {name: big, type: sphere, radius_m: 5, " + pose + "}\n",
       {"objects[0] 'big'", "world cube"}},
  };
  ExpectBadInputFilesRejected("typed_bad.yaml", cases,
                              [](const std::string& path) { LoadWorkcell(kUrdf, path); });
}

}  // namespace
}  // namespace arm_collision_monitor
