// Mesh fitting (geometry/mesh_fit.h): containment of every fit over seeded random meshes, checked
// with the exact distance routines; tightness on cylinders and boxes; capsule chains against one
// capsule on bent meshes; each degenerate mesh refused with its reason; volumes; the cache key.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/geometry/mesh_fit.h"
#include "test_geometry_shapes.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Vector3d;
using Triangle = std::array<std::uint32_t, 3>;

constexpr double kPi = 3.14159265358979323846;
constexpr std::uint64_t kSeed = 20261123;

std::mt19937_64 SeededRng(const char* test) {
  std::printf("[%s] seed %llu\n", test, static_cast<unsigned long long>(kSeed));
  return std::mt19937_64(kSeed);
}

double Uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// ---------------------------------------------------------------------------------------------
// Mesh builders: closed, outward-oriented (counter-clockwise seen from outside).

TriangleMesh BoxMesh(const Vector3d& half_m) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices_L.emplace_back((i & 1 ? 1 : -1) * half_m.x(), (i & 2 ? 1 : -1) * half_m.y(),
                                 (i & 4 ? 1 : -1) * half_m.z());
  }
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

// A tube of `sides`-gon cross sections of radius radius_m(s) around the curve centre(s),
// s in [0, 1] at `rings` stations, closed by fans at both ends. The cross-section frame
// follows the curve's tangent (rotation-minimising is not needed for the gentle curves here).
template <typename Centre, typename Radius>
TriangleMesh TubeMesh(const Centre& centre, const Radius& radius_m, int rings, int sides) {
  TriangleMesh mesh;
  for (int i = 0; i < rings; ++i) {
    const double s = static_cast<double>(i) / (rings - 1);
    const double ds = 1e-6;
    const Vector3d tangent = (centre(std::min(1.0, s + ds)) - centre(std::max(0.0, s - ds)))
                                 .normalized();
    const Vector3d a = tangent.unitOrthogonal();
    const Vector3d b = tangent.cross(a);
    for (int j = 0; j < sides; ++j) {
      const double phi = 2.0 * kPi * j / sides;
      mesh.vertices_L.push_back(centre(s) +
                                radius_m(s, phi) * (std::cos(phi) * a + std::sin(phi) * b));
    }
  }
  const auto n = static_cast<std::uint32_t>(mesh.vertices_L.size());
  mesh.vertices_L.push_back(centre(0.0));
  mesh.vertices_L.push_back(centre(1.0));
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(i * sides + j % sides); };
  for (int i = 0; i + 1 < rings; ++i) {
    for (int j = 0; j < sides; ++j) {
      mesh.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  }
  for (int j = 0; j < sides; ++j) {
    mesh.triangles.push_back({n, at(0, j + 1), at(0, j)});
    mesh.triangles.push_back({n + 1, at(rings - 1, j), at(rings - 1, j + 1)});
  }
  return mesh;
}

TriangleMesh CylinderMesh(double radius_m, double length_m, int sides = 32) {
  return TubeMesh([&](double s) { return Vector3d(0, 0, (s - 0.5) * length_m); },
                  [&](double, double) { return radius_m; }, 2, sides);
}

// An ellipsoid of semi-axes `radii_m` (a tube whose cross sections shrink to the poles), each
// vertex's radius scaled by 1 + bumpiness * uniform(-1, 1): a random star-shaped blob.
TriangleMesh BlobMesh(const Vector3d& radii_m, int rings, int sides, double bumpiness,
                      std::mt19937_64& rng) {
  TriangleMesh mesh = TubeMesh(
      [&](double s) { return Vector3d(0, 0, -std::cos(kPi * s)); },
      [&](double s, double) {
        return std::max(1e-3, std::sin(kPi * s)) * (1.0 + bumpiness * Uniform(rng, -1, 1));
      },
      rings, sides);
  for (Vector3d& p : mesh.vertices_L) p = p.cwiseProduct(radii_m);
  return mesh;
}

