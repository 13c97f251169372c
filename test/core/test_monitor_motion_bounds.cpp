// MotionBounds (monitor/motion_bounds.h): the levers of known chains (one with parallel axes),
// the pair bound's shared joints, and a differential test against exact forward kinematics:
// over seeded random joint motions, no sampled surface point of a primitive moves farther than
// its bound, and no pair's distance shrinks by more than its pair bound, at a dense set of
// samples along the motion.
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/geometry/distance.h"
#include "arm_collision_monitor/monitor/motion_bounds.h"
#include "arm_collision_monitor/scene/workcell.h"
#include "load_error_expect.h"
#include "test_monitor_util.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint64_t kSeed = 20261123;
constexpr int kMotions = 60;          // random joint motions per workcell
constexpr int kSamplesPerMotion = 64;  // points along each motion, both ends included

std::shared_ptr<const Workcell> ParallelAxesWorkcell() {
  static const auto workcell = std::make_shared<const Workcell>(
      LoadWorkcell(ACM_SOURCE_DIR "/test/data/parallel_axes_arm.urdf",
                   ACM_SOURCE_DIR "/test/data/parallel_axes_scene.yaml"));
  return workcell;
}

std::shared_ptr<const Workcell> ThreeLinkWorkcell() {
  static const auto workcell = std::make_shared<const Workcell>(
      LoadWorkcell(ACM_SOURCE_DIR "/test/data/three_link_arm.urdf",
                   ACM_SOURCE_DIR "/test/data/three_link_scene.yaml"));
  return workcell;
}

// Every primitive of the workcell carried by its link, as the Monitor sets them at start-up.
MotionBounds BoundsOf(const Workcell& wc) {
  MotionBounds bounds(wc.kinematics, static_cast<std::uint32_t>(wc.primitives.size()));
  for (PrimitiveId id = 0; id < wc.primitives.size(); ++id) {
    const PrimitiveSpec& spec = wc.primitives[id];
    bounds.SetCarrier(id, spec.link_index, spec.link_index >= 0 && !spec.is_static, spec.shape_L);
  }
  std::string why;
  EXPECT_TRUE(bounds.Validate(&why)) << why;
  return bounds;
}

double Margin_m(double bound_m) { return kLowerBoundMarginPerMetre * (1.0 + std::abs(bound_m)); }

// Surface points of a shape in its own frame: a capsule's endpoints pushed out by its radius
// along the axes and random directions, a box's vertices.
std::vector<Eigen::Vector3d> SurfacePoints(const Shape& shape, std::mt19937_64* rng) {
  std::vector<Eigen::Vector3d> points;
  if (const auto* c = std::get_if<Capsule>(&shape)) {
    std::normal_distribution<double> normal(0.0, 1.0);
    for (const Eigen::Vector3d& end : {c->p0_W, c->p1_W}) {
      for (int axis = 0; axis < 3; ++axis) {
        points.push_back(end + c->radius_m * Eigen::Vector3d::Unit(axis));
        points.push_back(end - c->radius_m * Eigen::Vector3d::Unit(axis));
      }
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector3d dir(normal(*rng), normal(*rng), normal(*rng));
        points.push_back(end + c->radius_m * dir.normalized());
      }
    }
    return points;
  }
  const Box& b = std::get<Box>(shape);
  for (int corner = 0; corner < 8; ++corner) points.push_back(b.X_WB * b.Vertex_B(corner));
  return points;
}

// Random q anywhere the monitor accepts, the limits widened by their margin (continuous joints
// within +-pi); the mimic joints follow.
Eigen::VectorXd RandomQ(const Workcell& wc, std::mt19937_64* rng) {
  test::JointLimits limits = test::LimitsOf(wc);
  limits.lower.array() -= kJointLimitMargin;
  limits.upper.array() += kJointLimitMargin;
  return test::RandomQ(limits, rng);
}

