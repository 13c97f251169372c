#include "arm_collision_monitor/ros/marker_builder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

#include <Eigen/Geometry>

#include "arm_collision_monitor/geometry/distance.h"

namespace arm_collision_monitor {
namespace {

// Drawing sizes (metres on screen, not physics): thin enough not to hide the primitives.
constexpr double kLineWidth_m = 0.006;
constexpr double kCellLineWidth_m = 0.002;
constexpr double kTextHeight_m = 0.05;
// A warning's label: the pair's names over its distance, two lines of text.
constexpr int kLabelLines = 2;
constexpr double kLabelHeight_m = kLabelLines * kTextHeight_m;
// Horizontal room a character takes (m), generously: "120 mm (< 61)" is about six text
// heights.
constexpr double kCharWidth_m = 0.5 * kTextHeight_m;
// Capsules opaque; boxes translucent so the arms stay visible behind tables and walls.
constexpr float kCapsuleAlpha = 1.0f;
constexpr float kBoxAlpha = 0.5f;
// Marker ids per primitive: a capsule is a cylinder plus two end spheres.
constexpr int kMarkersPerPrimitive = MarkerLayout::kMarkersPerPrimitive;

std_msgs::ColorRGBA Rgba(const float rgb[3], float alpha) {
  std_msgs::ColorRGBA c;
  c.r = rgb[0];
  c.g = rgb[1];
  c.b = rgb[2];
  c.a = alpha;
  return c;
}

geometry_msgs::Point ToPoint(const Eigen::Vector3d& p_W) {
  geometry_msgs::Point p;
  p.x = p_W.x();
  p.y = p_W.y();
  p.z = p_W.z();
  return p;
}

void SetPose(const Eigen::Vector3d& p_W, const Eigen::Quaterniond& R_W,
             visualization_msgs::Marker* m) {
  m->pose.position = ToPoint(p_W);
  m->pose.orientation.w = R_W.w();
  m->pose.orientation.x = R_W.x();
  m->pose.orientation.y = R_W.y();
  m->pose.orientation.z = R_W.z();
}

// Two labels at these centres would cover each other (text faces the viewer: its height is
// vertical, its width horizontal in some direction). Labels a slot apart (a label's height, up
// to rounding) do not overlap.
bool LabelsOverlap(const Eigen::Vector3d& a_W, double a_width_m, const Eigen::Vector3d& b_W,
                   double b_width_m) {
  return std::abs(a_W.z() - b_W.z()) < (1.0 - 1e-9) * kLabelHeight_m &&
         (a_W - b_W).head<2>().norm() < 0.5 * (a_width_m + b_width_m);
}

}  // namespace

MarkerBuilder::MarkerBuilder(const Monitor& monitor, std::string frame_id)
    : monitor_(monitor), frame_id_(std::move(frame_id)) {}

void MarkerBuilder::ComputeStates(const CycleReport& report) {
  const std::uint32_t n = monitor_.primitive_count();
  state_.assign(n, PrimitiveState::kClear);
  near_box_W_.resize(n);
  for (PrimitiveId id = 0; id < n; ++id) {
    if (monitor_.is_active(id)) {
      near_box_W_[id] =
          ComputeAabb(monitor_.shape_W(id)).Inflated(kNearFactor * monitor_.tolerance_m(id));
    }
  }
  // Every pair the Monitor checks has a moving primitive: pair each moving one with every
  // active primitive (a moving partner only once), boxes first.
  for (PrimitiveId a = 0; a < n; ++a) {
    if (!monitor_.is_active(a) || monitor_.primitive(a).is_static) {
      continue;
    }
    for (PrimitiveId b = 0; b < n; ++b) {
      if (b == a || !monitor_.is_active(b) || (!monitor_.primitive(b).is_static && b < a) ||
          !near_box_W_[a].Overlaps(near_box_W_[b]) || monitor_.AreCompatibleNow(a, b)) {
        continue;
      }
      const double near_m = kNearFactor * (monitor_.tolerance_m(a) + monitor_.tolerance_m(b));
      if (IsCloserThan(monitor_.shape_W(a), monitor_.shape_W(b), near_m)) {
        state_[a] = PrimitiveState::kNear;
        state_[b] = PrimitiveState::kNear;
      }
    }
  }
  for (const Warning& w : report.warnings) {
    state_[w.a] = PrimitiveState::kWarning;
    state_[w.b] = PrimitiveState::kWarning;
  }
}

visualization_msgs::Marker& MarkerBuilder::NextMarker(const std::string& ns, int id, int type,
                                                      const ros::Time& stamp) {
  if (used_ == array_.markers.size()) {
    array_.markers.emplace_back();
  }
  visualization_msgs::Marker& m = array_.markers[used_++];
  m = visualization_msgs::Marker();
  m.header.frame_id = frame_id_;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  return m;
}

void MarkerBuilder::AddPrimitive(PrimitiveId id, const ros::Time& stamp) {
  const int base_id = static_cast<int>(id) * kMarkersPerPrimitive;
  const bool is_active = monitor_.is_active(id);
  const Shape& shape = monitor_.shape_W(id);
  const float* rgb = state_[id] == PrimitiveState::kWarning ? MarkerPalette::kWarningRgb
                     : state_[id] == PrimitiveState::kNear  ? MarkerPalette::kNearRgb
                                                            : MarkerPalette::kClearRgb;
  if (const Capsule* capsule = std::get_if<Capsule>(&shape)) {
    const Eigen::Vector3d axis_W = capsule->p1_W - capsule->p0_W;
    const double length_m = axis_W.norm();
    visualization_msgs::Marker& cylinder =
        NextMarker(MarkerLayout::kCapsules, base_id, visualization_msgs::Marker::CYLINDER, stamp);
    if (!is_active || length_m <= 0.0) {
      // rviz rejects zero-size markers: a zero-length capsule is its sphere alone.
      cylinder.action = visualization_msgs::Marker::DELETE;
    } else {
      SetPose(0.5 * (capsule->p0_W + capsule->p1_W),
              Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis_W), &cylinder);
      cylinder.scale.x = cylinder.scale.y = 2.0 * capsule->radius_m;
      cylinder.scale.z = length_m;
      cylinder.color = Rgba(rgb, kCapsuleAlpha);
    }
    const Eigen::Vector3d* ends_W[2] = {&capsule->p0_W, &capsule->p1_W};
    for (int e = 0; e < 2; ++e) {
      visualization_msgs::Marker& sphere =
          NextMarker(MarkerLayout::kCapsules, base_id + 1 + e,
                     visualization_msgs::Marker::SPHERE, stamp);
      if (!is_active || capsule->radius_m <= 0.0) {
        sphere.action = visualization_msgs::Marker::DELETE;
        continue;
      }
      SetPose(*ends_W[e], Eigen::Quaterniond::Identity(), &sphere);
      sphere.scale.x = sphere.scale.y = sphere.scale.z = 2.0 * capsule->radius_m;
      sphere.color = Rgba(rgb, kCapsuleAlpha);
    }
  } else {
    const Box& box = std::get<Box>(shape);
    visualization_msgs::Marker& cube =
        NextMarker(MarkerLayout::kBoxes, base_id, visualization_msgs::Marker::CUBE, stamp);
    if (!is_active || (box.half_extents_m.array() <= 0.0).any()) {
      cube.action = visualization_msgs::Marker::DELETE;
      return;
    }
    SetPose(box.X_WB.translation(), Eigen::Quaterniond(box.X_WB.linear()), &cube);
    cube.scale.x = 2.0 * box.half_extents_m.x();
    cube.scale.y = 2.0 * box.half_extents_m.y();
    cube.scale.z = 2.0 * box.half_extents_m.z();
    cube.color = Rgba(rgb, kBoxAlpha);
  }
}

