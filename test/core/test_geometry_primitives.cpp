// geometry/primitives' transforms and constructors: TransformShape (identity, composition
// X_AB * X_BC, rigid-transform invariance of the distances between capsules and boxes),
// PoseFromXyzRpy (the URDF convention, against hand-derived rotations and against Eigen's
// AngleAxis composition Rz(yaw) Ry(pitch) Rx(roll)), Aabb::Cube and Aabb::Nowhere. Seeded: the
// seed is printed (ACM_PRIMITIVES_SEED=<n> overrides it).
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "test_geometry_shapes.h"

namespace arm_collision_monitor {
namespace {

using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kEps = std::numeric_limits<double>::epsilon() / 2.0;  // 2^-53
constexpr int kCases = 2000;
// Rounding of one rigid transform applied to a point or composed with a pose: a few ulps of the
// largest coordinate involved (three products and three sums per coordinate).
constexpr double kTransformUlps = 8.0;
// Rounding of a rotation built from three angle-axis rotations (quaternion products, then the
// conversion to a matrix), and of one rotation applied to a unit vector: a few ulps per step;
// seeds 1..200 all pass, the worst seen being 17 ulps (orthonormality, seed 2).
constexpr double kRotationUlps = 64.0;
// Poses are drawn with translations up to this far from the origin (m), shapes of up to 1 m.
constexpr double kMaxTranslation_m = 10.0;

std::uint64_t Seed() {
  const char* env = std::getenv("ACM_PRIMITIVES_SEED");
  return env != nullptr ? std::strtoull(env, nullptr, 10) : 20261123u;
}

class Random {
 public:
  explicit Random(std::uint64_t seed) : rng_(seed) {}
  double Uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng_); }
  Vector3d Vector(double half_range) {
    return Vector3d(Uniform(-half_range, half_range), Uniform(-half_range, half_range),
                    Uniform(-half_range, half_range));
  }
  Vector3d UnitVector() {
    Vector3d v;
    do {
      v = Vector(1.0);
    } while (v.norm() < 0.1 || v.norm() > 1.0);
    return v.normalized();
  }
  // A rigid transform: rotation about a random axis by a random angle, random translation.
  Isometry3d Pose() {
    Isometry3d X = Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(Uniform(-M_PI, M_PI), UnitVector()).toRotationMatrix();
    X.translation() = Vector(kMaxTranslation_m);
    return X;
  }
  Capsule MakeRandomCapsule() {
    const Vector3d p0 = Vector(1.0);
    return MakeCapsule(p0, p0 + Vector(0.5), Uniform(0.0, 0.2));
  }
  Box MakeRandomBox() {
    Box b;
    b.X_WB = Pose();
    b.X_WB.translation() = Vector(1.0);
    b.half_extents_m = Vector3d(Uniform(0.0, 0.5), Uniform(0.0, 0.5), Uniform(0.0, 0.5));
    return b;
  }
  Shape MakeRandomShape() {
    if (Uniform(0.0, 1.0) < 0.5) return MakeRandomCapsule();
    return MakeRandomBox();
  }

 private:
  std::mt19937_64 rng_;
};

class PrimitivesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    seed_ = Seed();
    std::printf("[primitives] seed %" PRIu64 " (ACM_PRIMITIVES_SEED)\n", seed_);
  }
  std::uint64_t seed_ = 0;
};

// Largest |coordinate| of a shape's defining points (segment ends; box centre and corners).
double CoordinateScale(const Shape& shape) {
  const Aabb box = ComputeAabb(shape);
  return std::max(box.min_W.cwiseAbs().maxCoeff(), box.max_W.cwiseAbs().maxCoeff());
}

// Asserts that two shapes are the same kind and coincide within `tol_m` (poses compared as
// matrices: a rotation entry's error scaled by a unit length).
void ExpectShapesNear(const Shape& a, const Shape& b, double tol_m, const char* what) {
  ASSERT_EQ(a.index(), b.index()) << what;
  if (const auto* ca = std::get_if<Capsule>(&a)) {
    const Capsule& cb = std::get<Capsule>(b);
    EXPECT_LE((ca->p0_W - cb.p0_W).norm(), tol_m) << what;
    EXPECT_LE((ca->p1_W - cb.p1_W).norm(), tol_m) << what;
    EXPECT_EQ(ca->radius_m, cb.radius_m) << what;
    return;
  }
  const Box& ba = std::get<Box>(a);
  const Box& bb = std::get<Box>(b);
  EXPECT_LE((ba.X_WB.translation() - bb.X_WB.translation()).norm(), tol_m) << what;
  EXPECT_LE((ba.X_WB.linear() - bb.X_WB.linear()).cwiseAbs().maxCoeff(), tol_m) << what;
  EXPECT_EQ(ba.half_extents_m, bb.half_extents_m) << what;
}

