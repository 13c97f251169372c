// Meshes of the scene inputs (URDF <mesh> collision elements, objects: of type mesh, inline
// planning-scene meshes) as primitives: read through the fetcher, fitted per mesh_fit (FitMesh),
// with the fit cache, and one report line per mesh.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "arm_collision_monitor/geometry/mesh_fit.h"
#include "arm_collision_monitor/scene/mesh_fit_cache.h"
#include "arm_collision_monitor/scene/resource_fetch.h"
#include "arm_collision_monitor/scene/workcell.h"

namespace arm_collision_monitor {

/// Fits the meshes of one start-up; counts the fits and collects the report lines.
class MeshFitter {
 public:
  MeshFitter(ResourceFetcher fetch, std::string cache_dir, const MeshFitOptions& options);

  /// The primitives, in the mesh file's frame M (after `scale`), enclosing the mesh named
  /// `name` (a path relative to `base_dir` unless absolute, or a URL). `where` names the
  /// element ("file: element"): it prefixes every LoadError and the report line. Throws
  /// LoadError naming `where` and the file for an unreadable or corrupt file, a scale that is
  /// not 3 finite, non-zero numbers (a negative one mirrors), and a mesh that CheckMesh refuses
  /// (no volume, too large, ...).
  std::vector<Shape> FitFile(const std::string& name, const std::string& base_dir,
                             const Eigen::Vector3d& scale, const std::string& where);

  /// The same for a mesh given inline (a planning scene's shape_msgs/Mesh, or a file's once
  /// read), in its frame M.
  std::vector<Shape> FitInline(const TriangleMesh& mesh, const std::string& where);

  /// Adds the report lines, the warnings (meshes under kSmallMeshEdge_m), the cache's trouble
  /// (if any) and the fit counts to `workcell`.
  void ReportTo(Workcell* workcell) const;

 private:
  ResourceFetcher fetch_;
  MeshFitCache cache_;
  MeshFitOptions options_;
  std::vector<std::string> notices_;
  std::vector<std::string> warnings_;
  std::string cache_trouble_;  // the first failed store, "" if none
  MeshFitCounts counts_;
};

}  // namespace arm_collision_monitor
