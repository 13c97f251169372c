// Conservative primitive fits of triangle meshes (see mesh_fit.h for the algorithms and their
// sources). Everything is computed in local coordinates q = p_L - o_L, o_L the centre of the
// vertices' bounding box, so that rounding depends on the mesh's size rather than on its
// distance from the link origin; the margin (kMeshFitMarginRel * S) absorbs the rest.
#include "arm_collision_monitor/geometry/mesh_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <tuple>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/smallest_circle.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Matrix2d;
using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Points = std::vector<Vector3d>;


double CapsuleVolume_m3(double radius_m, double length_m) {
  return kPi * radius_m * radius_m * length_m + 4.0 / 3.0 * kPi * radius_m * radius_m * radius_m;
}

// Eigenvectors of a symmetric 3x3 matrix as the columns of a rotation, largest eigenvalue first.
Matrix3d PrincipalAxes(const Matrix3d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Matrix3d> solver(covariance);
  Matrix3d axes = solver.eigenvectors().rowwise().reverse();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);
  return axes;
}

Matrix3d VertexCovariance(const Points& q) {
  Vector3d mean = Vector3d::Zero();
  for (const Vector3d& p : q) mean += p;
  mean /= static_cast<double>(q.size());
  Matrix3d covariance = Matrix3d::Zero();
  for (const Vector3d& p : q) covariance += (p - mean) * (p - mean).transpose();
  return covariance / static_cast<double>(q.size());
}

// The points' extents along the axes of a frame (the columns of R_LB), and the box volume.
struct FrameBox {
  Matrix3d R_LB = Matrix3d::Identity();  // columns: the box axes
  Vector3d lo = Vector3d::Zero();        // extents along them (local coordinates)
  Vector3d hi = Vector3d::Zero();
  double volume_m3 = std::numeric_limits<double>::infinity();
};

FrameBox BoxInFrame(const Points& q, const Matrix3d& R_LB) {
  FrameBox box;
  box.R_LB = R_LB;
  box.lo = Vector3d::Constant(std::numeric_limits<double>::infinity());
  box.hi = -box.lo;
  for (const Vector3d& p : q) {
    const Vector3d p_B = R_LB.transpose() * p;
    box.lo = box.lo.cwiseMin(p_B);
    box.hi = box.hi.cwiseMax(p_B);
  }
  box.volume_m3 = (box.hi - box.lo).prod();
  return box;
}

// Covariance of the surface with uniform area density: a triangle's second moment about the
// origin is A/12 (9 m m^T + sum of p p^T over its corners), m its centroid (Gottschalk et al.,
// OBBTree, §4). Falls back to the vertices' covariance when the triangles have no area.
Matrix3d SurfaceCovariance(const Points& q, const TriangleMesh& mesh) {
  double area_sum = 0.0;
  Vector3d first_moment = Vector3d::Zero();
  Matrix3d second_moment = Matrix3d::Zero();
  for (const auto& tri : mesh.triangles) {
    const Vector3d& a = q[tri[0]];
    const Vector3d& b = q[tri[1]];
    const Vector3d& c = q[tri[2]];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const Vector3d m = (a + b + c) / 3.0;
    area_sum += area;
    first_moment += area * m;
    second_moment += area / 12.0 *
                     (9.0 * m * m.transpose() + a * a.transpose() + b * b.transpose() +
                      c * c.transpose());
  }
  if (!(area_sum > 0.0)) return VertexCovariance(q);
  const Vector3d mean = first_moment / area_sum;
  return second_moment / area_sum - mean * mean.transpose();
}

// The distinct points in a fixed pseudo-random order (Fisher-Yates with a seeded mt19937_64,
// whose sequence the standard fixes, so every platform shuffles alike). Repeated points (a
// corner shared by six triangles, clipped once per triangle or stored once per STL facet) would
// only slow every pass of the fit.
Points ShuffledDistinct(Points points) {
  auto less = [](const Vector3d& p, const Vector3d& r) {
    return std::tie(p.x(), p.y(), p.z()) < std::tie(r.x(), r.y(), r.z());
  };
  std::sort(points.begin(), points.end(), less);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  std::mt19937_64 rng(kMeshFitShuffleSeed);
  for (std::size_t i = points.size(); i > 1; --i) std::swap(points[i - 1], points[rng() % i]);
  return points;
}

// ---------------------------------------------------------------------------------------------
// One capsule about a given axis direction.

