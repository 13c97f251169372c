// MarkerBuilder on the bundled workcell, no ROS master: the index's occupied leaf cells (static
// and moving apart, counted), the closest-point lines of the warnings, the "near" colour against
// a brute-force reference that uses the Monitor's run-time compatibility, and a held object
// never drawn near its holder.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../core/test_monitor_util.h"
#include "arm_collision_monitor/ros/marker_builder.h"

namespace arm_collision_monitor {
namespace {

using test::ArmReachDown;
using test::LoadBundledWorkcell;
using test::MakeQ;
using test::Prim;

enum class Shown { kClear, kNear, kWarning, kAbsent };

const char* Name(Shown s) {
  switch (s) {
    case Shown::kClear:
      return "clear";
    case Shown::kNear:
      return "near";
    case Shown::kWarning:
      return "warning";
    case Shown::kAbsent:
      return "absent";
  }
  return "?";
}

const visualization_msgs::Marker* FindMarker(const visualization_msgs::MarkerArray& array,
                                             const std::string& ns, int id) {
  for (const visualization_msgs::Marker& m : array.markers) {
    if (m.ns == ns && m.id == id) return &m;
  }
  return nullptr;
}

bool HasRgb(const std_msgs::ColorRGBA& c, const float rgb[3]) {
  return c.r == rgb[0] && c.g == rgb[1] && c.b == rgb[2];
}

// The state primitive `id` is drawn in (its first marker: the cylinder or the cube).
Shown ShownState(const visualization_msgs::MarkerArray& array, const Workcell& wc,
                 PrimitiveId id) {
  const bool is_capsule = std::holds_alternative<Capsule>(wc.primitives[id].shape_L);
  const int marker_id = static_cast<int>(id) * MarkerLayout::kMarkersPerPrimitive;
  const visualization_msgs::Marker* m =
      FindMarker(array, is_capsule ? MarkerLayout::kCapsules : MarkerLayout::kBoxes, marker_id);
  EXPECT_NE(m, nullptr) << wc.primitives[id].name;
  if (m == nullptr || m->action != visualization_msgs::Marker::ADD) return Shown::kAbsent;
  if (HasRgb(m->color, MarkerPalette::kWarningRgb)) return Shown::kWarning;
  if (HasRgb(m->color, MarkerPalette::kNearRgb)) return Shown::kNear;
  EXPECT_TRUE(HasRgb(m->color, MarkerPalette::kClearRgb)) << wc.primitives[id].name;
  return Shown::kClear;
}

// Brute force over all pairs with the exact distance, independent of the builder's boxes:
// a pair is near when checked now (active, not both static, not excused at run time) and
// closer than kNearFactor times its threshold; a warned primitive is red. Zero-length capsules
// (a cylinder of length 0 is deleted) are looked at through the capsule of length > 0 only.
std::vector<Shown> ReferenceStates(const Monitor& monitor, bool use_startup_matrix) {
  const Workcell& wc = monitor.workcell();
  const std::uint32_t n = monitor.primitive_count();
  std::vector<Shown> state(n, Shown::kClear);
  for (PrimitiveId a = 0; a < n; ++a) {
    for (PrimitiveId b = a + 1; b < n; ++b) {
      if (!monitor.is_active(a) || !monitor.is_active(b) ||
          (wc.primitives[a].is_static && wc.primitives[b].is_static)) {
        continue;
      }
      const bool is_excused = use_startup_matrix ? wc.compatible.AreCompatible(a, b)
                                                 : monitor.AreCompatibleNow(a, b);
      const double near_m =
          MarkerBuilder::kNearFactor * (monitor.tolerance_m(a) + monitor.tolerance_m(b));
      if (!is_excused &&
          ShapeDistance(monitor.shape_W(a), monitor.shape_W(b)).distance_m < near_m) {
        state[a] = state[b] = Shown::kNear;
      }
    }
  }
  for (const Warning& w : monitor.report().warnings) state[w.a] = state[w.b] = Shown::kWarning;
  for (PrimitiveId id = 0; id < n; ++id) {
    if (!monitor.is_active(id)) state[id] = Shown::kAbsent;
  }
  return state;
}

bool IsZeroLengthCapsule(const Monitor& monitor, PrimitiveId id) {
  const Capsule* c = std::get_if<Capsule>(&monitor.shape_W(id));
  return c != nullptr && c->p0_W == c->p1_W;
}

// Every primitive drawn as the reference says; returns how many are drawn near.
int ExpectStatesAsReference(const visualization_msgs::MarkerArray& array,
                            const Monitor& monitor, const std::string& context) {
  const std::vector<Shown> expected = ReferenceStates(monitor, /*use_startup_matrix=*/false);
  int near = 0;
  for (PrimitiveId id = 0; id < monitor.primitive_count(); ++id) {
    if (IsZeroLengthCapsule(monitor, id)) continue;
    const Shown shown = ShownState(array, monitor.workcell(), id);
    EXPECT_EQ(shown, expected[id]) << context << ": " << monitor.workcell().primitives[id].name
                                   << " drawn " << Name(shown) << ", expected "
                                   << Name(expected[id]);
    near += shown == Shown::kNear ? 1 : 0;
  }
  return near;
}

TEST(MarkerBuilder, IndexLeafCellsAreDrawnAndMovingOnesApart) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, test::OptionsFor(BroadPhaseMethod::kOctree));
  monitor.Update(MakeQ(*wc, {}));
  MarkerBuilder builder(monitor, "world");
  const visualization_msgs::MarkerArray& array = builder.Build(ros::Time(0));

