// Narrow phase: exact distances between capsules and oriented boxes.
//
// Error model used by every bound below: eps = 2^-53 is the unit roundoff; S is the local length
// scale of a query (see kSegmentDistanceErrorUlps in core/constants.h). All differences are
// taken between nearby points before anything is scaled, so the distance error depends on S, not
// on how far the shapes are from the origin; the witness points, being absolute coordinates,
// additionally carry the unavoidable rounding eps * |coordinate|.
#include "arm_collision_monitor/geometry/distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Vector3d;

inline double Clamp01(double x) { return std::min(1.0, std::max(0.0, x)); }

// The closest pair of two segments, relative to q0: P - q0 and Q - q0 (both small when the
// segments are near each other, whatever the absolute coordinates).
struct LocalSegmentPair {
  double s = 0.0;
  double t = 0.0;
  Vector3d p_rel;  // P - q0
  Vector3d q_rel;  // Q - q0
};

// Closest points of segments p0 + s d1 and q0 + t d2, given r = p0 - q0 and r1 = p1 - q0.
// Follows Ericson, Real-Time Collision Detection (2005) §5.1.9, with length-relative degeneracy
// tests and the numerator and denominator of s written as n.(d2 x r) and |n|^2, n = d1 x d2
// (Lagrange's identity), instead of b f - c e and a e - b^2. For nearly parallel segments
// a e - b^2 cancels catastrophically (the stress suite measured 5e-8 m errors with it), whereas
// the rounding of n is, up to a part along d2 that only shrinks s, the exact cross product of a
// direction d1' with |d1' - d1| ~ eps |d1|: s is then exact for a segment within rounding of the
// given one. t is then the projection of the chosen point, and s is recomputed from a clamped t,
// so every step can only lower the distance. Error of |Q - P|: <= kSegmentDistanceErrorUlps *
// eps * S, S = max(|r|, |d1|, |d2|) (+ kDistanceErrorFloor_m); pinned by the stress suite.
inline LocalSegmentPair ClosestLocal(const Vector3d& d1, const Vector3d& d2, const Vector3d& r,
                                     const Vector3d& r1) {
  LocalSegmentPair out;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double deg2 = kSegmentDegenerateLengthRel * kSegmentDegenerateLengthRel;
  const bool is_point1 = a <= deg2 * e || a < kSegmentMinSquaredLength_m2;
  const bool is_point2 = e <= deg2 * a || e < kSegmentMinSquaredLength_m2;
  double s = 0.0;
  double t = 0.0;
  if (is_point1 && is_point2) {
    // Both points: s = t = 0.
  } else if (is_point1) {
    t = Clamp01(d2.dot(r) / e);
  } else if (is_point2) {
    s = Clamp01(-d1.dot(r) / a);
  } else if (!(a * e >= kSegmentRescaleBelow_m4)) {
    // Tiny segments: |d1 x d2|^2 (four lengths) would underflow. The problem is homogeneous, so
    // solve it scaled by the power of two that brings the longer direction to ~1 m (exact). The
    // scaled product a e is then >= ~1e-31 (neither is a point), so this recurses only once.
    // Segments shorter than 1e-150 |r| act as their start points (error <= their lengths).
    int exponent = 0;
    std::frexp(std::max(d1.cwiseAbs().maxCoeff(), d2.cwiseAbs().maxCoeff()), &exponent);
    if (std::max(r.cwiseAbs().maxCoeff(), r1.cwiseAbs().maxCoeff()) >
        std::ldexp(kSegmentRescaleMaxRatio, exponent)) {
      out.p_rel = r;
      out.q_rel = Vector3d::Zero();
      return out;
    }
    const double down = std::ldexp(1.0, -exponent);
    out = ClosestLocal(down * d1, down * d2, down * r, down * r1);
    const double up = std::ldexp(1.0, exponent);
    out.p_rel *= up;
    out.q_rel *= up;
    return out;
  } else {
    const Vector3d n = d1.cross(d2);
    const double denom = n.squaredNorm();
    if (denom > kSegmentParallelSinSquared * (a * e)) {
      s = Clamp01(n.dot(d2.cross(r)) / denom);
    }
    // t from the point actually chosen on segment 1 (its exact projection), then s again from
    // the clamped t: each step can only lower the distance, so an inexact s costs little.
    const Vector3d p_rel = s <= 0.5 ? Vector3d(r + s * d1) : Vector3d(r1 - (1.0 - s) * d1);
    t = d2.dot(p_rel) / e;
    if (t < 0.0) {
      t = 0.0;
      s = Clamp01(-d1.dot(r) / a);
    } else if (t > 1.0) {
      t = 1.0;
      s = Clamp01(d1.dot(d2 - r) / a);
    }
  }
  out.s = s;
  out.t = t;
  out.p_rel = s <= 0.5 ? Vector3d(r + s * d1) : Vector3d(r1 - (1.0 - s) * d1);
  out.q_rel = t * d2;
  return out;
}

