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
#include <limits>
#include <type_traits>

#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Vector3d;

// a*b - c*d with a relative error of a few eps even under heavy cancellation (an error-free
// product, Dekker 1971 / Kahan's fma form). Used only for nearly parallel directions.
inline double DiffOfProducts(double a, double b, double c, double d) {
#if defined(__FMA__)
  const double w = c * d;
  const double err_w = std::fma(-c, d, w);
  const double f = std::fma(a, b, -w);
  return f + err_w;
#else
  // Veltkamp splitting: hi parts have <= 26 significant bits, so hi*hi products are exact. The
  // build has no FMA contraction without __FMA__, so these expressions are evaluated as written.
  const auto split = [](double x, double& hi, double& lo) {
    const double c = 134217729.0 * x;  // 2^27 + 1
    hi = c - (c - x);
    lo = x - hi;
  };
  const auto two_product = [&split](double x, double y, double& p, double& e) {
    p = x * y;
    double xh, xl, yh, yl;
    split(x, xh, xl);
    split(y, yh, yl);
    e = ((xh * yh - p) + xh * yl + xl * yh) + xl * yl;
  };
  double p1, e1, p2, e2;
  two_product(a, b, p1, e1);
  two_product(c, d, p2, e2);
  return (p1 - p2) + (e1 - e2);
#endif
}

inline Vector3d AccurateCross(const Vector3d& u, const Vector3d& v) {
  return Vector3d(DiffOfProducts(u.y(), v.z(), u.z(), v.y()),
                  DiffOfProducts(u.z(), v.x(), u.x(), v.z()),
                  DiffOfProducts(u.x(), v.y(), u.y(), v.x()));
}

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
// Follows Ericson, Real-Time Collision Detection (2005) §5.1.9, with the numerator and
// denominator of s written as (d1 x d2).(d2 x r) and |d1 x d2|^2 (Lagrange's identity), the
// cross product made error-free when the segments are nearly parallel, and length-relative
// degeneracy tests. The returned pair is a closest pair of segments whose endpoints lie within a
// few eps * S of the given ones, so the distance |Q - P| errs by at most
// kSegmentDistanceErrorUlps * eps * S (S = max(|r|, |d1|, |d2|)); pinned by the stress suite.
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
  } else {
    Vector3d n = d1.cross(d2);
    double denom = n.squaredNorm();
    const double ae = a * e;
    if (denom < kSegmentNearParallelSinSquared * ae) {
      n = AccurateCross(d1, d2);
      denom = n.squaredNorm();
    }
    if (denom > kSegmentParallelSinSquared * ae) {
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

// Closest pair between a segment and an axis-aligned box [-h, h] (both in the box frame B).
struct SegmentBoxResult {
  double distance_m = 0.0;
  Vector3d p_seg_B;  // on the segment
  Vector3d p_box_B;  // on the box surface (or inside, when they intersect)
};

// Clips the segment a0 + u (a1 - a0), u in [0, 1], to the closed box [-h, h] (slab method, Kay &
// Kajiya 1986). Returns true and the clipped interval when they share a point.
inline bool ClipSegmentToBox(const Vector3d& a0, const Vector3d& a1, const Vector3d& h,
                             double& u_in, double& u_out) {
  const Vector3d d = a1 - a0;
  u_in = 0.0;
  u_out = 1.0;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (a0[i] < -h[i] || a0[i] > h[i]) return false;
      continue;
    }
    double u0 = (-h[i] - a0[i]) / d[i];
    double u1 = (h[i] - a0[i]) / d[i];
    if (u0 > u1) std::swap(u0, u1);
    u_in = std::max(u_in, u0);
    u_out = std::min(u_out, u1);
    if (u_in > u_out) return false;
  }
  return true;
}

