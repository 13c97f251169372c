// Closedness and enclosed volume of a triangle mesh (see mesh_fit.h).
#include "arm_collision_monitor/geometry/mesh_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

namespace arm_collision_monitor {
namespace {

using Eigen::Vector3d;

// For each vertex, the first vertex at the identical position: exported meshes (STL) often
// repeat a corner once per triangle, which must not make a closed surface look open.
std::vector<std::uint32_t> MergedIndices(const std::vector<Vector3d>& vertices) {
  std::vector<std::uint32_t> order(vertices.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  auto less = [&](std::uint32_t a, std::uint32_t b) {
    const Vector3d& p = vertices[a];
    const Vector3d& r = vertices[b];
    return std::tie(p.x(), p.y(), p.z(), a) < std::tie(r.x(), r.y(), r.z(), b);
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> merged(vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    const bool is_repeat = i > 0 && vertices[order[i]] == vertices[order[i - 1]];
    merged[order[i]] = is_repeat ? merged[order[i - 1]] : order[i];
  }
  return merged;
}

}  // namespace

bool IsClosedMesh(const TriangleMesh& mesh) {
  const std::vector<std::uint32_t> merged = MergedIndices(mesh.vertices_L);
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    const std::array<std::uint64_t, 3> v{merged[tri[0]], merged[tri[1]], merged[tri[2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
    for (int k = 0; k < 3; ++k) edges.push_back(v[k] << 32 | v[(k + 1) % 3]);
  }
  if (edges.empty()) return false;
  std::sort(edges.begin(), edges.end());
  // Each edge as often in one direction as in the other: shells sharing an edge or a corner
  // stay closed, and their signed volumes add.
  for (auto it = edges.begin(); it != edges.end();) {
    const auto end = std::upper_bound(it, edges.end(), *it);
    const auto reverse =
        std::equal_range(edges.begin(), edges.end(), (*it & 0xffffffffu) << 32 | *it >> 32);
    if (reverse.second - reverse.first != end - it) return false;
    it = end;
  }
  return true;
}

double EnclosedVolume_m3(const TriangleMesh& mesh) {
  // The apex at the vertices' box centre, so that rounding depends on the mesh's size rather
  // than on its distance from the link origin.
  Eigen::AlignedBox3d box;
  for (const Vector3d& p : mesh.vertices_L) box.extend(p);
  const Vector3d c = box.center();
  double six_volume = 0.0;
  for (const auto& tri : mesh.triangles) {
    const std::vector<Vector3d>& v = mesh.vertices_L;
    six_volume += (v[tri[0]] - c).dot((v[tri[1]] - c).cross(v[tri[2]] - c));
  }
  return std::abs(six_volume) / 6.0;
}

}  // namespace arm_collision_monitor
