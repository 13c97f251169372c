// LoadMonitorOptions and the values derived from the options: the bundled config/monitor.yaml,
// overrides, and every kind of bad input, each rejected with a message naming the file and the
// element.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "arm_collision_monitor/monitor/monitor_options.h"
#include "load_error_expect.h"

namespace arm_collision_monitor {
namespace {

const std::string kSource = ACM_SOURCE_DIR;
const std::string kMonitorYaml = kSource + "/config/monitor.yaml";
const std::string kData = kSource + "/test/data/";

TEST(MonitorOptions, BundledMonitorOptions) {
  const MonitorOptions o = LoadMonitorOptions(kMonitorYaml);
  EXPECT_EQ(o.broad_phase.method, BroadPhaseMethod::kAuto);
  EXPECT_EQ(o.broad_phase.max_objects_per_leaf, 10);
  EXPECT_EQ(o.tolerance_m, 0.0305);
  EXPECT_EQ(o.max_speed_mps, 0.61);
  EXPECT_EQ(o.cycle_period_s, 0.05);
  EXPECT_NEAR(MinCellSize_m(o), 0.0305 + kDefaultIndexSlack_m, 1e-15);
  EXPECT_FALSE(o.speed_scaled_tolerance);
  EXPECT_EQ(MonitorOptions{}.broad_phase.method, BroadPhaseMethod::kAuto);  // same default
  EXPECT_EQ(o.index_slack_m, kDefaultIndexSlack_m);
  EXPECT_EQ(o.fixed_frame, "");  // the URDF root link
  EXPECT_EQ(o.live_objects.capacity, 16u);
  EXPECT_EQ(o.live_objects.max_primitives_per_object, 8u);
  EXPECT_TRUE(o.swept_check);
  EXPECT_EQ(o.swept_resolution_m, 0.001);
  EXPECT_EQ(o.max_step_m, 1.0);
}

TEST(MonitorOptions, MonitorOptionsOverridesAndErrors) {
  const MonitorOptions o = LoadMonitorOptions(
      WriteTempFile("monitor.yaml",
                "broad_phase: grid\ngrid_cells_per_axis: 8\nmax_speed_mps: 1.0\n"
                "cycle_period_s: 0.01\ntechniques: {inside_node_exit: false}\nindex_slack_m: 0\n"
                "live_objects: {capacity: 0, max_primitives_per_object: 3}\n"
                "swept_check: false\nswept_resolution_m: 0.002\nmax_step_m: 0.3\n"
                "fixed_frame: odom\n"));
  EXPECT_EQ(o.fixed_frame, "odom");
  EXPECT_EQ(o.live_objects.capacity, 0u);
  EXPECT_EQ(o.live_objects.max_primitives_per_object, 3u);
  EXPECT_EQ(o.index_slack_m, 0.0);
  EXPECT_FALSE(o.swept_check);
  EXPECT_EQ(o.swept_resolution_m, 0.002);
  EXPECT_EQ(o.max_step_m, 0.3);
  EXPECT_EQ(o.broad_phase.method, BroadPhaseMethod::kGrid);
  EXPECT_EQ(o.broad_phase.grid_cells_per_axis, 8);
  EXPECT_NEAR(MinCellSize_m(o), 0.01, 1e-15);
  EXPECT_FALSE(o.broad_phase.techniques.inside_node_exit);
  EXPECT_TRUE(o.broad_phase.techniques.directional_neighbours);

  const struct {
    std::string text;
    std::vector<std::string> parts;
  } bad[] = {
      {"broad_phase: kdtree\n", {"broad_phase", "kdtree", "auto, octree"}},
      {"auto_broad_phase: true\n", {"auto_broad_phase", "broad_phase: auto"}},
      {"max_speed_mps: -1\n", {"max_speed_mps", "> 0"}},
      {"index_slack_m: -0.1\n", {"index_slack_m", ">= 0"}},
      {"swept_resolution_m: 0\n", {"swept_resolution_m", "> 0"}},
      {"max_step_m: -1\n", {"max_step_m", "> 0"}},
      {"swept_check: 1.5\n", {"swept_check", "true or false"}},
      {"cycle_period_s: .nan\n", {"cycle_period_s", "finite"}},
      {"max_objects_per_leaf: 0\n", {"max_objects_per_leaf", "positive integer"}},
      {"tolerence_m: 0.03\n", {"unknown key 'tolerence_m'"}},
      {"speed_scaled_tolerance: maybe\n", {"speed_scaled_tolerance", "true or false"}},
      {"max_speed_mps: [1, 2\n", {"malformed YAML"}},
      {"live_objects: {capacity: 2.5}\n", {"live_objects.capacity", "whole number"}},
      {"live_objects: {capacity: 100000}\n", {"live_objects.capacity", "4096"}},
      {"live_objects: {max_primitives_per_object: 0}\n",
       {"live_objects.max_primitives_per_object", "positive integer"}},
      {"live_objects: {max_primitives_per_object: 65}\n",
       {"live_objects.max_primitives_per_object", "at most 64"}},
      {"live_objects: {capacty: 3}\n", {"live_objects", "unknown key 'capacty'"}},
      {"live_objects: 3\n", {"live_objects"}},
  };
  for (const auto& b : bad) {
    const std::string path = WriteTempFile("monitor_bad.yaml", b.text);
    std::vector<std::string> parts = b.parts;
    parts.push_back(path);
    ExpectLoadError([&] { LoadMonitorOptions(path); }, parts);
  }
  ExpectLoadError([&] { LoadMonitorOptions(kData + "no_such_monitor.yaml"); },
                  {"no_such_monitor.yaml", "cannot open"});
}

}  // namespace
}  // namespace arm_collision_monitor
