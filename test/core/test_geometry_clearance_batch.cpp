// The batched float clearance bounds (geometry/clearance_batch.h) against the exact double
// distance (geometry/distance.h): no bound may exceed the exact distance, so the float test never
// calls a pair clear whose exact distance is at or below its threshold. Random pairs of every
// type, and adversarial families built at a known distance (touching to 1 cm; near the origin
// and up to 10 km from it; spheres as zero-length capsules; boxes of zero thickness). Seeded
// (kSeed, printed); the worst observed bound, in units of the margin, is printed per family.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/clearance_batch.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "test_geometry_shapes.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint64_t kSeed = 20261124;
constexpr int kCasesPerFamily = 4000;
constexpr double kFloatUnitRoundoff = 5.9604644775390625e-8;  // 2^-24
constexpr double kDoubleUnitRoundoff = 1.1102230246251565e-16;  // 2^-53

using Rng = std::mt19937_64;

double Uniform(Rng* rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(*rng);
}

Eigen::Vector3d RandomPoint(Rng* rng, double half_edge_m) {
  return {Uniform(rng, -half_edge_m, half_edge_m), Uniform(rng, -half_edge_m, half_edge_m),
          Uniform(rng, -half_edge_m, half_edge_m)};
}

Eigen::Vector3d RandomUnit(Rng* rng) {
  std::normal_distribution<double> normal;
  Eigen::Vector3d v(normal(*rng), normal(*rng), normal(*rng));
  return v.norm() > 1e-6 ? v.normalized() : Eigen::Vector3d::UnitX();
}

Eigen::Matrix3d RandomRotation(Rng* rng) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(*rng), normal(*rng), normal(*rng), normal(*rng));
  if (q.norm() < 1e-6) q = Eigen::Quaterniond::Identity();
  return q.normalized().toRotationMatrix();
}

Box MakeBox(const Eigen::Vector3d& centre_W, const Eigen::Matrix3d& R_WB,
            const Eigen::Vector3d& half_extents_m) {
  Box box;
  box.X_WB.linear() = R_WB;
  box.X_WB.translation() = centre_W;
  box.half_extents_m = half_extents_m;
  return box;
}

FloatPrimitive ToFloat(const Shape& shape_W) {
  FloatPrimitive f;
  ToFloatPrimitive(shape_W, &f);
  return f;
}

/// The length scale of a pair as the margin counts it (constants.h), in double.
double MarginScale_m(const FloatPrimitive& a, const FloatPrimitive& b) {
  double s = 0.0;
  for (const FloatPrimitive* p : {&a, &b}) {
    for (int k = 0; k < 3; ++k) s += std::abs(p->c_W[k]) + p->half_m[k];
    s += p->radius_m;
  }
  return s;
}

/// The bound of each pair, one batch for all (several blocks and a partial one).
std::vector<double> Bounds(const std::vector<std::pair<Shape, Shape>>& pairs,
                           std::vector<FloatPrimitive>* floats) {
  floats->clear();
  std::vector<PrimitiveId> a, b;
  for (const auto& [sa, sb] : pairs) {
    a.push_back(static_cast<PrimitiveId>(floats->size()));
    floats->push_back(ToFloat(sa));
    b.push_back(static_cast<PrimitiveId>(floats->size()));
    floats->push_back(ToFloat(sb));
  }
  std::vector<double> bounds(pairs.size());
  ComputeClearanceLowerBounds(floats->data(), a.data(), b.data(), pairs.size(), bounds.data());
  return bounds;
}

/// Checks every bound against the exact distance; returns the worst (bound - distance) in units
/// of the pair's margin (negative: below the distance) and counts the settled pairs (bound > 0).
struct FamilyResult {
  double worst_in_margins = -std::numeric_limits<double>::infinity();
  int positive = 0;
  int separated = 0;
};