  std::vector<IndexCell> cells;
  monitor.CollectIndexCells(&cells);
  std::vector<const IndexCell*> static_cells, moving_cells;
  for (const IndexCell& cell : cells) {
    if (cell.primitive_count == 0) continue;
    (cell.holds_moving ? moving_cells : static_cells).push_back(&cell);
  }
  ASSERT_FALSE(static_cells.empty());
  ASSERT_FALSE(moving_cells.empty());
  const auto* static_wire =
      FindMarker(array, MarkerLayout::kIndexCells, MarkerLayout::kStaticCellsId);
  const auto* moving_wire =
      FindMarker(array, MarkerLayout::kIndexCells, MarkerLayout::kMovingCellsId);
  ASSERT_NE(static_wire, nullptr);
  ASSERT_NE(moving_wire, nullptr);
  EXPECT_TRUE(HasRgb(static_wire->color, MarkerPalette::kStaticCellRgb));
  EXPECT_TRUE(HasRgb(moving_wire->color, MarkerPalette::kMovingCellRgb));
  const std::pair<const visualization_msgs::Marker*, const std::vector<const IndexCell*>*>
      kinds[2] = {{static_wire, &static_cells}, {moving_wire, &moving_cells}};
  for (const auto& [wire, expected] : kinds) {
    ASSERT_EQ(wire->points.size(), MarkerLayout::kPointsPerCell * expected->size());
    for (std::size_t k = 0; k < expected->size(); ++k) {
      // Every point of cell k's 12 edges is one of its corners, and both extreme ones occur.
      const Aabb& box = (*expected)[k]->box_W;
      bool has_min = false, has_max = false;
      for (int e = 0; e < MarkerLayout::kPointsPerCell; ++e) {
        const auto& p = wire->points[k * MarkerLayout::kPointsPerCell + e];
        const Eigen::Vector3d p_W(p.x, p.y, p.z);
        for (int axis = 0; axis < 3; ++axis) {
          EXPECT_TRUE(p_W[axis] == box.min_W[axis] || p_W[axis] == box.max_W[axis]);
        }
        has_min = has_min || p_W == box.min_W;
        has_max = has_max || p_W == box.max_W;
      }
      EXPECT_TRUE(has_min && has_max) << "cell " << k;
    }
  }
}

