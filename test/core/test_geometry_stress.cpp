// Numerical stability stress suite of the distance routines.
//
// Every case is checked against an independent reference computed in extended precision
// (long double, and __float128 where the long double one is ill-conditioned): different
// algorithms, in the world frame, by enumeration of features (every vertex-face and edge-edge
// pair, after a separating-axis overlap test). Per case: the error against the reference within
// the routine's stated bound, symmetry with witnesses swapped, invariance under a random rigid
// transform, witnesses on the surfaces (or common, inside both, when overlapping) at the reported
// distance, no NaN/inf, and IsCloserThan agreeing with the reference outside the boundary band.
//
// Seeded: ACM_STRESS_SEED=<n> (default printed), ACM_STRESS_CASES=<n> cases per family (default
// 3000, a few seconds in all). Each case draws from its own generator seeded by (seed, family,
// case index), so a failure message names everything needed to rerun it. The worst error per
// family is printed as a table at the end (scripts/stress_geometry prints it).
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "test_geometry_shapes.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Vector3d;
using ld = long double;
using qd = __float128;

constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff

// ------------------------------------------------------------------------------------------
// Extended-precision reference (independent of src/geometry/distance.cpp).

template <typename R>
struct V {
  R x, y, z;
};
template <typename R>
V<R> Make(const Vector3d& v) {
  return {R(v.x()), R(v.y()), R(v.z())};
}
template <typename R>
V<R> operator+(const V<R>& a, const V<R>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename R>
V<R> operator-(const V<R>& a, const V<R>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename R>
V<R> operator*(const V<R>& a, R k) {
  return {a.x * k, a.y * k, a.z * k};
}
template <typename R>
R Dot(const V<R>& a, const V<R>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename R>
V<R> Cross(const V<R>& a, const V<R>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename R>
R Clamp01(R t) {
  return t < R(0) ? R(0) : (t > R(1) ? R(1) : t);
}
template <typename R>
V<R> To(const V<ld>& v) {
  return {R(v.x), R(v.y), R(v.z)};
}

// Squared distance from p to segment a-b (projection, clamped), in R.
template <typename R>
R PointSegmentSqIn(const V<R>& p, const V<R>& a, const V<R>& b) {
  const V<R> d = b - a;
  const R dd = Dot(d, d);
  const R t = dd > R(0) ? Clamp01(Dot(p - a, d) / dd) : R(0);
  const V<R> x = a + d * t - p;
  return Dot(x, x);
}
ld PointSegmentSq(const V<ld>& p, const V<ld>& a, const V<ld>& b) {
  return PointSegmentSqIn<ld>(p, a, b);
}

// The stationary point (s, t) of |p(s) - q(t)|^2 on the two lines (Cramer on the 2x2 normal
// equations). Its points are scored by their distance to the other segment: p(s) to segment q
// and q(t) to segment p, each a true distance between the segments' points (an upper bound),
// and tight to ~|error of s| * length * sin(angle) even when the lines are nearly parallel.
template <typename R>
bool InteriorSq(const V<ld>& p0l, const V<ld>& p1l, const V<ld>& q0l, const V<ld>& q1l,
                ld& out) {
  const V<R> p0 = To<R>(p0l), p1 = To<R>(p1l), q0 = To<R>(q0l), q1 = To<R>(q1l);
  const V<R> d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const R a = Dot(d1, d1), b = Dot(d1, d2), c = Dot(d1, r), e = Dot(d2, d2), f = Dot(d2, r);
  const R denom = a * e - b * b;
  if (!(denom > R(0))) return false;
  const R s = (b * f - c * e) / denom;
  const R t = (a * f - b * c) / denom;
  bool found = false;
  R best = 0;
  if (s >= R(0) && s <= R(1)) {
    best = PointSegmentSqIn<R>(p0 + d1 * s, q0, q1);
    found = true;
  }
  if (t >= R(0) && t <= R(1)) {
    const R x = PointSegmentSqIn<R>(q0 + d2 * t, p0, p1);
    best = found && best < x ? best : x;
    found = true;
  }
  out = ld(best);
  return found;
}

// Segment-segment distance: the least of the four endpoint-segment distances and the interior
// stationary point. The interior point is solved in long double when the segments are far from
// parallel (error ~ eps_ld * S / sin(angle) <= 1e-17 S) and in __float128 otherwise.
ld RefSegmentSegment(const V<ld>& p0, const V<ld>& p1, const V<ld>& q0, const V<ld>& q1) {
  ld best = std::min(std::min(PointSegmentSq(p0, q0, q1), PointSegmentSq(p1, q0, q1)),
                     std::min(PointSegmentSq(q0, p0, p1), PointSegmentSq(q1, p0, p1)));
  const V<ld> d1 = p1 - p0, d2 = q1 - q0;
  const ld a = Dot(d1, d1), e = Dot(d2, d2);
  if (a > 0 && e > 0) {
    // Squared sine of the angle, to within ~(5e-20)^2 absolute in long double.
    const V<ld> n = Cross(d1, d2);
    const ld sin_sq = Dot(n, n) / (a * e);
    ld interior = 0;
    // Below sin(angle) ~ 1e-18 the endpoint candidates are within ~1e-18 * length of the
    // minimum, so the (costly) __float128 solve is skipped: parallel box edges are common.
    const bool found = sin_sq > ld(1e-4)    ? InteriorSq<ld>(p0, p1, q0, q1, interior)
                       : sin_sq > ld(1e-36) ? InteriorSq<qd>(p0, p1, q0, q1, interior)
                                            : false;
    if (found) best = std::min(best, interior);
  }
  return std::sqrt(best);
}

// A box in W in extended precision: centre, axes (unit columns of R) and half extents.
struct RefBox {
  V<ld> c;
  V<ld> axis[3];
  ld h[3];
  V<ld> vertex[8];
};
RefBox MakeRefBox(const Box& b) {
  RefBox r;
  r.c = Make<ld>(b.X_WB.translation());
  for (int k = 0; k < 3; ++k) {
    r.axis[k] = Make<ld>(b.X_WB.linear().col(k));
    r.h[k] = b.half_extents_m[k];
  }
  for (int v = 0; v < 8; ++v) {
    V<ld> x = r.c;
    for (int k = 0; k < 3; ++k) x = x + r.axis[k] * ((v >> k) & 1 ? r.h[k] : -r.h[k]);
    r.vertex[v] = x;
  }
  return r;
}
// Distance from p to face (k, sign) of the box: the rectangle centre + sign h_k axis_k spanned
// by h_i axis_i and h_j axis_j.
ld PointFaceDistance(const V<ld>& p, const RefBox& b, int k, int sign) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const V<ld> fc = b.c + b.axis[k] * (sign * b.h[k]);
  const ld alpha = std::max(-b.h[i], std::min(b.h[i], Dot(p - fc, b.axis[i])));
  const ld beta = std::max(-b.h[j], std::min(b.h[j], Dot(p - fc, b.axis[j])));
  const V<ld> x = fc + b.axis[i] * alpha + b.axis[j] * beta - p;
  return std::sqrt(Dot(x, x));
}
ld PointBoxFacesDistance(const V<ld>& p, const RefBox& b) {
  ld best = std::numeric_limits<ld>::infinity();
  for (int k = 0; k < 3; ++k) {
    for (int sign : {-1, 1}) best = std::min(best, PointFaceDistance(p, b, k, sign));
  }
  return best;
}
// True iff the projections of two point sets on `n` are disjoint, computed in R.
template <typename R>
bool SeparatedAlongIn(const V<R>& n, const V<ld>* a, int na, const V<ld>* b, int nb) {
  R amin = R(std::numeric_limits<ld>::max()), amax = -amin, bmin = amin, bmax = -amin;
  for (int i = 0; i < na; ++i) {
    const R x = Dot(To<R>(a[i]), n);
    amin = x < amin ? x : amin;
    amax = x > amax ? x : amax;
  }
  for (int i = 0; i < nb; ++i) {
    const R x = Dot(To<R>(b[i]), n);
    bmin = x < bmin ? x : bmin;
    bmax = x > bmax ? x : bmax;
  }
  return amax < bmin || bmax < amin;
}
bool SeparatedAlong(const V<ld>& n, const V<ld>* a, int na, const V<ld>* b, int nb) {
  return SeparatedAlongIn<ld>(n, a, na, b, nb);
}
// The same along u x v. A nearly degenerate cross product has a direction error of
// eps / sin(angle) that could hide a thin separation, so it is formed in __float128 then; below
// sin(angle) = 1e-18 the axis is skipped, as for parallel edges (the face normals then show any
// separation thicker than ~1e-18 * size).
bool SeparatedAlongCross(const V<ld>& u, const V<ld>& v, const V<ld>* a, int na, const V<ld>* b,
                         int nb) {
  const V<ld> n = Cross(u, v);
  const ld sin_sq = Dot(n, n) / (Dot(u, u) * Dot(v, v));
  if (sin_sq > ld(1e-4)) return SeparatedAlongIn<ld>(n, a, na, b, nb);
  if (!(sin_sq > ld(1e-36))) return false;
  return SeparatedAlongIn<qd>(Cross(To<qd>(u), To<qd>(v)), a, na, b, nb);
}
constexpr int kEdges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                               {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

// Segment-box: separating axes (3 box normals, 3 segment x box axes; Gottschalk/Eberly) for
// overlap, else the least of endpoint-face (2 x 6) and segment-edge (12) distances.
ld RefSegmentBox(const V<ld>& p0, const V<ld>& p1, const RefBox& b) {
  const V<ld> seg[2] = {p0, p1};
  bool separated = false;
  for (int k = 0; k < 3 && !separated; ++k) {
    separated = SeparatedAlong(b.axis[k], seg, 2, b.vertex, 8) ||
                SeparatedAlongCross(p1 - p0, b.axis[k], seg, 2, b.vertex, 8);
  }
  if (!separated) return 0;
  ld best = std::min(PointBoxFacesDistance(p0, b), PointBoxFacesDistance(p1, b));
  for (const auto& e : kEdges) {
    best = std::min(best, RefSegmentSegment(p0, p1, b.vertex[e[0]], b.vertex[e[1]]));
  }
  return best;
}

// Box-box: 15 separating axes for overlap, else the least of vertex-face (2 x 8 x 6) and
// edge-edge (12 x 12) distances.
ld RefBoxBox(const RefBox& a, const RefBox& b) {
  bool separated = false;
  for (int i = 0; i < 3 && !separated; ++i) {
    separated = SeparatedAlong(a.axis[i], a.vertex, 8, b.vertex, 8) ||
                SeparatedAlong(b.axis[i], a.vertex, 8, b.vertex, 8);
    for (int j = 0; j < 3 && !separated; ++j) {
      separated = SeparatedAlongCross(a.axis[i], b.axis[j], a.vertex, 8, b.vertex, 8);
    }
  }
  if (!separated) return 0;
  ld best = std::numeric_limits<ld>::infinity();
  for (int v = 0; v < 8; ++v) {
    best = std::min(best, PointBoxFacesDistance(a.vertex[v], b));
    best = std::min(best, PointBoxFacesDistance(b.vertex[v], a));
  }
  for (const auto& ea : kEdges) {
    for (const auto& eb : kEdges) {
      best = std::min(best, RefSegmentSegment(a.vertex[ea[0]], a.vertex[ea[1]],
                                              b.vertex[eb[0]], b.vertex[eb[1]]));
    }
  }
  return best;
}

ld RefDistance(const Shape& a, const Shape& b) {
  if (const auto* ca = std::get_if<Capsule>(&a)) {
    if (const auto* cb = std::get_if<Capsule>(&b)) {
      const ld axis = RefSegmentSegment(Make<ld>(ca->p0_W), Make<ld>(ca->p1_W),
                                        Make<ld>(cb->p0_W), Make<ld>(cb->p1_W));
      return std::max(ld(0), axis - ld(ca->radius_m) - ld(cb->radius_m));
    }
    const ld axis =
        RefSegmentBox(Make<ld>(ca->p0_W), Make<ld>(ca->p1_W), MakeRefBox(std::get<Box>(b)));
    return std::max(ld(0), axis - ld(ca->radius_m));
  }
  if (std::holds_alternative<Capsule>(b)) return RefDistance(b, a);
  return RefBoxBox(MakeRefBox(std::get<Box>(a)), MakeRefBox(std::get<Box>(b)));
}

// Signed distance from p to the surface of a shape (negative inside), in long double.
ld RefSignedDistance(const Vector3d& p_W, const Shape& s) {
  const V<ld> p = Make<ld>(p_W);
  if (const auto* c = std::get_if<Capsule>(&s)) {
    return std::sqrt(PointSegmentSq(p, Make<ld>(c->p0_W), Make<ld>(c->p1_W))) - c->radius_m;
  }
  const RefBox b = MakeRefBox(std::get<Box>(s));
  ld outside_sq = 0, max_q = -std::numeric_limits<ld>::infinity();
  for (int k = 0; k < 3; ++k) {
    const ld q = std::fabs(Dot(p - b.c, b.axis[k])) - b.h[k];
    outside_sq += q > 0 ? q * q : 0;
    max_q = std::max(max_q, q);
  }
  return std::sqrt(outside_sq) + std::min(max_q, ld(0));
}

// ------------------------------------------------------------------------------------------
// Bounds, scales and case generation.

// Largest |coordinate| of a shape's defining points (for the absolute rounding of witnesses).
double MaxCoordinate(const Shape& s) {
  if (const auto* c = std::get_if<Capsule>(&s)) {
    return std::max(c->p0_W.cwiseAbs().maxCoeff(), c->p1_W.cwiseAbs().maxCoeff());
  }
  const Box& b = std::get<Box>(s);
  return b.X_WB.translation().cwiseAbs().maxCoeff() + b.half_extents_m.norm();
}
Vector3d ReferencePoint(const Shape& s) {
  if (const auto* c = std::get_if<Capsule>(&s)) return c->p0_W;
  return std::get<Box>(s).X_WB.translation();
}
double Size(const Shape& s) {
  if (const auto* c = std::get_if<Capsule>(&s)) {
    return std::max((c->p1_W - c->p0_W).norm(), c->radius_m);
  }
  return 2.0 * std::get<Box>(s).half_extents_m.norm();
}
// The local length scale S of the bounds (core/constants.h).
double LocalScale(const Shape& a, const Shape& b) {
  return std::max({(ReferencePoint(a) - ReferencePoint(b)).norm(), Size(a), Size(b)});
}
double StatedBound(const Shape& a, const Shape& b) {
  const bool both_capsules =
      std::holds_alternative<Capsule>(a) && std::holds_alternative<Capsule>(b);
  const double ulps = both_capsules ? kSegmentDistanceErrorUlps : kBoxDistanceErrorUlps;
  return ulps * kEps * LocalScale(a, b) + kDistanceErrorFloor_m;
}

// SplitMix64 (Steele et al. 2014): a per-case generator from (seed, family, case).
struct Rng {
  uint64_t state;
  uint64_t Next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * ((Next() >> 11) * 0x1.0p-53); }
  int Int(int n) { return static_cast<int>(Next() % static_cast<uint64_t>(n)); }
  bool Chance(double p) { return Uniform(0, 1) < p; }
  Vector3d InCube(double half) {
    return Vector3d(Uniform(-half, half), Uniform(-half, half), Uniform(-half, half));
  }
  Vector3d UnitVector() {
    for (;;) {
      const Vector3d v = InCube(1.0);
      const double n = v.norm();
      if (n > 1e-3 && n <= 1.0) return v / n;
    }
  }
  Eigen::Quaterniond Rotation() {
    Eigen::Quaterniond q(Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1), Uniform(-1, 1));
    while (q.norm() < 1e-3) q.coeffs() = Eigen::Vector4d(Uniform(-1, 1), 1, 0, 0);
    return q.normalized();
  }
  // A log-uniform magnitude in [10^lo, 10^hi].
  double LogUniform(double lo, double hi) { return std::pow(10.0, Uniform(lo, hi)); }
};

Box MakeBox(const Eigen::Quaterniond& q, const Vector3d& centre, const Vector3d& h) {
  Box b;
  b.X_WB.linear() = q.toRotationMatrix();
  b.X_WB.translation() = centre;
  b.half_extents_m = h;
  return b;
}
// A unit vector at `angle` rad from u (in a random plane through u).
Vector3d Tilted(Rng& rng, const Vector3d& u, double angle) {
  const Vector3d w = u.cross(rng.UnitVector()).normalized();
  return std::cos(angle) * u + std::sin(angle) * w;
}
Vector3d Offset1e4(Rng& rng) {
  Vector3d o;
  for (int i = 0; i < 3; ++i) o[i] = (rng.Chance(0.5) ? 1 : -1) * rng.Uniform(0.5e4, 1e4);
  return o;
}
Shape Shifted(const Shape& s, const Vector3d& o) {
  if (const auto* c = std::get_if<Capsule>(&s)) {
    return MakeCapsule(c->p0_W + o, c->p1_W + o, c->radius_m);
  }
  Box b = std::get<Box>(s);
  b.X_WB.translation() += o;
  return b;
}
Shape Transformed(const Shape& s, const Eigen::Isometry3d& T) {
  if (const auto* c = std::get_if<Capsule>(&s)) {
    return MakeCapsule(T * c->p0_W, T * c->p1_W, c->radius_m);
  }
  Box b = std::get<Box>(s);
  b.X_WB = T * b.X_WB;
  return b;
}

struct Pair {
  Shape a, b;
};
using Generator = Pair (*)(Rng&);

// --- Capsule-capsule families (their axes also test SegmentSegmentClosestPoints).
double Radius(Rng& rng) { return rng.Chance(0.2) ? 0.0 : rng.Uniform(0.0, 0.5); }
Pair SegRandom(Rng& rng) {
  return {MakeCapsule(rng.InCube(10), rng.InCube(10), Radius(rng)),
          MakeCapsule(rng.InCube(10), rng.InCube(10), Radius(rng))};
}
Pair SegZeroLength(Rng& rng) {
  const Vector3d p = rng.InCube(5);
  const Vector3d q0 = rng.InCube(5);
  const Vector3d q1 = rng.Chance(0.3) ? q0 : rng.InCube(5);
  return {MakeCapsule(p, p, Radius(rng)), MakeCapsule(q0, q1, Radius(rng))};
}
Pair SegParallel(Rng& rng, double sign) {
  const Vector3d p0 = rng.InCube(5);
  const Vector3d d = rng.InCube(3);
  // Scale by a power of two so that d2 is exactly parallel to d1.
  const double k = sign * std::ldexp(1.0, rng.Int(5) - 2);
  const Vector3d q0 = p0 + rng.InCube(3);
  return {MakeCapsule(p0, p0 + d, Radius(rng)), MakeCapsule(q0, q0 + k * d, Radius(rng))};
}
Pair SegParallelSame(Rng& rng) { return SegParallel(rng, 1.0); }
Pair SegAntiParallel(Rng& rng) { return SegParallel(rng, -1.0); }
Pair SegCollinearOverlap(Rng& rng) {
  const Vector3d o = rng.InCube(5);
  const Vector3d u = rng.UnitVector();
  const double a0 = rng.Uniform(-3, 0), a1 = rng.Uniform(0, 3);
  const double b0 = rng.Uniform(-3, 3), b1 = rng.Uniform(-3, 3);
  return {MakeCapsule(o + a0 * u, o + a1 * u, Radius(rng)),
          MakeCapsule(o + b0 * u, o + b1 * u, Radius(rng))};
}
Pair SegNearlyParallel(Rng& rng) {
  const Vector3d p0 = rng.InCube(5);
  const Vector3d u = rng.UnitVector();
  const double angle = rng.LogUniform(-15, -2);
  const Vector3d v = Tilted(rng, rng.Chance(0.5) ? u : Vector3d(-u), angle);
  const Vector3d q0 = p0 + rng.InCube(2) - rng.Uniform(0, 3) * v;
  return {MakeCapsule(p0, p0 + rng.Uniform(0.1, 4) * u, Radius(rng)),
          MakeCapsule(q0, q0 + rng.Uniform(0.1, 6) * v, Radius(rng))};
}
Pair SegCrossingAxes(Rng& rng) {
  // Lines through a common point x, the capsules' axes crossing (distance 0).
  const Vector3d x = rng.InCube(5);
  const Vector3d u = rng.UnitVector(), v = rng.UnitVector();
  return {MakeCapsule(x - rng.Uniform(0.1, 3) * u, x + rng.Uniform(0.1, 3) * u, Radius(rng)),
          MakeCapsule(x - rng.Uniform(0.1, 3) * v, x + rng.Uniform(0.1, 3) * v, Radius(rng))};
}
Pair SegTouching(Rng& rng) {
  // Axes h apart along their common normal, with radii summing to h: touching capsules.
  const Vector3d x = rng.InCube(5);
  const Vector3d u = rng.UnitVector();
  const Vector3d v = Tilted(rng, u, rng.Uniform(0.05, 3.1));
  const Vector3d n = u.cross(v).normalized();
  const double h = rng.Uniform(0.01, 1.0), ra = rng.Uniform(0, h);
  const Vector3d y = x + h * n;
  return {MakeCapsule(x - rng.Uniform(0.1, 3) * u, x + rng.Uniform(0.1, 3) * u, ra),
          MakeCapsule(y - rng.Uniform(0.1, 3) * v, y + rng.Uniform(0.1, 3) * v, h - ra)};
}
Pair SegFar1e4(Rng& rng) {
  const Pair p = SegRandom(rng);
  const Vector3d o = Offset1e4(rng);
  return {Shifted(p.a, o), Shifted(p.b, o)};
}

// --- Capsule-box families.
Vector3d HalfExtents(Rng& rng) {
  return Vector3d(rng.Uniform(0.02, 1.5), rng.Uniform(0.02, 1.5), rng.Uniform(0.02, 1.5));
}
Pair CapBoxRandom(Rng& rng) {
  return {MakeCapsule(rng.InCube(4), rng.InCube(4), Radius(rng)),
          MakeBox(rng.Rotation(), rng.InCube(1), HalfExtents(rng))};
}
Pair CapBoxSphere(Rng& rng) {
  const Vector3d p = rng.InCube(3);
  return {MakeCapsule(p, p, Radius(rng)),
          MakeBox(rng.Rotation(), rng.InCube(1), HalfExtents(rng))};
}
Pair CapBoxAxisParallel(Rng& rng) {
  // Segment along a box axis (exactly, or tilted by 1e-15..1e-2 rad), near a face or an edge.
  const Eigen::Quaterniond q = rng.Chance(0.3) ? Eigen::Quaterniond::Identity() : rng.Rotation();
  const Box b = MakeBox(q, rng.InCube(1), HalfExtents(rng));
  const int k = rng.Int(3);
  Vector3d dir_B = Vector3d::Unit(k);
  if (rng.Chance(0.6)) dir_B = Tilted(rng, dir_B, rng.LogUniform(-15, -2));
  Vector3d start_B;
  for (int i = 0; i < 3; ++i) {
    const double h = b.half_extents_m[i];
    start_B[i] =
        (rng.Chance(0.5) ? 1 : -1) * (h + (rng.Chance(0.2) ? 0.0 : rng.Uniform(-0.2, 0.5)));
  }
  start_B -= rng.Uniform(0, 3) * dir_B;
  const Vector3d p0 = b.X_WB * start_B;
  const Vector3d p1 = b.X_WB * (start_B + rng.Uniform(0.1, 5) * dir_B);
  return {MakeCapsule(p0, p1, Radius(rng)), b};
}
Pair CapBoxTouching(Rng& rng) {
  // A capsule whose radius is the reference axis-box distance: touching the box.
  Pair p = CapBoxRandom(rng);
  Capsule& c = std::get<Capsule>(p.a);
  c.radius_m = 0.0;
  c.radius_m = static_cast<double>(RefDistance(p.a, p.b));
  return p;
}
Pair CapBoxFar1e4(Rng& rng) {
  const Pair p = CapBoxRandom(rng);
  const Vector3d o = Offset1e4(rng);
  return {Shifted(p.a, o), Shifted(p.b, o)};
}

// --- Box-box families.
Pair BoxBoxRandom(Rng& rng) {
  return {MakeBox(rng.Rotation(), rng.InCube(1.5), HalfExtents(rng)),
          MakeBox(rng.Rotation(), rng.InCube(1.5), HalfExtents(rng))};
}
// Same orientation (up to `angle`), B placed face-, edge- or vertex-adjacent to A with small
// gaps (some exactly 0), others random.
Pair BoxBoxAligned(Rng& rng, double angle) {
  const Eigen::Quaterniond q = rng.Chance(0.3) ? Eigen::Quaterniond::Identity() : rng.Rotation();
  const Vector3d ha = HalfExtents(rng), hb = HalfExtents(rng);
  Vector3d offset_A;
  for (int i = 0; i < 3; ++i) {
    const double contact = ha[i] + hb[i];
    const double gap = rng.Chance(0.3) ? 0.0 : rng.Uniform(-0.05, 0.3);
    offset_A[i] = rng.Chance(0.5) ? (rng.Chance(0.5) ? 1 : -1) * (contact + gap)
                                  : rng.Uniform(-contact, contact);
  }
  const Box a = MakeBox(q, rng.InCube(1), ha);
  Eigen::Quaterniond qb = q;
  if (angle > 0) qb = q * Eigen::Quaterniond(Eigen::AngleAxisd(angle, rng.UnitVector()));
  return {a, MakeBox(qb, a.X_WB * offset_A, hb)};
}
Pair BoxBoxExactlyAligned(Rng& rng) { return BoxBoxAligned(rng, 0.0); }
Pair BoxBoxNearlyAligned(Rng& rng) { return BoxBoxAligned(rng, rng.LogUniform(-15, -3)); }
Pair BoxBoxFar1e4(Rng& rng) {
  const Pair p = BoxBoxRandom(rng);
  const Vector3d o = Offset1e4(rng);
  return {Shifted(p.a, o), Shifted(p.b, o)};
}

// --- Any finite input within the stated range: magnitudes from 1e-300 m to 1e60 m.
double Extreme(Rng& rng) {
  return (rng.Chance(0.5) ? 1 : -1) *
         (rng.Chance(0.1) ? 0.0 : rng.LogUniform(-300, std::log10(kMaxSupportedCoordinate_m)));
}
Vector3d ExtremeVector(Rng& rng) {
  return Vector3d(Extreme(rng), Extreme(rng), Extreme(rng));
}
Shape ExtremeShape(Rng& rng) {
  if (rng.Chance(0.5)) {
    const Vector3d p0 = ExtremeVector(rng);
    return MakeCapsule(p0, rng.Chance(0.3) ? p0 : ExtremeVector(rng), std::fabs(Extreme(rng)));
  }
  return MakeBox(rng.Rotation(), ExtremeVector(rng), ExtremeVector(rng).cwiseAbs());
}
Pair ExtremePair(Rng& rng) { return {ExtremeShape(rng), ExtremeShape(rng)}; }

// ------------------------------------------------------------------------------------------
// The checks.

struct FamilyResult {
  long cases = 0;
  double worst_error_m = 0.0;
  double worst_ratio = 0.0;  // error / stated bound
  long worst_case = -1;
};
std::map<std::string, FamilyResult>& Results() {
  static std::map<std::string, FamilyResult> results;
  return results;
}

uint64_t Seed() {
  const char* env = std::getenv("ACM_STRESS_SEED");
  return env ? std::strtoull(env, nullptr, 10) : 20261121ull;
}
long CasesPerFamily() {
  const char* env = std::getenv("ACM_STRESS_CASES");
  return env ? std::max(1L, std::atol(env)) : 3000L;
}
uint64_t FamilyHash(const std::string& name) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a
  for (char c : name) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

std::string Describe(const Shape& s) {
  char buf[600];
  if (const auto* c = std::get_if<Capsule>(&s)) {
    std::snprintf(buf, sizeof(buf),
                  "Capsule{(%.17g, %.17g, %.17g), (%.17g, %.17g, %.17g), r=%.17g}", c->p0_W.x(),
                  c->p0_W.y(), c->p0_W.z(), c->p1_W.x(), c->p1_W.y(), c->p1_W.z(), c->radius_m);
  } else {
    const Box& b = std::get<Box>(s);
    const Eigen::Matrix3d& R = b.X_WB.linear();
    std::snprintf(buf, sizeof(buf),
                  "Box{c=(%.17g, %.17g, %.17g), R=(%.17g, %.17g, %.17g; %.17g, %.17g, %.17g; "
                  "%.17g, %.17g, %.17g), h=(%.17g, %.17g, %.17g)}",
                  b.X_WB.translation().x(), b.X_WB.translation().y(), b.X_WB.translation().z(),
                  R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2),
                  b.half_extents_m.x(), b.half_extents_m.y(), b.half_extents_m.z());
  }
  return buf;
}

class Checker {
 public:
  Checker(const std::string& family, long index, const Pair& p)
      : family_(family), index_(index), pair_(p) {}

  // Records a failed property; only the first few per family are printed in full.
  void Fail(const std::string& what, double got, double want, double tol) {
    ++failures_;
    if (printed_ < 5) {
      ++printed_;
      ADD_FAILURE() << family_ << " case " << index_ << " (seed " << Seed() << "): " << what
                    << ": got " << got << ", want " << want << " +/- " << tol << "\n  a = "
                    << Describe(pair_.a) << "\n  b = " << Describe(pair_.b);
    }
  }
  void Near(const std::string& what, double got, double want, double tol) {
    if (!(std::fabs(got - want) <= tol)) Fail(what, got, want, tol);
  }
  void True(const std::string& what, bool ok) {
    if (!ok) Fail(what, 0, 1, 0);
  }
  static long failures() { return failures_; }
  static void ResetFamily() {
    failures_ = 0;
    printed_ = 0;
  }

 private:
  std::string family_;
  long index_;
  const Pair& pair_;
  static long failures_;
  static int printed_;
};
long Checker::failures_ = 0;
int Checker::printed_ = 0;

// Witnesses: on the surfaces at the reported distance, or one common point inside both.
void CheckWitnesses(Checker& check, const std::string& tag, const DistanceResult& r,
                    const Shape& a, const Shape& b, double tol) {
  check.True(tag + " witnesses finite", r.p_WA.allFinite() && r.p_WB.allFinite());
  const double sa = static_cast<double>(RefSignedDistance(r.p_WA, a));
  const double sb = static_cast<double>(RefSignedDistance(r.p_WB, b));
  if (r.distance_m > 0.0) {
    check.Near(tag + " witness A on surface of A", sa, 0.0, tol);
    check.Near(tag + " witness B on surface of B", sb, 0.0, tol);
    check.Near(tag + " |p_WA - p_WB| = distance", (r.p_WA - r.p_WB).norm(), r.distance_m, tol);
  } else {
    check.Near(tag + " overlap witnesses coincide", (r.p_WA - r.p_WB).norm(), 0.0, tol);
    check.True(tag + " overlap witness inside A", sa <= tol);
    check.True(tag + " overlap witness inside B", static_cast<double>(
                                                      RefSignedDistance(r.p_WA, b)) <= tol);
  }
}

void CheckCase(Checker& check, const Pair& p, Rng& rng, FamilyResult& result, long index) {
  const Shape& a = p.a;
  const Shape& b = p.b;
  const double bound = StatedBound(a, b);
  const double scale = LocalScale(a, b);
  const double coord = std::max(MaxCoordinate(a), MaxCoordinate(b));
  // Witnesses are absolute coordinates: they also carry eps * |coordinate| rounding.
  const double witness_tol = bound + 16 * kEps * (coord + scale);
  const double ref = static_cast<double>(RefDistance(a, b));

  const DistanceResult ab = ShapeDistance(a, b);
  check.True("distance finite and >= 0", std::isfinite(ab.distance_m) && ab.distance_m >= 0);
  const double error = std::fabs(ab.distance_m - ref);
  check.Near("distance vs extended-precision reference", ab.distance_m, ref, bound);
  if (error > result.worst_error_m) {
    result.worst_error_m = error;
    result.worst_case = index;
  }
  if (bound > 0) result.worst_ratio = std::max(result.worst_ratio, error / bound);
  CheckWitnesses(check, "d(a,b)", ab, a, b, witness_tol);

  // Symmetry, witnesses swapped.
  const DistanceResult ba = ShapeDistance(b, a);
  check.Near("symmetry d(b,a) = d(a,b)", ba.distance_m, ab.distance_m, 2 * bound);
  CheckWitnesses(check, "d(b,a)", ba, b, a, witness_tol);

  // Invariance under a random rigid transform (its rounding perturbs the inputs by ~eps|x|).
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rng.Rotation().toRotationMatrix();
  T.translation() = rng.InCube(10);
  const Shape ta = Transformed(a, T), tb = Transformed(b, T);
  const double coord_t = std::max(MaxCoordinate(ta), MaxCoordinate(tb));
  check.Near("rigid transform invariance", ShapeDistance(ta, tb).distance_m, ref,
             bound + 16 * kEps * (coord + coord_t + scale));

  // IsCloserThan agrees with the reference outside the boundary band (the AABB pre-test works in
  // absolute coordinates, hence the coordinate term).
  const double band = 2 * bound + 16 * kEps * (coord + scale);
  const double above = ref + band + rng.Uniform(0, 0.1) * scale;
  check.True("IsCloserThan just above the distance", IsCloserThan(a, b, above));
  const double below = ref - band - rng.Uniform(0, 0.1) * scale;
  if (below > 0) check.True("!IsCloserThan just below the distance", !IsCloserThan(a, b, below));
  check.True("!IsCloserThan(0)", !IsCloserThan(a, b, 0.0));

  // Zero-length capsule = sphere: the distance from its centre to the other shape, less radius.
  for (const auto* pair_order : {&a, &b}) {
    const auto* c = std::get_if<Capsule>(pair_order);
    if (c == nullptr || c->p0_W != c->p1_W) continue;
    const Shape& other = pair_order == &a ? b : a;
    const double centre_distance =
        static_cast<double>(RefSignedDistance(c->p0_W, other));
    check.Near("zero-length capsule = sphere", ab.distance_m,
               std::max(0.0, centre_distance - c->radius_m), bound);
  }

  // The axes' closest points through the public segment routine.
  const auto* ca = std::get_if<Capsule>(&a);
  const auto* cb = std::get_if<Capsule>(&b);
  if (ca && cb) {
    const SegmentClosestPoints s =
        SegmentSegmentClosestPoints(ca->p0_W, ca->p1_W, cb->p0_W, cb->p1_W);
    const double seg_ref = static_cast<double>(RefSegmentSegment(
        Make<ld>(ca->p0_W), Make<ld>(ca->p1_W), Make<ld>(cb->p0_W), Make<ld>(cb->p1_W)));
    check.Near("segment distance vs reference", s.distance_m, seg_ref, bound);
    check.True("s, t in [0, 1]", s.s >= 0 && s.s <= 1 && s.t >= 0 && s.t <= 1);
    check.Near("p_W = p0 + s (p1 - p0)", (s.p_W - (ca->p0_W + s.s * (ca->p1_W - ca->p0_W))).norm(),
               0.0, witness_tol);
    check.Near("q_W = q0 + t (q1 - q0)", (s.q_W - (cb->p0_W + s.t * (cb->p1_W - cb->p0_W))).norm(),
               0.0, witness_tol);
    check.Near("|p_W - q_W| = distance", (s.p_W - s.q_W).norm(), s.distance_m, witness_tol);
  }
}

void RunFamily(const std::string& family, Generator generate) {
  const long n = CasesPerFamily();
  const uint64_t seed = Seed();
  std::printf("[stress] family %s: seed %" PRIu64 ", %ld cases\n", family.c_str(), seed, n);
  Checker::ResetFamily();
  FamilyResult result;
  for (long i = 0; i < n; ++i) {
    Rng rng{seed ^ FamilyHash(family) ^ (static_cast<uint64_t>(i) * 0xD1B54A32D192ED03ull)};
    const Pair p = generate(rng);
    Checker check(family, i, p);
    CheckCase(check, p, rng, result, i);
  }
  result.cases = n;
  Results()[family] = result;
  EXPECT_EQ(Checker::failures(), 0) << family << ": failed checks (seed " << seed << ")";
}

TEST(GeometryStress, SegmentRandom) { RunFamily("seg_random", SegRandom); }
TEST(GeometryStress, SegmentZeroLength) { RunFamily("seg_zero_length", SegZeroLength); }
TEST(GeometryStress, SegmentParallel) { RunFamily("seg_parallel", SegParallelSame); }
TEST(GeometryStress, SegmentAntiParallel) { RunFamily("seg_antiparallel", SegAntiParallel); }
TEST(GeometryStress, SegmentCollinearOverlap) {
  RunFamily("seg_collinear_overlap", SegCollinearOverlap);
}
TEST(GeometryStress, SegmentNearlyParallel) {
  RunFamily("seg_nearly_parallel_1e-15..1e-2rad", SegNearlyParallel);
}
TEST(GeometryStress, SegmentCrossingAxes) { RunFamily("seg_crossing_axes", SegCrossingAxes); }
TEST(GeometryStress, CapsuleTouching) { RunFamily("capsule_touching", SegTouching); }
TEST(GeometryStress, SegmentFar1e4) { RunFamily("seg_far_1e4m", SegFar1e4); }
TEST(GeometryStress, CapsuleBoxRandom) { RunFamily("capbox_random", CapBoxRandom); }
TEST(GeometryStress, CapsuleBoxSphere) { RunFamily("capbox_sphere", CapBoxSphere); }
TEST(GeometryStress, CapsuleBoxAxisParallel) {
  RunFamily("capbox_axis_parallel", CapBoxAxisParallel);
}
TEST(GeometryStress, CapsuleBoxTouching) { RunFamily("capbox_touching", CapBoxTouching); }
TEST(GeometryStress, CapsuleBoxFar1e4) { RunFamily("capbox_far_1e4m", CapBoxFar1e4); }
TEST(GeometryStress, BoxBoxRandom) { RunFamily("boxbox_random", BoxBoxRandom); }
TEST(GeometryStress, BoxBoxAligned) { RunFamily("boxbox_aligned", BoxBoxExactlyAligned); }
TEST(GeometryStress, BoxBoxNearlyAligned) {
  RunFamily("boxbox_nearly_aligned_1e-15..1e-3rad", BoxBoxNearlyAligned);
}
TEST(GeometryStress, BoxBoxFar1e4) { RunFamily("boxbox_far_1e4m", BoxBoxFar1e4); }
TEST(GeometryStress, ExtremeMagnitudes) {
  RunFamily("extreme_1e-300..1e60m", ExtremePair);
}

// Prints the worst error per family once every family has run.
class PrintTable : public ::testing::Environment {
 public:
  void TearDown() override {
    long total = 0;
    std::printf("\n[stress] seed %" PRIu64 "; error = |distance - extended-precision reference|\n",
                Seed());
    std::printf("[stress] %-38s %10s %14s %14s %10s\n", "family", "cases", "worst_err_m",
                "worst/bound", "worst_case");
    for (const auto& [name, r] : Results()) {
      total += r.cases;
      std::printf("[stress] %-38s %10ld %14.3e %14.3e %10ld\n", name.c_str(), r.cases,
                  r.worst_error_m, r.worst_ratio, r.worst_case);
    }
    std::printf("[stress] total cases: %ld\n", total);
  }
};
const auto* const kPrintTable = ::testing::AddGlobalTestEnvironment(new PrintTable);

}  // namespace
}  // namespace arm_collision_monitor