FamilyResult CheckFamily(const std::string& family,
                         const std::vector<std::pair<Shape, Shape>>& pairs) {
  std::vector<FloatPrimitive> floats;
  const std::vector<double> bounds = Bounds(pairs, &floats);
  FamilyResult result;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const double exact_m = ShapeDistance(pairs[k].first, pairs[k].second).distance_m;
    const double scale_m = MarginScale_m(floats[2 * k], floats[2 * k + 1]);
    // The exact routine's own error bound (distance.h), far below the float margin.
    const double exact_error_m = kBoxDistanceErrorUlps * kDoubleUnitRoundoff * 4.0 * scale_m;
    EXPECT_LE(bounds[k], exact_m + exact_error_m)
        << family << " pair " << k << " (seed " << kSeed << "): float bound " << bounds[k]
        << " m above the exact distance " << exact_m << " m";
    const double margin_m = kClearanceBatchMarginUlps * kFloatUnitRoundoff * scale_m;
    result.worst_in_margins = std::max(result.worst_in_margins, (bounds[k] - exact_m) / margin_m);
    result.positive += bounds[k] > 0.0;
    result.separated += exact_m > 0.0;
  }
  std::printf("[clearance] %-28s seed %llu: %zu pairs, worst (bound - distance) = %+.3f "
              "margins, bound > 0 for %d of %d separated\n",
              family.c_str(), static_cast<unsigned long long>(kSeed), pairs.size(),
              result.worst_in_margins, result.positive, result.separated);
  return result;
}

// --- random pairs of every type ------------------------------------------------------------

Shape RandomShape(Rng* rng, const Eigen::Vector3d& offset_W, bool is_box) {
  const Eigen::Vector3d centre_W = offset_W + RandomPoint(rng, 1.5);
  if (is_box) {
    return MakeBox(centre_W, RandomRotation(rng),
                   {Uniform(rng, 0.0, 0.6), Uniform(rng, 0.0, 0.6), Uniform(rng, 0.0, 0.6)});
  }
  const Eigen::Vector3d half_W = Uniform(rng, 0.0, 0.5) * RandomUnit(rng);
  return MakeCapsule(centre_W - half_W, centre_W + half_W, Uniform(rng, 0.0, 0.2));
}

std::vector<std::pair<Shape, Shape>> RandomPairs(Rng* rng, const Eigen::Vector3d& offset_W,
                                                 bool box_a, bool box_b) {
  std::vector<std::pair<Shape, Shape>> pairs;
  for (int i = 0; i < kCasesPerFamily; ++i) {
    pairs.emplace_back(RandomShape(rng, offset_W, box_a), RandomShape(rng, offset_W, box_b));
  }
  return pairs;
}

TEST(ClearanceBatch, RandomPairsNeverAboveTheExactDistance) {
  Rng rng(kSeed);
  for (const double offset_m : {0.0, 1e2, 1e4}) {
    const Eigen::Vector3d offset_W = offset_m * Eigen::Vector3d(1.0, -0.7, 0.4);
    const std::string at = " at " + std::to_string(static_cast<int>(offset_m)) + " m";
    CheckFamily("capsule-capsule" + at, RandomPairs(&rng, offset_W, false, false));
    CheckFamily("capsule-box" + at, RandomPairs(&rng, offset_W, false, true));
    CheckFamily("box-capsule" + at, RandomPairs(&rng, offset_W, true, false));
    CheckFamily("box-box" + at, RandomPairs(&rng, offset_W, true, true));
  }
}

// --- adversarial families at a known distance ------------------------------------------------

/// Gaps from touching (0) and overlapping to a centimetre.
double RandomGap_m(Rng* rng) {
  static const double kGaps_m[] = {-1e-3, 0.0, 1e-9, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2};
  return kGaps_m[std::uniform_int_distribution<int>(0, 8)(*rng)] * Uniform(rng, 0.5, 1.0);
}

