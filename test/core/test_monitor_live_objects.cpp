// Live objects (Monitor::AddObject, MoveObject, RemoveObject): random sequences of adds, moves
// and removes of every solid type interleaved with arm motion, each step's report against an
// independent all-pairs brute force; refusals that change nothing; capacity; no allocation in
// Update after the scene changes.
#include <cmath>
#include <cstdlib>
#include <random>

#include "allocation_counter.h"
#include "arm_collision_monitor/scene/solid_spec.h"
#include "test_monitor_util.h"

namespace arm_collision_monitor {
namespace {

constexpr std::uint32_t kCapacity = 6;
constexpr std::uint32_t kMaxPrimitives = 4;

MonitorOptions LiveOptions(BroadPhaseMethod method) {
  MonitorOptions options = test::OptionsFor(method);
  options.live_objects.capacity = kCapacity;
  options.live_objects.max_primitives_per_object = kMaxPrimitives;
  return options;
}

// What the test knows of a live object, independently of the Monitor.
struct LiveRecord {
  std::vector<Shape> shapes_O;
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  double tolerance_m = 0.0;
};

Eigen::Isometry3d RandomPose(std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Quaterniond R(g(*rng), g(*rng), g(*rng), g(*rng));
  R.normalize();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R.toRotationMatrix();
  // Where the arms reach (bases at y = +/-0.55, z = 0.8; links up to ~1.6 m long).
  X.translation() << 0.6 + 0.7 * u(*rng), 1.0 * u(*rng), 1.4 + 0.7 * u(*rng);
  return X;
}

// A closed, jittered box mesh (8 vertices, 12 triangles) of edges up to `size_m`.
TriangleMesh RandomBoxMesh(double size_m, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(0.3, 1.0);
  const Eigen::Vector3d half = 0.5 * size_m * Eigen::Vector3d(u(*rng), u(*rng), u(*rng));
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.vertices_L.emplace_back((i & 1 ? 1 : -1) * half.x(), (i & 2 ? 1 : -1) * half.y(),
                                 (i & 4 ? 1 : -1) * half.z());
  }
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

// Shapes of a random solid of every type in turn, with the options varied too.
std::vector<Shape> RandomSolidShapes(int type, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> size(0.05, 0.4);
  SolidSpec solid;
  SolidShapeOptions options;
  options.cylinder_model = (*rng)() % 2 ? CylinderModel::kBox : CylinderModel::kCapsule;
  const MeshFitKind kinds[] = {MeshFitKind::kOneCapsule, MeshFitKind::kCapsuleChain,
                               MeshFitKind::kOrientedBox};
  options.mesh_fit.kind = kinds[(*rng)() % 3];
  options.mesh_fit.capsule_count = 3;
  switch (type % 5) {
    case 0:
      solid.type = SolidType::kBox;
      solid.dimensions_m = {size(*rng), size(*rng), size(*rng)};
      break;
    case 1:
      solid.type = SolidType::kSphere;
      solid.dimensions_m = {size(*rng)};
      break;
    case 2:
      solid.type = SolidType::kCylinder;
      solid.dimensions_m = {size(*rng), size(*rng)};
      break;
    case 3:
      solid.type = SolidType::kCapsule;
      solid.dimensions_m = {size(*rng), size(*rng)};
      break;
    default:
      solid.type = SolidType::kMesh;
      solid.mesh = RandomBoxMesh(0.5, rng);
      break;
  }
  std::vector<Shape> shapes;
  std::string error;
  EXPECT_TRUE(MakeSolidShapes_O(solid, options, &shapes, &error)) << error;
  return shapes;
}

// The reference: the scene file's pairs (test::ReferenceWarnings), plus every live primitive
// against every moving primitive of the default models (live objects rest: never against other
// statics; excused with nothing), by brute force.
std::vector<test::ReferenceWarning> Reference(const Workcell& wc, const Monitor& monitor,
                                              const Eigen::VectorXd& q,
                                              const std::map<std::string, LiveRecord>& live) {
  std::vector<test::ReferenceWarning> expected = test::ReferenceWarnings(wc, q);
  std::vector<Eigen::Isometry3d> X_WL(wc.kinematics.link_count());
  wc.kinematics.ComputeLinkPoses(q, &X_WL);
  for (const auto& [name, record] : live) {
    for (std::size_t k = 0; k < record.shapes_O.size(); ++k) {
      // The Monitor's id of this primitive, found by its name.
      const std::string prim_name =
          record.shapes_O.size() == 1 ? name : name + "/" + std::to_string(k);
      PrimitiveId live_id = monitor.primitive_count();
      for (PrimitiveId id = 0; id < monitor.primitive_count(); ++id) {
        if (monitor.primitive(id).name == prim_name) live_id = id;
      }
      EXPECT_LT(live_id, monitor.primitive_count()) << "no primitive named " << prim_name;
      if (live_id == monitor.primitive_count()) continue;
      const Shape live_W = TransformShape(record.X_WO, record.shapes_O[k]);
      for (PrimitiveId id = 0; id < wc.primitives.size(); ++id) {
        const PrimitiveSpec& p = wc.primitives[id];
        const bool is_moving = p.link_index >= 0 ? !p.is_static && p.variant.empty()
                                                 : !wc.objects[p.object_index].frame.empty();
        if (!is_moving) continue;
        const Shape other_W =
            p.link_index >= 0 ? TransformShape(X_WL[p.link_index], p.shape_L) : p.shape_L;
        const double d = ShapeDistance(other_W, live_W).distance_m;
        const double threshold_m = p.tolerance_m + record.tolerance_m;
        if (d < threshold_m || d <= 0.0) expected.push_back({id, live_id, d, threshold_m});
      }
    }
  }
  std::sort(expected.begin(), expected.end());
  return expected;
}

void ExpectValid(const Monitor& monitor, const std::string& context) {
  std::string error;
  EXPECT_TRUE(monitor.Validate(&error)) << context << ": " << error;
  EXPECT_TRUE(monitor.ValidateIndex(&error)) << context << ": " << error;
}

// The right arm reaching down to (0.9, -0.4, 1.0), `monitor` updated there: a pose at the tip of
// its tool (right_link7's capsule end), unrotated, in W.
Eigen::Isometry3d RightToolTipAtGrasp(const Workcell& wc, Monitor* monitor,
                                      Eigen::VectorXd* grasp_q) {
  *grasp_q = test::ArmReachDown(wc, "right", 0.9, -0.4, 1.0);
  monitor->Update(*grasp_q);
  monitor->SyncShapes();
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() = std::get<Capsule>(monitor->shape_W(test::Prim(wc, "right_link7"))).p1_W;
  return X_WO;
}

class MonitorLiveObjects : public ::testing::TestWithParam<BroadPhaseMethod> {};

TEST_P(MonitorLiveObjects, RandomAddMoveRemoveMatchesBruteForce) {
  const auto wc = test::LoadBundledWorkcell();
  Monitor monitor(wc, LiveOptions(GetParam()));
  std::mt19937_64 rng(test::PrintSeed(1313));
  const test::JointLimits limits = test::LimitsOf(*wc);
  const test::SmoothTrajectory path(limits, 0.8, &rng);
  std::map<std::string, LiveRecord> live;
  Eigen::VectorXd q;
  int next_name = 0, warned_live = 0, adds = 0, moves = 0, removes = 0;
  std::string error;
  for (int step = 0; step < 400; ++step) {
    const int action = static_cast<int>(rng() % 4);
    auto random_live = [&]() {
      auto it = live.begin();
      std::advance(it, rng() % live.size());
      return it;
    };
    if (action == 0 && live.size() < kCapacity) {
      LiveRecord record;
      record.shapes_O = RandomSolidShapes(next_name, &rng);
      record.X_WO = RandomPose(&rng);
      record.tolerance_m = std::uniform_real_distribution<double>(0.0, 0.05)(rng);
      const std::string name = "live" + std::to_string(next_name++);
      ASSERT_TRUE(monitor.AddObject(name, record.shapes_O, record.X_WO, record.tolerance_m,
                                    rng() % 2 == 0, &error))
          << error;
      live[name] = record;
      ++adds;
    } else if (action == 1 && !live.empty()) {
      auto it = random_live();
      it->second.X_WO = RandomPose(&rng);
      ASSERT_TRUE(monitor.MoveObject(it->first, it->second.X_WO, &error)) << error;
      ++moves;
    } else if (action == 2 && !live.empty()) {
      auto it = random_live();
      ASSERT_TRUE(monitor.RemoveObject(it->first, &error)) << error;
      live.erase(it);
      ++removes;
    }
    ExpectValid(monitor, "after the scene change of step " + std::to_string(step));
    path.At(step * 0.2, &q);  // the arms move every step
    const CycleReport& report = monitor.Update(q);
    ASSERT_EQ(report.input, InputStatus::kOk);
    const std::string context = "step " + std::to_string(step);
    test::ExpectSameWarnings(monitor.workcell(), Reference(*wc, monitor, q, live),
                             report.warnings, context);
    EXPECT_EQ(monitor.live_object_count(), live.size()) << context;
    ExpectValid(monitor, context);
    for (const Warning& w : report.warnings) warned_live += w.b >= wc->primitives.size();
    if (HasFailure()) return;
  }
  // The sequence exercised every call and live objects did warn.
  EXPECT_GT(adds, 20);
  EXPECT_GT(moves, 20);
  EXPECT_GT(removes, 10);
  EXPECT_GT(warned_live, 0);
  std::printf("%s: %d adds, %d moves, %d removes, %d live warnings\n",
              BroadPhaseMethodName(GetParam()).c_str(), adds, moves, removes, warned_live);
}

TEST_P(MonitorLiveObjects, RefusalsChangeNothing) {
  const auto wc = test::LoadBundledWorkcell();
  Monitor monitor(wc, LiveOptions(GetParam()));
  const Eigen::VectorXd q = test::MakeQ(*wc, {});
  const std::vector<Shape> box = {
      Box{Eigen::Isometry3d::Identity(), Eigen::Vector3d(0.1, 0.1, 0.1)}};
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() << 0.8, 0.0, 1.5;
  std::string error;
  ASSERT_TRUE(monitor.AddObject("crate", box, X_WO, 0.01, false, &error)) << error;
  monitor.Update(q);
  const std::vector<Warning> before = monitor.report().warnings;
  auto expect_refused = [&](bool ok, const std::string& needle) {
    EXPECT_FALSE(ok) << needle;
    EXPECT_NE(error.find(needle), std::string::npos)
        << "'" << error << "' lacks '" << needle << "'";
    EXPECT_EQ(monitor.live_object_count(), 1u) << needle;
    ExpectValid(monitor, needle);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_refused(monitor.AddObject("crate", box, X_WO, 0.0, false, &error), "already used");
  expect_refused(monitor.AddObject("left_link3", box, X_WO, 0.0, false, &error), "already used");
  expect_refused(monitor.AddObject("front_box", box, X_WO, 0.0, false, &error), "already used");
  expect_refused(monitor.AddObject("", box, X_WO, 0.0, false, &error), "empty name");
  expect_refused(monitor.AddObject("b", {}, X_WO, 0.0, false, &error), "expected 1 to 4");
  expect_refused(monitor.AddObject("b", std::vector<Shape>(5, box[0]), X_WO, 0.0, false, &error),
                 "expected 1 to 4");
  expect_refused(monitor.AddObject("b", box, X_WO, -0.1, false, &error), "tolerance_m");
  expect_refused(monitor.AddObject("b", box, X_WO, nan, false, &error), "tolerance_m");
  Eigen::Isometry3d bad = X_WO;
  bad.translation().x() = nan;
  expect_refused(monitor.AddObject("b", box, bad, 0.0, false, &error), "pose not finite");
  bad = X_WO;
  bad.linear() *= 2.0;
  expect_refused(monitor.AddObject("b", box, bad, 0.0, false, &error), "not orthonormal");
  expect_refused(
      monitor.AddObject("b", {Capsule{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), nan}}, X_WO,
                        0.0, false, &error),
      "radius");
  expect_refused(
      monitor.AddObject("b", {Box{Eigen::Isometry3d::Identity(), Eigen::Vector3d(0.1, 0.0, 0.1)}},
                        X_WO, 0.0, false, &error),
      "half extents");
  Eigen::Isometry3d far = X_WO;
  far.translation().x() = 50.0;
  expect_refused(monitor.AddObject("b", box, far, 0.0, false, &error), "world cube");
  // A second object whose primitive names would collide with an existing one's.
  const std::vector<Shape> two(2, box[0]);
  ASSERT_TRUE(monitor.AddObject("pair", two, X_WO, 0.0, false, &error)) << error;
  EXPECT_FALSE(monitor.AddObject("pair/1", box, X_WO, 0.0, false, &error));
  EXPECT_NE(error.find("already used"), std::string::npos) << error;
  ASSERT_TRUE(monitor.RemoveObject("pair", &error)) << error;
  // Moves and removes: unknown, scene-file, bad pose, out of the world.
  expect_refused(monitor.MoveObject("nothing", X_WO, &error), "unknown object");
  expect_refused(monitor.RemoveObject("nothing", &error), "unknown object");
  expect_refused(monitor.RemoveObject("pair", &error), "unknown object");
  expect_refused(monitor.MoveObject("front_box", X_WO, &error), "scene file");
  expect_refused(monitor.RemoveObject("front_table_top", &error), "scene file");
  expect_refused(monitor.RemoveObject("front_box", &error), "scene file");
  expect_refused(monitor.MoveObject("crate", bad, &error), "not orthonormal");
  expect_refused(monitor.MoveObject("crate", far, &error), "world cube");
  // A slot's placeholder name is no object.
  expect_refused(monitor.RemoveObject("~live0", &error), "unknown object");
  monitor.Update(q);
  EXPECT_EQ(monitor.report().warnings.size(), before.size());
  // Capacity: full, then refused; a removal frees a slot.
  for (std::uint32_t i = 1; i < kCapacity; ++i) {
    ASSERT_TRUE(monitor.AddObject("fill" + std::to_string(i), box, X_WO, 0.0, false, &error))
        << error;
  }
  EXPECT_FALSE(monitor.AddObject("one_more", box, X_WO, 0.0, false, &error));
  EXPECT_NE(error.find("no free slot"), std::string::npos) << error;
  EXPECT_EQ(monitor.live_object_count(), kCapacity);
  ASSERT_TRUE(monitor.RemoveObject("fill3", &error)) << error;
  EXPECT_TRUE(monitor.AddObject("one_more", box, X_WO, 0.0, false, &error)) << error;
  ExpectValid(monitor, "refill");
}

TEST(MonitorLiveObjectsSolids, BadSolidsAreRefused) {
  SolidShapeOptions options;
  std::vector<Shape> shapes;
  std::string error;
  auto refused = [&](const SolidSpec& solid, const std::string& needle) {
    EXPECT_FALSE(MakeSolidShapes_O(solid, options, &shapes, &error)) << needle;
    EXPECT_NE(error.find(needle), std::string::npos)
        << "'" << error << "' lacks '" << needle << "'";
  };
  SolidSpec s;
  s.type = SolidType::kBox;
  s.dimensions_m = {0.1, 0.1};
  refused(s, "2 dimensions given, expected 3");
  s.dimensions_m = {0.1, -0.1, 0.1};
  refused(s, "dimension y");
  s.type = SolidType::kSphere;
  s.dimensions_m = {std::numeric_limits<double>::infinity()};
  refused(s, "dimension radius");
  s.type = SolidType::kCylinder;
  s.dimensions_m = {0.1, 0.0};
  refused(s, "dimension length");
  s.type = SolidType::kCapsule;  // a capsule's length may be 0: a sphere
  EXPECT_TRUE(MakeSolidShapes_O(s, options, &shapes, &error)) << error;
  s.type = SolidType::kMesh;
  refused(s, "expected 0");
  s.dimensions_m.clear();
  refused(s, "mesh: empty");
  s.mesh.vertices_L = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.mesh.triangles = {{0, 1, 2}};
  refused(s, "mesh: no volume");
  s.mesh.triangles = {{0, 1, 7}};
  refused(s, "mesh: ");
  SolidType type;
  EXPECT_FALSE(ParseSolidType("cone", &type));
  EXPECT_TRUE(ParseSolidType("mesh", &type));
  EXPECT_EQ(type, SolidType::kMesh);
}

// An attachable live object is held and let go like a scene object; removing it while held lets
// it go first.
TEST_P(MonitorLiveObjects, AttachableLiveObjectIsHeldAndRemoved) {
  const auto wc = test::LoadBundledWorkcell();
  Monitor monitor(wc, LiveOptions(GetParam()));
  Eigen::VectorXd grasp_q;
  const Eigen::Isometry3d X_WO = RightToolTipAtGrasp(*wc, &monitor, &grasp_q);
  std::vector<Shape> chain;
  for (int k = 0; k < 3; ++k) {
    chain.push_back(Capsule{Eigen::Vector3d(0.05 * k, 0, 0), Eigen::Vector3d(0.05 * k + 0.1, 0, 0),
                            0.04});
  }
  std::string error;
  // Out of the grasp (0.5 m below the tip), it is refused, and held by nothing.
  ASSERT_TRUE(monitor.AddObject("far", chain, X_WO * Eigen::Translation3d(0, 0, -0.5), 0.01,
                                true, &error))
      << error;
  EXPECT_FALSE(monitor.Attach("far", "right_link7", &error));
  const std::string said = "Attach: object 'far' is ";
  ASSERT_EQ(error.rfind(said, 0), 0u) << error;
  // 0.5 m less the capsules' radii and the tip's reach below the link's capsule.
  const double gap_m = std::atof(error.c_str() + said.size());
  EXPECT_GT(gap_m, 0.3) << error;
  EXPECT_LT(gap_m, 0.5) << error;
  EXPECT_NE(error.find(" m from the geometry of link 'right_link7' and the links it carries, "
                       "more than the 0.1 m"),
            std::string::npos)
      << error;
  EXPECT_EQ(monitor.HolderOf("far"), "");
  ASSERT_TRUE(monitor.RemoveObject("far", &error)) << error;
  ASSERT_TRUE(monitor.AddObject("tool", chain, X_WO, 0.01, true, &error)) << error;
  EXPECT_EQ(monitor.HolderOf("tool"), "");
  ASSERT_TRUE(monitor.Attach("tool", "right_link6", &error)) << error;
  EXPECT_EQ(monitor.HolderOf("tool"), "right_link6");
  ASSERT_TRUE(monitor.Attach("tool", "right_link7", &error)) << error;  // handed on
  EXPECT_EQ(monitor.HolderOf("tool"), "right_link7");
  Eigen::VectorXd carry_q = grasp_q;
  carry_q[test::JointIndex(*wc, "right_joint1")] += 0.3;
  const CycleReport& report = monitor.Update(carry_q);
  // Held: its own overlapping capsules and its holder do not warn against each other.
  for (const Warning& w : report.warnings) {
    EXPECT_FALSE(monitor.primitive(w.b).owner == "tool" &&
                 (monitor.primitive(w.a).owner == "tool" ||
                  monitor.primitive(w.a).owner == "right_link7"))
        << monitor.primitive(w.a).name << " - " << monitor.primitive(w.b).name;
  }
  ExpectValid(monitor, "held");
  ASSERT_TRUE(monitor.RemoveObject("tool", &error)) << error;
  EXPECT_EQ(monitor.live_object_count(), 0u);
  monitor.Update(grasp_q);
  ExpectValid(monitor, "removed while held");
}

// A live object may be made a grasp target of any link (a dual UR5e user's gripper closing on a
// box added at run time was refused: only the scene file's grasp_targets were allowed), and
// the excuse goes with the object: the next object in its slot is checked against that link.
TEST_P(MonitorLiveObjects, LiveObjectIsAGraspTargetOfAnyLinkUntilRemoved) {
  const auto wc = test::LoadBundledWorkcell();
  Monitor monitor(wc, LiveOptions(GetParam()));
  Eigen::VectorXd grasp_q;
  const Eigen::Isometry3d X_WO = RightToolTipAtGrasp(*wc, &monitor, &grasp_q);
  const std::vector<Shape> box = {Box{Eigen::Isometry3d::Identity(), {0.03, 0.03, 0.03}}};
  auto tip_warns = [&](const std::string& object) {
    for (const Warning& w : monitor.Check(grasp_q).warnings) {
      if (monitor.primitive(w.a).owner == "right_link7" && monitor.primitive(w.b).owner == object) {
        return true;
      }
    }
    return false;
  };
  std::string error;
  ASSERT_TRUE(monitor.AddObject("crate", box, X_WO, 0.0, false, &error)) << error;
  ASSERT_TRUE(tip_warns("crate"));
  EXPECT_FALSE(monitor.Attach("crate", "right_link7", &error));
  EXPECT_EQ(error, "Attach: object 'crate' is not attachable (added with attachable false)");
  ASSERT_TRUE(monitor.SetGraspTarget("right_link7", "crate", true, &error)) << error;
  EXPECT_FALSE(tip_warns("crate"));
  // A scene object still only with the links its scene file names.
  EXPECT_FALSE(monitor.SetGraspTarget("right_link7", "front_table_top", true, &error));
  EXPECT_NE(error.find("is not a grasp target of link 'right_link7'"), std::string::npos) << error;
  ASSERT_TRUE(monitor.RemoveObject("crate", &error)) << error;
  ASSERT_TRUE(monitor.AddObject("drum", box, X_WO, 0.0, false, &error)) << error;
  EXPECT_TRUE(tip_warns("drum"));
  ExpectValid(monitor, "after the grasp target's object was removed");
}

// After adds, moves and removes (each once for warm-up), the cycles that follow allocate nothing.
TEST_P(MonitorLiveObjects, UpdateAfterLiveChangesDoesNotAllocate) {
  const auto wc = test::LoadBundledWorkcell();
  Monitor monitor(wc, LiveOptions(GetParam()));
  std::mt19937_64 rng(test::PrintSeed(77));
  const test::JointLimits limits = test::LimitsOf(*wc);
  const test::SmoothTrajectory path(limits, 0.8, &rng);
  std::vector<std::vector<Shape>> solids;
  for (int t = 0; t < 5; ++t) solids.push_back(RandomSolidShapes(t, &rng));
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < 20; ++i) poses.push_back(RandomPose(&rng));
  const std::vector<std::string> names = {"a", "b", "c", "d", "e"};
  std::string error;
  error.reserve(512);
  Eigen::VectorXd q;
  std::uint64_t update_allocations = 0;
  int cycle = 0;
  auto updates = [&](int count) {
    for (int i = 0; i < count; ++i, ++cycle) {
      path.At(cycle * 0.05, &q);
      const std::uint64_t before = test::AllocationCount();
      monitor.Update(q);
      update_allocations += test::AllocationCount() - before;
    }
  };
  auto round = [&](int r) {
    for (std::size_t i = 0; i < names.size(); ++i) {
      ASSERT_TRUE(monitor.AddObject(names[i], solids[i], poses[(r + i) % poses.size()], 0.02,
                                    false, &error))
          << error;
      updates(3);
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
      ASSERT_TRUE(monitor.MoveObject(names[i], poses[(r + 7 * i + 3) % poses.size()], &error))
          << error;
      updates(3);
    }
    for (const std::string& name : names) {
      ASSERT_TRUE(monitor.RemoveObject(name, &error)) << error;
      updates(3);
    }
  };
  q.resize(static_cast<int>(wc->joint_names.size()));
  for (int r = 0; r < 2; ++r) round(r);  // warm-up: pools may grow once
  update_allocations = 0;
  for (int r = 2; r < 30; ++r) round(r);
  EXPECT_EQ(update_allocations, 0u) << BroadPhaseMethodName(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Methods, MonitorLiveObjects,
                         ::testing::Values(BroadPhaseMethod::kOctree, BroadPhaseMethod::kNaive),
                         [](const auto& info) { return BroadPhaseMethodName(info.param); });

}  // namespace
}  // namespace arm_collision_monitor