TEST_F(PrimitivesTest, TransformShapeByIdentityIsExact) {
  Random random(seed_);
  for (int i = 0; i < kCases; ++i) {
    const Shape shape = random.MakeRandomShape();
    const Shape moved = TransformShape(Isometry3d::Identity(), shape);
    ExpectShapesNear(moved, shape, 0.0, "identity");
    if (HasFailure()) FAIL() << "case " << i << ", seed " << seed_;
  }
}

TEST_F(PrimitivesTest, TransformShapeMovesCapsuleEndsAndBoxPose) {
  Random random(seed_);
  for (int i = 0; i < kCases; ++i) {
    const Isometry3d X_WL = random.Pose();
    const Capsule c_L = random.MakeRandomCapsule();
    const Capsule c_W = std::get<Capsule>(TransformShape(X_WL, c_L));
    EXPECT_EQ(c_W.p0_W, X_WL * c_L.p0_W);
    EXPECT_EQ(c_W.p1_W, X_WL * c_L.p1_W);
    EXPECT_EQ(c_W.radius_m, c_L.radius_m);
    const Box b_L = random.MakeRandomBox();
    const Box b_W = std::get<Box>(TransformShape(X_WL, b_L));
    EXPECT_TRUE(b_W.X_WB.matrix() == (X_WL * b_L.X_WB).matrix());
    EXPECT_EQ(b_W.half_extents_m, b_L.half_extents_m);
    if (HasFailure()) FAIL() << "case " << i << ", seed " << seed_;
  }
}

TEST_F(PrimitivesTest, TransformShapeComposes) {
  Random random(seed_);
  for (int i = 0; i < kCases; ++i) {
    const Isometry3d X_AB = random.Pose();
    const Isometry3d X_BC = random.Pose();
    const Shape shape_C = random.MakeRandomShape();
    const Shape twice = TransformShape(X_AB, TransformShape(X_BC, shape_C));
    const Shape once = TransformShape(X_AB * X_BC, shape_C);
    // Two roundings of coordinates up to ~2 kMaxTranslation_m + 2 m on either side.
    const double scale_m = 2.0 * kMaxTranslation_m + 2.0;
    ExpectShapesNear(twice, once, 4.0 * kTransformUlps * kEps * scale_m, "composition");
    if (HasFailure()) FAIL() << "case " << i << ", seed " << seed_;
  }
}

TEST_F(PrimitivesTest, DistancesAreInvariantUnderRigidTransforms) {
  Random random(seed_);
  for (int i = 0; i < kCases; ++i) {
    const Shape a_L = random.MakeRandomShape();
    const Shape b_L = random.MakeRandomShape();
    const Isometry3d X_WL = random.Pose();
    const Shape a_W = TransformShape(X_WL, a_L);
    const Shape b_W = TransformShape(X_WL, b_L);
    const double d_L = ShapeDistance(a_L, b_L).distance_m;
    const double d_W = ShapeDistance(a_W, b_W).distance_m;
    // Both distances within their bound (S <= the largest coordinate scale, doubled for the
    // diagonals), plus the rounding of the transformed shapes themselves.
    const double scale_m = 2.0 * std::max({CoordinateScale(a_W), CoordinateScale(b_W),
                                           CoordinateScale(a_L), CoordinateScale(b_L)});
    const double tol_m = (2.0 * kBoxDistanceErrorUlps + 2.0 * kTransformUlps) * kEps * scale_m;
    EXPECT_NEAR(d_W, d_L, tol_m) << "case " << i << ", seed " << seed_;
    if (HasFailure()) FAIL() << "case " << i << ", seed " << seed_;
  }
}

// Hand-derived: the URDF applies roll about the fixed x axis first, then pitch about fixed y,
// then yaw about fixed z.
TEST(PoseFromXyzRpy, SingleAxisQuarterTurns) {
  const Vector3d p(1.0, -2.0, 3.0);
  const double h = M_PI / 2.0;
  constexpr double kTol = 1e-15;
  // Roll +90 deg about x: y -> z, z -> -y.
  Isometry3d X = PoseFromXyzRpy(p, Vector3d(h, 0.0, 0.0));
  EXPECT_TRUE((X.linear() * Vector3d::UnitY()).isApprox(Vector3d::UnitZ(), kTol));
  EXPECT_TRUE((X.linear() * Vector3d::UnitZ()).isApprox(-Vector3d::UnitY(), kTol));
  EXPECT_EQ(X.translation(), p);
  // Pitch +90 deg about y: z -> x, x -> -z.
  X = PoseFromXyzRpy(p, Vector3d(0.0, h, 0.0));
  EXPECT_TRUE((X.linear() * Vector3d::UnitZ()).isApprox(Vector3d::UnitX(), kTol));
  EXPECT_TRUE((X.linear() * Vector3d::UnitX()).isApprox(-Vector3d::UnitZ(), kTol));
  // Yaw +90 deg about z: x -> y, y -> -x.
  X = PoseFromXyzRpy(p, Vector3d(0.0, 0.0, h));
  EXPECT_TRUE((X.linear() * Vector3d::UnitX()).isApprox(Vector3d::UnitY(), kTol));
  EXPECT_TRUE((X.linear() * Vector3d::UnitY()).isApprox(-Vector3d::UnitX(), kTol));
}

