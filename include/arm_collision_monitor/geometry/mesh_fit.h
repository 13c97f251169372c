// Conservative primitive fits of triangle meshes: a URDF link's mesh collision geometry becomes
// one capsule, a chain of capsules or an oriented box that encloses every point of the mesh (and
// of the solid it bounds). Pure geometry, ROS-free; nothing here throws: bad input comes back
// as a MeshStatus with a message.
//
// Frames: the mesh is given in its own frame L (metres, URDF scale already applied: the mesh
// file's frame, which a URDF <origin> then places in the link), and the fitted shapes are in L
// too. Capsule::p0_W / p1_W and Box::X_WB are named for the world frame in primitives.h; here
// they hold L coordinates (the caller poses them).
//
// Conservative in floating point: every fitted radius and half extent is grown by
// kMeshFitMarginRel times the mesh's scale S (the diagonal of its vertices' bounding box plus
// their largest |coordinate|), far above the fit's own rounding (a few hundred eps * S).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arm_collision_monitor/geometry/primitives.h"

namespace arm_collision_monitor {

/// A triangle mesh: vertex positions in the link frame L (m) and triangles as index triples
/// into them (counter-clockwise seen from outside for a closed mesh; orientation only matters
/// for the enclosed volume).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices_L;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// Why a mesh (or a fit request) was accepted or refused.
enum class MeshStatus {
  kOk,
  kEmpty,                ///< No vertex or no triangle.
  kNonFiniteVertex,      ///< A vertex coordinate is NaN or infinite.
  kIndexOutOfRange,      ///< A triangle refers to a vertex that does not exist.
  kTooLarge,             ///< Extent > kMeshMaxExtent_m or |coordinate| > kMeshMaxCoordinate_m.
  kNoVolume,             ///< All vertices (nearly) on a plane, a line or at one point.
  kTooSmall,             ///< Extent < kMeshMinExtent_m.
  kBadOptions,           ///< MeshFitOptions out of range.
};

/// Short lower-case name of a status ("ok", "no volume", ...), for reports.
const char* MeshStatusName(MeshStatus status);

/// A status and, unless kOk, a message naming the offending element and the expected value.
struct MeshCheck {
  MeshStatus status = MeshStatus::kOk;
  std::string message;
};

/// Checks, in this order: empty, non-finite vertex, index out of range, absurd size (extent
/// above kMeshMaxExtent_m or a coordinate above kMeshMaxCoordinate_m), no volume (every vertex
/// within kMeshMinThicknessRel times the extent of a plane; covers collinear and single-point
/// meshes), too small (extent below kMeshMinExtent_m). The extent is the diagonal of the
/// vertices' axis-aligned bounding box. Unreferenced vertices count (they are fitted too).
MeshCheck CheckMesh(const TriangleMesh& mesh);

/// Which primitives to fit.
enum class MeshFitKind {
  kOneCapsule,    ///< One capsule (the default: links are capsules in this monitor).
  kCapsuleChain,  ///< capsule_count capsules, one per slab along the principal axis.
  kOrientedBox,   ///< One oriented box.
  kTighter,       ///< The one capsule or the one box, whichever has the smaller volume.
};

/// Fit request; part of the cache key (MeshFitHash).
struct MeshFitOptions {
  MeshFitKind kind = MeshFitKind::kOneCapsule;
  /// Capsules of a kCapsuleChain fit, in [1, kMeshFitMaxCapsules]; ignored by the other kinds.
  int capsule_count = 3;
};

/// The fitted primitives and the volumes for the start-up report.
struct MeshFit {
  MeshCheck check;             ///< kOk, or why nothing was fitted (shapes_L empty).
  std::vector<Shape> shapes_L;  ///< In L; their union contains the mesh's solid.
  /// Sum of the primitives' volumes, m^3 (for a chain an upper bound of the union's volume:
  /// neighbouring capsules' overlaps are counted twice, as the start-up report says).
  double fitted_volume_m3 = 0.0;
  /// IsClosedMesh(mesh).
  bool is_mesh_closed = false;
  /// EnclosedVolume_m3(mesh), m^3. NaN when the mesh is not closed: an open surface encloses no
  /// defined volume, and the report should say so.
  double mesh_volume_m3 = 0.0;
  /// fitted_volume_m3 / mesh_volume_m3 (>= 1 up to the margin for a one-primitive fit); NaN
  /// when the mesh is not closed.
  double excess_ratio = 0.0;
};

/// Fits `options.kind` to `mesh` after CheckMesh (and the options' range). Deterministic.
///
/// One capsule: for each candidate axis direction u, the capsule's axis line passes through the
/// centre of the smallest circle enclosing the vertices projected along u (Welzl's randomised
/// algorithm, de Berg et al., Computational Geometry 3rd ed., §4.7, with a fixed shuffle seed);
/// the radius R is the largest distance of a vertex from that line, and the segment is the
/// shortest one that still holds every vertex: a vertex at axial coordinate t and distance r
/// needs the segment to reach t -/+ sqrt(R^2 - r^2). Candidate axes: the three principal axes of
/// the surface (area-weighted triangle covariance, Gottschalk, Lin & Manocha, "OBBTree", SIGGRAPH
/// 1996, §4) and of the vertices, the four diagonals of the principal-axes box, then a
/// compass search around the best (steps kMeshFitSearchStartStep_rad halving to
/// kMeshFitSearchMinStep_rad); the smallest-volume capsule is kept.
///
/// Capsule chain: the mesh is cut into capsule_count equal slabs along its surface's principal
/// axis; every triangle is clipped to every slab it crosses (Sutherland-Hodgman). Two chains are
/// fitted to the slabs' vertices and clip points: each slab's tight capsule along the chain's
/// axis, and each slab's one-capsule fit as above (candidate axes from the principal axes of
/// its points). Of these and the one capsule of the whole mesh, the one whose union holds the
/// fewest points of a grid over all three is kept (a straight round link keeps its axis, where a
/// squat slab's own capsule would lie across it; a bent one follows its bend; a ball or a knob
/// stays one capsule). Slabs holding no point (a mesh in separate parts) get no capsule.
///
/// Tighter: the one-capsule fit above and the oriented-box fit below, the one of smaller volume
/// kept (a boxy part gets a box, a long round one a capsule).
///
/// Oriented box: exact extents along candidate frames (the surface's principal axes, the link
/// frame's axes, and each candidate capsule axis completed by the principal axes of the
/// projection), then a compass search of small rotations; the smallest-volume box is kept.
MeshFit FitMesh(const TriangleMesh& mesh, const MeshFitOptions& options);

/// True iff the mesh, with vertices at identical positions merged, is closed and consistently
/// oriented: every edge is used as often in one direction as in the other (one closed shell, or
/// several sharing edges or corners); triangles that merging collapses to a segment or a point
/// bound nothing and are skipped.
bool IsClosedMesh(const TriangleMesh& mesh);

/// The volume a closed mesh encloses, m^3: by the divergence theorem the sum of the signed
/// tetrahedra of the triangles with a common apex, its absolute value (shells that overlap count
/// their common part twice).
double EnclosedVolume_m3(const TriangleMesh& mesh);

/// Cache key of a fit: 64-bit FNV-1a (Fowler, Noll, Vo) over kMeshFitAlgorithmVersion, the vertex
/// coordinates' IEEE-754 bits, the triangle indices and the options (the capsule count only for
/// a chain, the one kind it changes), each fed as little-endian 64-bit words, lists with their
/// length first. Deterministic across runs and platforms; any changed bit (even -0.0 for 0.0, a
/// rotated triangle) changes the key except for 64-bit collisions.
std::uint64_t MeshFitHash(const TriangleMesh& mesh, const MeshFitOptions& options);

}  // namespace arm_collision_monitor
