// LoadWorkcell with mesh collision geometry: URDF <mesh> links and objects: of type mesh, read
// from files the tests write (binary and ASCII STL, OBJ, COLLADA), fitted per mesh_fit, cached
// by content (bad mesh input: test_scene_mesh_refusals.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/scene/resource_fetch.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "load_error_expect.h"
#include "mesh_file_writers.h"
#include "mesh_robot_files.h"
#include "test_geometry_shapes.h"

namespace arm_collision_monitor {
namespace {

namespace fs = std::filesystem;

TriangleMesh Scaled(TriangleMesh mesh, const Eigen::Vector3d& scale) {
  for (Eigen::Vector3d& v : mesh.vertices_L) v = v.cwiseProduct(scale);
  return mesh;
}

// The workcell's notices but the one on meshes named by paths relative to the URDF's folder,
// as these tests name them.
std::vector<std::string> FitNotices(const Workcell& w) {
  std::vector<std::string> notices;
  for (const std::string& notice : w.notices) {
    if (notice.find("named by a path relative") == std::string::npos) notices.push_back(notice);
  }
  return notices;
}

const std::string kOrigin = "<origin xyz=\"0.1 -0.2 0.3\" rpy=\"0.3 0.2 0.1\"/>";
const Eigen::Isometry3d kX_LC =
    PoseFromXyzRpy(Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(0.3, 0.2, 0.1));

TEST(SceneMeshLinks, EveryFormatLoadsEnclosedAndAlike) {
  const std::string dir = FreshDir("formats");
  const TriangleMesh l_shape = LShapeMesh(0.1, 0.05);
  WriteBytes(dir + "l_binary.stl", BinaryStl(l_shape));
  WriteBytes(dir + "l_ascii.STL", AsciiStl(l_shape));
  WriteBytes(dir + "l.obj", Obj(l_shape));
  WriteBytes(dir + "l.dae", Dae(l_shape));
  const std::vector<std::string> names = {"l_binary.stl", "l_ascii.STL", "l.obj", "l.dae"};
  std::vector<std::string> collisions;
  for (const std::string& name : names) collisions.push_back(MeshCollision(name, kOrigin));
  const Files files = WriteRobot(dir, collisions);
  const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  std::string why;
  EXPECT_TRUE(w.Validate(&why)) << why;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string link = "link" + std::to_string(k);
    ExpectEncloses(w, link, l_shape, kX_LC);
    // The same vertices and triangles in every format: the same fit.
    ASSERT_EQ(ShapesOf(w, link).size(), 1u) << names[k];
    EXPECT_TRUE(IsSameShape(ShapesOf(w, link)[0], ShapesOf(w, "link0")[0])) << names[k];
  }
  EXPECT_EQ(FitNotices(w).size(), names.size());
  // rviz's RobotModel cannot read relative mesh paths: a notice counts them.
  ASSERT_EQ(w.notices.size(), names.size() + 1);
  for (const std::string& part :
       std::vector<std::string>{files.urdf + ": 4 meshes named by a path relative to the URDF's "
                                             "folder ('l_binary.stl' of link 'link0', ...)",
                                "rviz's RobotModel", "package://"}) {
    EXPECT_NE(w.notices.back().find(part), std::string::npos) << part << w.notices.back();
  }
}

// Absolute paths and URLs give no such notice; a relative <visual> mesh counts too.
TEST(SceneMeshLinks, RelativeMeshPathsAreNoticedForRviz) {
  const std::string dir = FreshDir("relative_paths");
  WriteBytes(dir + "box.stl", BinaryStl(BoxMesh(Eigen::Vector3d(0.2, 0.1, 0.1))));
  const auto relative_notices = [](const Workcell& w) {
    return w.notices.size() - FitNotices(w).size();
  };
  const Files absolute = WriteRobot(
      dir, {MeshCollision(dir + "box.stl"), MeshCollision("file://" + dir + "box.stl")});
  EXPECT_EQ(relative_notices(LoadWorkcell(absolute.urdf, absolute.scene, CacheIn(dir))), 0u);
  const Files visual = WriteRobot(
      dir, {"<visual><geometry><mesh filename=\"box.stl\"/></geometry></visual>" +
            MeshCollision(dir + "box.stl")});
  const Workcell w = LoadWorkcell(visual.urdf, visual.scene, CacheIn(dir));
  ASSERT_EQ(relative_notices(w), 1u);
  EXPECT_NE(w.notices.back().find("1 mesh named by a path relative to the URDF's folder "
                                  "('box.stl' of link 'link0'): the monitor finds collision "
                                  "meshes there"),
            std::string::npos)
      << w.notices.back();
}

TEST(SceneMeshLinks, ScaleAndOriginAreHonoured) {
  const std::string dir = FreshDir("scale_origin");
  const TriangleMesh box = BoxMesh(Eigen::Vector3d(0.4, 0.1, 0.1));
  WriteBytes(dir + "box.stl", BinaryStl(box));
  const Files files = WriteRobot(dir, {MeshCollision("box.stl", kOrigin, "2 1 0.5")});
  const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  const TriangleMesh scaled = Scaled(box, Eigen::Vector3d(2, 1, 0.5));  // 0.8 x 0.1 x 0.05
  ExpectEncloses(w, "link0", scaled, kX_LC);
  const Capsule c = std::get<Capsule>(ShapesOf(w, "link0").at(0));
  const Eigen::Vector3d axis_L = (c.p1_W - c.p0_W).normalized();
  EXPECT_GT(std::abs(axis_L.dot(kX_LC.linear() * Eigen::Vector3d::UnitX())), 0.999);
  EXPECT_LT((0.5 * (c.p0_W + c.p1_W) - kX_LC.translation()).norm(), 1e-6);
  const double half_diagonal_m = std::hypot(0.05, 0.025);
  // The tight capsule of the scaled box: its cross-section's half diagonal as radius, and (the
  // corners lie at that radius) its whole 0.8 m length as segment.
  EXPECT_GE(c.radius_m, half_diagonal_m);
  EXPECT_NEAR(c.radius_m, half_diagonal_m, 1e-6);
  EXPECT_NEAR((c.p1_W - c.p0_W).norm(), 0.8, 1e-6);
}

TEST(SceneMeshLinks, NegativeScaleMirrorsTheMesh) {
  const std::string dir = FreshDir("mirror");
  const TriangleMesh l_shape = LShapeMesh(0.1, 0.05);
  WriteBytes(dir + "l.stl", BinaryStl(l_shape));
  const Files files = WriteRobot(dir, {MeshCollision("l.stl", kOrigin, "1 -1 1")});
  const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  ExpectEncloses(w, "link0", Scaled(l_shape, Eigen::Vector3d(1, -1, 1)), kX_LC);
}

TEST(SceneMeshLinks, MeshFitKindsEncloseTheNonConvexShape) {
  const std::string dir = FreshDir("kinds");
  const TriangleMesh l_shape = LShapeMesh(0.1, 0.05);
  WriteBytes(dir + "l.obj", Obj(l_shape));
  for (const std::string& kind : std::vector<std::string>{"box", "capsules:3", "tighter"}) {
    const Files files = WriteRobot(dir, {MeshCollision("l.obj", kOrigin)}, "mesh_fit: " + kind);
    const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
    ExpectEncloses(w, "link0", l_shape, kX_LC);
    const std::vector<Shape> shapes = ShapesOf(w, "link0");
    if (kind == "box") {
      ASSERT_EQ(shapes.size(), 1u);
      EXPECT_TRUE(std::holds_alternative<Box>(shapes[0]));
      EXPECT_GE(w.FindPrimitive("link0"), 0);
    } else if (kind == "tighter") {
      // Whichever it keeps, the report names it and the kind.
      ASSERT_EQ(shapes.size(), 1u);
      ASSERT_EQ(FitNotices(w).size(), 1u);
      const std::string fitted = std::holds_alternative<Box>(shapes[0]) ? "1 box" : "1 capsule";
      EXPECT_NE(w.notices[0].find("mesh fit: " + fitted + " (tighter) ("), std::string::npos)
          << w.notices[0];
      EXPECT_EQ(w.notices[0].find("loose capsule"), std::string::npos) << w.notices[0];
    } else {
      ASSERT_EQ(shapes.size(), 3u);
      for (int k = 0; k < 3; ++k) EXPECT_GE(w.FindPrimitive("link0/" + std::to_string(k)), 0);
      ASSERT_EQ(FitNotices(w).size(), 1u);
      EXPECT_NE(w.notices[0].find("3 capsules (capsules:3)"), std::string::npos) << w.notices[0];
      // A chain's volume is the sum of its capsules', which the report says.
      EXPECT_NE(w.notices[0].find(" (the capsules' volumes summed: overlaps count twice)"),
                std::string::npos)
          << w.notices[0];
    }
  }
  // A ball: no chain of slabs is smaller than its one capsule (a sphere), which it keeps.
  std::mt19937_64 rng(7);
  WriteBytes(dir + "ball.obj", Obj(TessellatedCapsuleMesh(0.05, 0.0, 24, 8, 0.0, &rng)));
  const Files files = WriteRobot(dir, {MeshCollision("ball.obj", kOrigin)}, "mesh_fit: capsules:3");
  const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  EXPECT_EQ(ShapesOf(w, "link0").size(), 1u);
  ASSERT_EQ(FitNotices(w).size(), 1u);
  EXPECT_NE(w.notices[0].find("mesh fit: 1 capsule (capsules:3: no chain is smaller) (radius "),
            std::string::npos)
      << w.notices[0];
}

TEST(SceneMeshLinks, ReportHasOneLinePerMeshWithTheExcessVolume) {
  const std::string dir = FreshDir("report");
  TriangleMesh open_box = BoxMesh(Eigen::Vector3d(0.2, 0.1, 0.1));
  open_box.triangles.pop_back();  // one triangle less: not closed
  WriteBytes(dir + "closed.stl", BinaryStl(BoxMesh(Eigen::Vector3d(0.2, 0.1, 0.1))));
  WriteBytes(dir + "open.obj", Obj(open_box));
  const Files files = WriteRobot(dir, {MeshCollision("closed.stl"), MeshCollision("open.obj")});
  const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  ASSERT_EQ(FitNotices(w).size(), 2u);
  for (const std::string& part :
       std::vector<std::string>{files.urdf, "link 'link0'", "closed.stl", "mesh fit: 1 capsule",
                                "fitted/mesh volume "}) {
    EXPECT_NE(w.notices[0].find(part), std::string::npos) << part << " not in " << w.notices[0];
  }
  // The capsule around a 0.2 x 0.1 x 0.1 box: its ratio, from the fitted shape.
  const Capsule c = std::get<Capsule>(ShapesOf(w, "link0").at(0));
  const double ratio = (M_PI * c.radius_m * c.radius_m * (c.p1_W - c.p0_W).norm() +
                        4.0 / 3.0 * M_PI * std::pow(c.radius_m, 3)) /
                       (0.2 * 0.1 * 0.1);
  std::ostringstream expected;
  expected.precision(3);
  expected << "fitted/mesh volume " << ratio;
  EXPECT_NE(w.notices[0].find(expected.str()), std::string::npos) << w.notices[0];
  // Over kLooseMeshFitRatio, the notice points at mesh_fit: tighter.
  ASSERT_GE(ratio, kLooseMeshFitRatio);
  EXPECT_NE(w.notices[0].find("(a loose capsule: mesh_fit: tighter would give a boxy part its "
                              "box)"),
            std::string::npos)
      << w.notices[0];
  // Its size beside the fit.
  std::ostringstream size;
  size.precision(3);
  size << "mesh fit: 1 capsule (radius " << c.radius_m << " m, "
       << (c.p1_W - c.p0_W).norm() + 2.0 * c.radius_m << " m end to end), ";
  EXPECT_NE(w.notices[0].find(size.str()), std::string::npos) << size.str() << w.notices[0];
  // An open mesh has no volume to compare with: the span of its vertices instead.
  EXPECT_NE(w.notices[1].find("open mesh: volume undefined (its vertices span 0.2 x 0.1 x 0.1 m "
                              "along the mesh axes)"),
            std::string::npos)
      << w.notices[1];
  EXPECT_NE(w.notices[1].find("link 'link1'"), std::string::npos) << w.notices[1];
}

TEST(SceneMeshLinks, OverridesWinAndSeveralCollisionsKeepTheirNames) {
  const std::string dir = FreshDir("overrides");
  WriteBytes(dir + "l.stl", BinaryStl(LShapeMesh(0.1, 0.05)));
  const std::string box = "<collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>";
  const Files files = WriteRobot(
      dir,
      {MeshCollision("missing.stl"), MeshCollision("missing.stl"), box + MeshCollision("l.stl")},
      "links:\n  link0: {p0_m: [0, 0, 0], p1_m: [0.3, 0, 0], radius_m: 0.05}\n"
      "  link1: {ignore: true}\nmesh_fit: capsules:2\n");
  const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  const Capsule& c = std::get<Capsule>(w.primitives[w.FindPrimitive("link0")].shape_L);
  EXPECT_EQ(c.p1_W, Eigen::Vector3d(0.3, 0, 0));
  EXPECT_EQ(c.radius_m, 0.05);
  EXPECT_TRUE(ShapesOf(w, "link1").empty());
  // link2: the box is element 0, the mesh element 1 fitted with two capsules.
  for (const std::string& name : std::vector<std::string>{"link2/0", "link2/1/0", "link2/1/1"}) {
    EXPECT_GE(w.FindPrimitive(name), 0) << name;
  }
  EXPECT_EQ(w.mesh_fits.computed, 1);
}

TEST(SceneMeshLinks, SecondLoadTakesEveryFitFromTheCache) {
  const std::string dir = FreshDir("cache");
  WriteBytes(dir + "l.stl", BinaryStl(LShapeMesh(0.1, 0.05)));
  WriteBytes(dir + "prism.obj", Obj(PrismMesh(0.05, 0.3, 12)));
  const Files files = WriteRobot(
      dir, {MeshCollision("l.stl"), MeshCollision("prism.obj"), MeshCollision("l.stl", kOrigin)});
  const Workcell first = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  // link2's mesh is link0's: one content, one fit.
  EXPECT_EQ(first.mesh_fits.computed, 2);
  EXPECT_EQ(first.mesh_fits.from_cache, 1);
  const Workcell second = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  EXPECT_EQ(second.mesh_fits.computed, 0);
  EXPECT_EQ(second.mesh_fits.from_cache, 3);
  ASSERT_EQ(first.primitives.size(), second.primitives.size());
  for (std::size_t i = 0; i < first.primitives.size(); ++i) {
    EXPECT_TRUE(IsSameShape(first.primitives[i].shape_L, second.primitives[i].shape_L)) << i;
  }
  EXPECT_NE(second.notices[0].find("(cached)"), std::string::npos);
  // No cache: every fit computed.
  WorkcellLoadOptions no_cache;
  no_cache.mesh_fit_cache_dir = "";
  EXPECT_EQ(LoadWorkcell(files.urdf, files.scene, no_cache).mesh_fits.computed, 3);
}

TEST(SceneMeshLinks, CorruptOrWrongCacheEntriesAreRefitted) {
  const std::string dir = FreshDir("corrupt");
  const TriangleMesh l_shape = LShapeMesh(0.1, 0.05);
  WriteBytes(dir + "l.stl", BinaryStl(l_shape));
  const Files files = WriteRobot(dir, {MeshCollision("l.stl")});
  const Workcell fitted = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  ASSERT_EQ(fitted.mesh_fits.computed, 1);
  std::vector<fs::path> entries;
  for (const auto& entry : fs::directory_iterator(dir + "cache")) entries.push_back(entry.path());
  ASSERT_EQ(entries.size(), 1u);  // no temporary file left behind
  const std::string good = ReadTextFile(entries[0].string());
  const Capsule c = std::get<Capsule>(ShapesOf(fitted, "link0").at(0));
  char radius[64], smaller[64];
  std::snprintf(radius, sizeof radius, "%a", c.radius_m);
  std::snprintf(smaller, sizeof smaller, "%a", 0.9 * c.radius_m);
  const std::string shrunk = EditedText(good, {{radius, smaller}});
  for (const std::string& bad : {std::string("\x01\x02garbage"), good.substr(0, good.size() / 2),
                                 shrunk, good + "capsule 0 0 0 0 0 0 1\n", std::string("")}) {
    WriteBytes(entries[0].string(), bad);
    const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
    EXPECT_EQ(w.mesh_fits.computed, 1) << bad;
    EXPECT_EQ(w.mesh_fits.from_cache, 0) << bad;
    ExpectEncloses(w, "link0", l_shape, Eigen::Isometry3d::Identity());
    EXPECT_TRUE(IsSameShape(ShapesOf(w, "link0")[0], c));
    // Rewritten: the next load uses it.
    EXPECT_EQ(LoadWorkcell(files.urdf, files.scene, CacheIn(dir)).mesh_fits.from_cache, 1);
  }
}

TEST(SceneMeshLinks, UnwritableCacheIsANotice) {
  const std::string dir = FreshDir("unwritable");
  WriteBytes(dir + "l.stl", BinaryStl(LShapeMesh(0.1, 0.05)));
  WriteBytes(dir + "a_file", "not a folder");
  const Files files = WriteRobot(dir, {MeshCollision("l.stl")});
  WorkcellLoadOptions options;
  options.mesh_fit_cache_dir = dir + "a_file/cache";  // below a regular file: never creatable
  const Workcell w = LoadWorkcell(files.urdf, files.scene, options);
  EXPECT_EQ(w.mesh_fits.computed, 1);
  ASSERT_EQ(FitNotices(w).size(), 2u);
  EXPECT_NE(w.notices[1].find("mesh fit cache " + dir + "a_file/cache not written"),
            std::string::npos)
      << w.notices[1];
}

TEST(SceneMeshLinks, ColladaUnitIsAppliedAndItsUpAxisIgnored) {
  const std::string dir = FreshDir("collada");
  // A 40 x 10 x 200 mm box: long along the file's z.
  const TriangleMesh box_mm = BoxMesh(Eigen::Vector3d(40, 10, 200));
  for (const std::string& up : std::vector<std::string>{"Z_UP", "Y_UP"}) {
    WriteBytes(dir + "box.dae", Dae(box_mm, "0.001", up));
    const Files files = WriteRobot(dir, {MeshCollision("box.dae")});
    const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
    const Capsule c = std::get<Capsule>(ShapesOf(w, "link0").at(0));
    // In metres, the long axis along the link's z whatever <up_axis> says (rviz's reading).
    EXPECT_GT(std::abs((c.p1_W - c.p0_W).normalized().z()), 0.999) << up;
    EXPECT_NEAR(c.radius_m, std::hypot(0.020, 0.005), 1e-6) << up;
    // The corners (at the radius) need the whole 200 mm of segment.
    EXPECT_NEAR((c.p1_W - c.p0_W).norm(), 0.2, 1e-6) << up;
  }
}

// A mesh under a millimetre across (a COLLADA <unit> in mm and a scale of 0.001 too: the helper-66
// trial's 0.5 mm speck for a 0.5 m part) is loaded as it is, with a warning naming the link and
// the likely unit error; the part at its real size gets none.
TEST(SceneMeshLinks, AMeshUnderAMillimetreIsAWarning) {
  const std::string dir = FreshDir("speck");
  WriteBytes(dir + "box.dae", Dae(BoxMesh(Eigen::Vector3d(40, 10, 500)), "0.001"));
  auto unit_warnings = [](const Workcell& w) {
    std::vector<std::string> found;
    for (const std::string& warning : w.warnings) {
      if (warning.find("a unit error?") != std::string::npos) found.push_back(warning);
    }
    return found;
  };
  Files files = WriteRobot(dir, {MeshCollision("box.dae")});
  EXPECT_EQ(unit_warnings(LoadWorkcell(files.urdf, files.scene, CacheIn(dir))),
            std::vector<std::string>{});
  files = WriteRobot(dir, {MeshCollision("box.dae", "", "0.001 0.001 0.001")});
  const std::vector<std::string> found =
      unit_warnings(LoadWorkcell(files.urdf, files.scene, CacheIn(dir)));
  ASSERT_EQ(found.size(), 1u);
  for (const std::string& part : {files.urdf, std::string("link 'link0'"),
                                  std::string("mesh 'box.dae'"), std::string("0.0005 m across")}) {
    EXPECT_NE(found[0].find(part), std::string::npos) << part << " in " << found[0];
  }
}

TEST(SceneMeshLinks, ObjectsOfTypeMesh) {
  const std::string dir = FreshDir("objects");
  const TriangleMesh l_shape = LShapeMesh(0.1, 0.05);
  fs::create_directories(dir + "meshes");
  WriteBytes(dir + "meshes/l.obj", Obj(l_shape));
  const Files files = WriteRobot(
      dir, {},
      "mesh_fit: capsules:2\nobjects:\n"
      "  - {name: bracket, type: mesh, mesh: meshes/l.obj, scale: [2, 1, 1], attachable: true,\n"
      "     tolerance_m: 0.01, pose: {xyz_m: [0.5, 0.2, 0.8], rpy: [0, 0, 0.5]}}\n"
      "  - {name: plate, type: mesh, mesh: 'file://" +
          dir + "meshes/l.obj', pose: {xyz_m: [-0.5, 0, 0.5]}}\n");
  const Workcell w = LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  const int bracket = w.FindObject("bracket");
  ASSERT_GE(bracket, 0);
  EXPECT_EQ(w.objects[bracket].primitive_count, 2);
  EXPECT_TRUE(w.objects[bracket].is_attachable);
  for (const std::string& name :
       std::vector<std::string>{"bracket/0", "bracket/1", "plate/0", "plate/1"}) {
    const int id = w.FindPrimitive(name);
    ASSERT_GE(id, 0) << name;
    EXPECT_EQ(w.primitives[id].tolerance_m, name[0] == 'b' ? 0.01 : 0.0);
    EXPECT_EQ(w.primitives[id].is_static, name[0] == 'p');
  }
  ExpectEncloses(w, "bracket", Scaled(l_shape, Eigen::Vector3d(2, 1, 1)),
                 w.objects[bracket].X_WO_start);
  ExpectEncloses(w, "plate", l_shape, w.objects[w.FindObject("plate")].X_WO_start);
  std::string why;
  EXPECT_TRUE(w.Validate(&why)) << why;
}

// A relative name in a URDF or scene file is taken from the file's folder and made absolute, so
// that an error names the file looked for (a Reachy 2 user read a relative path as taken from
// the working directory). Not normalised: '..' after a symbolic link is the parent of the link's
// target, as the system opens it (package folders are often links into a source tree).
TEST(SceneMeshLinks, ResourceNamesResolveFromTheirFilesFolder) {
  EXPECT_EQ(ResolveResourceName("package://p/m.stl", "rel"), "package://p/m.stl");
  EXPECT_EQ(ResolveResourceName("file:///a/m.stl", "rel"), "file:///a/m.stl");
  EXPECT_EQ(ResolveResourceName("/a/../m.stl", "rel"), "/a/../m.stl");
  EXPECT_EQ(ResolveResourceName("m.stl", "/base/dir"), "/base/dir/m.stl");
  EXPECT_EQ(ResolveResourceName("m.stl", "rel/dir"),
            (fs::current_path() / "rel/dir/m.stl").string());
  const fs::path dir = fs::path(::testing::TempDir()) / "acm_resolve_link";
  fs::remove_all(dir);
  fs::create_directories(dir / "real" / "robot" / "urdf");
  fs::create_directories(dir / "real" / "robot" / "meshes");
  fs::create_directories(dir / "ws");
  std::ofstream(dir / "real" / "robot" / "meshes" / "x.stl") << "solid x\nendsolid x\n";
  fs::create_directory_symlink(dir / "real" / "robot" / "urdf", dir / "ws" / "urdf");
  const std::string url = ResolveResourceName("../meshes/x.stl", (dir / "ws" / "urdf").string());
  EXPECT_TRUE(fs::path(url).is_absolute()) << url;
  EXPECT_EQ(ReadWholeFile(url, "a mesh"), "solid x\nendsolid x\n");
}

}  // namespace
}  // namespace arm_collision_monitor