/// A box and a capsule (sphere when `is_sphere`) lying along one of its faces at `gap_m`: the
/// capsule's axis parallel to the face (the worst case for the direction bound) or tilted.
std::pair<Shape, Shape> CapsuleOverFace(Rng* rng, const Eigen::Vector3d& offset_W,
                                        bool is_sphere, bool is_thin) {
  const Eigen::Matrix3d R_WB = RandomRotation(rng);
  const Eigen::Vector3d half_m(Uniform(rng, 0.05, 1.0), Uniform(rng, 0.05, 1.0),
                               is_thin ? 0.0 : Uniform(rng, 0.0, 0.5));
  const Eigen::Vector3d centre_W = offset_W + RandomPoint(rng, 1.0);
  const Box box = MakeBox(centre_W, R_WB, half_m);
  const double radius_m = Uniform(rng, 0.0, 0.2);
  const double gap_m = RandomGap_m(rng);
  // A point above the face (z in the box frame), inside the face's extent.
  const Eigen::Vector3d on_face_B(Uniform(rng, -half_m.x(), half_m.x()),
                                  Uniform(rng, -half_m.y(), half_m.y()), half_m.z());
  const Eigen::Vector3d normal_B = Eigen::Vector3d::UnitZ();
  const double half_length_m = is_sphere ? 0.0 : Uniform(rng, 0.0, 0.5);
  const double tilt_rad = Uniform(rng, 0.0, 1.0) < 0.5 ? 0.0 : Uniform(rng, 0.0, 1.4);
  const double turn_rad = Uniform(rng, 0.0, 2.0 * M_PI);
  const Eigen::Vector3d axis_B(std::cos(turn_rad) * std::cos(tilt_rad),
                               std::sin(turn_rad) * std::cos(tilt_rad), std::sin(tilt_rad));
  // The capsule's lowest point is its end nearest the face: put that end at gap + radius.
  const Eigen::Vector3d low_B = on_face_B + (gap_m + radius_m) * normal_B;
  const Eigen::Vector3d p0_B = low_B;
  const Eigen::Vector3d p1_B = low_B + 2.0 * half_length_m * axis_B;
  const Capsule capsule = MakeCapsule(box.X_WB * p0_B, box.X_WB * p1_B, radius_m);
  return Uniform(rng, 0.0, 1.0) < 0.5 ? std::pair<Shape, Shape>{capsule, box}
                                      : std::pair<Shape, Shape>{box, capsule};
}

/// Two capsules whose axes' closest points are `gap` + both radii apart: crossing (random angle)
/// or parallel, or spheres.
std::pair<Shape, Shape> CapsulesAtGap(Rng* rng, const Eigen::Vector3d& offset_W, bool parallel,
                                      bool spheres) {
  const Eigen::Vector3d u = RandomUnit(rng);
  Eigen::Vector3d normal = u.cross(RandomUnit(rng));
  if (normal.norm() < 1e-3) normal = u.unitOrthogonal();
  normal.normalize();
  const Eigen::Vector3d v =
      parallel ? u : (std::cos(Uniform(rng, 0.01, 3.13)) * u +
                      std::sin(Uniform(rng, 0.01, 3.13)) * normal.cross(u))
                         .normalized();
  const double ra = Uniform(rng, 0.0, 0.2), rb = Uniform(rng, 0.0, 0.2);
  const double gap_m = RandomGap_m(rng);
  const Eigen::Vector3d o_W = offset_W + RandomPoint(rng, 1.0);
  const double la = spheres ? 0.0 : Uniform(rng, 0.0, 0.5);
  const double lb = spheres ? 0.0 : Uniform(rng, 0.0, 0.5);
  // Both axes pass through their closest points o and o + (gap + radii) n, n normal to both.
  const Eigen::Vector3d n = parallel || spheres ? normal : u.cross(v).normalized();
  const Eigen::Vector3d o2_W = o_W + (gap_m + ra + rb) * n;
  const double sa = Uniform(rng, 0.0, 1.0), sb = Uniform(rng, 0.0, 1.0);
  return {MakeCapsule(o_W - sa * la * u, o_W + (1.0 - sa) * la * u, ra),
          MakeCapsule(o2_W - sb * lb * v, o2_W + (1.0 - sb) * lb * v, rb)};
}

