// rviz markers of the monitor's current state: capsules and boxes coloured by state (clear /
// within twice their threshold / warned), lines between the closest points of warned pairs
// with the distance as text, and the spatial index's occupied leaf cells as wireframe cubes.
#pragma once

#include <string>
#include <vector>

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include "arm_collision_monitor/CollisionWarning.h"
#include "arm_collision_monitor/monitor/monitor.h"

namespace arm_collision_monitor {

/// Colours (RGB, 0..1) of the primitive states; the headless rviz test looks for kWarningRgb.
struct MarkerPalette {
  static constexpr float kClearRgb[3] = {0.15f, 0.75f, 0.25f};
  static constexpr float kNearRgb[3] = {1.0f, 0.8f, 0.0f};
  static constexpr float kWarningRgb[3] = {1.0f, 0.0f, 0.0f};
};

class MarkerBuilder {
 public:
  /// `frame_id`: the fixed frame the markers are expressed in (the workcell's W).
  MarkerBuilder(const Monitor& monitor, std::string frame_id);

  /// The markers for the monitor's current shapes and `warnings` (the last published ones).
  /// Every id published before is either re-added or deleted, so nothing stale stays on
  /// screen. Allocates (visualisation runs at a bounded rate, outside the cycle's budget).
  const visualization_msgs::MarkerArray& Build(const std::vector<CollisionWarning>& warnings,
                                               const ros::Time& stamp);

 private:
  enum class PrimitiveState { kClear, kNear, kWarning };
  void ComputeStates(const std::vector<CollisionWarning>& warnings);
  visualization_msgs::Marker& NextMarker(const std::string& ns, int id, int type,
                                         const ros::Time& stamp);
  void AddPrimitive(PrimitiveId id, const ros::Time& stamp);
  void AddWarnings(const std::vector<CollisionWarning>& warnings, const ros::Time& stamp);
  void AddIndexCells(const ros::Time& stamp);

  const Monitor& monitor_;
  std::string frame_id_;
  std::vector<PrimitiveState> state_;
  std::vector<IndexCell> cells_;
  visualization_msgs::MarkerArray array_;
  std::size_t used_ = 0;               ///< markers of array_ filled this Build()
  std::size_t previous_text_count_ = 0;
};

}  // namespace arm_collision_monitor