void MarkerBuilder::AddWarnings(const std::vector<Warning>& warnings, const ros::Time& stamp) {
  visualization_msgs::Marker& lines =
      NextMarker(MarkerLayout::kClosestPoints, 0, visualization_msgs::Marker::LINE_LIST, stamp);
  if (warnings.empty()) {
    lines.action = visualization_msgs::Marker::DELETE;
  } else {
    lines.scale.x = kLineWidth_m;
    lines.color = Rgba(MarkerPalette::kWarningRgb, 1.0f);
    for (const Warning& w : warnings) {
      lines.points.push_back(ToPoint(w.p_WA));
      lines.points.push_back(ToPoint(w.p_WB));
    }
  }
  char distance[64];
  placed_labels_.clear();
  for (std::size_t i = 0; i < warnings.size(); ++i) {
    const Warning& w = warnings[i];
    visualization_msgs::Marker& label =
        NextMarker(MarkerLayout::kDistances, static_cast<int>(i),
                   visualization_msgs::Marker::TEXT_VIEW_FACING, stamp);
    std::snprintf(distance, sizeof(distance), "%.0f mm (< %.0f)", 1e3 * w.distance_m,
                  1e3 * w.threshold_m);
    const std::string names = monitor_.primitive(w.a).name + " -- " + monitor_.primitive(w.b).name;
    label.text = names + "\n" + distance;
    // Above the closest-point line's middle, or in the lowest free slot a label's height apart
    // above it (a hand on a box warns for several primitives at nearly one point). A placed
    // label blocks at most two slots, so one of the first 2 n + 1 is free.
    const Eigen::Vector3d base_W =
        0.5 * (w.p_WA + w.p_WB) + Eigen::Vector3d(0.0, 0.0, kLabelHeight_m);
    PlacedLabel placed{base_W,
                       kCharWidth_m * static_cast<double>(std::max(names.size(),
                                                                   std::strlen(distance)))};
    for (std::size_t slot = 1; slot <= 2 * placed_labels_.size() + 1; ++slot) {
      const bool is_free =
          std::none_of(placed_labels_.begin(), placed_labels_.end(),
                       [&](const PlacedLabel& other) {
                         return LabelsOverlap(placed.p_W, placed.width_m, other.p_W,
                                              other.width_m);
                       });
      if (is_free) break;
      placed.p_W.z() = base_W.z() + static_cast<double>(slot) * kLabelHeight_m;
    }
    placed_labels_.push_back(placed);
    label.pose.position = ToPoint(placed.p_W);
    label.scale.z = kTextHeight_m;
    const float white[3] = {1.0f, 1.0f, 1.0f};
    label.color = Rgba(white, 1.0f);
  }
  for (std::size_t i = warnings.size(); i < previous_text_count_; ++i) {
    NextMarker(MarkerLayout::kDistances, static_cast<int>(i),
               visualization_msgs::Marker::TEXT_VIEW_FACING, stamp)
        .action = visualization_msgs::Marker::DELETE;
  }
  previous_text_count_ = warnings.size();
}