// Closest pair between a segment and the axis-aligned box [-h, h], both in the box frame.
struct SegmentBoxPair {
  double distance_sq = 0.0;  // m^2
  Vector3d p_seg;            // on the segment
  Vector3d p_box;            // on the box (inside when they meet: then p_box = p_seg)
};

// Half the derivative of f(u) = |x - clamp(x, -h, h)|^2 at x = a0 + u d: the part of x outside
// the box, projected on d. Nondecreasing in u because f is convex.
inline double HalfSlope(const Vector3d& a0, const Vector3d& d, const Vector3d& h, double u) {
  const Vector3d x = a0 + u * d;
  return (x - x.cwiseMax(-h).cwiseMin(h)).dot(d);
}

// Exact segment-box closest pair by minimising f(u) = dist^2(a0 + u d, box) over u in [0, 1].
// f is the sum over the axes of the squared excess of one coordinate beyond [-h_i, h_i]: convex,
// continuously differentiable and quadratic between the <= 6 parameters where the segment crosses
// a slab plane. So its minimiser is an endpoint, or the root of the (linear) derivative on the
// one piece where the derivative changes sign: found by walking the sorted crossings, then
// solved in closed form. It finds the same minimum as enumerating the two endpoint-box distances
// and the segment against the 12 box edges (the stress suite's oracle does that), ~10x faster.
// That enumeration is exact as well: at a closest pair the box point is on a vertex or an edge
// (both on the 12 edges) or inside a face, and then the segment point is an endpoint or the
// segment is parallel to the face, so sliding along it keeps the distance until an endpoint or a
// face edge is reached. The search here needs no such case analysis. The returned pair
// is evaluated at the computed u, so the distance is that of true points of the segment (within
// a few eps * S) to the box: error <= kBoxDistanceErrorUlps * eps * S, S = max(|a0|, |d|, |h|).
SegmentBoxPair SegmentBoxClosest(const Vector3d& a0, const Vector3d& a1, const Vector3d& h) {
  const Vector3d d = a1 - a0;
  double u;
  if (HalfSlope(a0, d, h, 0.0) >= 0.0) {
    u = 0.0;
  } else if (HalfSlope(a0, d, h, 1.0) <= 0.0) {
    u = 1.0;
  } else {
    // The slope goes from < 0 to > 0 inside (0, 1), so d != 0 there.
    double crossings[6];
    int n = 0;
    for (int i = 0; i < 3; ++i) {
      if (d[i] == 0.0) continue;
      for (const double plane : {-h[i], h[i]}) {
        const double c = (plane - a0[i]) / d[i];
        if (c > 0.0 && c < 1.0) crossings[n++] = c;
      }
    }
    for (int k = 1; k < n; ++k) {  // insertion sort: n <= 6
      for (int j = k; j > 0 && crossings[j] < crossings[j - 1]; --j) {
        std::swap(crossings[j], crossings[j - 1]);
      }
    }
    double lo = 0.0;
    double hi = 1.0;
    for (int k = 0; k < n; ++k) {
      if (HalfSlope(a0, d, h, crossings[k]) >= 0.0) {
        hi = crossings[k];
        break;
      }
      lo = crossings[k];
    }
    // On (lo, hi) the axes outside the box are fixed: slope = num + u * den.
    const Vector3d x_mid = a0 + (0.5 * (lo + hi)) * d;
    double num = 0.0;
    double den = 0.0;
    for (int i = 0; i < 3; ++i) {
      if (x_mid[i] > h[i]) {
        num += d[i] * (a0[i] - h[i]);
        den += d[i] * d[i];
      } else if (x_mid[i] < -h[i]) {
        num += d[i] * (a0[i] + h[i]);
        den += d[i] * d[i];
      }
    }
    // den = 0: the segment runs inside the box on this piece (f = 0 there); take its middle,
    // which rounding cannot push out of the box.
    u = den > 0.0 ? std::min(hi, std::max(lo, -num / den)) : 0.5 * (lo + hi);
  }
  SegmentBoxPair out;
  // From the nearer endpoint, so u = 0 and u = 1 give the endpoints exactly.
  out.p_seg = u <= 0.5 ? Vector3d(a0 + u * d) : Vector3d(a1 - (1.0 - u) * d);
  out.p_box = out.p_seg.cwiseMax(-h).cwiseMin(h);
  out.distance_sq = (out.p_seg - out.p_box).squaredNorm();
  return out;
}