// The differential test for one workcell: bounds against exact forward kinematics.
void ExpectBoundsHold(const Workcell& wc, std::mt19937_64* rng) {
  MotionBounds bounds = BoundsOf(wc);
  const KinematicModel& model = wc.kinematics;
  const std::uint32_t n = static_cast<std::uint32_t>(wc.primitives.size());
  std::vector<std::vector<Eigen::Vector3d>> points_L(n);
  std::vector<PrimitiveId> moving;
  for (PrimitiveId id = 0; id < n; ++id) {
    points_L[id] = SurfacePoints(wc.primitives[id].shape_L, rng);
    if (bounds.lever_count(id) > 0) moving.push_back(id);
  }
  ASSERT_FALSE(moving.empty());
  std::vector<Eigen::Isometry3d> X0(model.link_count()), Xt(model.link_count());
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked_points = 0, checked_pairs = 0;
  for (int motion = 0; motion < kMotions; ++motion) {
    const Eigen::VectorXd q0 = RandomQ(wc, rng);
    Eigen::VectorXd q1 = RandomQ(wc, rng);
    if (motion % 3 == 1) q1 = q0 + unit(*rng) * 0.05 * (q1 - q0);  // small motions too
    if (motion % 3 == 2) {
      // One joint alone: no other joint's lever arm leaves slack in the bound.
      const int moved = std::uniform_int_distribution<int>(0, model.q_size() - 1)(*rng);
      q1 = q0;
      q1[moved] = RandomQ(wc, rng)[moved];
    }
    bounds.SetJointMotion(q1, q0);
    for (const PrimitiveId id : moving) bounds.ComputeBound_m(id);
    model.ComputeLinkPoses(q0, &X0);
    for (int s = 0; s <= kSamplesPerMotion; ++s) {
      const Eigen::VectorXd qt = q0 + (static_cast<double>(s) / kSamplesPerMotion) * (q1 - q0);
      model.ComputeLinkPoses(qt, &Xt);
      for (const PrimitiveId id : moving) {
        const int link = wc.primitives[id].link_index;
        double moved_m = 0.0;
        for (const Eigen::Vector3d& p_L : points_L[id]) {
          moved_m = std::max(moved_m, (Xt[link] * p_L - X0[link] * p_L).norm());
          ++checked_points;
        }
        ASSERT_LE(moved_m, bounds.bound_m(id) + Margin_m(bounds.bound_m(id)))
            << "primitive " << wc.primitives[id].name << " motion " << motion << " sample " << s;
      }
      for (std::size_t i = 0; i < moving.size(); ++i) {
        for (std::size_t j = i + 1; j < moving.size(); ++j) {
          const PrimitiveId a = moving[i], b = moving[j];
          const int la = wc.primitives[a].link_index, lb = wc.primitives[b].link_index;
          const Shape& a_L = wc.primitives[a].shape_L;
          const Shape& b_L = wc.primitives[b].shape_L;
          const double then_m =
              ShapeDistance(TransformShape(X0[la], a_L), TransformShape(X0[lb], b_L)).distance_m;
          const double now_m =
              ShapeDistance(TransformShape(Xt[la], a_L), TransformShape(Xt[lb], b_L)).distance_m;
          const double bound_m = bounds.PairBound_m(a, b);
          ASSERT_GE(now_m, then_m - bound_m - Margin_m(then_m + bound_m))
              << "pair " << wc.primitives[a].name << ", " << wc.primitives[b].name << " motion "
              << motion << " sample " << s;
          ++checked_pairs;
        }
      }
    }
  }
  std::printf("motion bounds: %d point displacements, %d pair distances checked\n",
              checked_points, checked_pairs);
}