// Exact segment-box distance in the box frame. If the segment meets the box the distance is 0
// and both witnesses are the midpoint of the clipped part. Otherwise the minimum over the two
// endpoint-box distances (clamping) and the segment against the 12 box edges is exact: at a
// closest pair the box point lies on a vertex, an edge or inside a face; a vertex lies on an
// edge, and inside a face the segment direction is parallel to the face (else the segment point
// could move closer), so sliding along the segment keeps the distance until the segment reaches
// an endpoint or its foot reaches a face edge. Error <= kBoxDistanceErrorUlps * eps * S.
SegmentBoxResult SegmentBoxLocal(const Vector3d& a0, const Vector3d& a1, const Vector3d& h) {
  SegmentBoxResult best;
  double u_in, u_out;
  if (ClipSegmentToBox(a0, a1, h, u_in, u_out)) {
    const double u = 0.5 * (u_in + u_out);
    best.p_seg_B = a0 + u * (a1 - a0);
    best.p_box_B = best.p_seg_B.cwiseMax(-h).cwiseMin(h);
    best.p_seg_B = best.p_box_B;
    best.distance_m = 0.0;
    return best;
  }
  double best_sq = std::numeric_limits<double>::infinity();
  for (const Vector3d* a : {&a0, &a1}) {
    const Vector3d c = a->cwiseMax(-h).cwiseMin(h);
    const double dsq = (*a - c).squaredNorm();
    if (dsq < best_sq) {
      best_sq = dsq;
      best.p_seg_B = *a;
      best.p_box_B = c;
    }
  }
  const Vector3d d = a1 - a0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3;
    const int j = (k + 2) % 3;
    for (int corner = 0; corner < 4; ++corner) {
      Vector3d e0;
      e0[i] = (corner & 1) ? h[i] : -h[i];
      e0[j] = (corner & 2) ? h[j] : -h[j];
      e0[k] = -h[k];
      Vector3d e1 = e0;
      e1[k] = h[k];
      const LocalSegmentPair pair = ClosestLocal(d, e1 - e0, a0 - e0, a1 - e0);
      const double dsq = (pair.q_rel - pair.p_rel).squaredNorm();
      if (dsq < best_sq) {
        best_sq = dsq;
        best.p_seg_B = e0 + pair.p_rel;
        best.p_box_B = e0 + pair.q_rel;
      }
    }
  }
  best.distance_m = std::sqrt(best_sq);
  return best;
}

// The 8 vertices of box `b` expressed in frame F, given X_FB; vertex v has coordinate i at
// +h_i when bit i of v is set.
std::array<Vector3d, 8> BoxVertices(const Eigen::Isometry3d& X_FB, const Vector3d& h) {
  std::array<Vector3d, 8> v;
  for (int k = 0; k < 8; ++k) {
    const Vector3d c((k & 1) ? h.x() : -h.x(), (k & 2) ? h.y() : -h.y(),
                     (k & 4) ? h.z() : -h.z());
    v[k] = X_FB.translation() + X_FB.linear() * c;
  }
  return v;
}

// The 12 edges of a box as vertex index pairs (differ in exactly one bit).
constexpr std::array<std::array<int, 2>, 12> kBoxEdges = {{{0, 1}, {2, 3}, {4, 5}, {6, 7},
                                                           {0, 2}, {1, 3}, {4, 6}, {5, 7},
                                                           {0, 4}, {1, 5}, {2, 6}, {3, 7}}};

// X_WB^-1 * p_W for a rigid pose, differencing first so far-away poses lose nothing.
inline Vector3d ToFrame(const Eigen::Isometry3d& X_WB, const Vector3d& p_W) {
  return X_WB.linear().transpose() * (p_W - X_WB.translation());
}

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

// Works in the box frame (see SegmentBoxLocal). Error <= kBoxDistanceErrorUlps * eps * S.
DistanceResult CapsuleBoxDistance(const Capsule& a, const Box& b) {
  const Vector3d a0_B = ToFrame(b.X_WB, a.p0_W);
  const Vector3d a1_B = ToFrame(b.X_WB, a.p1_W);
  const SegmentBoxResult sb = SegmentBoxLocal(a0_B, a1_B, b.half_extents_m);
  DistanceResult out;
  const Eigen::Isometry3d& X = b.X_WB;
  if (sb.distance_m > a.radius_m) {
    const Vector3d u = (sb.p_box_B - sb.p_seg_B) / sb.distance_m;
    out.distance_m = sb.distance_m - a.radius_m;
    out.p_WA = X * (sb.p_seg_B + a.radius_m * u);
    out.p_WB = X * sb.p_box_B;
  } else {
    // Overlap: the box point is within the radius of the axis, so it is common to both.
    out.distance_m = 0.0;
    out.p_WA = X * sb.p_box_B;
    out.p_WB = out.p_WA;
  }
  return out;
}