// Squared distance between the axis-aligned bounds of segment e0-e1 and the box [-h, h]: a
// lower bound of the segment-box squared distance, used to skip edges that cannot win.
inline double SegmentBoxLowerBoundSq(const Vector3d& e0, const Vector3d& e1, const Vector3d& h) {
  const Vector3d below = (-h - e0.cwiseMax(e1)).cwiseMax(0.0);
  const Vector3d above = (e0.cwiseMin(e1) - h).cwiseMax(0.0);
  return (below + above).squaredNorm();
}

// The 8 vertices of `box` in frame F (X_FB given), in Box::Vertex_B's order: the centre plus or
// minus each of the box's axes scaled by its half extent, by halves (2, then 4, then 8 sums).
std::array<Vector3d, 8> BoxVertices(const Eigen::Matrix3d& R_FB, const Vector3d& p_FB,
                                    const Box& box) {
  const Eigen::Matrix3d half_axes = R_FB * box.half_extents_m.asDiagonal();
  std::array<Vector3d, 8> v;
  v[0] = p_FB - half_axes.col(2);
  v[4] = p_FB + half_axes.col(2);
  for (const int k : {0, 4}) {
    v[k + 2] = v[k] + half_axes.col(1);
    v[k] -= half_axes.col(1);
  }
  for (const int k : {0, 2, 4, 6}) {
    v[k + 1] = v[k] + half_axes.col(0);
    v[k] -= half_axes.col(0);
  }
  return v;
}

// The 12 edges of a box as vertex index pairs (differ in exactly one bit).
constexpr std::array<std::array<int, 2>, 12> kBoxEdges = {{{0, 1}, {2, 3}, {4, 5}, {6, 7},
                                                           {0, 2}, {1, 3}, {4, 6}, {5, 7},
                                                           {0, 4}, {1, 5}, {2, 6}, {3, 7}}};

// The closest pair found so far between two boxes, in the frame of one of them.
struct BoxBoxSearch {
  double best_sq = std::numeric_limits<double>::infinity();
  bool in_frame_of_a = true;  // which frame the two points below are in
  bool edge_of_b = true;      // true: p_edge is on B (and p_box on A); false: the reverse
  Vector3d p_edge = Vector3d::Zero();
  Vector3d p_box = Vector3d::Zero();
};

// Per face of a box (bit 2k + 1: face +k, bit 2k: face -k, in its frame) whether the other box,
// of centre c and half extents h_other rotated by R (its frame to this one's), reaches up to the
// face's plane or beyond it, up to `margin` for rounding. At a closest pair the direction from
// this box's point to the other's lies in the normal cone there, so it has no negative component
// along the normal of a face through the point: an edge of this box can hold the point only
// when the other box reaches both its faces' planes (in an overlap too: a common point on the
// edge lies on both planes).
unsigned FacesReached(const Eigen::Matrix3d& R, const Vector3d& c, const Vector3d& h_other,
                      const Vector3d& h, double margin) {
  const Vector3d reach = R.cwiseAbs() * h_other;
  unsigned faces = 0;
  for (int k = 0; k < 3; ++k) {
    // Written so that NaN counts as reached.
    if (!(c[k] - reach[k] > -h[k] + margin)) faces |= 1u << (2 * k);
    if (!(c[k] + reach[k] < h[k] - margin)) faces |= 1u << (2 * k + 1);
  }
  return faces;
}