// A tube bent through `bend_rad` about a circle of radius bend_radius_m (a banana).
TriangleMesh BentTubeMesh(double bend_radius_m, double bend_rad, double tube_radius_m) {
  return TubeMesh(
      [&](double s) -> Vector3d {  // not an expression of a temporary
        return bend_radius_m * Vector3d(std::cos(bend_rad * s), std::sin(bend_rad * s), 0.0);
      },
      [&](double, double) { return tube_radius_m; }, 24, 16);
}

// An L: the polygon (0,0) (a,0) (a,t) (t,t) (t,a) (0,a) extruded by `depth_m` along z.
TriangleMesh LShapeMesh(double arm_m, double thickness_m, double depth_m) {
  const double a = arm_m;
  const double t = thickness_m;
  const std::array<Eigen::Vector2d, 6> outline{{{0, 0}, {a, 0}, {a, t}, {t, t}, {t, a}, {0, a}}};
  TriangleMesh mesh;
  for (const double z : {0.0, depth_m}) {
    for (const auto& p : outline) mesh.vertices_L.emplace_back(p.x(), p.y(), z);
  }
  // The outline is counter-clockwise seen from +z: its fan from corner 3 (the inner corner, which
  // sees every other corner) triangulates it.
  for (const Triangle& tri : std::vector<Triangle>{{3, 4, 5}, {3, 5, 0}, {3, 0, 1}, {3, 1, 2}}) {
    mesh.triangles.push_back({tri[0] + 6, tri[1] + 6, tri[2] + 6});
    mesh.triangles.push_back({tri[0], tri[2], tri[1]});
  }
  for (std::uint32_t j = 0; j < 6; ++j) {
    const std::uint32_t k = (j + 1) % 6;
    mesh.triangles.push_back({j, k, k + 6});
    mesh.triangles.push_back({j, k + 6, j + 6});
  }
  return mesh;
}

Eigen::Isometry3d RandomPose(std::mt19937_64& rng, double max_offset_m) {
  Eigen::Vector4d q(Uniform(rng, -1, 1), Uniform(rng, -1, 1), Uniform(rng, -1, 1),
                    Uniform(rng, -1, 1));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(q.normalized()).toRotationMatrix();
  X.translation() = Vector3d(Uniform(rng, -1, 1), Uniform(rng, -1, 1), Uniform(rng, -1, 1)) *
                    max_offset_m;
  return X;
}

TriangleMesh Transformed(TriangleMesh mesh, const Eigen::Isometry3d& X, double scale) {
  for (Vector3d& p : mesh.vertices_L) p = X * (scale * p);
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// Containment, decided by the exact distance routines.

bool ShapeContains(const Shape& shape, const Vector3d& p) {
  if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    return SegmentSegmentClosestPoints(p, p, capsule->p0_W, capsule->p1_W).distance_m <=
           capsule->radius_m;
  }
  return CapsuleBoxDistance(MakeCapsule(p, p, 0.0), std::get<Box>(shape)).distance_m <= 0.0;
}

bool UnionContains(const std::vector<Shape>& shapes, const Vector3d& p) {
  return std::any_of(shapes.begin(), shapes.end(),
                     [&](const Shape& s) { return ShapeContains(s, p); });
}

// The vertices, `per_triangle` random points on each triangle and, for a convex mesh, as many
// random convex combinations of four vertices (points of the solid).
std::vector<Vector3d> SamplePoints(const TriangleMesh& mesh, int per_triangle, bool is_convex,
                                   std::mt19937_64& rng) {
  std::vector<Vector3d> points = mesh.vertices_L;
  for (const Triangle& tri : mesh.triangles) {
    for (int k = 0; k < per_triangle; ++k) {
      double u = Uniform(rng, 0, 1);
      double v = Uniform(rng, 0, 1);
      if (u + v > 1.0) std::tie(u, v) = std::make_pair(1.0 - u, 1.0 - v);
      const Vector3d& a = mesh.vertices_L[tri[0]];
      points.push_back(a + u * (mesh.vertices_L[tri[1]] - a) + v * (mesh.vertices_L[tri[2]] - a));
    }
  }
  std::uniform_int_distribution<std::size_t> pick(0, mesh.vertices_L.size() - 1);
  for (std::size_t k = 0; is_convex && k < per_triangle * mesh.triangles.size(); ++k) {
    Eigen::Vector4d w(Uniform(rng, 0, 1), Uniform(rng, 0, 1), Uniform(rng, 0, 1),
                      Uniform(rng, 0, 1));
    w /= w.sum();
    Vector3d p = Vector3d::Zero();
    for (int c = 0; c < 4; ++c) p += w[c] * mesh.vertices_L[pick(rng)];
    points.push_back(p);
  }
  return points;
}

