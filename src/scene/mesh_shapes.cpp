#include "mesh_shapes.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <variant>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "mesh_file.h"

namespace arm_collision_monitor {
namespace {

// "1 capsule", "3 capsules (capsules:3)", "1 capsule (capsules:3: no chain is smaller)",
// "1 box", "1 box (tighter)".
std::string FitText(const MeshFitOptions& options, const std::vector<Shape>& shapes) {
  const std::size_t count = shapes.size();
  const bool is_box = count > 0 && std::holds_alternative<Box>(shapes.front());
  std::string text = std::to_string(count) + (is_box ? " box" : " capsule");
  if (count != 1) text += is_box ? "es" : "s";
  if (options.kind == MeshFitKind::kCapsuleChain) {
    text += " (capsules:" + std::to_string(options.capsule_count) +
            (count == 1 && options.capsule_count > 1 ? ": no chain is smaller)" : ")");
  } else if (options.kind == MeshFitKind::kTighter) {
    text += " (tighter)";
  }
  return text;
}

// The size of a one-primitive fit, "" for more: " (radius 0.052 m, 0.31 m end to end)" for a
// capsule, " (0.1 x 0.08 x 0.2 m)" for a box (its edges).
std::string SizeText(const std::vector<Shape>& shapes) {
  if (shapes.size() != 1) return "";
  std::ostringstream text;
  text.precision(3);
  if (const Capsule* c = std::get_if<Capsule>(&shapes.front())) {
    text << " (radius " << c->radius_m << " m, " << (c->p1_W - c->p0_W).norm() + 2.0 * c->radius_m
         << " m end to end)";
  } else {
    const Eigen::Vector3d edges_m = 2.0 * std::get<Box>(shapes.front()).half_extents_m;
    text << " (" << edges_m.x() << " x " << edges_m.y() << " x " << edges_m.z() << " m)";
  }
  return text.str();
}

// The extent of the mesh's vertices along the axes of its frame (m).
Eigen::Vector3d Extent_m(const TriangleMesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Eigen::Vector3d& v : mesh.vertices_L) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return hi - lo;
}

// One report line: "<where>: mesh fit: 1 capsule, 1204 vertices, fitted/mesh volume 1.37 (cached)".
std::string ReportLine(const std::string& where, const MeshFitOptions& options,
                       const TriangleMesh& mesh, const MeshFit& fit, bool is_cached) {
  std::ostringstream line;
  line << where << ": mesh fit: " << FitText(options, fit.shapes_L) << SizeText(fit.shapes_L)
       << ", " << mesh.vertices_L.size() << " vertices, " << mesh.triangles.size()
       << " triangles, ";
  if (fit.is_mesh_closed) {
    line.precision(3);
    line << "fitted/mesh volume " << fit.excess_ratio;
    if (fit.shapes_L.size() > 1) line << " (the capsules' volumes summed: overlaps count twice)";
    if (options.kind == MeshFitKind::kOneCapsule && fit.excess_ratio >= kLooseMeshFitRatio) {
      line << " (a loose capsule: mesh_fit: tighter would give a boxy part its box)";
    }
  } else {
    // No volume to compare with: the vertices' extent gives the fit a scale.
    const Eigen::Vector3d extent_m = Extent_m(mesh);
    line.precision(3);
    line << "open mesh: volume undefined (its vertices span " << extent_m.x() << " x "
         << extent_m.y() << " x " << extent_m.z() << " m along the mesh axes)";
  }
  if (is_cached) line << " (cached)";
  return line.str();
}

}  // namespace

MeshFitter::MeshFitter(ResourceFetcher fetch, std::string cache_dir, const MeshFitOptions& options)
    : fetch_(std::move(fetch)), cache_(std::move(cache_dir)), options_(options) {}

std::vector<Shape> MeshFitter::FitFile(const std::string& name, const std::string& base_dir,
                                       const Eigen::Vector3d& scale, const std::string& where) {
  const std::string element = where + " mesh '" + name + "'";
  // A negative factor mirrors the mesh (URDFs reuse one mesh for left and right parts this way);
  // the fit only needs the vertices, so mirroring is fine. Zero flattens it.
  if (!scale.allFinite() || (scale.array() == 0.0).any()) {
    std::ostringstream text;
    text << element << ": scale (" << scale.x() << ", " << scale.y() << ", " << scale.z()
         << ") must be 3 finite, non-zero numbers";
    throw LoadError(text.str());
  }
  if (name.find_first_not_of(" \t\r\n") == std::string::npos) {
    throw LoadError(element + ": an empty file name (expected a mesh file: a path, or a "
                    "package:// or file:// URL)");
  }
  TriangleMesh mesh;
  try {
    const std::string url = ResolveResourceName(name, base_dir);
    mesh = ReadMeshFileBytes(fetch_(url), url, scale);
  } catch (const LoadError& e) {
    throw LoadError(element + ": " + e.what());
  }
  return FitInline(mesh, element);
}

std::vector<Shape> MeshFitter::FitInline(const TriangleMesh& mesh, const std::string& where) {
  const MeshCheck check = CheckMesh(mesh);
  if (check.status != MeshStatus::kOk) {
    throw LoadError(where + ": " + MeshStatusName(check.status) + ": " + check.message);
  }
  const double across_m = Extent_m(mesh).maxCoeff();
  if (across_m < kSmallMeshEdge_m) {
    std::ostringstream text;
    text << where << ": the mesh is " << across_m
         << " m across at most: a unit error? (a mesh in metres given scale=\"0.001 0.001 "
            "0.001\", or a COLLADA <unit> and a scale both applied); its part is modelled that "
            "small, and the real part's contacts would be missed";
    warnings_.push_back(text.str());
  }
  const std::uint64_t key = MeshFitHash(mesh, options_);
  if (const std::optional<MeshFit> cached = cache_.Find(key, mesh)) {
    ++counts_.from_cache;
    notices_.push_back(ReportLine(where, options_, mesh, *cached, true));
    return cached->shapes_L;
  }
  const MeshFit fit = FitMesh(mesh, options_);
  if (fit.check.status != MeshStatus::kOk) {  // the options (checked when read) or the mesh
    throw LoadError(where + ": " + MeshStatusName(fit.check.status) + ": " + fit.check.message);
  }
  ++counts_.computed;
  const std::string trouble = cache_.Store(key, fit);
  if (!trouble.empty() && cache_trouble_.empty()) cache_trouble_ = trouble;
  notices_.push_back(ReportLine(where, options_, mesh, fit, false));
  return fit.shapes_L;
}

void MeshFitter::ReportTo(Workcell* workcell) const {
  workcell->notices.insert(workcell->notices.end(), notices_.begin(), notices_.end());
  workcell->warnings.insert(workcell->warnings.end(), warnings_.begin(), warnings_.end());
  if (!cache_trouble_.empty()) {
    workcell->notices.push_back("mesh fit cache " + cache_.dir() + " not written (" +
                                cache_trouble_ +
                                "): the fits are recomputed at every start-up; set "
                                "ACM_MESH_FIT_CACHE to a writable folder");
  }
  workcell->mesh_fits.computed += counts_.computed;
  workcell->mesh_fits.from_cache += counts_.from_cache;
}

}  // namespace arm_collision_monitor
