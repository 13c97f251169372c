// FetchRosResource: package:// URLs resolved through resource_retriever (the ROS package index)
// for URDF meshes and the scene file's srdf:, as the node and replay load them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/ros/resource_fetch_ros.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {
namespace {

namespace fs = std::filesystem;

// This package is found in the folder that holds its source (rostest and catkin set
// ROS_PACKAGE_PATH too; a bare run of the binary may not).
void AddThisPackageToRosPackagePath() {
  const std::string folder = fs::path(ACM_SOURCE_DIR).parent_path().string();
  const char* current = std::getenv("ROS_PACKAGE_PATH");
  const std::string path = current ? folder + ":" + current : folder;
  setenv("ROS_PACKAGE_PATH", path.c_str(), 1);
}

// True iff p_L lies in the closed capsule c.
bool InCapsule(const Capsule& c, const Eigen::Vector3d& p_L) {
  const Eigen::Vector3d d = c.p1_W - c.p0_W;
  const double s = std::clamp((p_L - c.p0_W).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p_L - c.p0_W - s * d).norm() <= c.radius_m;
}

// The corners of test/data/meshes/forearm.stl (|x|, |y| <= 0.045, |z| <= 0.175) placed by X_LC.
void ExpectForearmEnclosed(const Capsule& c, const Eigen::Isometry3d& X_LC) {
  for (const double x : {-0.045, 0.045}) {
    for (const double y : {-0.045, 0.045}) {
      for (const double z : {-0.175, 0.175}) {
        const Eigen::Vector3d p_L = X_LC * Eigen::Vector3d(x, y, z);
        EXPECT_TRUE(InCapsule(c, p_L)) << p_L.transpose();
      }
    }
  }
  EXPECT_NEAR((c.p1_W - c.p0_W).norm(), 0.35, 1e-6);
}

TEST(RosResourceFetch, PackageUrlsOfUrdfMeshesAndSrdfResolve) {
  AddThisPackageToRosPackagePath();
  const std::string dir = ::testing::TempDir() + "acm_ros_fetch/";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string urdf = dir + "robot.urdf";
  std::ofstream(urdf)
      << "<robot name=\"workcell\"><link name=\"base_link\"/>"
         "<link name=\"forearm\"><collision><origin xyz=\"0 0 0.1\"/><geometry><mesh filename="
         "\"package://arm_collision_monitor/test/data/meshes/forearm.stl\"/></geometry>"
         "</collision></link><joint name=\"j\" type=\"revolute\"><parent link=\"base_link\"/>"
         "<child link=\"forearm\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" "
         "effort=\"1\" velocity=\"1\"/></joint></robot>\n";
  const std::string scene = dir + "scene.yaml";
  std::ofstream(scene) << "world: {center_m: [0, 0, 0], edge_m: 4}\n"
                          "srdf: package://arm_collision_monitor/test/data/moveit/workcell.srdf\n";
  WorkcellLoadOptions options;
  options.fetch = FetchRosResource;
  options.mesh_fit_cache_dir = "";
  const Workcell w = LoadWorkcell(urdf, scene, options);
  const int forearm = w.FindPrimitive("forearm");
  ASSERT_GE(forearm, 0);
  Eigen::Isometry3d X_LC = Eigen::Isometry3d::Identity();
  X_LC.translation().z() = 0.1;
  ExpectForearmEnclosed(std::get<Capsule>(w.primitives[forearm].shape_L), X_LC);
  EXPECT_EQ(w.mesh_fits.computed, 1);
  // The SRDF was read: its links are not this robot's, so it leaves a notice naming them.
  bool has_srdf_notice = false;
  for (const std::string& warning : w.warnings) {
    has_srdf_notice |= warning.find("workcell.srdf: collision rules: skipped") != std::string::npos;
  }
  EXPECT_TRUE(has_srdf_notice);
}

// The bundled third-party-style arm loads with no override through the ROS fetcher.
TEST(RosResourceFetch, ThreeLinkArmWithPackageMeshLoadsWithoutOverride) {
  AddThisPackageToRosPackagePath();
  WorkcellLoadOptions options;
  options.fetch = FetchRosResource;
  options.mesh_fit_cache_dir = "";
  const std::string data = std::string(ACM_SOURCE_DIR) + "/test/data/";
  const Workcell w =
      LoadWorkcell(data + "three_link_arm_mesh.urdf", data + "three_link_scene.yaml", options);
  const int forearm = w.FindPrimitive("forearm");
  ASSERT_GE(forearm, 0);
  ExpectForearmEnclosed(
      std::get<Capsule>(w.primitives[forearm].shape_L),
      PoseFromXyzRpy(Eigen::Vector3d(0.175, 0, 0), Eigen::Vector3d(0, M_PI / 2, 0)));
  ASSERT_EQ(w.notices.size(), 1u);
  EXPECT_NE(w.notices[0].find("link 'forearm'"), std::string::npos) << w.notices[0];
}

TEST(RosResourceFetch, UnknownPackageIsALoadError) {
  AddThisPackageToRosPackagePath();
  ::testing::internal::CaptureStderr();
  try {
    FetchRosResource("package://no_such_package_acm/meshes/a.stl");
    ADD_FAILURE() << "expected a LoadError";
  } catch (const LoadError& e) {
    // What to do (a Sawyer user read only "Package [...] does not exist").
    EXPECT_NE(std::string(e.what()).find("ROS knows no package 'no_such_package_acm' (source "
                                         "the setup.bash of the workspace that holds it, or add "
                                         "the directory above it to ROS_PACKAGE_PATH)"),
              std::string::npos)
        << e.what();
  }
  // The load error alone: not rospack's own lines before it (an Aubo user's typo got both).
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(printed.find("rospack"), std::string::npos) << printed;
  // A file missing from a package ROS knows (its name saying "does not exist"): no such advice.
  try {
    FetchRosResource("package://arm_collision_monitor/does not exist.stl");
    ADD_FAILURE() << "expected a LoadError";
  } catch (const LoadError& e) {
    EXPECT_EQ(std::string(e.what()).find("ROS knows no package"), std::string::npos) << e.what();
  }
}

// Plain paths (what a scene file's srdf: and planning_scene: resolve to, relative to the scene
// file) are read as files: resource_retriever alone hands them to curl, which refuses them.
TEST(RosResourceFetch, PlainPathsAreReadAsFiles) {
  const std::string dir = ::testing::TempDir() + "acm_ros_fetch_plain/";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string bytes = std::string("solid\0binary\xff", 13);
  std::ofstream(dir + "a.bin", std::ios::binary) << bytes;
  EXPECT_EQ(FetchRosResource(dir + "a.bin"), bytes);
  EXPECT_EQ(FetchRosResource("file://" + dir + "a.bin"), bytes);
  const fs::path previous = fs::current_path();
  fs::current_path(dir);
  EXPECT_EQ(FetchRosResource("a.bin"), bytes);
  fs::current_path(previous);
  try {
    FetchRosResource(dir + "missing.bin");
    ADD_FAILURE() << "expected a LoadError";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.bin"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace arm_collision_monitor