TEST(MonitorMotionBounds, LeversOfTheThreeLinkChain) {
  const auto wc = ThreeLinkWorkcell();
  const KinematicModel& model = wc->kinematics;
  MotionBounds bounds(model, 3);
  const Capsule unit_ball{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 1.0};
  // finger_b: below a mimic prismatic joint (multiplier -1), the continuous spin, the elbow and
  // the shoulder.
  bounds.SetCarrier(0, model.FindLink("finger_b"), true, unit_ball);
  ASSERT_EQ(bounds.lever_count(0), 4);
  const MotionBounds::Lever* l = bounds.levers(0);
  EXPECT_EQ(l[0].q_index, model.joint(model.FindLink("finger_a")).q_index);  // mimics slide
  EXPECT_EQ(l[0].m_per_unit, 1.0);  // prismatic: 1 m per m, times |-1|
  EXPECT_EQ(l[1].q_index, model.joint(model.FindLink("wrist")).q_index);
  // Revolute levers: the unit ball's extent plus the chain of joint offsets (and the prismatic
  // travel, 0.2 m and the limit's margin, as far as the monitor accepts) below the joint, of
  // which the first offset counts only across the joint's axis. The finger joint's 0.05 m
  // offset lies on the spin's axis (x), the spin's 0.35 m is across the elbow's (y), the
  // elbow's 0.4 m lies on the shoulder's (z).
  const double travel_m = 0.2 + kJointLimitMargin;
  EXPECT_NEAR(l[1].m_per_unit, 1.0 + travel_m, 1e-12);
  EXPECT_NEAR(l[2].m_per_unit, 1.0 + 0.05 + travel_m + 0.35, 1e-12);
  EXPECT_NEAR(l[3].m_per_unit, 1.0 + 0.05 + travel_m + 0.35, 1e-12);
  // On the joint's own link, the lever is the farthest distance from its axis: a capsule along
  // the elbow's axis (y) reaches only its radius from it.
  const Capsule along_elbow{Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0.3, 0), 0.05};
  bounds.SetCarrier(1, model.FindLink("forearm"), true, along_elbow);
  ASSERT_EQ(bounds.lever_count(1), 2);
  EXPECT_NEAR(bounds.levers(1)[0].m_per_unit, 0.05, 1e-12);
  // The shoulder's: the elbow lies on its axis, so the capsule's reach from the elbow.
  EXPECT_NEAR(bounds.levers(1)[1].m_per_unit, 0.3 + 0.05, 1e-12);
  // A primitive that does not move, or has no carrier, has no levers and no motion.
  bounds.SetCarrier(1, model.FindLink("finger_b"), false, unit_ball);
  bounds.SetCarrier(2, -1, true, unit_ball);
  EXPECT_EQ(bounds.lever_count(1), 0);
  EXPECT_EQ(bounds.lever_count(2), 0);
  std::string why;
  EXPECT_TRUE(bounds.Validate(&why)) << why;
  // An attached object moves to another carrier and back to none: levers follow.
  bounds.SetCarrier(2, model.FindLink("forearm"), true, unit_ball);
  EXPECT_EQ(bounds.lever_count(2), 2);
  EXPECT_TRUE(bounds.Validate(&why)) << why;
  bounds.SetCarrier(2, -1, true, unit_ball);
  EXPECT_EQ(bounds.lever_count(2), 0);
  EXPECT_TRUE(bounds.Validate(&why)) << why;
  Eigen::VectorXd q0 = Eigen::VectorXd::Zero(model.q_size());
  Eigen::VectorXd q1 = q0;
  bounds.SetJointMotion(q1, q0);
  EXPECT_EQ(bounds.ComputeBound_m(0), 0.0);
  q1[l[0].q_index] = 0.1;   // slide by 0.1 m
  q1[l[3].q_index] = -0.5;  // shoulder by 0.5 rad
  bounds.SetJointMotion(q1, q0);
  EXPECT_NEAR(bounds.ComputeBound_m(0), 0.1 + 0.5 * l[3].m_per_unit, 1e-12);
  EXPECT_EQ(bounds.ComputeBound_m(1), 0.0);
  EXPECT_EQ(bounds.PairBound_m(1, 2), 0.0);
  // One that does not move shares no joint with one that does, whose whole motion counts.
  EXPECT_EQ(bounds.PairBound_m(1, 0), bounds.bound_m(0));
  q1[0] = std::numeric_limits<double>::quiet_NaN();
  bounds.SetJointMotion(q1, q0);
  EXPECT_TRUE(std::isnan(bounds.ComputeBound_m(0)));
}

// Parallel axes (the shoulder's and the elbow's): the shoulder's lever is the elbow's offset
// across it plus the primitive's distance from the elbow's axis, not plus its whole reach.
TEST(MonitorMotionBounds, LeversOfParallelAxes) {
  const auto wc = ParallelAxesWorkcell();
  const KinematicModel& model = wc->kinematics;
  MotionBounds bounds(model, 1);
  // A ball on the elbow's axis (y), 0.1 m from the forearm's origin.
  const Capsule ball{Eigen::Vector3d(0, 0.1, 0), Eigen::Vector3d(0, 0.1, 0), 0.05};
  bounds.SetCarrier(0, model.FindLink("forearm"), true, ball);
  ASSERT_EQ(bounds.lever_count(0), 3);
  const MotionBounds::Lever* l = bounds.levers(0);
  EXPECT_NEAR(l[0].m_per_unit, 0.05, 1e-12);        // the elbow: the radius
  EXPECT_NEAR(l[1].m_per_unit, 0.4 + 0.05, 1e-12);  // the shoulder: 0.4 m offset, then 0.05
  // The pan (z) is across the shoulder: the ball's whole reach, 0.15 m, from the shoulder's
  // origin, whose 0.1 m offset lies on the pan's axis.
  EXPECT_NEAR(l[2].m_per_unit, 0.4 + 0.15, 1e-12);
}