struct AxisCapsule {
  Vector3d axis = Vector3d::UnitX();     // unit direction u
  Vector3d line_point = Vector3d::Zero();  // the axis line's point with zero coordinate along u
  double s0 = 0.0;                       // segment = line_point + [s0, s1] * u
  double s1 = 0.0;
  double radius_m = 0.0;  // before the margin
  double volume_m3 = std::numeric_limits<double>::infinity();
};

// The tight capsule of axis direction `direction` around `q` (shuffled): the axis line through
// the smallest enclosing circle's centre of the projections, the exact radius about it, then the
// shortest segment: a point at axial t and distance r needs [s0, s1] to reach t -/+ sqrt(R^2 -
// r^2). Containment is decided by h^2 + r^2 <= R^2, so the cancellation in R^2 - r^2 costs only
// ~eps R in distance. When every point fits one sphere of radius R, the segment is its centre.
AxisCapsule CapsuleAlong(const Points& q, const Vector3d& direction,
                         std::vector<Vector2d>& projected) {
  AxisCapsule fit;
  fit.axis = direction.normalized();
  const Vector3d a = fit.axis.unitOrthogonal();
  const Vector3d b = fit.axis.cross(a);
  projected.resize(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) projected[i] = Vector2d(q[i].dot(a), q[i].dot(b));
  const Vector2d centre = SmallestCircleCentre(projected);
  double radius2 = 0.0;
  for (const Vector2d& p : projected) radius2 = std::max(radius2, (p - centre).squaredNorm());
  double lowest_end = std::numeric_limits<double>::infinity();
  double highest_start = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double t = q[i].dot(fit.axis);
    const double h = std::sqrt(std::max(0.0, radius2 - (projected[i] - centre).squaredNorm()));
    highest_start = std::max(highest_start, t - h);
    lowest_end = std::min(lowest_end, t + h);
  }
  const bool is_sphere = lowest_end > highest_start;
  fit.s0 = is_sphere ? 0.5 * (lowest_end + highest_start) : lowest_end;
  fit.s1 = is_sphere ? fit.s0 : highest_start;
  fit.line_point = centre.x() * a + centre.y() * b;
  fit.radius_m = std::sqrt(radius2);
  fit.volume_m3 = CapsuleVolume_m3(fit.radius_m, fit.s1 - fit.s0);
  return fit;
}

// Compass search (Kolda, Lewis & Torczon, "Optimization by direct search", SIAM Review 2003,
// §3.3): try `direction_count` perturbations of size `step` of the best fit, keep the first that
// lowers the volume, halve the step when none does.
template <typename Fit, typename Perturb>
Fit CompassSearch(Fit best, int direction_count, const Perturb& perturbed) {
  double step_rad = kMeshFitSearchStartStep_rad;
  int evaluations = 0;
  while (step_rad >= kMeshFitSearchMinStep_rad && evaluations < kMeshFitMaxSearchEvaluations) {
    bool is_improved = false;
    for (int k = 0; k < direction_count && !is_improved; ++k) {
      Fit trial = perturbed(best, k, step_rad);
      ++evaluations;
      if (trial.volume_m3 < best.volume_m3) {
        best = trial;
        is_improved = true;
      }
    }
    if (!is_improved) step_rad *= 0.5;
  }
  return best;
}

// Each frame's three axes and the four diagonals of the points' box in that frame.
Points CandidateAxes(const Points& q, const std::vector<Matrix3d>& frames) {
  Points axes;
  for (const Matrix3d& frame : frames) {
    const FrameBox box = BoxInFrame(q, frame);
    const Vector3d half = 0.5 * (box.hi - box.lo);
    for (int k = 0; k < 3; ++k) axes.push_back(frame.col(k));
    for (const double s1 : {1.0, -1.0}) {
      for (const double s2 : {1.0, -1.0}) {
        const Vector3d diagonal = frame * Vector3d(half.x(), s1 * half.y(), s2 * half.z());
        if (diagonal.squaredNorm() > 0.0) axes.push_back(diagonal);
      }
    }
  }
  return axes;
}