// Exact box-box distance: the edges of B against box A (segment-box, exact as above) and the
// vertices of A against box B, plus a clip of A's edges against B to catch every overlap. This
// covers every closest pair: if B's point is on a vertex or edge, a B edge sees it; if it is
// inside a face of B, A's point is a vertex of A, or an A edge or face parallel to that face
// slides to an A vertex or to a B face edge. Two overlapping convex boxes always have an edge of
// one meeting the other (an extreme point of the intersection lies on such an edge), which the
// clipping finds. Error <= kBoxDistanceErrorUlps * eps * S.
DistanceResult BoxBoxDistance(const Box& a, const Box& b) {
  // Relative poses from the difference of the centres, so far-away pairs keep local accuracy.
  const Eigen::Matrix3d& R_WA = a.X_WB.linear();
  const Eigen::Matrix3d& R_WB = b.X_WB.linear();
  const Vector3d p_AB_W = b.X_WB.translation() - a.X_WB.translation();
  Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
  X_AB.linear() = R_WA.transpose() * R_WB;
  X_AB.translation() = R_WA.transpose() * p_AB_W;
  Eigen::Isometry3d X_BA = Eigen::Isometry3d::Identity();
  X_BA.linear() = R_WB.transpose() * R_WA;
  X_BA.translation() = -(R_WB.transpose() * p_AB_W);
  const std::array<Vector3d, 8> vb_A = BoxVertices(X_AB, b.half_extents_m);
  const std::array<Vector3d, 8> va_B = BoxVertices(X_BA, a.half_extents_m);
  const Vector3d& ha = a.half_extents_m;
  const Vector3d& hb = b.half_extents_m;
  DistanceResult out;

  // Overlap: an edge of A meeting B (in B's frame).
  for (const auto& edge : kBoxEdges) {
    double u_in, u_out;
    const Vector3d& e0 = va_B[edge[0]];
    const Vector3d& e1 = va_B[edge[1]];
    if (ClipSegmentToBox(e0, e1, hb, u_in, u_out)) {
      const Vector3d x_B = (e0 + 0.5 * (u_in + u_out) * (e1 - e0)).cwiseMax(-hb).cwiseMin(hb);
      out.distance_m = 0.0;
      out.p_WA = b.X_WB * x_B;
      out.p_WB = out.p_WA;
      return out;
    }
  }
  // Edges of B against box A (in A's frame): finds the other overlaps and the edge contacts.
  double best = std::numeric_limits<double>::infinity();
  Vector3d best_a_A = Vector3d::Zero();
  Vector3d best_b_A = Vector3d::Zero();
  for (const auto& edge : kBoxEdges) {
    const SegmentBoxResult sb = SegmentBoxLocal(vb_A[edge[0]], vb_A[edge[1]], ha);
    if (sb.distance_m < best) {
      best = sb.distance_m;
      best_a_A = sb.p_box_B;
      best_b_A = sb.p_seg_B;
      if (best == 0.0) break;
    }
  }
  if (best == 0.0) {
    out.distance_m = 0.0;
    out.p_WA = a.X_WB * best_a_A;
    out.p_WB = out.p_WA;
    return out;
  }
  // Vertices of A against box B (in B's frame).
  bool vertex_of_a_wins = false;
  Vector3d best_a_B = Vector3d::Zero();
  Vector3d best_b_B = Vector3d::Zero();
  double best_sq = best * best;
  for (const Vector3d& v : va_B) {
    const Vector3d c = v.cwiseMax(-hb).cwiseMin(hb);
    const double dsq = (v - c).squaredNorm();
    if (dsq < best_sq) {
      best_sq = dsq;
      vertex_of_a_wins = true;
      best_a_B = v;
      best_b_B = c;
    }
  }
  if (vertex_of_a_wins) {
    out.distance_m = std::sqrt(best_sq);
    out.p_WA = b.X_WB * best_a_B;
    out.p_WB = b.X_WB * best_b_B;
  } else {
    out.distance_m = best;
    out.p_WA = a.X_WB * best_a_A;
    out.p_WB = a.X_WB * best_b_A;
  }
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

bool IsCloserThan(const Shape& a, const Shape& b, double threshold_m) {
  if (!(threshold_m > 0.0)) return false;  // distances are >= 0; also refuses NaN
  if (!ComputeAabb(a).Inflated(threshold_m).Overlaps(ComputeAabb(b))) return false;
  return ShapeDistance(a, b).distance_m < threshold_m;
}

}  // namespace arm_collision_monitor