/// Two boxes face to face at `gap` (the second's face normal flipped onto the first's),
/// thin (zero thickness) or not, the second turned about the common normal.
std::pair<Shape, Shape> BoxesFaceToFace(Rng* rng, const Eigen::Vector3d& offset_W,
                                        bool is_thin) {
  const Eigen::Matrix3d R_WA = RandomRotation(rng);
  const Eigen::Vector3d half_a(Uniform(rng, 0.05, 1.0), Uniform(rng, 0.05, 1.0),
                               is_thin ? 0.0 : Uniform(rng, 0.0, 0.5));
  const Eigen::Vector3d half_b(Uniform(rng, 0.05, 1.0), Uniform(rng, 0.05, 1.0),
                               is_thin ? 0.0 : Uniform(rng, 0.0, 0.5));
  const Eigen::Vector3d centre_a = offset_W + RandomPoint(rng, 1.0);
  const double gap_m = RandomGap_m(rng);
  const Eigen::Matrix3d R_AB =
      Eigen::AngleAxisd(Uniform(rng, 0.0, 2.0 * M_PI), Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Vector3d shift_A(Uniform(rng, -half_a.x(), half_a.x()),
                                Uniform(rng, -half_a.y(), half_a.y()),
                                half_a.z() + gap_m + half_b.z());
  return {MakeBox(centre_a, R_WA, half_a),
          MakeBox(centre_a + R_WA * shift_A, R_WA * R_AB, half_b)};
}

TEST(ClearanceBatch, NearThresholdPairsNeverAboveTheExactDistance) {
  Rng rng(kSeed + 1);
  for (const double offset_m : {0.0, 1e2, 1e4}) {
    const Eigen::Vector3d offset_W = offset_m * Eigen::Vector3d(-0.3, 1.0, 0.8);
    const std::string at = " at " + std::to_string(static_cast<int>(offset_m)) + " m";
    std::vector<std::pair<Shape, Shape>> over_face, sphere_face, thin_face, crossing, parallel,
        spheres, boxes, thin_boxes;
    for (int i = 0; i < kCasesPerFamily; ++i) {
      over_face.push_back(CapsuleOverFace(&rng, offset_W, false, false));
      sphere_face.push_back(CapsuleOverFace(&rng, offset_W, true, false));
      thin_face.push_back(CapsuleOverFace(&rng, offset_W, false, true));
      crossing.push_back(CapsulesAtGap(&rng, offset_W, false, false));
      parallel.push_back(CapsulesAtGap(&rng, offset_W, true, false));
      spheres.push_back(CapsulesAtGap(&rng, offset_W, false, true));
      boxes.push_back(BoxesFaceToFace(&rng, offset_W, false));
      thin_boxes.push_back(BoxesFaceToFace(&rng, offset_W, true));
    }
    CheckFamily("capsule over face" + at, over_face);
    CheckFamily("sphere over face" + at, sphere_face);
    CheckFamily("capsule over thin box" + at, thin_face);
    CheckFamily("capsules crossing" + at, crossing);
    CheckFamily("capsules parallel" + at, parallel);
    const FamilyResult sphere_result = CheckFamily("spheres" + at, spheres);
    // Two spheres: the centres' direction is exact, so the bound is the distance less at most
    // the margin and its own rounding (two margins): the margin is not wider than it says.
    EXPECT_GE(sphere_result.worst_in_margins, -2.0) << "spheres" << at;
    CheckFamily("boxes face to face" + at, boxes);
    CheckFamily("thin boxes face to face" + at, thin_boxes);
  }
}

TEST(ClearanceBatch, SpheresBoundWithinTwoMarginsOfTheDistance) {
  // Every sphere pair's bound, not only the worst: d - 2 margins <= bound <= d.
  Rng rng(kSeed + 2);
  std::vector<std::pair<Shape, Shape>> pairs;
  const Eigen::Vector3d at_origin_W = Eigen::Vector3d::Zero();
  for (int i = 0; i < kCasesPerFamily; ++i) {
    pairs.push_back(CapsulesAtGap(&rng, at_origin_W, false, true));
  }
  std::vector<FloatPrimitive> floats;
  const std::vector<double> bounds = Bounds(pairs, &floats);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const double exact_m = ShapeDistance(pairs[k].first, pairs[k].second).distance_m;
    if (exact_m <= 0.0) continue;  // overlap: the bound is negative, the distance 0
    const double margin_m = kClearanceBatchMarginUlps * kFloatUnitRoundoff *
                            MarginScale_m(floats[2 * k], floats[2 * k + 1]);
    EXPECT_GE(bounds[k], exact_m - 2.0 * margin_m) << "pair " << k << " (seed " << kSeed + 2 << ")";
    EXPECT_LE(bounds[k], exact_m) << "pair " << k << " (seed " << kSeed + 2 << ")";
  }
}