TEST(MonitorMotionBounds, PairBoundLeavesOutTheSharedJoints) {
  const auto wc = ThreeLinkWorkcell();
  const KinematicModel& model = wc->kinematics;
  MotionBounds bounds(model, 3);
  const Capsule ball{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.1};
  bounds.SetCarrier(0, model.FindLink("finger_a"), true, ball);
  bounds.SetCarrier(1, model.FindLink("finger_a"), true, ball);
  bounds.SetCarrier(2, model.FindLink("finger_b"), true, ball);
  std::mt19937_64 rng(kSeed);
  std::printf("seed %llu\n", static_cast<unsigned long long>(kSeed));
  const Eigen::VectorXd q0 = RandomQ(*wc, &rng), q1 = RandomQ(*wc, &rng);
  bounds.SetJointMotion(q1, q0);
  for (PrimitiveId id = 0; id < 3; ++id) EXPECT_GT(bounds.ComputeBound_m(id), 0.0);
  // Two primitives of one link move rigidly together.
  EXPECT_EQ(bounds.PairBound_m(0, 1), 0.0);
  // The fingers share every joint but their own slides: only those count.
  const int slide = bounds.levers(0)[0].q_index;
  const double slide_m = std::abs(q1[slide] - q0[slide]);
  EXPECT_EQ(bounds.PairBound_m(0, 2), 2.0 * slide_m);
  EXPECT_EQ(bounds.PairBound_m(0, 2), bounds.PairBound_m(2, 0));
}

TEST(MonitorMotionBounds, BoundsHoldAgainstExactKinematics) {
  std::printf("seed %llu\n", static_cast<unsigned long long>(kSeed));
  std::mt19937_64 rng(kSeed);
  ExpectBoundsHold(*test::LoadBundledWorkcell(), &rng);
  ExpectBoundsHold(*ThreeLinkWorkcell(), &rng);
  ExpectBoundsHold(*ParallelAxesWorkcell(), &rng);
  // A finger mimicking the slide three times over, offset 0.1 m: it slides past its own
  // <limit>, as far as the slide's range puts it.
  const std::string path =
      WriteEditedFile(ACM_SOURCE_DIR "/test/data/three_link_arm.urdf", "mimic_times_3.urdf",
                      {{"multiplier=\"-1\" offset=\"0\"", "multiplier=\"-3\" offset=\"0.1\""}});
  ExpectBoundsHold(LoadWorkcell(path, ACM_SOURCE_DIR "/test/data/three_link_scene.yaml"), &rng);
}

// The largest bound, taken over the undominated primitives only, equals the largest over all,
// over seeded random motions; and again after a primitive's carrier changes (an attached box
// on the gripper, which then dominates it).
TEST(MonitorMotionBounds, LargestBoundOverUndominatedEqualsLargestOverAll) {
  const auto wc = test::LoadBundledWorkcell();
  MotionBounds bounds = BoundsOf(*wc);
  const test::JointLimits limits = test::LimitsOf(*wc);
  std::mt19937_64 rng(test::PrintSeed(kSeed + 7));
  const PrimitiveId box = test::Prim(*wc, "front_box");
  const int gripper = wc->kinematics.FindLink("left_link7");
  for (int round = 0; round < 2; ++round) {
    if (round == 1) {
      bounds.SetCarrier(box, gripper, true, wc->primitives[box].shape_L);
    }
    for (int k = 0; k < 200; ++k) {
      const Eigen::VectorXd q0 = test::RandomQ(limits, &rng);
      const Eigen::VectorXd q1 = test::RandomQ(limits, &rng);
      bounds.SetJointMotion(q1, q0);
      const double largest_m = bounds.ComputeLargestBound_m();
      double expected_m = 0.0;
      for (PrimitiveId id = 0; id < wc->primitives.size(); ++id) {
        if (bounds.lever_count(id) > 0)
          expected_m = std::max(expected_m, bounds.ComputeBound_m(id));
      }
      ASSERT_EQ(largest_m, expected_m) << "round " << round << " motion " << k;
      ASSERT_GT(largest_m, 0.0);
    }
  }
}

