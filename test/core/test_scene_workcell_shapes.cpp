// WorkcellShapes on the bundled workcell: at seeded random joint positions every world shape it
// holds equals the primitive's shape_L moved by its link's pose, computed here from the same
// forward kinematics; objects keep their scene-file shapes; moving() is the default model's
// primitives on links that move with q (with Models::kAll, every model's).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <string>
#include <variant>
#include <vector>

#include "arm_collision_monitor/scene/workcell.h"
#include "arm_collision_monitor/scene/workcell_shapes.h"

namespace arm_collision_monitor {
namespace {

const std::string kSource = ACM_SOURCE_DIR;
const std::string kUrdf = kSource + "/urdf/workcell.urdf";
const std::string kScene = kSource + "/config/scene.yaml";

constexpr std::uint64_t kSeed = 20261121;
constexpr int kConfigurations = 200;

// Bit-for-bit equality: both sides run the same FK and the same TransformShape, so any
// difference means WorkcellShapes used a different pose, primitive or link.
::testing::AssertionResult SameShape(const Shape& got, const Shape& want) {
  if (IsSameShape(got, want)) return ::testing::AssertionSuccess();
  if (got.index() != want.index()) return ::testing::AssertionFailure() << "shape kinds differ";
  if (const auto* g = std::get_if<Capsule>(&got)) {
    const auto& w = std::get<Capsule>(want);
    return ::testing::AssertionFailure()
           << "capsule p0 " << g->p0_W.transpose() << " p1 " << g->p1_W.transpose() << " r "
           << g->radius_m << ", expected p0 " << w.p0_W.transpose() << " p1 "
           << w.p1_W.transpose() << " r " << w.radius_m;
  }
  const auto& g = std::get<Box>(got);
  const auto& w = std::get<Box>(want);
  return ::testing::AssertionFailure() << "box centre " << g.X_WB.translation().transpose()
                                       << ", expected " << w.X_WB.translation().transpose();
}

// A position within each actuated joint's limits (continuous joints: one turn about 0).
Eigen::VectorXd RandomQ(const KinematicModel& model, std::mt19937_64* rng) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.q_size());
  for (int link = 1; link < model.link_count(); ++link) {
    const JointSpec& j = model.joint(link);
    if (j.q_index < 0) continue;
    const double lo = std::isfinite(j.lower) ? j.lower : -M_PI;
    const double hi = std::isfinite(j.upper) ? j.upper : M_PI;
    q[j.q_index] = std::uniform_real_distribution<double>(lo, hi)(*rng);
  }
  return q;
}

class WorkcellShapesTest : public ::testing::Test {
 protected:
  WorkcellShapesTest() : workcell_(LoadWorkcell(kUrdf, kScene)) {}
  const Workcell workcell_;
};

TEST_F(WorkcellShapesTest, MovingIsTheDefaultModelOnMovingLinks) {
  const WorkcellShapes shapes(workcell_);
  std::vector<PrimitiveId> want;
  for (std::size_t id = 0; id < workcell_.primitives.size(); ++id) {
    const PrimitiveSpec& p = workcell_.primitives[id];
    EXPECT_EQ(shapes.is_default_model(static_cast<PrimitiveId>(id)), p.variant.empty()) << p.name;
    if (p.variant.empty() && p.link_index >= 0 && workcell_.kinematics.is_moving(p.link_index)) {
      want.push_back(static_cast<PrimitiveId>(id));
    }
  }
  ASSERT_FALSE(want.empty());
  EXPECT_EQ(shapes.moving(), want);
}

TEST_F(WorkcellShapesTest, ShapesAreLinkPosesTimesShapesInTheLinkFrame) {
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 rng(kSeed);
  const KinematicModel& model = workcell_.kinematics;
  std::vector<Eigen::Isometry3d> X_WL_home(model.link_count()), X_WL(model.link_count());
  model.ComputeLinkPoses(Eigen::VectorXd::Zero(model.q_size()), &X_WL_home);
  WorkcellShapes shapes(workcell_);
  int moved_from_home = 0;  // link primitives checked away from their home pose
  for (int k = 0; k < kConfigurations; ++k) {
    const Eigen::VectorXd q = RandomQ(model, &rng);
    shapes.Evaluate(q);
    model.ComputeLinkPoses(q, &X_WL);
    ASSERT_EQ(shapes.X_WL().size(), X_WL.size());
    for (int link = 0; link < model.link_count(); ++link) {
      ASSERT_TRUE(shapes.X_WL()[link].matrix() == X_WL[link].matrix())
          << "configuration " << k << ", link " << model.link_name(link);
    }
    for (std::size_t id = 0; id < workcell_.primitives.size(); ++id) {
      const PrimitiveSpec& p = workcell_.primitives[id];
      const Shape& got = shapes.shape_W(static_cast<PrimitiveId>(id));
      if (p.link_index < 0) {
        // Environment objects stay at their scene-file pose.
        ASSERT_TRUE(SameShape(got, p.shape_L)) << "configuration " << k << ", " << p.name;
      } else if (!p.variant.empty()) {
        // Inactive model variants keep their home-pose shapes.
        ASSERT_TRUE(SameShape(got, TransformShape(X_WL_home[p.link_index], p.shape_L)))
            << "configuration " << k << ", " << p.name;
      } else {
        ASSERT_TRUE(SameShape(got, TransformShape(X_WL[p.link_index], p.shape_L)))
            << "configuration " << k << ", " << p.name;
        moved_from_home += !(X_WL[p.link_index].matrix() == X_WL_home[p.link_index].matrix());
      }
    }
  }
  // The random configurations really moved the arms' primitives.
  EXPECT_GT(moved_from_home, 0);
}

// Models::kAll (the loader's start-up check): the variants' capsules move with their links too.
TEST_F(WorkcellShapesTest, AllModelsMovesTheVariantsToo) {
  std::cout << "seed " << kSeed << "\n";
  std::mt19937_64 rng(kSeed);
  const KinematicModel& model = workcell_.kinematics;
  std::vector<Eigen::Isometry3d> X_WL(model.link_count());
  WorkcellShapes shapes(workcell_, WorkcellShapes::Models::kAll);
  std::vector<PrimitiveId> want;
  int variants = 0;
  for (std::size_t id = 0; id < workcell_.primitives.size(); ++id) {
    const PrimitiveSpec& p = workcell_.primitives[id];
    variants += !p.variant.empty();
    if (p.link_index >= 0 && model.is_moving(p.link_index)) {
      want.push_back(static_cast<PrimitiveId>(id));
    }
  }
  ASSERT_GT(variants, 0);
  EXPECT_EQ(shapes.moving(), want);
  for (int k = 0; k < kConfigurations; ++k) {
    const Eigen::VectorXd q = RandomQ(model, &rng);
    shapes.Evaluate(q);
    model.ComputeLinkPoses(q, &X_WL);
    for (std::size_t id = 0; id < workcell_.primitives.size(); ++id) {
      const PrimitiveSpec& p = workcell_.primitives[id];
      const Shape want_W = p.link_index >= 0 ? TransformShape(X_WL[p.link_index], p.shape_L)
                                             : p.shape_L;
      ASSERT_TRUE(SameShape(shapes.shape_W(static_cast<PrimitiveId>(id)), want_W))
          << "configuration " << k << ", " << p.name;
      EXPECT_EQ(shapes.is_default_model(static_cast<PrimitiveId>(id)), p.variant.empty());
    }
  }
}

}  // namespace
}  // namespace arm_collision_monitor