// Number of sampled points outside the union of `shapes`, printing the first few.
int CountOutside(const std::vector<Shape>& shapes, const std::vector<Vector3d>& points,
                 const std::string& what) {
  int outside = 0;
  for (const Vector3d& p : points) {
    if (UnionContains(shapes, p)) continue;
    if (++outside <= 3) {
      std::printf("  %s: point (%.17g, %.17g, %.17g) outside the fit\n", what.c_str(), p.x(),
                  p.y(), p.z());
    }
  }
  return outside;
}

const std::vector<MeshFitOptions>& AllKinds() {
  static const std::vector<MeshFitOptions> kinds{{MeshFitKind::kOneCapsule, 1},
                                                 {MeshFitKind::kCapsuleChain, 1},
                                                 {MeshFitKind::kCapsuleChain, 4},
                                                 {MeshFitKind::kOrientedBox, 1},
                                                 {MeshFitKind::kTighter, 1}};
  return kinds;
}

std::string KindName(const MeshFitOptions& options) {
  switch (options.kind) {
    case MeshFitKind::kOneCapsule: return "one capsule";
    case MeshFitKind::kCapsuleChain: return std::to_string(options.capsule_count) + " capsules";
    case MeshFitKind::kOrientedBox: return "oriented box";
    case MeshFitKind::kTighter: return "tighter";
  }
  return "?";
}

// ---------------------------------------------------------------------------------------------
// Containment over seeded random meshes.

struct NamedMesh {
  std::string name;
  TriangleMesh mesh;
  bool is_convex;
};

std::vector<NamedMesh> RandomBaseMeshes(std::mt19937_64& rng) {
  const Vector3d box_half(Uniform(rng, 0.2, 1), Uniform(rng, 0.2, 1), Uniform(rng, 0.2, 1));
  const Vector3d radii(Uniform(rng, 0.2, 1), Uniform(rng, 0.2, 1), Uniform(rng, 0.2, 1));
  return {
      {"box", BoxMesh(box_half), true},
      {"cylinder", CylinderMesh(Uniform(rng, 0.1, 1), Uniform(rng, 0.1, 3)), true},
      {"ellipsoid", BlobMesh(radii, 12, 16, 0.0, rng), true},
      {"blob", BlobMesh(radii, 10, 14, 0.3, rng), false},
      {"rod", CylinderMesh(0.01, Uniform(rng, 1, 3), 8), true},
      {"flat box", BoxMesh(Vector3d(1, Uniform(rng, 0.5, 1), 1e-4)), true},
      {"bent tube", BentTubeMesh(1.0, Uniform(rng, 0.5, 3), 0.2), false},
      {"L", LShapeMesh(1.0, Uniform(rng, 0.1, 0.4), Uniform(rng, 0.1, 0.5)), false},
  };
}

TEST(MeshFit, EveryFitContainsEveryVertexAndSurfacePointOfRandomMeshes) {
  std::mt19937_64 rng = SeededRng("containment");
  int fits = 0;
  for (int round = 0; round < 12; ++round) {
    for (const NamedMesh& base : RandomBaseMeshes(rng)) {
      const double scale = std::pow(10.0, Uniform(rng, -3, 1));  // 1 mm to 10 m
      const double offset_m = round % 3 == 0 ? 0.0 : std::pow(10.0, Uniform(rng, 0, 3));
      const TriangleMesh mesh = Transformed(base.mesh, RandomPose(rng, offset_m), scale);
      const std::vector<Vector3d> points = SamplePoints(mesh, 4, base.is_convex, rng);
      for (const MeshFitOptions& options : AllKinds()) {
        const MeshFit fit = FitMesh(mesh, options);
        const std::string what = base.name + " x" + std::to_string(scale) + " at " +
                                 std::to_string(offset_m) + " m, " + KindName(options);
        ASSERT_EQ(fit.check.status, MeshStatus::kOk) << what << ": " << fit.check.message;
        ASSERT_FALSE(fit.shapes_L.empty()) << what;
        EXPECT_EQ(CountOutside(fit.shapes_L, points, what), 0) << what;
        ++fits;
      }
    }
  }
  std::printf("  %d fits checked\n", fits);
}