TEST(MarkerBuilder, ClosestPointLinesEndAtTheWarningsPoints) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  // The right tool tip touching the top of the box on the right table.
  const CycleReport& report = monitor.Update(ArmReachDown(*wc, "right", 0.1, -1.55, 0.95));
  ASSERT_FALSE(report.warnings.empty());
  MarkerBuilder builder(monitor, "world");
  const visualization_msgs::MarkerArray& array = builder.Build(ros::Time(0));
  const auto* lines = FindMarker(array, MarkerLayout::kClosestPoints, 0);
  ASSERT_NE(lines, nullptr);
  EXPECT_EQ(lines->action, visualization_msgs::Marker::ADD);
  ASSERT_EQ(lines->points.size(), 2 * report.warnings.size());
  for (std::size_t k = 0; k < report.warnings.size(); ++k) {
    const Warning& w = report.warnings[k];
    const auto& a = lines->points[2 * k];
    const auto& b = lines->points[2 * k + 1];
    EXPECT_EQ(Eigen::Vector3d(a.x, a.y, a.z), w.p_WA) << k;
    EXPECT_EQ(Eigen::Vector3d(b.x, b.y, b.z), w.p_WB) << k;
    EXPECT_EQ(ShownState(array, *wc, w.a), Shown::kWarning);
    EXPECT_EQ(ShownState(array, *wc, w.b), Shown::kWarning);
    // The label names the pair over its distance and threshold in millimetres.
    const auto* label = FindMarker(array, MarkerLayout::kDistances, static_cast<int>(k));
    ASSERT_NE(label, nullptr);
    char distance[64];
    std::snprintf(distance, sizeof(distance), "%.0f mm (< %.0f)", 1e3 * w.distance_m,
                  1e3 * w.threshold_m);
    EXPECT_EQ(label->text, wc->primitives[w.a].name + " -- " + wc->primitives[w.b].name + "\n" +
                               distance);
  }
  ExpectStatesAsReference(array, monitor, "touching");
  // Back home (the step leaves the box's zone: the swept check warns on its way; idle at home
  // it clears): no warning, the lines and labels of the previous build are deleted.
  monitor.Update(MakeQ(*wc, {}));
  monitor.Update(MakeQ(*wc, {}));
  ASSERT_TRUE(monitor.report().warnings.empty());
  const visualization_msgs::MarkerArray& clear = builder.Build(ros::Time(0));
  EXPECT_EQ(FindMarker(clear, MarkerLayout::kClosestPoints, 0)->action,
            visualization_msgs::Marker::DELETE);
  for (std::size_t k = 0; k < report.warnings.size(); ++k) {
    const auto* label = FindMarker(clear, MarkerLayout::kDistances, static_cast<int>(k));
    ASSERT_NE(label, nullptr);
    EXPECT_EQ(label->action, visualization_msgs::Marker::DELETE);
  }
}

// The labels of warnings at nearly one point stack rather than cover each other: no two are
// within a label's height (two lines of 0.05 m, up to rounding) vertically and half their widths
// (0.025 m a character of their longest line) horizontally. The right arm pushed into the box on the right table, its tip ever lower, warns
// for more and more of its primitives; the arms turned towards each other warn for pairs with
// labels at one point (where stacking by "just above the label in the way" met rounding and
// never ended).
TEST(MarkerBuilder, DistanceLabelsOfNearbyWarningsDoNotOverlap) {
  const auto wc = LoadBundledWorkcell();
  std::vector<Eigen::VectorXd> poses;
  for (int k = 0; k <= 6; ++k) {
    poses.push_back(ArmReachDown(*wc, "right", 0.1, -1.55, 0.95 - 0.05 * k));
  }
  poses.push_back(MakeQ(*wc, {{"left_joint1", -1.5708}, {"left_joint2", 0.5},
                              {"right_joint1", 1.5708}, {"right_joint2", 0.5}}));
  std::size_t most_labels = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    Monitor monitor(wc, MonitorOptions{});
    const CycleReport& report = monitor.Update(poses[k]);
    MarkerBuilder builder(monitor, "world");
    const visualization_msgs::MarkerArray& array = builder.Build(ros::Time(0));
    std::vector<Eigen::Vector3d> labels_W;
    std::vector<double> widths_m;
    for (std::size_t i = 0; i < report.warnings.size(); ++i) {
      const auto* label = FindMarker(array, MarkerLayout::kDistances, static_cast<int>(i));
      ASSERT_NE(label, nullptr);
      labels_W.emplace_back(label->pose.position.x, label->pose.position.y,
                            label->pose.position.z);
      const std::size_t newline = label->text.find('\n');
      ASSERT_NE(newline, std::string::npos) << label->text;
      widths_m.push_back(0.025 * std::max(newline, label->text.size() - newline - 1));
    }
    most_labels = std::max(most_labels, labels_W.size());
    for (std::size_t i = 0; i < labels_W.size(); ++i) {
      for (std::size_t j = i + 1; j < labels_W.size(); ++j) {
        const Eigen::Vector3d d = labels_W[i] - labels_W[j];
        EXPECT_FALSE(std::abs(d.z()) < 0.1 * (1.0 - 1e-6) &&
                     d.head<2>().norm() < 0.5 * (widths_m[i] + widths_m[j]))
            << "pose " << k << ": labels " << i << " and " << j << " overlap: " << d.transpose();
      }
    }
  }
  EXPECT_GE(most_labels, 3u);
}