// Past MotionBounds::kMaxDominanceSearch primitives with levers none is left out, and the
// largest bound is still the largest of all (and just below, with the search).
TEST(MonitorMotionBounds, LargestBoundOfManyPrimitivesIsTheLargestOfAll) {
  const auto wc = test::LoadBundledWorkcell();
  const KinematicModel& model = wc->kinematics;
  const test::JointLimits limits = test::LimitsOf(*wc);
  std::mt19937_64 rng(test::PrintSeed(kSeed + 11));
  std::uniform_real_distribution<double> offset(-0.2, 0.2);
  std::vector<int> moving_links;
  for (int link = 1; link < model.link_count(); ++link) {
    if (model.is_moving(link)) moving_links.push_back(link);
  }
  for (const std::size_t count :
       {MotionBounds::kMaxDominanceSearch, MotionBounds::kMaxDominanceSearch + 44}) {
    MotionBounds bounds(model, static_cast<std::uint32_t>(count));
    for (PrimitiveId id = 0; id < count; ++id) {
      const Eigen::Vector3d p(offset(rng), offset(rng), offset(rng));
      bounds.SetCarrier(id, moving_links[id % moving_links.size()], true,
                        Capsule{p, p + Eigen::Vector3d(0.0, 0.0, 0.1), 0.02});
    }
    for (int k = 0; k < 50; ++k) {
      bounds.SetJointMotion(test::RandomQ(limits, &rng), test::RandomQ(limits, &rng));
      const double largest_m = bounds.ComputeLargestBound_m();
      double expected_m = 0.0;
      for (PrimitiveId id = 0; id < count; ++id) {
        expected_m = std::max(expected_m, bounds.ComputeBound_m(id));
      }
      ASSERT_EQ(largest_m, expected_m) << count << " primitives, motion " << k;
    }
  }
}

// A NaN joint motion makes the largest bound NaN whichever primitive it reaches, before or
// after the others in the undominated set: the first arm's joint (its primitives come first)
// and the last joint.
TEST(MonitorMotionBounds, LargestBoundIsNaNForANaNJointMotion) {
  const auto wc = test::LoadBundledWorkcell();
  MotionBounds bounds = BoundsOf(*wc);
  const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(wc->kinematics.q_size());
  for (const Eigen::Index joint : {Eigen::Index{0}, q0.size() - 1}) {
    Eigen::VectorXd q1 = Eigen::VectorXd::Constant(q0.size(), 0.1);
    q1[joint] = std::numeric_limits<double>::quiet_NaN();
    bounds.SetJointMotion(q1, q0);
    EXPECT_TRUE(std::isnan(bounds.ComputeLargestBound_m())) << "joint " << joint;
  }
  bounds.SetJointMotion(Eigen::VectorXd::Constant(q0.size(), 0.1), q0);
  EXPECT_GT(bounds.ComputeLargestBound_m(), 0.0);
}

TEST(MonitorMotionBounds, PointHelpers) {
  const Capsule c{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 0.5};
  EXPECT_DOUBLE_EQ(MaxDistanceFromPoint_m(c, Eigen::Vector3d(-1, 0, 0)), 2.5);
  Box b;
  b.X_WB = Eigen::Isometry3d::Identity();
  b.half_extents_m = Eigen::Vector3d(1, 2, 2);
  EXPECT_DOUBLE_EQ(MaxDistanceFromPoint_m(b, Eigen::Vector3d::Zero()), 3.0);
  Box moved = b;
  moved.X_WB.translation() = Eigen::Vector3d(0, 0, 0.25);
  EXPECT_DOUBLE_EQ(MaxPointDisplacement_m(b, moved), 0.25);
  // From an axis through the origin: a capsule's farthest endpoint plus its radius; a box's
  // farthest vertex.
  EXPECT_DOUBLE_EQ(MaxDistanceFromAxis_m(c, Eigen::Vector3d::UnitX()), 0.5);
  EXPECT_DOUBLE_EQ(MaxDistanceFromAxis_m(c, Eigen::Vector3d::UnitY()), 1.5);
  EXPECT_DOUBLE_EQ(MaxDistanceFromAxis_m(b, Eigen::Vector3d::UnitX()), std::sqrt(8.0));
  EXPECT_DOUBLE_EQ(MaxDistanceFromAxis_m(moved, Eigen::Vector3d::UnitZ()), std::sqrt(5.0));
  EXPECT_DOUBLE_EQ(MaxDistanceFromAxis_m(moved, Eigen::Vector3d::UnitY()),
                   std::sqrt(1.0 + 2.25 * 2.25));
  Capsule turned = c;
  turned.p1_W = Eigen::Vector3d(0, 1, 0);
  EXPECT_DOUBLE_EQ(MaxPointDisplacement_m(c, turned), std::sqrt(2.0));
}