// ---------------------------------------------------------------------------------------------
// Tightness.

TEST(MeshFit, OneCapsuleOfACylinderHasItsRadiusAndLength) {
  std::mt19937_64 rng = SeededRng("cylinder tightness");
  double worst_radius_error = 0.0;
  double worst_length_error = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    const double radius_m = Uniform(rng, 0.01, 0.5);
    const double length_m = Uniform(rng, 3, 10) * radius_m;
    const TriangleMesh mesh =
        Transformed(CylinderMesh(radius_m, length_m), RandomPose(rng, 10.0), 1.0);
    const MeshFit fit = FitMesh(mesh, MeshFitOptions{});
    ASSERT_EQ(fit.shapes_L.size(), 1u);
    const Capsule& capsule = std::get<Capsule>(fit.shapes_L.front());
    const double length_error = (capsule.p1_W - capsule.p0_W).norm() / length_m - 1.0;
    EXPECT_NEAR(capsule.radius_m, radius_m, 0.01 * radius_m) << "trial " << trial;
    EXPECT_NEAR(length_error, 0.0, 0.01) << "trial " << trial;
    worst_radius_error = std::max(worst_radius_error, std::abs(capsule.radius_m / radius_m - 1));
    worst_length_error = std::max(worst_length_error, std::abs(length_error));
  }
  std::printf("  worst relative error: radius %.3g, length %.3g\n", worst_radius_error,
              worst_length_error);
}

TEST(MeshFit, OrientedBoxOfABoxIsTheBox) {
  std::mt19937_64 rng = SeededRng("box tightness");
  for (int trial = 0; trial < 20; ++trial) {
    const Vector3d half_m = Vector3d(0.3, 0.2, 0.1) * Uniform(rng, 0.01, 10);
    const Eigen::Isometry3d X = RandomPose(rng, 100.0);
    const MeshFit fit =
        FitMesh(Transformed(BoxMesh(half_m), X, 1.0), {MeshFitKind::kOrientedBox, 1});
    ASSERT_EQ(fit.shapes_L.size(), 1u);
    const Box& box = std::get<Box>(fit.shapes_L.front());
    // Rounding: the margin, 1e-9 of (diagonal + |offset|) <= ~200 m, and a few eps of that.
    const double tol_m = 1e-8 * (2 * half_m.norm() + X.translation().norm());
    Vector3d fitted = box.half_extents_m;
    std::sort(fitted.data(), fitted.data() + 3, std::greater<double>());
    EXPECT_LT((fitted - half_m).cwiseAbs().maxCoeff(), tol_m) << "trial " << trial;
    EXPECT_LT((box.X_WB.translation() - X.translation()).norm(), tol_m) << "trial " << trial;
    // Each half extent grows by at most tol_m.
    EXPECT_GE(fit.excess_ratio, 1.0) << "trial " << trial;
    EXPECT_LE(fit.excess_ratio, (1.0 + tol_m / half_m.array()).prod()) << "trial " << trial;
  }
}