void MarkerBuilder::AddIndexCells(const ros::Time& stamp) {
  monitor_.CollectIndexCells(&cells_);
  // Marker 0: occupied leaves holding only static primitives; marker 1: leaves holding moving
  // ones (where the per-cycle update works). Empty leaves are not drawn.
  for (const int k : {MarkerLayout::kStaticCellsId, MarkerLayout::kMovingCellsId}) {
    visualization_msgs::Marker& wire =
        NextMarker(MarkerLayout::kIndexCells, k, visualization_msgs::Marker::LINE_LIST, stamp);
    wire.scale.x = kCellLineWidth_m;
    wire.color = Rgba(k == MarkerLayout::kStaticCellsId ? MarkerPalette::kStaticCellRgb
                                                        : MarkerPalette::kMovingCellRgb,
                      0.8f);
  }
  // Taken after both were added: NextMarker() may reallocate the array.
  visualization_msgs::Marker* wires[2] = {&array_.markers[used_ - 2], &array_.markers[used_ - 1]};
  for (const IndexCell& cell : cells_) {
    if (cell.primitive_count == 0) {
      continue;
    }
    auto& points = wires[cell.holds_moving ? 1 : 0]->points;
    const Eigen::Vector3d& lo = cell.box_W.min_W;
    const Eigen::Vector3d& hi = cell.box_W.max_W;
    // The 12 edges of the cube: corner c has coordinate bit k set -> hi on axis k.
    auto corner = [&](int c) {
      return ToPoint(Eigen::Vector3d((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(),
                                     (c & 4) ? hi.z() : lo.z()));
    };
    for (int c = 0; c < 8; ++c) {
      for (int axis_bit = 1; axis_bit < 8; axis_bit <<= 1) {
        if (!(c & axis_bit)) {
          points.push_back(corner(c));
          points.push_back(corner(c | axis_bit));
        }
      }
    }
  }
  for (visualization_msgs::Marker* wire : wires) {
    if (wire->points.empty()) {
      wire->action = visualization_msgs::Marker::DELETE;
    }
  }
}

const visualization_msgs::MarkerArray& MarkerBuilder::Build(const ros::Time& stamp) {
  const CycleReport& report = monitor_.report();
  used_ = 0;
  ComputeStates(report);
  for (PrimitiveId id = 0; id < monitor_.primitive_count(); ++id) {
    AddPrimitive(id, stamp);
  }
  AddWarnings(report.warnings, stamp);
  AddIndexCells(stamp);
  array_.markers.resize(used_);
  return array_;
}

}  // namespace arm_collision_monitor
