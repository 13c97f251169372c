// MeshFit's cache key (MeshFitHash): 64-bit FNV-1a over the algorithm's version, the mesh and
// the options.
#include "arm_collision_monitor/geometry/mesh_fit.h"

#include <cstdint>
#include <cstring>

#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

// 64-bit FNV-1a, fed little-endian so the key does not depend on the platform's byte order.
class Fnv1a64 {
 public:
  void AddU64(std::uint64_t x) {
    for (int byte = 0; byte < 8; ++byte) {
      hash_ ^= (x >> (8 * byte)) & 0xffu;
      hash_ *= 1099511628211ull;  // the FNV 64-bit prime
    }
  }
  void AddDouble(double x) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &x, sizeof bits);
    AddU64(bits);
  }
  std::uint64_t hash() const { return hash_; }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;  // the FNV 64-bit offset basis
};

}  // namespace

std::uint64_t MeshFitHash(const TriangleMesh& mesh, const MeshFitOptions& options) {
  Fnv1a64 hash;
  hash.AddU64(kMeshFitAlgorithmVersion);
  hash.AddU64(mesh.vertices_L.size());
  for (const Eigen::Vector3d& p : mesh.vertices_L) {
    for (int k = 0; k < 3; ++k) hash.AddDouble(p[k]);
  }
  hash.AddU64(mesh.triangles.size());
  for (const auto& tri : mesh.triangles) {
    for (const std::uint32_t index : tri) hash.AddU64(index);
  }
  hash.AddU64(static_cast<std::uint64_t>(options.kind));
  // The capsule count changes only a chain's result; keying it otherwise would split the cache.
  hash.AddU64(options.kind == MeshFitKind::kCapsuleChain
                  ? static_cast<std::uint64_t>(options.capsule_count)
                  : 0u);
  return hash.hash();
}

}  // namespace arm_collision_monitor