// The tighter of one capsule and one box: a box for a box (a capsule around it is 2.5 times as
// large), a capsule for a long cylinder (a box around it 4 / pi times), each equal to that
// kind's own fit.
TEST(MeshFit, TighterKeepsTheBoxOfABoxAndTheCapsuleOfACylinder) {
  std::mt19937_64 rng = SeededRng("tighter");
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Isometry3d X = RandomPose(rng, 10.0);
    const TriangleMesh box = Transformed(BoxMesh(Vector3d(0.3, 0.2, 0.1)), X, 1.0);
    const MeshFit box_fit = FitMesh(box, {MeshFitKind::kTighter, 1});
    ASSERT_EQ(box_fit.shapes_L.size(), 1u);
    ASSERT_TRUE(std::holds_alternative<Box>(box_fit.shapes_L[0])) << "trial " << trial;
    EXPECT_EQ(box_fit.fitted_volume_m3,
              FitMesh(box, {MeshFitKind::kOrientedBox, 1}).fitted_volume_m3);
    EXPECT_LT(box_fit.fitted_volume_m3, FitMesh(box, {}).fitted_volume_m3);
    const TriangleMesh rod = Transformed(CylinderMesh(0.05, Uniform(rng, 0.3, 1.0)), X, 1.0);
    const MeshFit rod_fit = FitMesh(rod, {MeshFitKind::kTighter, 1});
    ASSERT_EQ(rod_fit.shapes_L.size(), 1u);
    ASSERT_TRUE(std::holds_alternative<Capsule>(rod_fit.shapes_L[0])) << "trial " << trial;
    EXPECT_EQ(rod_fit.fitted_volume_m3, FitMesh(rod, {}).fitted_volume_m3);
    EXPECT_LT(rod_fit.fitted_volume_m3,
              FitMesh(rod, {MeshFitKind::kOrientedBox, 1}).fitted_volume_m3);
  }
}

TEST(MeshFit, CapsuleChainsOfBentMeshesAreSmallerThanOneCapsule) {
  const std::vector<NamedMesh> meshes{{"L", LShapeMesh(1.0, 0.2, 0.2), false},
                                      {"banana", BentTubeMesh(1.0, 1.5, 0.15), false},
                                      {"half ring", BentTubeMesh(0.5, kPi, 0.05), false}};
  for (const NamedMesh& named : meshes) {
    const double one_m3 = FitMesh(named.mesh, MeshFitOptions{}).fitted_volume_m3;
    for (const int count : {2, 3, 4, 8}) {
      const MeshFit chain = FitMesh(named.mesh, {MeshFitKind::kCapsuleChain, count});
      std::printf("  %s: %d capsules %.4g m^3, one capsule %.4g m^3, mesh %.4g m^3\n",
                  named.name.c_str(), count, chain.fitted_volume_m3, one_m3,
                  chain.mesh_volume_m3);
      EXPECT_LE(chain.fitted_volume_m3, one_m3) << named.name << ", " << count << " capsules";
    }
  }
}

// The points of a 64^3 grid over the shapes' box that `chain` holds over those `one` holds:
// the ratio of the unions' volumes, to a fraction of a per cent for these sizes.
double UnionVolumeRatio(const std::vector<Shape>& chain, const std::vector<Shape>& one) {
  Eigen::AlignedBox3d box;
  for (const std::vector<Shape>* shapes : {&chain, &one}) {
    for (const Shape& shape : *shapes) {
      const Capsule& c = std::get<Capsule>(shape);
      for (const Vector3d& end : {c.p0_W, c.p1_W}) {
        box.extend(end - Vector3d::Constant(c.radius_m));
        box.extend(end + Vector3d::Constant(c.radius_m));
      }
    }
  }
  constexpr int kPoints = 64;
  const Vector3d cell = box.sizes() / kPoints;
  auto holds = [](const std::vector<Shape>& shapes, const Vector3d& p) {
    return std::any_of(shapes.begin(), shapes.end(),
                       [&](const Shape& shape) { return ShapeContains(shape, p); });
  };
  double in_chain = 0.0;
  double in_one = 0.0;
  for (int i = 0; i < kPoints; ++i) {
    for (int j = 0; j < kPoints; ++j) {
      for (int k = 0; k < kPoints; ++k) {
        const Vector3d p = box.min() + cell.cwiseProduct(Vector3d(i + 0.5, j + 0.5, k + 0.5));
        in_chain += holds(chain, p);
        in_one += holds(one, p);
      }
    }
  }
  return in_chain / in_one;
}

