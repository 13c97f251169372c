// The robots of the mesh tests (test_scene_mesh_links.cpp, test_scene_mesh_refusals.cpp): a
// chain of links holding given <collision> elements, written with its scene file to a fresh
// folder of the test's own, and what the tests check of the loaded workcell.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "arm_collision_monitor/scene/workcell.h"
#include "mesh_file_writers.h"
#include "test_geometry_shapes.h"

namespace arm_collision_monitor {

inline const std::string kWorld = "world: {center_m: [0.0, 0.0, 1.0], edge_m: 8.0}\n";

// An empty folder of the test's own (a fresh one per call).
inline std::string FreshDir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("acm_mesh_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string() + "/";
}

// A URDF: base_link (a box) and a chain of revolute links link0, link1, ..., link k holding the
// raw <collision> elements collisions[k].
inline std::string ChainUrdf(const std::vector<std::string>& collisions) {
  std::string urdf =
      "<robot name=\"mesh_robot\">\n<link name=\"base_link\"><collision><geometry><box size=\"0.2 "
      "0.2 0.2\"/></geometry></collision></link>\n";
  std::string parent = "base_link";
  for (std::size_t k = 0; k < collisions.size(); ++k) {
    const std::string link = "link" + std::to_string(k);
    urdf += "<link name=\"" + link + "\">" + collisions[k] + "</link>\n<joint name=\"joint" +
            std::to_string(k) + "\" type=\"revolute\"><parent link=\"" + parent +
            "\"/><child link=\"" + link +
            "\"/><origin xyz=\"0 0 0.5\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" upper=\"1\" "
            "effort=\"1\" velocity=\"1\"/></joint>\n";
    parent = link;
  }
  return urdf + "</robot>\n";
}

inline std::string MeshCollision(const std::string& filename, const std::string& origin = "",
                          const std::string& scale = "") {
  return "<collision>" + origin + "<geometry><mesh filename=\"" + filename + "\"" +
         (scale.empty() ? "" : " scale=\"" + scale + "\"") + "/></geometry></collision>";
}

struct Files {
  std::string urdf;
  std::string scene;
};

inline Files WriteRobot(const std::string& dir, const std::vector<std::string>& collisions,
                 const std::string& scene_extra = "") {
  Files files{dir + "robot.urdf", dir + "scene.yaml"};
  WriteBytes(files.urdf, ChainUrdf(collisions));
  WriteBytes(files.scene, kWorld + scene_extra);
  return files;
}

inline WorkcellLoadOptions CacheIn(const std::string& dir) {
  WorkcellLoadOptions options;
  options.mesh_fit_cache_dir = dir + "cache";
  return options;
}

inline std::vector<Shape> ShapesOf(const Workcell& w, const std::string& owner) {
  std::vector<Shape> shapes;
  for (const PrimitiveSpec& p : w.primitives) {
    if (p.owner == owner) shapes.push_back(p.shape_L);
  }
  return shapes;
}

// Every vertex of `mesh`, placed by X_LC, lies in one of `owner`'s primitives.
inline void ExpectEncloses(const Workcell& w, const std::string& owner, const TriangleMesh& mesh,
                    const Eigen::Isometry3d& X_LC) {
  const std::vector<Shape> shapes = ShapesOf(w, owner);
  ASSERT_FALSE(shapes.empty()) << owner;
  for (const Eigen::Vector3d& v : mesh.vertices_L) {
    const Eigen::Vector3d p = X_LC * v;
    bool inside = false;
    for (const Shape& s : shapes) inside = inside || InShape(s, p);
    ASSERT_TRUE(inside) << owner << ": vertex " << p.transpose() << " outside the fit";
  }
}

}  // namespace arm_collision_monitor