TEST(PoseFromXyzRpy, RollThenYawAboutFixedAxes) {
  // Roll 90 then yaw 90 (fixed axes): x -> x -> y, y -> z -> z, z -> -y -> x. The other order
  // (yaw first) would send x to y then to z instead.
  const double h = M_PI / 2.0;
  const Matrix3d R = PoseFromXyzRpy(Vector3d::Zero(), Vector3d(h, 0.0, h)).linear();
  Matrix3d expected;
  expected << 0, 0, 1,  //
      1, 0, 0,          //
      0, 1, 0;
  EXPECT_LE((R - expected).cwiseAbs().maxCoeff(), 1e-15) << R;
}

TEST_F(PrimitivesTest, PoseFromXyzRpyMatchesFixedAxisComposition) {
  Random random(seed_);
  for (int i = 0; i < kCases; ++i) {
    const Vector3d p = random.Vector(kMaxTranslation_m);
    const Vector3d rpy(random.Uniform(-M_PI, M_PI), random.Uniform(-M_PI / 2, M_PI / 2),
                       random.Uniform(-M_PI, M_PI));
    const Isometry3d X = PoseFromXyzRpy(p, rpy);
    const Matrix3d expected = (Eigen::AngleAxisd(rpy.z(), Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(rpy.y(), Vector3d::UnitY()) *
                               Eigen::AngleAxisd(rpy.x(), Vector3d::UnitX()))
                                  .toRotationMatrix();
    EXPECT_LE((X.linear() - expected).cwiseAbs().maxCoeff(), kRotationUlps * kEps);
    EXPECT_EQ(X.translation(), p);
    // The same rotation, applied to a vector one fixed axis at a time: roll, pitch, yaw.
    const Vector3d v = random.Vector(1.0);
    const Vector3d v_rolled = Eigen::AngleAxisd(rpy.x(), Vector3d::UnitX()) * v;
    const Vector3d v_pitched = Eigen::AngleAxisd(rpy.y(), Vector3d::UnitY()) * v_rolled;
    const Vector3d v_yawed = Eigen::AngleAxisd(rpy.z(), Vector3d::UnitZ()) * v_pitched;
    EXPECT_LE((X.linear() * v - v_yawed).norm(), 2.0 * kRotationUlps * kEps);
    // A rotation: orthonormal, determinant +1; bottom row of the pose 0 0 0 1.
    EXPECT_LE((X.linear().transpose() * X.linear() - Matrix3d::Identity()).cwiseAbs().maxCoeff(),
              kRotationUlps * kEps);
    EXPECT_NEAR(X.linear().determinant(), 1.0, kRotationUlps * kEps);
    EXPECT_EQ(X.matrix().row(3), Eigen::RowVector4d(0, 0, 0, 1));
    if (HasFailure()) FAIL() << "case " << i << ", rpy " << rpy.transpose() << ", seed " << seed_;
  }
}

TEST(AabbCube, HandCase) {
  const Aabb cube = Aabb::Cube(Vector3d(1.0, 2.0, 3.0), 2.0);
  EXPECT_EQ(cube.min_W, Vector3d(0.0, 1.0, 2.0));
  EXPECT_EQ(cube.max_W, Vector3d(2.0, 3.0, 4.0));
}

TEST(AabbNowhere, OverlapsNothingNotEvenItself) {
  const Aabb nowhere = Aabb::Nowhere();
  const double inf = std::numeric_limits<double>::infinity();
  const Aabb everywhere{Vector3d::Constant(-inf), Vector3d::Constant(inf)};
  EXPECT_FALSE(nowhere.Overlaps(everywhere));
  EXPECT_FALSE(everywhere.Overlaps(nowhere));
  EXPECT_FALSE(nowhere.Overlaps(nowhere));
  EXPECT_FALSE(everywhere.Contains(nowhere));
  EXPECT_TRUE(everywhere.Overlaps(Aabb::Cube(Vector3d::Zero(), 1.0)));
}

TEST_F(PrimitivesTest, CubeHasItsCentreAndEdge) {
  Random random(seed_);
  for (int i = 0; i < kCases; ++i) {
    const Vector3d centre_W = random.Vector(kMaxTranslation_m);
    const double edge_m = random.Uniform(1e-3, 5.0);
    const Aabb cube = Aabb::Cube(centre_W, edge_m);
    const double tol_m = 4.0 * kEps * (kMaxTranslation_m + edge_m);
    EXPECT_LE((0.5 * (cube.min_W + cube.max_W) - centre_W).cwiseAbs().maxCoeff(), tol_m);
    EXPECT_LE(((cube.max_W - cube.min_W).array() - edge_m).abs().maxCoeff(), tol_m);
    EXPECT_TRUE(cube.Contains(Aabb{centre_W, centre_W}));
    if (HasFailure()) FAIL() << "case " << i << ", seed " << seed_;
  }
}

}  // namespace
}  // namespace arm_collision_monitor