TEST(MeshFit, CapsuleChainsAreNoLargerThanOneCapsule) {
  // Slabs squat against the link's width (a KUKA iiwa's wrist): each slab's own smallest capsule
  // lies across the link and sticks out of its sides, where capsules along the link overlap
  // their neighbours inside the one capsule. A ball (an xArm's round wrist, a knob) is one
  // capsule, a sphere: any chain of slabs along it is larger, so it stays one.
  std::mt19937_64 rng(29);
  const std::vector<NamedMesh> meshes{
      {"round link", CylinderMesh(0.065, 0.2), false},
      {"tapered link", TubeMesh([](double s) { return Vector3d(0, 0, 0.25 * s); },
                                [](double s, double) { return 0.07 - 0.03 * s; }, 9, 24),
       false},
      {"ball", BlobMesh(Vector3d(0.06, 0.06, 0.06), 12, 24, 0.0, rng), false}};
  for (const NamedMesh& named : meshes) {
    for (int trial = 0; trial < 2; ++trial) {
      const TriangleMesh mesh = Transformed(named.mesh, RandomPose(rng, 0.5), 1.0);
      const MeshFit one = FitMesh(mesh, MeshFitOptions{});
      for (const int count : {2, 3, 4, 8}) {
        const MeshFit chain = FitMesh(mesh, {MeshFitKind::kCapsuleChain, count});
        const double ratio = UnionVolumeRatio(chain.shapes_L, one.shapes_L);
        std::printf("  %s, trial %d: %zu of %d capsules' union %.4f of the one capsule's\n",
                    named.name.c_str(), trial, chain.shapes_L.size(), count, ratio);
        EXPECT_LE(ratio, 1.0) << named.name << ", trial " << trial << ", " << count;
        if (named.name == "ball") {
          EXPECT_EQ(chain.shapes_L.size(), 1u) << "trial " << trial << ", " << count;
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Refusals.

void ExpectRefused(const TriangleMesh& mesh, MeshStatus expected, const char* what) {
  EXPECT_EQ(CheckMesh(mesh).status, expected) << what;
  for (const MeshFitOptions& options : AllKinds()) {
    const MeshFit fit = FitMesh(mesh, options);
    EXPECT_EQ(fit.check.status, expected) << what << ", " << KindName(options);
    EXPECT_FALSE(fit.check.message.empty()) << what;
    EXPECT_TRUE(fit.shapes_L.empty()) << what;
  }
  std::printf("  %s: %s: %s\n", what, MeshStatusName(expected), CheckMesh(mesh).message.c_str());
}

TEST(MeshFit, DegenerateMeshesAreRefusedWithTheirReason) {
  ExpectRefused(TriangleMesh{}, MeshStatus::kEmpty, "empty");
  ExpectRefused(TriangleMesh{{Vector3d(0, 0, 0), Vector3d(1, 0, 0)}, {}}, MeshStatus::kEmpty,
                "no triangle");
  ExpectRefused(TriangleMesh{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}},
                MeshStatus::kNoVolume, "flat square");
  ExpectRefused(TriangleMesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}},
                MeshStatus::kNoVolume, "one triangle");
  ExpectRefused(TriangleMesh{{{0, 0, 0}, {1, 1, 1}, {3, 3, 3}, {2, 2, 2}}, {{0, 1, 2}, {1, 3, 2}}},
                MeshStatus::kNoVolume, "collinear points");
  ExpectRefused(TriangleMesh{{{0.5, -2, 7}}, {{0, 0, 0}}}, MeshStatus::kNoVolume, "single point");
  // A flat square lifted far from the origin and tilted: flat relative to its own size.
  ExpectRefused(
      Transformed(
          TriangleMesh{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}},
          Eigen::Isometry3d(Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()))
              .pretranslate(Vector3d(900, -900, 500)),
          0.01),
      MeshStatus::kNoVolume, "tilted flat square far away");
  TriangleMesh nan_vertex = BoxMesh(Vector3d(1, 1, 1));
  nan_vertex.vertices_L[5].y() = std::numeric_limits<double>::quiet_NaN();
  ExpectRefused(nan_vertex, MeshStatus::kNonFiniteVertex, "NaN vertex");
  TriangleMesh inf_vertex = BoxMesh(Vector3d(1, 1, 1));
  inf_vertex.vertices_L[2].x() = -std::numeric_limits<double>::infinity();
  ExpectRefused(inf_vertex, MeshStatus::kNonFiniteVertex, "infinite vertex");
  TriangleMesh bad_index = BoxMesh(Vector3d(1, 1, 1));
  bad_index.triangles[7][1] = 8;
  ExpectRefused(bad_index, MeshStatus::kIndexOutOfRange, "bad index");
  ExpectRefused(BoxMesh(Vector3d(600, 600, 1)), MeshStatus::kTooLarge, "1.2 km box");
  ExpectRefused(Transformed(BoxMesh(Vector3d(1, 1, 1)),
                            Eigen::Isometry3d(Eigen::Translation3d(2e4, 0, 0)), 1.0),
                MeshStatus::kTooLarge, "box 20 km from its link");
  ExpectRefused(BoxMesh(Vector3d(1e-7, 1e-7, 1e-7)), MeshStatus::kTooSmall, "0.2 um box");
}

