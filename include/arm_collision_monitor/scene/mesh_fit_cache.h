// The mesh-fit cache: FitMesh's results kept on disk by content (MeshFitHash of the scaled mesh
// and the fit options), so that a second start-up skips the fits. An entry is never trusted
// blindly: it is used only when it parses completely and its primitives contain every vertex of
// the mesh being loaded; otherwise the mesh is refitted and the entry rewritten. The vertex check
// proves one convex primitive right, but not a capsule chain's cover of the triangles between
// its capsules: for a chain the key (which holds kMeshFitAlgorithmVersion) is the guarantee.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "arm_collision_monitor/geometry/mesh_fit.h"

namespace arm_collision_monitor {

/// The cache folder used unless the caller names one: $ACM_MESH_FIT_CACHE when set (set but
/// empty: no cache), else <ros_home>/arm_collision_monitor/mesh_fit_cache with ros_home
/// $ROS_HOME, else $HOME/.ros (ROS's own default); "" (no cache) when neither is set.
std::string DefaultMeshFitCacheDir();

/// Whether every vertex of `mesh` lies in at least one of the closed primitives `shapes_L`
/// (exact double tests: a capsule's squared distance to its segment against its squared radius,
/// a box's |coordinates| in its frame against its half extents).
bool ContainsAllVertices(const std::vector<Shape>& shapes_L, const TriangleMesh& mesh);

/// A folder of fits, one small text file <key as 16 hex digits>.fit each: a format line, the
/// closedness, the volumes and the primitives, every number as a C hexfloat (exact). The folder
/// is created on the first store.
class MeshFitCache {
 public:
  /// `dir` "" disables the cache (Find finds nothing, Store stores nothing).
  explicit MeshFitCache(std::string dir) : dir_(std::move(dir)) {}

  const std::string& dir() const { return dir_; }
  bool is_enabled() const { return !dir_.empty(); }
  std::string PathOf(std::uint64_t key) const;

  /// The fit stored under `key` when its file is well formed and its primitives contain every
  /// vertex of `mesh` (ContainsAllVertices); nullopt when it is missing, unreadable, malformed
  /// or does not contain the mesh.
  std::optional<MeshFit> Find(std::uint64_t key, const TriangleMesh& mesh) const;

  /// Writes `fit` (check kOk) under `key` atomically: a temporary file in the folder renamed
  /// over the entry, so that a reader never sees half an entry. Returns "" on success, else why
  /// not (the folder cannot be created or written); never throws.
  std::string Store(std::uint64_t key, const MeshFit& fit) const;

 private:
  std::string dir_;
};

}  // namespace arm_collision_monitor