// The smallest-volume capsule over the candidate axes, refined by the compass search.
AxisCapsule BestCapsule(const Points& shuffled_q, const std::vector<Matrix3d>& frames) {
  std::vector<Vector2d> projected;
  AxisCapsule best;
  for (const Vector3d& axis : CandidateAxes(shuffled_q, frames)) {
    const AxisCapsule trial = CapsuleAlong(shuffled_q, axis, projected);
    if (trial.volume_m3 < best.volume_m3) best = trial;
  }
  return CompassSearch(best, 4, [&](const AxisCapsule& from, int k, double step_rad) {
    const Vector3d a = from.axis.unitOrthogonal();
    const Vector3d side = (k < 2 ? a : from.axis.cross(a)) * (k % 2 == 0 ? 1.0 : -1.0);
    return CapsuleAlong(shuffled_q, from.axis + std::tan(step_rad) * side, projected);
  });
}

Capsule ToCapsule_L(const AxisCapsule& fit, const Vector3d& o_L, double margin_m) {
  Capsule capsule;
  capsule.p0_W = o_L + (fit.line_point + fit.s0 * fit.axis);
  capsule.p1_W = o_L + (fit.line_point + fit.s1 * fit.axis);
  capsule.radius_m = fit.radius_m + margin_m;
  return capsule;
}

// ---------------------------------------------------------------------------------------------
// Capsule chain: slabs along the principal axis, triangles clipped to each slab.

struct ClipVertex {
  Vector3d q;
  double t;  // coordinate along the slab axis
};
struct ClipPolygon {
  std::array<ClipVertex, 5> v;  // a triangle cut by two parallel planes has at most 5 corners
  int n = 0;
};

// Sutherland-Hodgman against one plane: keeps the part where sign * (t - bound) >= 0; the new
// corners lie on the plane (t = bound exactly).
ClipPolygon ClipToHalfSpace(const ClipPolygon& in, double bound, double sign) {
  ClipPolygon out;
  for (int i = 0; i < in.n; ++i) {
    const ClipVertex& p = in.v[i];
    const ClipVertex& r = in.v[(i + 1) % in.n];
    const double dp = sign * (p.t - bound);
    const double dr = sign * (r.t - bound);
    if (dp >= 0.0) out.v[out.n++] = p;
    if ((dp >= 0.0) != (dr >= 0.0)) {
      out.v[out.n++] = ClipVertex{p.q + (dp / (dp - dr)) * (r.q - p.q), bound};
    }
  }
  return out;
}

// The points of each slab: its vertices and the corners of every triangle clipped to it. The
// part of a closed solid inside a slab lies in the convex hull of its surface points inside the
// slab (every line through an inner point, within the plane t = const, meets the surface on
// both sides of it), and a triangle's part in the slab is the hull of its clipped corners: so a
// capsule holding a slab's points holds the solid's slab part.
std::vector<Points> SlabPoints(const Points& q, const TriangleMesh& mesh, const Vector3d& axis,
                               int slab_count) {
  std::vector<double> t(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) t[i] = q[i].dot(axis);
  const double t_min = *std::min_element(t.begin(), t.end());
  const double t_max = *std::max_element(t.begin(), t.end());
  const double width = (t_max - t_min) / slab_count;
  auto bound = [&](int k) { return k == slab_count ? t_max : t_min + k * width; };
  auto slab_of = [&](double tk) {
    return std::clamp(static_cast<int>(std::floor((tk - t_min) / width)), 0, slab_count - 1);
  };
  std::vector<Points> slabs(slab_count);
  for (std::size_t i = 0; i < q.size(); ++i) slabs[slab_of(t[i])].push_back(q[i]);
  for (const auto& tri : mesh.triangles) {
    ClipPolygon triangle;
    for (const std::uint32_t index : tri) triangle.v[triangle.n++] = ClipVertex{q[index], t[index]};
    const auto [lo, hi] = std::minmax({t[tri[0]], t[tri[1]], t[tri[2]]});
    // One slab beyond each end: a corner exactly on a boundary belongs to both slabs.
    const int k_last = std::min(slab_count - 1, slab_of(hi) + 1);
    for (int k = std::max(0, slab_of(lo) - 1); k <= k_last; ++k) {
      const ClipPolygon part =
          ClipToHalfSpace(ClipToHalfSpace(triangle, bound(k), 1.0), bound(k + 1), -1.0);
      for (int c = 0; c < part.n; ++c) slabs[k].push_back(part.v[c].q);
    }
  }
  return slabs;
}

bool IsInCapsule(const AxisCapsule& c, const Vector3d& p) {
  const Vector3d d = p - c.line_point;
  const double t = std::clamp(d.dot(c.axis), c.s0, c.s1);
  return (d - t * c.axis).squaredNorm() <= c.radius_m * c.radius_m;
}

