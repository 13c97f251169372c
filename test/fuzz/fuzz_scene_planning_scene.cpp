// libFuzzer harness for the planning-scene readers: a moveit_msgs/PlanningScene YAML file or a
// MoveIt scene geometry text (.scene) as a user (or MoveIt, or a benchmark suite) could supply
// it, through ReadPlanningSceneFile, then, when it is read, through LoadWorkcell as the
// planning_scene: (with planning_scene_acm) of a small arm's scene
// (test/data/three_link_arm.urdf), which turns its objects into primitives (meshes fitted).
// LoadError is the expected answer to bad input; any other exception, a crash, undefined
// behaviour, a leak or a broken invariant of the result is a finding.
//
// Input: the planning-scene text, read both as YAML (a .yaml file) and as scene geometry text (a
// .scene file). Seeds: test/fuzz/corpus/scene_planning_scene/.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/scene/planning_scene_reader.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "fuzz_files.h"

namespace arm_collision_monitor {
namespace {

// The fuzzed planning scene as a file of extension `extension` ("yaml" or "scene").
std::string PlanningScenePath(const std::string& extension) {
  return fuzz::ScratchDirectory("planning_scene") + "/scene_dump." + extension;
}

// The three-link arm's scene with the fuzzed planning scene of `extension` and its matrix.
std::string ScenePath(const std::string& extension) {
  const std::string scene = fuzz::ScratchDirectory("planning_scene") + "/" + extension + ".yaml";
  fuzz::WriteScratchFile(scene,
                         "world: {center_m: [0.0, 0.0, 1.0], edge_m: 4.0}\n"
                         "arms:\n  - {name: arm, root_link: upper_arm}\n"
                         "planning_scene: " + PlanningScenePath(extension) + "\n"
                         "planning_scene_acm: true\n");
  return scene;
}

// The reader's contract (planning_scene_reader.h): ids, finite positive dimensions, finite
// poses, triangle indices within the vertices.
bool IsWellFormed(const SceneCollisionObject& object) {
  if (object.id.empty() || (object.primitives.empty() && object.meshes.empty())) return false;
  for (const ScenePrimitive& p : object.primitives) {
    if (!p.X_FP.matrix().allFinite()) return false;
    for (const double d : p.dimensions_m) {
      if (!std::isfinite(d) || !(d > 0.0)) return false;
    }
  }
  for (const SceneMesh& mesh : object.meshes) {
    if (!mesh.X_FM.matrix().allFinite() || mesh.vertices_M.empty() || mesh.triangles.empty()) {
      return false;
    }
    for (const auto& triangle : mesh.triangles) {
      for (const std::uint32_t index : triangle) {
        if (index >= mesh.vertices_M.size()) return false;
      }
    }
    for (const Eigen::Vector3d& v : mesh.vertices_M) {
      if (!v.allFinite()) return false;
    }
  }
  return true;
}

}  // namespace
}  // namespace arm_collision_monitor

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  arm_collision_monitor::fuzz::SilenceConsoleBridge();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arm_collision_monitor;
  for (const char* extension : {"yaml", "scene"}) {
    const std::string path = PlanningScenePath(extension);
    fuzz::WriteScratchFile(path, std::string_view(reinterpret_cast<const char*>(data), size));
    PlanningSceneFile file;
    try {
      file = ReadPlanningSceneFile(path);
    } catch (const LoadError&) {
      continue;  // refused with a message: the expected answer to bad input
    }
    for (const SceneCollisionObject& object : file.objects) {
      if (!IsWellFormed(object)) std::abort();
    }
    fuzz::LoadThreeLinkArmAndValidate(ScenePath(extension));
  }
  return 0;
}