// Per set of faces reached (FacesReached), the edges (bit e: kBoxEdges[e]) both of whose faces
// are in it: an edge's faces are those of the two axes its vertices share, on their bits' side.
constexpr std::array<std::uint16_t, 64> EdgesOfFacesTable() {
  std::array<std::uint16_t, 64> table{};
  for (unsigned faces = 0; faces < 64; ++faces) {
    for (int e = 0; e < 12; ++e) {
      const int v = kBoxEdges[e][0];
      const int along = e / 4;  // kBoxEdges runs along x, then y, then z
      unsigned needed = 0;
      for (int k = 0; k < 3; ++k) {
        if (k != along) needed |= 1u << (2 * k + ((v >> k) & 1));
      }
      if ((faces & needed) == needed) table[faces] |= static_cast<std::uint16_t>(1u << e);
    }
  }
  return table;
}
constexpr std::array<std::uint16_t, 64> kEdgesOfFaces = EdgesOfFacesTable();

// Minimum over the edges of each box against the other box (segment-box, exact). Every closest
// pair is covered: if either point is on an edge or a vertex, that edge is tried; if both are
// inside faces, the faces are parallel and sliding along them keeps the distance until one
// point reaches an edge. If the boxes meet, an extreme point of their intersection lies on an
// edge of one inside the other, so that edge scores 0. Edges of faces the other box does not
// reach (kEdgesOfFaces) cannot hold a closest point, and edges whose bounds are already
// farther than `stop_sq` or the best so far are skipped; the search ends once best_sq < stop_sq
// (use stop_sq = 0 for the exact minimum: it then ends at the first contact).
// Error <= kBoxDistanceErrorUlps * eps * S, S = max(|c_A - c_B|, box diagonals).
BoxBoxSearch SearchBoxBox(const Box& a, const Box& b, double stop_sq) {
  // Relative poses from the difference of the centres, so far-away pairs keep local accuracy.
  const Eigen::Matrix3d& R_WA = a.X_WB.linear();
  const Eigen::Matrix3d& R_WB = b.X_WB.linear();
  const Vector3d p_AB_W = b.X_WB.translation() - a.X_WB.translation();
  const Eigen::Matrix3d R_AB = R_WA.transpose() * R_WB;
  const Vector3d p_AB_A = R_WA.transpose() * p_AB_W;
  const Vector3d p_BA_B = -(R_WB.transpose() * p_AB_W);
  // A few roundings of the centres' difference and of the extents, with room to spare.
  const double margin = kBoxDistanceErrorUlps * std::numeric_limits<double>::epsilon() *
                        (p_AB_W.cwiseAbs().sum() + a.half_extents_m.sum() +
                         b.half_extents_m.sum());
  const unsigned edges_of_b_kept = kEdgesOfFaces[FacesReached(
      R_AB.transpose(), p_BA_B, a.half_extents_m, b.half_extents_m, margin)];
  const unsigned edges_of_a_kept = kEdgesOfFaces[FacesReached(
      R_AB, p_AB_A, b.half_extents_m, a.half_extents_m, margin)];
  const std::array<Vector3d, 8> vb_A = BoxVertices(R_AB, p_AB_A, b);
  const std::array<Vector3d, 8> va_B = BoxVertices(R_AB.transpose(), p_BA_B, a);
  BoxBoxSearch search;
  for (const bool edges_of_b : {true, false}) {
    const std::array<Vector3d, 8>& v = edges_of_b ? vb_A : va_B;
    const Vector3d& h = edges_of_b ? a.half_extents_m : b.half_extents_m;
    for (unsigned kept = edges_of_b ? edges_of_b_kept : edges_of_a_kept; kept != 0;
         kept &= kept - 1) {
      const std::array<int, 2>& edge = kBoxEdges[__builtin_ctz(kept)];
      const Vector3d& e0 = v[edge[0]];
      const Vector3d& e1 = v[edge[1]];
      const double limit_sq = stop_sq > 0.0 ? std::min(search.best_sq, stop_sq) : search.best_sq;
      if (SegmentBoxLowerBoundSq(e0, e1, h) >= limit_sq) continue;
      const SegmentBoxPair sb = SegmentBoxClosest(e0, e1, h);
      if (sb.distance_sq < search.best_sq) {
        search.best_sq = sb.distance_sq;
        search.in_frame_of_a = edges_of_b;
        search.edge_of_b = edges_of_b;
        search.p_edge = sb.p_seg;
        search.p_box = sb.p_box;
        if (search.best_sq < stop_sq || search.best_sq == 0.0) return search;
      }
    }
  }
  return search;
}