// A box's displacement is that of its farthest-moving corner, each corner moved by both poses.
TEST(MonitorMotionBounds, BoxDisplacementIsItsFarthestMovingCorner) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random_pose = [&] {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() =
        Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized())
            .toRotationMatrix();
    X.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 3.0;
    return X;
  };
  for (int trial = 0; trial < 1000; ++trial) {
    Box b0;
    b0.X_WB = random_pose();
    b0.half_extents_m = Eigen::Vector3d(u(rng), u(rng), u(rng)).cwiseAbs() * 0.5;
    Box b1 = b0;
    // Half the trials a small motion (a cycle's), half an arbitrary one.
    b1.X_WB = trial % 2 == 0 ? random_pose()
                             : b0.X_WB * Eigen::AngleAxisd(0.01 * u(rng), Eigen::Vector3d(
                                                               u(rng), u(rng), u(rng))
                                                               .normalized());
    if (trial % 2 == 1) b1.X_WB.translation() += Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.01;
    double expected_m = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d v_B = b0.Vertex_B(corner);
      expected_m = std::max(expected_m, (b1.X_WB * v_B - b0.X_WB * v_B).norm());
    }
    EXPECT_NEAR(MaxPointDisplacement_m(b0, b1), expected_m, 1e-14 * (1.0 + expected_m))
        << "trial " << trial;
  }
}

// The swept check's interval bounds: tight for a point that runs straight at an obstacle point
// and back (smallest) or away and back (largest), and bounds for any path of that length.
TEST(MonitorMotionBounds, StretchBoundsAreTightAndHoldOnAnyPath) {
  // Head-on: from 0.5 m in to 0.02 m, then back out to 0.3 m (0.48 + 0.28 m of motion).
  EXPECT_NEAR(SmallestOverStretch_m(0.5, 0.3, 0.48 + 0.28), 0.02, 1e-15);
  // Away: from 0.1 m out to 0.9 m, then back in to 0.4 m.
  EXPECT_NEAR(LargestOverStretch_m(0.1, 0.4, 0.8 + 0.5), 0.9, 1e-15);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(SmallestOverStretch_m(nan, 0.3, 0.1)));
  EXPECT_TRUE(std::isnan(LargestOverStretch_m(0.1, 0.4, nan)));
  // Random polylines of four segments: the distance to a point along them, densely sampled.
  std::mt19937_64 rng(test::PrintSeed(kSeed + 8));
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  auto random_point = [&] {
    return Eigen::Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
  };
  for (int path = 0; path < 2000; ++path) {
    const Eigen::Vector3d obstacle = random_point();
    std::vector<Eigen::Vector3d> corners;
    for (int k = 0; k < 5; ++k) corners.push_back(random_point());
    double length_m = 0.0, smallest_m = std::numeric_limits<double>::infinity(), largest_m = 0.0;
    for (int k = 0; k + 1 < 5; ++k) {
      length_m += (corners[k + 1] - corners[k]).norm();
      for (int i = 0; i <= kSamplesPerMotion; ++i) {
        const double d_m =
            (corners[k] + (corners[k + 1] - corners[k]) * (static_cast<double>(i) /
                                                           kSamplesPerMotion) -
             obstacle)
                .norm();
        smallest_m = std::min(smallest_m, d_m);
        largest_m = std::max(largest_m, d_m);
      }
    }
    const double d0_m = (corners.front() - obstacle).norm();
    const double d1_m = (corners.back() - obstacle).norm();
    ASSERT_LE(SmallestOverStretch_m(d0_m, d1_m, length_m), smallest_m + 1e-12) << path;
    ASSERT_GE(LargestOverStretch_m(d0_m, d1_m, length_m), largest_m - 1e-12) << path;
    // With a lower bound at the start and an upper bound at the end (as the swept check uses).
    ASSERT_LE(SmallestOverStretch_m(0.5 * d0_m, d1_m, length_m), smallest_m + 1e-12) << path;
    ASSERT_GE(LargestOverStretch_m(d0_m, 2.0 * d1_m, length_m), largest_m - 1e-12) << path;
  }
}

}  // namespace
}  // namespace arm_collision_monitor