TEST(MeshFit, ThinButSolidMeshesAndOutOfRangeOptions) {
  // 1e-4 of its size thick: above kMeshMinThicknessRel, so a (flat-ish) solid.
  const TriangleMesh plate = BoxMesh(Vector3d(1, 1, 1e-4));
  EXPECT_EQ(CheckMesh(plate).status, MeshStatus::kOk) << CheckMesh(plate).message;
  EXPECT_EQ(CheckMesh(BoxMesh(Vector3d(1e-6, 1e-6, 1e-6))).status, MeshStatus::kOk);
  for (const int count : {0, -1, kMeshFitMaxCapsules + 1}) {
    const MeshFit fit = FitMesh(plate, {MeshFitKind::kCapsuleChain, count});
    EXPECT_EQ(fit.check.status, MeshStatus::kBadOptions) << count;
    EXPECT_TRUE(fit.shapes_L.empty());
  }
  EXPECT_EQ(FitMesh(plate, {MeshFitKind::kCapsuleChain, kMeshFitMaxCapsules}).check.status,
            MeshStatus::kOk);
}

// ---------------------------------------------------------------------------------------------
// Volumes.

TEST(MeshFit, EnclosedVolumeOfClosedMeshesAndNaNForOpenOnes) {
  const TriangleMesh box = BoxMesh(Vector3d(0.5, 0.25, 0.125));  // 1 x 0.5 x 0.25 m
  const MeshFit box_fit = FitMesh(Transformed(box, Eigen::Isometry3d::Identity(), 1.0), {});
  EXPECT_TRUE(box_fit.is_mesh_closed);
  EXPECT_NEAR(box_fit.mesh_volume_m3, 0.125, 1e-15);
  EXPECT_NEAR(box_fit.excess_ratio, box_fit.fitted_volume_m3 / 0.125, 1e-12);
  EXPECT_GT(box_fit.excess_ratio, 1.0);
  // A 32-gon prism: 32 triangles of area r^2 sin(2 pi / 32) / 2, times the length.
  const MeshFit cylinder = FitMesh(CylinderMesh(0.1, 2.0), {});
  EXPECT_NEAR(cylinder.mesh_volume_m3, 16 * 0.01 * std::sin(2 * kPi / 32) * 2.0, 1e-15);
  // Corners repeated once per triangle (as STL files store them) still close the surface.
  TriangleMesh unshared;
  for (const Triangle& tri : box.triangles) {
    const auto base = static_cast<std::uint32_t>(unshared.vertices_L.size());
    for (const std::uint32_t index : tri) unshared.vertices_L.push_back(box.vertices_L[index]);
    unshared.triangles.push_back({base, base + 1, base + 2});
  }
  EXPECT_TRUE(FitMesh(unshared, {}).is_mesh_closed);
  EXPECT_NEAR(FitMesh(unshared, {}).mesh_volume_m3, 0.125, 1e-15);
  // Two closed boxes sharing an edge (exported parts often do): still closed, their volumes add.
  TriangleMesh shells = box;
  for (const Vector3d& p : box.vertices_L) shells.vertices_L.push_back(p + Vector3d(1, 0.5, 0));
  for (const Triangle& tri : box.triangles) {
    shells.triangles.push_back({tri[0] + 8, tri[1] + 8, tri[2] + 8});
  }
  EXPECT_TRUE(IsClosedMesh(shells));
  EXPECT_NEAR(EnclosedVolume_m3(shells), 0.25, 1e-15);
  TriangleMesh open = box;
  open.triangles.pop_back();
  TriangleMesh flipped = box;
  std::swap(flipped.triangles[3][0], flipped.triangles[3][1]);
  for (const TriangleMesh& mesh : {open, flipped}) {
    const MeshFit fit = FitMesh(mesh, {});
    EXPECT_FALSE(fit.is_mesh_closed);
    EXPECT_TRUE(std::isnan(fit.mesh_volume_m3));
    EXPECT_TRUE(std::isnan(fit.excess_ratio));
    EXPECT_EQ(fit.shapes_L.size(), 1u);  // still fitted: the vertices are what is enclosed
  }
}