// X_WB^-1 * p_W for a rigid pose, differencing first so far-away poses lose nothing.
inline Vector3d ToFrame(const Eigen::Isometry3d& X_WB, const Vector3d& p_W) {
  return X_WB.linear().transpose() * (p_W - X_WB.translation());
}

// The capsule's axis against the box, in the box frame.
inline SegmentBoxPair AxisBoxClosest(const Capsule& c, const Box& b) {
  return SegmentBoxClosest(ToFrame(b.X_WB, c.p0_W), ToFrame(b.X_WB, c.p1_W), b.half_extents_m);
}
inline bool IsFinite(const Shape& shape) {
  if (const auto* c = std::get_if<Capsule>(&shape)) {
    return c->p0_W.allFinite() && c->p1_W.allFinite() && std::isfinite(c->radius_m);
  }
  const Box& b = std::get<Box>(shape);
  return b.X_WB.linear().allFinite() && b.X_WB.translation().allFinite() &&
         b.half_extents_m.allFinite();
}
inline const Capsule& ChooseCapsule(const Capsule& c, const Box&) { return c; }
inline const Capsule& ChooseCapsule(const Box&, const Capsule& c) { return c; }
inline const Box& ChooseBox(const Capsule&, const Box& b) { return b; }
inline const Box& ChooseBox(const Box& b, const Capsule&) { return b; }

}  // namespace

SegmentClosestPoints SegmentSegmentClosestPoints(const Vector3d& p0_W, const Vector3d& p1_W,
                                                 const Vector3d& q0_W, const Vector3d& q1_W) {
  const LocalSegmentPair pair = ClosestLocal(p1_W - p0_W, q1_W - q0_W, p0_W - q0_W, p1_W - q0_W);
  SegmentClosestPoints out;
  out.s = pair.s;
  out.t = pair.t;
  out.p_W = q0_W + pair.p_rel;
  out.q_W = q0_W + pair.q_rel;
  out.distance_m = (pair.q_rel - pair.p_rel).norm();
  return out;
}

// Capsules are their axes' closest pair, pushed out by the radii along the pair's direction.
// Error: that of SegmentSegmentClosestPoints plus a few eps * (radii).
DistanceResult CapsuleCapsuleDistance(const Capsule& a, const Capsule& b) {
  const Vector3d& q0 = b.p0_W;
  const LocalSegmentPair pair =
      ClosestLocal(a.p1_W - a.p0_W, b.p1_W - q0, a.p0_W - q0, a.p1_W - q0);
  const Vector3d w = pair.q_rel - pair.p_rel;  // from A's axis point to B's
  const double axis_distance = w.norm();
  const double gap = axis_distance - a.radius_m - b.radius_m;
  DistanceResult out;
  if (gap > 0.0) {
    // gap > 0 implies axis_distance > 0, so the unit direction is finite.
    const Vector3d u = w / axis_distance;
    out.distance_m = gap;
    out.p_WA = q0 + (pair.p_rel + a.radius_m * u);
    out.p_WB = q0 + (pair.q_rel - b.radius_m * u);
  } else {
    // Overlap: a common point on the axis pair's segment, centred in the shared stretch
    // [axis_distance - rb, ra] (no normal needed, so crossing axes give no NaN).
    const double along = std::min(
        axis_distance, std::max(0.0, 0.5 * (a.radius_m + axis_distance - b.radius_m)));
    const Vector3d x_rel = axis_distance > 0.0
                               ? Vector3d(pair.p_rel + (along / axis_distance) * w)
                               : pair.p_rel;
    out.distance_m = 0.0;
    out.p_WA = q0 + x_rel;
    out.p_WB = out.p_WA;
  }
  return out;
}

// Works in the box frame (see SegmentBoxClosest). Error <= kBoxDistanceErrorUlps * eps * S,
// S = max(|p0 - c|, segment length, box diagonal, radius).
DistanceResult CapsuleBoxDistance(const Capsule& a, const Box& b) {
  const SegmentBoxPair sb = AxisBoxClosest(a, b);
  const double axis_distance = std::sqrt(sb.distance_sq);
  DistanceResult out;
  const Eigen::Isometry3d& X_WB = b.X_WB;
  if (axis_distance > a.radius_m) {
    // axis_distance > radius >= 0, so the unit direction is finite.
    const Vector3d u_B = (sb.p_box - sb.p_seg) / axis_distance;
    out.distance_m = axis_distance - a.radius_m;
    out.p_WA = X_WB * (sb.p_seg + a.radius_m * u_B);
    out.p_WB = X_WB * sb.p_box;
  } else {
    // Overlap: the box point is within the radius of the axis, so it is common to both.
    out.distance_m = 0.0;
    out.p_WA = X_WB * sb.p_box;
    out.p_WB = out.p_WA;
  }
  return out;
}