// How many points of a kMeshFitChainGridPoints^3 grid over all the chains' box each chain's
// union holds: comparable estimates of the unions' volumes, where the sum of the capsules'
// volumes counts every overlap of neighbours twice.
using Chain = std::vector<AxisCapsule>;
std::vector<int> GridPointsInside(const std::vector<Chain>& chains) {
  Eigen::AlignedBox3d box;
  for (const Chain& chain : chains) {
    for (const AxisCapsule& c : chain) {
      for (const double s : {c.s0, c.s1}) {
        const Vector3d end = c.line_point + s * c.axis;
        box.extend(end - Vector3d::Constant(c.radius_m));
        box.extend(end + Vector3d::Constant(c.radius_m));
      }
    }
  }
  const Vector3d cell = box.sizes() / kMeshFitChainGridPoints;
  std::vector<int> counts(chains.size(), 0);
  for (int i = 0; i < kMeshFitChainGridPoints; ++i) {
    for (int j = 0; j < kMeshFitChainGridPoints; ++j) {
      for (int k = 0; k < kMeshFitChainGridPoints; ++k) {
        const Vector3d p = box.min() + cell.cwiseProduct(Vector3d(i + 0.5, j + 0.5, k + 0.5));
        for (std::size_t n = 0; n < chains.size(); ++n) {
          counts[n] += std::any_of(chains[n].begin(), chains[n].end(),
                                   [&](const AxisCapsule& c) { return IsInCapsule(c, p); });
        }
      }
    }
  }
  return counts;
}

// A chain's capsules: per slab the one along the chain's axis, or the slab's own smallest, or
// the whole mesh's one capsule (`one`) when neither chain is smaller: the one whose union holds
// the fewest points of a grid over all three. A bent link wants its slabs' own axes; a straight
// round one the chain's (a squat slab's smallest capsule lies across the link, sticking out of
// its sides, where capsules along the axis overlap their neighbours); a knob on a short link
// may want one capsule.
Chain ChainCapsules(const Points& q, const TriangleMesh& mesh, const Vector3d& chain_axis,
                    int count, const AxisCapsule& one) {
  std::vector<Chain> chains(3);  // along the axis, the slabs' own, the one capsule
  std::vector<Vector2d> projected;
  for (const Points& slab : SlabPoints(q, mesh, chain_axis, count)) {
    if (slab.empty()) continue;
    const Points shuffled_slab = ShuffledDistinct(slab);
    chains[0].push_back(CapsuleAlong(shuffled_slab, chain_axis, projected));
    chains[1].push_back(
        BestCapsule(shuffled_slab, {PrincipalAxes(VertexCovariance(shuffled_slab))}));
  }
  chains[2] = {one};
  const std::vector<int> inside = GridPointsInside(chains);
  return chains[std::min_element(inside.begin(), inside.end()) - inside.begin()];
}

// ---------------------------------------------------------------------------------------------
// Oriented box.

// A frame whose first axis is `axis`, the other two the principal axes of the points' projection
// on the plane normal to it.
Matrix3d FrameAround(const Points& q, const Vector3d& axis) {
  const Vector3d u = axis.normalized();
  const Vector3d a = u.unitOrthogonal();
  const Vector3d b = u.cross(a);
  Vector2d mean = Vector2d::Zero();
  for (const Vector3d& p : q) mean += Vector2d(p.dot(a), p.dot(b));
  mean /= static_cast<double>(q.size());
  Matrix2d covariance = Matrix2d::Zero();
  for (const Vector3d& p : q) {
    const Vector2d d = Vector2d(p.dot(a), p.dot(b)) - mean;
    covariance += d * d.transpose();
  }
  // The major axis of a 2x2 covariance is at half the angle of (cxx - cyy, 2 cxy).
  const double angle_rad =
      0.5 * std::atan2(2.0 * covariance(0, 1), covariance(0, 0) - covariance(1, 1));
  Matrix3d frame;
  frame.col(0) = u;
  frame.col(1) = std::cos(angle_rad) * a + std::sin(angle_rad) * b;
  frame.col(2) = u.cross(frame.col(1));
  return frame;
}

