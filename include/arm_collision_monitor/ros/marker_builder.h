// rviz markers of the monitor's current state, built from the Monitor itself (its last
// CycleReport, shapes, tolerances and run-time compatibility), never from published messages:
// capsules and boxes coloured by state (clear / within twice their threshold of a pair the
// Monitor checks / warned), lines between the closest points of warned pairs labelled with the
// pair's names and distance, and the spatial index's occupied leaf cells as wireframe cubes.
#pragma once

#include <string>
#include <vector>

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include "arm_collision_monitor/monitor/monitor.h"

namespace arm_collision_monitor {

/// Colours (RGB, 0..1) of the primitive states; the headless rviz test looks for kWarningRgb.
struct MarkerPalette {
  static constexpr float kClearRgb[3] = {0.15f, 0.75f, 0.25f};
  static constexpr float kNearRgb[3] = {1.0f, 0.8f, 0.0f};
  static constexpr float kWarningRgb[3] = {1.0f, 0.0f, 0.0f};
  /// Index cells holding only static primitives, and cells holding moving ones.
  static constexpr float kStaticCellRgb[3] = {0.6f, 0.6f, 0.6f};
  static constexpr float kMovingCellRgb[3] = {0.1f, 0.6f, 1.0f};
};

/// Marker namespaces and ids, for rviz displays and tests.
struct MarkerLayout {
  static constexpr const char* kCapsules = "capsules";  ///< ids 3 * primitive + 0 (cylinder), 1, 2
  static constexpr const char* kBoxes = "boxes";        ///< id 3 * primitive
  static constexpr int kMarkersPerPrimitive = 3;
  static constexpr const char* kClosestPoints = "closest_points";  ///< id 0: one LINE_LIST
  static constexpr const char* kDistances = "distances";  ///< id k: text of warning k
  static constexpr const char* kIndexCells = "index_cells";  ///< id 0 static, 1 moving
  static constexpr int kStaticCellsId = 0;
  static constexpr int kMovingCellsId = 1;
  static constexpr int kPointsPerCell = 24;  ///< LINE_LIST points of a cube's 12 edges
};

class MarkerBuilder {
 public:
  /// `frame_id`: the fixed frame the markers are expressed in (the workcell's W).
  MarkerBuilder(const Monitor& monitor, std::string frame_id);

  /// The markers for the monitor's current shapes and its last report (monitor.report()).
  /// Every id published before is either re-added or deleted, so nothing stale stays on
  /// screen. Allocates (visualisation runs at a bounded rate, outside the cycle's budget).
  ///
  /// "Near": a pair the Monitor checks now (active, not both static, not AreCompatibleNow: a
  /// held object is never near its holder) closer than kNearFactor times its threshold. Cost:
  /// one AABB per active primitive, then an AABB overlap test of each moving primitive against
  /// every active one (m * n box tests, ~700 for the bundled workcell at the marker rate) and
  /// an exact distance test only for the overlapping pairs.
  const visualization_msgs::MarkerArray& Build(const ros::Time& stamp);

  /// Pairs drawn "near" when closer than this many times their warning threshold.
  static constexpr double kNearFactor = 2.0;

 private:
  enum class PrimitiveState { kClear, kNear, kWarning };
  void ComputeStates(const CycleReport& report);
  visualization_msgs::Marker& NextMarker(const std::string& ns, int id, int type,
                                         const ros::Time& stamp);
  void AddPrimitive(PrimitiveId id, const ros::Time& stamp);
  void AddWarnings(const std::vector<Warning>& warnings, const ros::Time& stamp);
  void AddIndexCells(const ros::Time& stamp);

  const Monitor& monitor_;
  std::string frame_id_;
  std::vector<PrimitiveState> state_;
  std::vector<Aabb> near_box_W_;  ///< each primitive's box grown by kNearFactor * tolerance
  std::vector<IndexCell> cells_;
  visualization_msgs::MarkerArray array_;
  std::size_t used_ = 0;               ///< markers of array_ filled this Build()
  std::size_t previous_text_count_ = 0;
  /// A warning's label as placed: its centre and width (m).
  struct PlacedLabel {
    Eigen::Vector3d p_W;
    double width_m;
  };
  std::vector<PlacedLabel> placed_labels_;  ///< AddWarnings' scratch
};

}  // namespace arm_collision_monitor