// Exact box-box distance (see SearchBoxBox). Error <= kBoxDistanceErrorUlps * eps * S.
DistanceResult BoxBoxDistance(const Box& a, const Box& b) {
  const BoxBoxSearch search = SearchBoxBox(a, b, 0.0);
  const Eigen::Isometry3d& X_WF = search.in_frame_of_a ? a.X_WB : b.X_WB;
  const Vector3d p_edge_W = X_WF * search.p_edge;
  DistanceResult out;
  if (search.best_sq == 0.0) {
    // The edge point lies in the other box: common to both.
    out.distance_m = 0.0;
    out.p_WA = p_edge_W;
    out.p_WB = p_edge_W;
    return out;
  }
  const Vector3d p_box_W = X_WF * search.p_box;
  out.distance_m = std::sqrt(search.best_sq);
  out.p_WA = search.edge_of_b ? p_box_W : p_edge_W;
  out.p_WB = search.edge_of_b ? p_edge_W : p_box_W;
  return out;
}

namespace {
DistanceResult Swapped(DistanceResult r) {
  std::swap(r.p_WA, r.p_WB);
  return r;
}
}  // namespace

DistanceResult ShapeDistance(const Shape& a, const Shape& b) {
  return std::visit(
      [](const auto& sa, const auto& sb) -> DistanceResult {
        using A = std::decay_t<decltype(sa)>;
        using B = std::decay_t<decltype(sb)>;
        if constexpr (std::is_same_v<A, Capsule> && std::is_same_v<B, Capsule>) {
          return CapsuleCapsuleDistance(sa, sb);
        } else if constexpr (std::is_same_v<A, Capsule> && std::is_same_v<B, Box>) {
          return CapsuleBoxDistance(sa, sb);
        } else if constexpr (std::is_same_v<A, Box> && std::is_same_v<B, Capsule>) {
          return Swapped(CapsuleBoxDistance(sb, sa));
        } else {
          return BoxBoxDistance(sa, sb);
        }
      },
      a, b);
}

// After the AABB test, the cheapest exact test per pair compares squared axis distances with
// the squared (threshold + radii), skipping square roots and witnesses; box-box stops at the
// first edge closer than the threshold. Agrees with ShapeDistance up to its error bound.
bool IsCloserThan(const Shape& a, const Shape& b, double threshold_m) {
  if (threshold_m <= 0.0) return false;  // distances are >= 0
  // A NaN or infinity anywhere answers "closer", so that the caller fails safe.
  if (!(std::isfinite(threshold_m) && IsFinite(a) && IsFinite(b))) return true;
  if (!ComputeAabb(a).Inflated(threshold_m).Overlaps(ComputeAabb(b))) return false;
  return std::visit(
      [threshold_m](const auto& sa, const auto& sb) -> bool {
        using A = std::decay_t<decltype(sa)>;
        using B = std::decay_t<decltype(sb)>;
        if constexpr (std::is_same_v<A, Capsule> && std::is_same_v<B, Capsule>) {
          const Vector3d& q0 = sb.p0_W;
          const LocalSegmentPair pair =
              ClosestLocal(sa.p1_W - sa.p0_W, sb.p1_W - q0, sa.p0_W - q0, sa.p1_W - q0);
          const double reach = threshold_m + sa.radius_m + sb.radius_m;
          return (pair.q_rel - pair.p_rel).squaredNorm() < reach * reach;
        } else if constexpr (std::is_same_v<A, Box> && std::is_same_v<B, Box>) {
          return SearchBoxBox(sa, sb, threshold_m * threshold_m).best_sq <
                 threshold_m * threshold_m;
        } else {
          const Capsule& c = ChooseCapsule(sa, sb);
          const double reach = threshold_m + c.radius_m;
          return AxisBoxClosest(c, ChooseBox(sa, sb)).distance_sq < reach * reach;
        }
      },
      a, b);
}

}  // namespace arm_collision_monitor