// ---------------------------------------------------------------------------------------------
// Cache key.

TEST(MeshFit, HashIsStableAndChangesWithContentAndOptions) {
  const TriangleMesh box = BoxMesh(Vector3d(0.5, 0.25, 0.125));
  const MeshFitOptions capsule{};
  const std::uint64_t key = MeshFitHash(box, capsule);
  EXPECT_EQ(key, MeshFitHash(BoxMesh(Vector3d(0.5, 0.25, 0.125)), capsule));
  // Pinned: a cache written by one run or build is read by the next, so the key of a fixed
  // input must never change unless kMeshFitAlgorithmVersion does (then update this value).
  EXPECT_EQ(key, 0xa13f164b187f9ac2u) << std::hex << "key 0x" << key;
  TriangleMesh nudged = box;
  nudged.vertices_L[3].z() = std::nextafter(nudged.vertices_L[3].z(), 1.0);
  TriangleMesh reindexed = box;
  reindexed.triangles[4] = {reindexed.triangles[4][1], reindexed.triangles[4][2],
                            reindexed.triangles[4][0]};
  TriangleMesh shorter = box;
  shorter.triangles.pop_back();
  TriangleMesh negative_zero = box;
  negative_zero.vertices_L.push_back(Vector3d(0, 0, 0));
  TriangleMesh positive_zero = negative_zero;
  negative_zero.vertices_L.back().x() = -0.0;
  std::vector<std::uint64_t> keys{key,
                                  MeshFitHash(nudged, capsule),
                                  MeshFitHash(reindexed, capsule),
                                  MeshFitHash(shorter, capsule),
                                  MeshFitHash(negative_zero, capsule),
                                  MeshFitHash(positive_zero, capsule),
                                  MeshFitHash(box, {MeshFitKind::kOrientedBox, 1}),
                                  MeshFitHash(box, {MeshFitKind::kCapsuleChain, 3}),
                                  MeshFitHash(box, {MeshFitKind::kCapsuleChain, 4})};
  std::sort(keys.begin(), keys.end());
  EXPECT_EQ(std::adjacent_find(keys.begin(), keys.end()), keys.end()) << "two keys collide";
  // The capsule count only changes a chain's result, so it is not part of the others' key.
  EXPECT_EQ(key, MeshFitHash(box, {MeshFitKind::kOneCapsule, 7}));
}

// ---------------------------------------------------------------------------------------------
// Time (printed, not asserted).

TEST(MeshFit, TimeOfA10kTriangleMesh) {
  std::mt19937_64 rng = SeededRng("timing");
  const TriangleMesh mesh = Transformed(
      BlobMesh(Vector3d(0.1, 0.15, 0.4), 51, 100, 0.05, rng), RandomPose(rng, 1.0), 1.0);
  std::printf("  %zu triangles, %zu vertices\n", mesh.triangles.size(), mesh.vertices_L.size());
  ASSERT_GE(mesh.triangles.size(), 10000u);
  for (const MeshFitOptions& options : AllKinds()) {
    const auto start = std::chrono::steady_clock::now();
    const MeshFit fit = FitMesh(mesh, options);
    const std::chrono::duration<double, std::milli> elapsed =
        std::chrono::steady_clock::now() - start;
    ASSERT_EQ(fit.check.status, MeshStatus::kOk);
    std::printf("  %s: %.2f ms, excess ratio %.3f\n", KindName(options).c_str(), elapsed.count(),
                fit.excess_ratio);
  }
}

}  // namespace
}  // namespace arm_collision_monitor