FrameBox BestBox(const Points& q, const std::vector<Matrix3d>& frames) {
  std::vector<Matrix3d> candidates = frames;
  candidates.push_back(Matrix3d::Identity());
  for (const Vector3d& axis : CandidateAxes(q, frames)) candidates.push_back(FrameAround(q, axis));
  FrameBox best;
  for (const Matrix3d& R_LB : candidates) {
    const FrameBox trial = BoxInFrame(q, R_LB);
    if (trial.volume_m3 < best.volume_m3) best = trial;
  }
  return CompassSearch(best, 6, [&](const FrameBox& from, int k, double step_rad) {
    const double angle_rad = k % 2 == 0 ? step_rad : -step_rad;
    const Eigen::AngleAxisd turn(angle_rad, from.R_LB.col(k / 2));
    return BoxInFrame(q, turn.toRotationMatrix() * from.R_LB);
  });
}

Box ToBox_L(const FrameBox& fit, const Vector3d& o_L, double margin_m) {
  Box box;
  box.X_WB.linear() = fit.R_LB;
  box.X_WB.translation() = o_L + fit.R_LB * (0.5 * (fit.lo + fit.hi));
  box.half_extents_m = (0.5 * (fit.hi - fit.lo)).array() + margin_m;
  return box;
}

double ShapeVolume_m3(const Shape& shape) {
  if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    return CapsuleVolume_m3(capsule->radius_m, (capsule->p1_W - capsule->p0_W).norm());
  }
  return 8.0 * std::get<Box>(shape).half_extents_m.prod();
}

// ---------------------------------------------------------------------------------------------
// Checks.

std::string VectorText(const Vector3d& v) {
  std::ostringstream text;
  text << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return text.str();
}

MeshCheck Refusal(MeshStatus status, const std::string& message) { return {status, message}; }

// Distance between the two planes, normal to the vertices' least principal axis, that hold
// them all: zero for coplanar, collinear and one-point meshes (up to rounding).
double Thickness_m(const Points& q) {
  const FrameBox box = BoxInFrame(q, PrincipalAxes(VertexCovariance(q)));
  return box.hi.z() - box.lo.z();
}

MeshCheck CheckOptions(const MeshFitOptions& options) {
  if (options.kind == MeshFitKind::kCapsuleChain &&
      (options.capsule_count < 1 || options.capsule_count > kMeshFitMaxCapsules)) {
    std::ostringstream text;
    text << "capsule_count " << options.capsule_count << " is outside [1, " << kMeshFitMaxCapsules
         << "]";
    return Refusal(MeshStatus::kBadOptions, text.str());
  }
  return {};
}

// The vertices' bounding-box centre and diagonal, and their largest |coordinate|.
struct MeshSize {
  Vector3d centre_L;
  double extent_m;
  double reach_m;
};

MeshSize SizeOf(const Points& vertices_L) {
  const FrameBox box = BoxInFrame(vertices_L, Matrix3d::Identity());
  return MeshSize{0.5 * (box.lo + box.hi), (box.hi - box.lo).norm(),
                  std::max(box.lo.cwiseAbs().maxCoeff(), box.hi.cwiseAbs().maxCoeff())};
}

// Vertices relative to the centre of their bounding box, and the fit's margin.
struct LocalMesh {
  Vector3d o_L;
  Points q;
  double margin_m;
};

LocalMesh ToLocal(const Points& vertices_L) {
  const MeshSize size = SizeOf(vertices_L);
  LocalMesh local;
  local.o_L = size.centre_L;
  local.q.reserve(vertices_L.size());
  for (const Vector3d& p : vertices_L) local.q.push_back(p - local.o_L);
  local.margin_m = kMeshFitMarginRel * (size.extent_m + size.reach_m);
  return local;
}

std::vector<Shape> FitShapes_L(const TriangleMesh& mesh, const MeshFitOptions& options) {
  const LocalMesh local = ToLocal(mesh.vertices_L);
  const Matrix3d surface_axes = PrincipalAxes(SurfaceCovariance(local.q, mesh));
  const Points shuffled_q = ShuffledDistinct(local.q);
  std::vector<Shape> shapes;
  AxisCapsule one;
  if (options.kind != MeshFitKind::kOrientedBox) {
    const Matrix3d vertex_axes = PrincipalAxes(VertexCovariance(shuffled_q));
    one = BestCapsule(shuffled_q, {surface_axes, vertex_axes});
  }
  if (options.kind == MeshFitKind::kCapsuleChain) {
    for (const AxisCapsule& fit : ChainCapsules(local.q, mesh, surface_axes.col(0),
                                                options.capsule_count, one)) {
      shapes.push_back(ToCapsule_L(fit, local.o_L, local.margin_m));
    }
    return shapes;
  }
  if (options.kind != MeshFitKind::kOrientedBox) {
    shapes.push_back(ToCapsule_L(one, local.o_L, local.margin_m));
  }
  if (options.kind != MeshFitKind::kOneCapsule) {
    const FrameBox fit = BestBox(shuffled_q, {surface_axes});
    shapes.push_back(ToBox_L(fit, local.o_L, local.margin_m));
  }
  // kTighter: of the capsule and the box (both hold every vertex), the smaller.
  if (shapes.size() == 2 && ShapeVolume_m3(shapes[1]) < ShapeVolume_m3(shapes[0])) {
    shapes.erase(shapes.begin());
  }
  shapes.resize(1);
  return shapes;
}

}  // namespace

