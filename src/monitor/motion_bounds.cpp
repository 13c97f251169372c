// Lever arms over a URDF chain for joint-space motion bounds (see motion_bounds.h).
#include "arm_collision_monitor/monitor/motion_bounds.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <sstream>

namespace arm_collision_monitor {

double MaxBoxVertexDisplacement_m(const Box& b0, const Box& b1) {
  // Corner v_B (+-h_x, +-h_y, +-h_z) moves by dt + (R1 - R0) v_B: the translation's change plus
  // the rotation change's columns, scaled by the half extents, each with the corner's sign.
  const Eigen::Matrix3d dR =
      (b1.X_WB.linear() - b0.X_WB.linear()) * b0.half_extents_m.asDiagonal();
  const Eigen::Vector3d dt = b1.X_WB.translation() - b0.X_WB.translation();
  double max_sq = 0.0;
  for (const double sx : {-1.0, 1.0}) {
    const Eigen::Vector3d x = dt + sx * dR.col(0);
    for (const double sy : {-1.0, 1.0}) {
      const Eigen::Vector3d xy = x + sy * dR.col(1);
      max_sq = std::max({max_sq, (xy + dR.col(2)).squaredNorm(), (xy - dR.col(2)).squaredNorm()});
    }
  }
  return std::sqrt(max_sq);
}

int DrivingQIndex(const JointSpec& joint) {
  if (joint.type == JointType::kFixed) return -1;
  return joint.q_index >= 0 ? joint.q_index : joint.mimic_q_index;
}

MotionBounds::MotionBounds(const KinematicModel& model, std::uint32_t primitive_count)
    : model_(&model), link_count_(model.link_count()) {
  link_depth_.assign(link_count_, 0);
  for (int link = 1; link < link_count_; ++link) {
    const bool moves = DrivingQIndex(model.joint(link)) >= 0;
    link_depth_[link] = link_depth_[model.parent_link(link)] + (moves ? 1 : 0);
    max_levers_ = std::max(max_levers_, link_depth_[link]);
  }
  // The levers two links share: the depth of their deepest common ancestor. Per link a, with
  // its ancestors (itself included) marked, in link order (parents precede children): an
  // ancestor of a is that ancestor, any other link shares what its parent shares with a. Linear
  // per link (a walk up from each pair was cubic in a chain's length: minutes for 4,000 links).
  shared_levers_.assign(static_cast<std::size_t>(link_count_) * link_count_, 0);
  std::vector<std::uint8_t> is_ancestor(link_count_, 0);
  for (int a = 0; a < link_count_; ++a) {
    std::fill(is_ancestor.begin(), is_ancestor.end(), std::uint8_t{0});
    for (int x = a; x > 0; x = model.parent_link(x)) is_ancestor[x] = 1;
    is_ancestor[0] = 1;
    std::uint8_t* const shared = &shared_levers_[static_cast<std::size_t>(a) * link_count_];
    for (int b = 0; b < link_count_; ++b) {
      // Saturated at 255 (a chain that deep): fewer levers left out, a larger pair bound.
      shared[b] = is_ancestor[b] ? static_cast<std::uint8_t>(std::min(link_depth_[b], 255))
                                 : shared[model.parent_link(b)];
    }
  }
  carrier_.assign(primitive_count, -1);
  lever_sums_m_.assign(static_cast<std::size_t>(primitive_count) * (max_levers_ + 1), 0.0);
  levers_.assign(static_cast<std::size_t>(primitive_count) * max_levers_, Lever{});
  lever_count_.assign(primitive_count, 0);
  undominated_.reserve(primitive_count);
  lever_lanes_.reserve((primitive_count + kLanes - 1) / kLanes * max_levers_);
  dq_abs_ = Eigen::VectorXd::Zero(model.q_size() + 1);
}

bool MotionBounds::Covers(PrimitiveId r, PrimitiveId p) const {
  const Lever* lr = levers(r);
  const Lever* lp = levers(p);
  for (int k = 0; k < lever_count_[p]; ++k) {
    bool is_matched = false;
    for (int i = 0; i < lever_count_[r] && !is_matched; ++i) {
      is_matched = lr[i].q_index == lp[k].q_index && lr[i].m_per_unit >= lp[k].m_per_unit;
    }
    if (!is_matched) return false;
  }
  return true;
}

void MotionBounds::FindUndominated() {
  undominated_.clear();
  const auto n = static_cast<PrimitiveId>(lever_count_.size());
  // The search compares every two primitives with levers, each comparison as long as their
  // lever lists: past kMaxDominanceSearch of them it would cost more than it saves (seconds at
  // start-up for a chain of 4,000 links, milliseconds at each attach for a thousand
  // primitives), and every primitive with levers is kept.
  const auto with_levers = static_cast<std::size_t>(
      std::count_if(lever_count_.begin(), lever_count_.end(), [](int c) { return c > 0; }));
  const bool is_searched = with_levers <= kMaxDominanceSearch;
  for (PrimitiveId p = 0; p < n; ++p) {
    if (lever_count_[p] == 0) continue;
    if (!is_searched) {
      undominated_.push_back(p);
      continue;
    }
    // Two levers on one joint (a mimic joint above its target): one matching lever would not
    // cover their sum, so such a primitive is always kept.
    const Lever* lp = levers(p);
    bool is_dominated = false;
    for (int k = 0; k < lever_count_[p]; ++k) {
      for (int i = 0; i < k; ++i) is_dominated = is_dominated || lp[i].q_index == lp[k].q_index;
    }
    if (is_dominated) {
      undominated_.push_back(p);
      continue;
    }
    for (PrimitiveId r = 0; r < n && !is_dominated; ++r) {
      // Equal lever sets: the lower id stands for both.
      is_dominated = r != p && lever_count_[r] > 0 && Covers(r, p) && (!Covers(p, r) || r < p);
    }
    if (!is_dominated) undominated_.push_back(p);
  }
  // Every slot a padding lever first, then each primitive's own levers over them.
  LeverLanes padding{};
  std::fill(std::begin(padding.q_index), std::end(padding.q_index), model_->q_size());
  lever_lanes_.assign((undominated_.size() + kLanes - 1) / kLanes * max_levers_, padding);
  for (std::size_t row = 0; row < undominated_.size(); ++row) {
    const PrimitiveId id = undominated_[row];
    LeverLanes* slots = &lever_lanes_[row / kLanes * max_levers_];
    for (int k = 0; k < lever_count_[id]; ++k) {
      slots[k].q_index[row % kLanes] = levers(id)[k].q_index;
      slots[k].m_per_unit[row % kLanes] = levers(id)[k].m_per_unit;
    }
  }
  is_undominated_stale_ = false;
}

double MotionBounds::ComputeLargestBound_m() {
  if (is_undominated_stale_) FindUndominated();
  double largest_m = 0.0;
  const double* const dq_abs = dq_abs_.data();
  const std::size_t rows = undominated_.size();
  for (std::size_t first = 0; first < rows; first += kLanes) {
    const LeverLanes* slots = &lever_lanes_[first / kLanes * max_levers_];
    double sums_m[kLanes] = {0.0, 0.0, 0.0, 0.0};
    for (int k = 0; k < max_levers_; ++k) {
      for (int lane = 0; lane < kLanes; ++lane) {
        sums_m[lane] += dq_abs[slots[k].q_index[lane]] * slots[k].m_per_unit[lane];
      }
    }
    const std::size_t count = std::min<std::size_t>(kLanes, rows - first);
    for (std::size_t lane = 0; lane < count; ++lane) {
      // NaN and inf propagate (NaN stays).
      if (!(sums_m[lane] <= largest_m) && !std::isnan(largest_m)) largest_m = sums_m[lane];
    }
  }
  return largest_m;
}

void MotionBounds::SetCarrier(PrimitiveId id, int link, bool is_moving, const Shape& shape_L) {
  carrier_[id] = is_moving ? link : -1;
  // Only a primitive with levers, before or after, can change the undominated set.
  if (lever_count_[id] > 0 || (link >= 0 && is_moving)) is_undominated_stale_ = true;
  lever_count_[id] = 0;
  if (link < 0 || !is_moving) return;
  // A revolute joint's lever is the primitive's largest distance from the joint's axis, which
  // passes through the origin of the joint's child link l. On l itself that distance is fixed.
  // Above, the primitive is within `reach` of the origin of l's child c on the chain, and c's
  // origin sits at the joint offset t_c in l's frame (plus c's prismatic travel): its distance
  // from the axis is at most the part of t_c across the axis plus the travel plus `reach`. The
  // reach grows by the whole offset and travel at each link upward. When c turns about an axis
  // a_c too, the part of the primitive's offset from c's origin across l's axis a is at most its
  // distance from a_c (`across`, c's own bound) plus 2 |a - a_c| times the reach (a_c turned
  // into l's frame, signed to match a): for parallel axes, as in a planar chain, c's bound.
  const double kNone = std::numeric_limits<double>::infinity();
  double reach_m = MaxDistanceFromPoint_m(shape_L, Eigen::Vector3d::Zero());
  double across_m = kNone;  // from the axis of `child` when it turns, else none
  const JointSpec* child = nullptr;
  Lever* out = &levers_[static_cast<std::size_t>(id) * max_levers_];
  for (int l = link; l > 0; l = model_->parent_link(l)) {
    const JointSpec& joint = model_->joint(l);
    double from_axis_m = kNone;
    if (joint.type == JointType::kRevolute || joint.type == JointType::kContinuous) {
      const Eigen::Vector3d axis = joint.axis_J.normalized();
      if (child == nullptr) {
        from_axis_m = MaxDistanceFromAxis_m(shape_L, axis);
      } else {
        Eigen::Vector3d child_axis = child->X_PJ.linear() * child->axis_J.normalized();
        if (child_axis.dot(axis) < 0.0) child_axis = -child_axis;
        const double below_m =
            std::min(reach_m, across_m + 2.0 * (axis - child_axis).norm() * reach_m);
        from_axis_m = child->X_PJ.translation().cross(axis).norm() + model_->Travel_m(*child) +
                      below_m;
      }
    }
    const int q_index = DrivingQIndex(joint);
    if (q_index >= 0) {  // as link_depth_ counts
      const double scale = joint.q_index >= 0 ? 1.0 : std::abs(joint.mimic_multiplier);
      // A prismatic joint's points move as far as the joint.
      const double lever_m = joint.type == JointType::kPrismatic ? 1.0 : from_axis_m;
      out[lever_count_[id]++] = Lever{q_index, scale * lever_m};
    }
    if (child != nullptr) reach_m += child->X_PJ.translation().norm() + model_->Travel_m(*child);
    across_m = from_axis_m;
    child = &joint;
  }
}

bool MotionBounds::Validate(std::string* why) const {
  std::ostringstream msg;
  for (std::size_t id = 0; id < carrier_.size() && msg.tellp() == 0; ++id) {
    const int link = carrier_[id];
    if (link < -1 || link >= link_count_) {
      msg << "primitive " << id << " carried by link " << link << " of " << link_count_;
      break;
    }
    const int count = lever_count_[id];
    if (count != 0 && (link < 0 || count != link_depth_[link])) {
      msg << "primitive " << id << " has " << count << " levers on link " << link;
      break;
    }
    const Lever* l = levers(static_cast<PrimitiveId>(id));
    for (int k = 0; k < count; ++k) {
      if (l[k].q_index < 0 || l[k].q_index >= model_->q_size() || !(l[k].m_per_unit >= 0.0)) {
        msg << "primitive " << id << " lever " << k << ": q index " << l[k].q_index << ", "
            << l[k].m_per_unit << " m per unit";
        break;
      }
    }
  }
  if (msg.tellp() == 0) return true;
  *why = msg.str();
  return false;
}

}  // namespace arm_collision_monitor
