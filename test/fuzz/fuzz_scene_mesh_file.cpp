// libFuzzer harness for the mesh file reader: the bytes of a mesh file as a URDF's <mesh> or a
// mesh object could name it, through ReadMeshFileBytes (assimp, from memory), then, when it is
// read, through the fit a start-up does (MeshFitter::FitInline: CheckMesh, then FitMesh; no
// cache). LoadError is the expected answer to bad input; otherwise every vertex of the mesh must
// lie in the fitted primitives. Any other exception, a crash, undefined behaviour, a leak or a
// broken invariant is a finding.
//
// Input: one selector byte, then the file. The selector's value modulo 3 picks the format hint
// (the file name's extension: stl, obj, dae), its value / 3 modulo 3 the fit (one capsule,
// capsules:3, box). Seeds: test/fuzz/corpus/scene_mesh_file/.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <variant>
#include <vector>

#include "../core/test_geometry_shapes.h"
#include "arm_collision_monitor/core/load_error.h"
#include "mesh_file.h"
#include "mesh_shapes.h"

namespace arm_collision_monitor {
namespace {

bool IsFinite(const Shape& shape) {
  if (const auto* c = std::get_if<Capsule>(&shape)) {
    return c->p0_W.allFinite() && c->p1_W.allFinite() && std::isfinite(c->radius_m) &&
           c->radius_m >= 0.0;
  }
  const Box& b = std::get<Box>(shape);
  return b.X_WB.matrix().allFinite() && b.half_extents_m.allFinite() &&
         (b.half_extents_m.array() >= 0.0).all();
}

// ReadMeshFileBytes's contract (mesh_file.h): triangles, indices within the vertices, finite
// vertices.
bool IsWellFormed(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return false;
  for (const auto& triangle : mesh.triangles) {
    for (const std::uint32_t index : triangle) {
      if (index >= mesh.vertices_L.size()) return false;
    }
  }
  return std::all_of(mesh.vertices_L.begin(), mesh.vertices_L.end(),
                     [](const Eigen::Vector3d& v) { return v.allFinite(); });
}

}  // namespace
}  // namespace arm_collision_monitor

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arm_collision_monitor;
  if (size < 1) return 0;
  static const char* const kHints[] = {"mesh.stl", "mesh.obj", "mesh.dae"};
  static const MeshFitKind kKinds[] = {MeshFitKind::kOneCapsule, MeshFitKind::kCapsuleChain,
                                       MeshFitKind::kOrientedBox, MeshFitKind::kTighter};
  const std::string name = kHints[data[0] % 3];
  MeshFitOptions options;
  options.kind = kKinds[(data[0] / 3) % 4];
  const std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  TriangleMesh mesh;
  try {
    mesh = ReadMeshFileBytes(bytes, name, Eigen::Vector3d::Ones());
  } catch (const LoadError&) {
    return 0;  // refused with a message: the expected answer to bad input
  }
  if (!IsWellFormed(mesh)) std::abort();
  MeshFitter fitter(FetchLocalResource, /*cache_dir=*/"", options);
  std::vector<Shape> shapes_M;
  try {
    shapes_M = fitter.FitInline(mesh, "fuzz: " + name);
  } catch (const LoadError&) {
    return 0;  // no volume, too large, ...
  }
  if (shapes_M.empty()) std::abort();
  for (const Shape& shape : shapes_M) {
    if (!IsFinite(shape)) std::abort();
  }
  for (const Eigen::Vector3d& v : mesh.vertices_L) {
    if (std::none_of(shapes_M.begin(), shapes_M.end(),
                     [&](const Shape& shape) { return InShape(shape, v); })) {
      std::abort();
    }
  }
  return 0;
}