const char* MeshStatusName(MeshStatus status) {
  switch (status) {
    case MeshStatus::kOk: return "ok";
    case MeshStatus::kEmpty: return "empty";
    case MeshStatus::kNonFiniteVertex: return "non-finite vertex";
    case MeshStatus::kIndexOutOfRange: return "index out of range";
    case MeshStatus::kTooLarge: return "too large";
    case MeshStatus::kNoVolume: return "no volume";
    case MeshStatus::kTooSmall: return "too small";
    case MeshStatus::kBadOptions: return "bad options";
  }
  return "unknown";
}

MeshCheck CheckMesh(const TriangleMesh& mesh) {
  const std::size_t n = mesh.vertices_L.size();
  if (n == 0 || mesh.triangles.empty()) {
    return Refusal(MeshStatus::kEmpty, "the mesh has " + std::to_string(n) + " vertices and " +
                                           std::to_string(mesh.triangles.size()) + " triangles");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!mesh.vertices_L[i].allFinite()) {
      return Refusal(MeshStatus::kNonFiniteVertex, "vertex " + std::to_string(i) +
                                                       " is not finite: " +
                                                       VectorText(mesh.vertices_L[i]));
    }
  }
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    for (const std::uint32_t index : mesh.triangles[k]) {
      if (index >= n) {
        return Refusal(MeshStatus::kIndexOutOfRange,
                       "triangle " + std::to_string(k) + " refers to vertex " +
                           std::to_string(index) + " but the mesh has " + std::to_string(n));
      }
    }
  }
  const MeshSize size = SizeOf(mesh.vertices_L);
  std::ostringstream text;
  if (size.extent_m > kMeshMaxExtent_m || size.reach_m > kMeshMaxCoordinate_m) {
    text << "the mesh spans " << size.extent_m << " m and reaches " << size.reach_m
         << " m from its link origin; expected at most " << kMeshMaxExtent_m << " m and "
         << kMeshMaxCoordinate_m << " m (wrong scale or units?)";
    return Refusal(MeshStatus::kTooLarge, text.str());
  }
  const double thickness_m = Thickness_m(ToLocal(mesh.vertices_L).q);
  if (thickness_m <= kMeshMinThicknessRel * size.extent_m) {
    text << "all vertices lie between two parallel planes " << thickness_m << " m apart (extent "
         << size.extent_m << " m, at least " << kMeshMinThicknessRel
         << " of it expected): flat, collinear or a single point";
    return Refusal(MeshStatus::kNoVolume, text.str());
  }
  if (size.extent_m < kMeshMinExtent_m) {
    text << "the mesh spans " << size.extent_m << " m, below " << kMeshMinExtent_m
         << " m (wrong scale or units?)";
    return Refusal(MeshStatus::kTooSmall, text.str());
  }
  return {};
}

MeshFit FitMesh(const TriangleMesh& mesh, const MeshFitOptions& options) {
  MeshFit fit;
  fit.check = CheckMesh(mesh);
  if (fit.check.status == MeshStatus::kOk) fit.check = CheckOptions(options);
  if (fit.check.status != MeshStatus::kOk) return fit;
  fit.shapes_L = FitShapes_L(mesh, options);
  for (const Shape& shape : fit.shapes_L) fit.fitted_volume_m3 += ShapeVolume_m3(shape);
  fit.is_mesh_closed = IsClosedMesh(mesh);
  fit.mesh_volume_m3 = fit.is_mesh_closed ? EnclosedVolume_m3(mesh)
                                          : std::numeric_limits<double>::quiet_NaN();
  fit.excess_ratio = fit.fitted_volume_m3 / fit.mesh_volume_m3;
  return fit;
}

}  // namespace arm_collision_monitor