TEST(ClearanceBatch, SeparatedCapsuleAndFaceAreSettled) {
  // The direction bound, not only the spheres: a capsule 5 cm over a 2 m face is bounded within
  // a millimetre of its distance (the spheres alone would give a negative bound).
  const Box floor = MakeBox({0.0, 0.0, -0.05}, Eigen::Matrix3d::Identity(), {1.0, 1.0, 0.05});
  const Capsule capsule = MakeCapsule({0.2, 0.1, 0.10}, {0.6, -0.2, 0.10}, 0.05);
  const std::vector<std::pair<Shape, Shape>> pairs = {{capsule, floor}, {floor, capsule}};
  std::vector<FloatPrimitive> floats;
  const std::vector<double> bounds = Bounds(pairs, &floats);
  for (const double bound_m : bounds) {
    EXPECT_GT(bound_m, 0.05 - 1e-3);
    EXPECT_LE(bound_m, 0.05);
  }
}

TEST(ClearanceBatch, PartialBlocksMatchSinglePairs) {
  // 13 pairs: a full block of 8 and a partial one of 5; each bound as computed alone.
  Rng rng(kSeed + 3);
  std::vector<FloatPrimitive> floats;
  const Eigen::Vector3d at_origin_W = Eigen::Vector3d::Zero();
  for (int i = 0; i < 26; ++i) {
    floats.push_back(ToFloat(RandomShape(&rng, at_origin_W, i % 3 == 0)));
  }
  std::vector<PrimitiveId> a, b;
  for (PrimitiveId k = 0; k < 13; ++k) {
    a.push_back(2 * k);
    b.push_back((7 * k + 3) % 26);
  }
  std::vector<double> all(13);
  ComputeClearanceLowerBounds(floats.data(), a.data(), b.data(), 13, all.data());
  for (std::size_t k = 0; k < 13; ++k) {
    double alone = 0.0;
    ComputeClearanceLowerBounds(floats.data(), &a[k], &b[k], 1, &alone);
    EXPECT_EQ(all[k], alone) << "pair " << k;
  }
}

TEST(ClearanceBatch, NonFiniteAndHugeInputsSayNothing) {
  const Capsule ok = MakeCapsule({0.0, 0.0, 0.0}, {0.1, 0.0, 0.0}, 0.01);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Shape> bad = {
      MakeCapsule({nan, 0.0, 0.0}, {1.0, 0.0, 0.0}, 0.01),
      MakeCapsule({5.0, 0.0, 0.0}, {6.0, 0.0, 0.0}, nan),
      MakeBox({5.0, 0.0, 0.0}, Eigen::Matrix3d::Constant(nan), {0.1, 0.1, 0.1}),
      MakeCapsule({1e16, 0.0, 0.0}, {1e16, 1.0, 0.0}, 0.01),
      MakeCapsule({-1e17, 0.0, 0.0}, {1e17, 0.0, 0.0}, 0.01),
      MakeBox({5.0, 0.0, 0.0}, Eigen::Matrix3d::Identity(), {1e16, 0.1, 0.1})};
  for (std::size_t i = 0; i < bad.size(); ++i) {
    const std::vector<FloatPrimitive> floats = {ToFloat(ok), ToFloat(bad[i])};
    const PrimitiveId a[] = {0, 1}, b[] = {1, 0};
    double bounds[2];
    ComputeClearanceLowerBounds(floats.data(), a, b, 2, bounds);
    EXPECT_FALSE(bounds[0] > 0.0) << "bad shape " << i << ": bound " << bounds[0];
    EXPECT_FALSE(bounds[1] > 0.0) << "bad shape " << i << ": bound " << bounds[1];
  }
}

}  // namespace
}  // namespace arm_collision_monitor