TEST(MarkerBuilder, NearStateMatchesTheBruteForceReference) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  MarkerBuilder builder(monitor, "world");
  // The right tool tip lowered onto the box in 16 steps: clear, then near, then warned.
  int near_steps = 0;
  for (int k = 0; k <= 16; ++k) {
    const double tip_z_m = 1.35 - 0.025 * k;
    monitor.Update(ArmReachDown(*wc, "right", 0.1, -1.55, tip_z_m));
    const int near = ExpectStatesAsReference(builder.Build(ros::Time(0)), monitor,
                                             "tip at z = " + std::to_string(tip_z_m));
    near_steps += near > 0 ? 1 : 0;
  }
  EXPECT_GT(near_steps, 0);  // the sweep does pass through the near band
}

TEST(MarkerBuilder, HeldObjectIsNeverNearItsHolder) {
  const auto wc = LoadBundledWorkcell();
  Monitor monitor(wc, MonitorOptions{});
  const PrimitiveId gripper = Prim(*wc, "right_link7");
  const PrimitiveId box = Prim(*wc, "right_box");
  std::string error;
  // Grasp the box on the right table, then lift it well clear of the table.
  ASSERT_TRUE(monitor.SetGraspTarget("right_link7", "right_box", true, &error)) << error;
  monitor.Update(ArmReachDown(*wc, "right", 0.1, -1.55, 0.95));
  ASSERT_TRUE(monitor.Attach("right_box", "right_link7", &error)) << error;
  ASSERT_TRUE(monitor.SetGraspTarget("right_link7", "right_box", false, &error)) << error;
  // (The box hangs close below link 6: that pair warns, so the box is red; the gripper's only
  // partner within the near band is the box it holds.)
  monitor.Update(ArmReachDown(*wc, "right", 0.1, -1.55, 1.35));
  ASSERT_FALSE(test::HasWarning(monitor.report().warnings, gripper, box));

  // The pair is within the near band and the start-up matrix does not excuse it: a builder
  // using that matrix would draw the gripper yellow.
  const double near_m =
      MarkerBuilder::kNearFactor * (monitor.tolerance_m(gripper) + monitor.tolerance_m(box));
  ASSERT_LT(ShapeDistance(monitor.shape_W(gripper), monitor.shape_W(box)).distance_m, near_m);
  ASSERT_FALSE(wc->compatible.AreCompatible(gripper, box));
  ASSERT_TRUE(monitor.AreCompatibleNow(gripper, box));
  const std::vector<Shown> startup = ReferenceStates(monitor, /*use_startup_matrix=*/true);
  ASSERT_EQ(startup[gripper], Shown::kNear);

  MarkerBuilder builder(monitor, "world");
  const visualization_msgs::MarkerArray& array = builder.Build(ros::Time(0));
  EXPECT_EQ(ShownState(array, *wc, gripper), Shown::kClear);
  EXPECT_NE(ShownState(array, *wc, box), Shown::kNear);
  ExpectStatesAsReference(array, monitor, "held");
}

}  // namespace
}  // namespace arm_collision_monitor
