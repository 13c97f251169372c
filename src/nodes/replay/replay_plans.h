// replay's planned samples (replay_bag.cpp reads them from a bag): the points of each plan of
// its joints, superseded by later plans as a trajectory controller replaces its trajectory, and
// what a plan under way gives between its points.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <ros/time.h>
#include <sensor_msgs/JointState.h>
#include <trajectory_msgs/JointTrajectory.h>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/safety/joint_merger.h"
#include "replay_output.h"

namespace arm_collision_monitor {
namespace replay {

// The stamp of `point` of a trajectory that starts at `start`, or false when it is out of
// ros::Time's range (ros::Time's own arithmetic would throw).
inline bool PointStamp(const ros::Time& start,
                       const trajectory_msgs::JointTrajectoryPoint& point, ros::Time* stamp) {
  const std::int64_t ns =
      static_cast<std::int64_t>(start.toNSec()) + point.time_from_start.toNSec();
  constexpr std::int64_t kLastNs =
      std::int64_t{std::numeric_limits<std::uint32_t>::max()} * 1000000000 + 999999999;
  if (ns < 0 || ns > kLastNs) return false;
  stamp->fromNSec(static_cast<std::uint64_t>(ns));
  return true;
}

// The time from `a` to `b`, ns (ros::Duration's arithmetic throws beyond 2^31 s; ros::Time's
// range, 2^32 s, fits).
inline std::int64_t NsBetween(const ros::Time& a, const ros::Time& b) {
  return static_cast<std::int64_t>(b.toNSec()) - static_cast<std::int64_t>(a.toNSec());
}

// Names the refusal of a sample stamped `stamp_s`, met at `arrival_s` of the replay's time, as
// the first if none met earlier was: "stamped <t> s: " and what `describe` gives (made only
// then). A message stamped backwards is met when it comes, after the later stamps before it;
// at the same time a recorded message is met before a planned point (`is_planned`), as the
// replay takes them.
template <typename Describe>
void NoteRefusal(double arrival_s, bool is_planned, double stamp_s, Describe describe,
                 Input* input) {
  const std::pair<double, bool> met{arrival_s, is_planned};
  if (!(met < std::pair{input->first_refused_arrival_s, input->is_first_refused_planned})) {
    return;
  }
  input->first_refused_arrival_s = arrival_s;
  input->is_first_refused_planned = is_planned;
  input->first_refused_message = "stamped " + std::to_string(stamp_s) + " s: " + describe();
}

// A bag's planned samples: per plan, its points of its joints. A later plan supersedes, for
// its joints, the earlier plans' points after its start (a trajectory controller's
// replacement); their other joints stay.
class Plans {
 public:
  /// Point::index of a start state and of a point put between two (AddBetween).
  static constexpr std::int64_t kStartState = -1;
  static constexpr std::int64_t kBetween = -2;
  struct Point {
    ros::Time stamp;
    std::uint64_t order;            // read order, which decides between equal stamps
    std::vector<double> positions;  // one per name of its Joints
    std::int64_t index;             // in its message's points, kStartState or kBetween
    bool is_superseded = false;     // split off a plan a later one cut (counted then)
  };
  struct Joints {
    std::vector<std::string> names;
    std::vector<Point> points;
    ros::Time last;     // no point is later
    std::string where;  // its message (and trajectory)
  };

  /// What names a sample of `joints` read from its message (its `point`) in a refusal.
  static std::string Describe(const Joints& joints, const Point& point) {
    return joints.where + (point.index >= 0 ? ", point " + std::to_string(point.index) : "");
  }

  /// `counts`: its messages (points read) and refused and superseded points are counted.
  /// `turning`: the model's joints without position limits, each with its velocity limit (0:
  /// none), which a trajectory controller turns from point to point as the positions literally
  /// say, however far (AddBetween).
  Plans(Input* counts, std::map<std::string, double> turning)
      : counts_(counts), turning_(std::move(turning)) {}

  const std::map<std::string, double>& turning() const { return turning_; }

  /// A trajectory starting at `start`; `where` names its message for a LoadError and a refused
  /// point. A point of the wrong size or out of ros::Time's range is refused and counted; one
  /// whose time_from_start does not increase past the last point taken, or with a position not
  /// finite, is a LoadError: a trajectory controller refuses such a plan. Returns its last
  /// point's stamp (`start` without one).
  ros::Time AddTrajectory(const trajectory_msgs::JointTrajectory& plan, const ros::Time& start,
                          const std::string& where) {
    Supersede(plan.joint_names, start);
    Joints joints{plan.joint_names, {}, start, where};
    ros::Time end = start;
    for (std::size_t k = 0; k < plan.points.size(); ++k) {
      const trajectory_msgs::JointTrajectoryPoint& point = plan.points[k];
      ros::Time stamp;
      const std::string point_where = where + ", point " + std::to_string(k);
      if (!IsReadable(joints.names, point.positions,
                      start.toSec() + point.time_from_start.toSec(), point_where) ||
          !IsInRange(start, point, &stamp, point_where)) {
        continue;
      }
      if (!joints.points.empty() && !(stamp > end)) {
        throw LoadError(point_where + ": time_from_start " +
                        std::to_string(point.time_from_start.toSec()) + " s does not increase "
                        "past the point before it (" + std::to_string((end - start).toSec()) +
                        " s)");
      }
      for (std::size_t j = 0; j < point.positions.size(); ++j) {
        if (!std::isfinite(point.positions[j])) {
          throw LoadError(point_where + ": joint '" + joints.names[j] + "' at " +
                          std::to_string(point.positions[j]));
        }
      }
      AddBetween(point_where, &joints, stamp, point.positions);
      joints.points.push_back({stamp, next_order_++, point.positions,
                               static_cast<std::int64_t>(k)});
      joints.last = stamp;
      end = stamp;
    }
    if (!joints.points.empty()) plans_.push_back(std::move(joints));
    return end;
  }

  /// A planned state (a DisplayTrajectory's start state) at `stamp`, of the message `where`: it
  /// supersedes nothing.
  void AddState(const sensor_msgs::JointState& state, const ros::Time& stamp,
                const std::string& where) {
    if (!IsReadable(state.name, state.position, stamp.toSec(), where + ", start state")) return;
    plans_.push_back({state.name,
                      {{stamp, next_order_++, state.position, kStartState}},
                      stamp,
                      where + ", start state"});
  }

  /// For each plan under way at `stamp` (a point before or at it and one after it), but
  /// `except`: its joints where its controller has them then, `f(NamedPositions, Joints)`, linear
  /// between its two points. So the cycles of plans of several arms (or of a plan beside
  /// recorded states) move every arm at once, on the straight joint-space path between
  /// consecutive cycles that the swept check takes, where holding the other arms at their last
  /// points checked a staircase.
  template <typename F>
  void ForEachUnderWayAt(const ros::Time& stamp, const Joints* except, F&& f) {
    for (const Joints& joints : plans_) {
      const std::vector<Point>& points = joints.points;
      if (&joints == except || points.size() < 2 || !(points.front().stamp < stamp) ||
          !(stamp < points.back().stamp)) {
        continue;
      }
      const auto after = std::upper_bound(
          points.begin(), points.end(), stamp,
          [](const ros::Time& t, const Point& point) { return t < point.stamp; });
      const Point& p0 = *(after - 1);
      const Point& p1 = *after;
      const double s = static_cast<double>(NsBetween(p0.stamp, stamp)) /
                       static_cast<double>(NsBetween(p0.stamp, p1.stamp));
      under_way_.resize(p0.positions.size());
      for (std::size_t j = 0; j < under_way_.size(); ++j) {
        under_way_[j] = p0.positions[j] + s * (p1.positions[j] - p0.positions[j]);
      }
      f(NamedPositions{joints.names, under_way_, stamp.toSec()}, joints);
    }
  }

  /// Every point with its joints, by stamp, then in read order.
  std::vector<std::pair<const Joints*, const Point*>> InTimeOrder() const {
    std::vector<std::pair<const Joints*, const Point*>> all;
    for (const Joints& joints : plans_) {
      for (const Point& point : joints.points) all.emplace_back(&joints, &point);
    }
    std::sort(all.begin(), all.end(), [](const auto& x, const auto& y) {
      return x.second->stamp < y.second->stamp ||
             (x.second->stamp == y.second->stamp && x.second->order < y.second->order);
    });
    return all;
  }

 private:
  // Counts a refused sample, stamped `stamp_s`, of `where` (its message and point), with its
  // `reason` (NoteRefusal).
  void Refuse(const char* status, double stamp_s, const std::string& where,
              const std::string& reason) {
    ++counts_->refused[status];
    NoteRefusal(
        stamp_s, true, stamp_s, [&] { return where + ": " + status + " (" + reason + ")"; },
        counts_);
  }

  // Whether a sample's positions match its names (one read message, refused if not; one
  // without positions is counted apart, JointMerger::GivesNoPositions).
  bool IsReadable(const std::vector<std::string>& names, const std::vector<double>& positions,
                  double stamp_s, const std::string& where) {
    ++counts_->messages;
    if (positions.size() == names.size()) return true;
    if (JointMerger::GivesNoPositions(NamedPositions{names, positions})) {
      ++counts_->position_less;
      return false;
    }
    Refuse(MergeStatusName(MergeStatus::kWrongSize), stamp_s, where,
           std::to_string(positions.size()) + " positions for " + std::to_string(names.size()) +
               " joint names");
    return false;
  }

  bool IsInRange(const ros::Time& start, const trajectory_msgs::JointTrajectoryPoint& point,
                 ros::Time* stamp, const std::string& where) {
    if (PointStamp(start, point, stamp)) return true;
    Refuse("time_out_of_range", start.toSec() + point.time_from_start.toSec(), where,
           "time_from_start " + std::to_string(point.time_from_start.toSec()) +
               " s from a start at " + std::to_string(start.toSec()) + " s");
    return false;
  }

  // Before a point at `stamp` of `positions` (`where`): where a turning joint with a velocity
  // limit moves over half a turn from the plan's last point, which the monitor would take the
  // short way round (a wrapped reading), points between them on the straight joint-space path,
  // a quarter turn or less apart (at most one a nanosecond), so that it follows the turn as a
  // trajectory controller makes it, however fast. More than kMostPointsBetween in all is a
  // LoadError.
  void AddBetween(const std::string& where, Joints* joints, const ros::Time& stamp,
                  const std::vector<double>& positions) {
    if (joints->points.empty()) return;
    const Point start = joints->points.back();
    double largest_move = 0.0;
    for (std::size_t j = 0; j < positions.size(); ++j) {
      const auto turning = turning_.find(joints->names[j]);
      if (turning == turning_.end() || !(turning->second > 0.0)) continue;
      largest_move = std::max(largest_move, std::abs(positions[j] - start.positions[j]));
    }
    if (!(largest_move > 0.5 * kTurn)) return;
    // At most duration_ns, the pieces convert.
    const std::int64_t duration_ns = NsBetween(start.stamp, stamp);
    const auto pieces = static_cast<std::int64_t>(
        std::min(std::ceil(largest_move / (0.25 * kTurn)), static_cast<double>(duration_ns)));
    if (pieces - 1 > kMostPointsBetween - between_count_) {
      throw LoadError(where + ": over " + std::to_string(kMostPointsBetween) + " points put "
                      "between the plans' points to follow continuous joints' turns (expected "
                      "plans that turn them less far)");
    }
    between_count_ += pieces - 1;
    for (std::int64_t k = 1; k < pieces; ++k) {
      // The stamp exactly (no overflow: pieces and the remainder are at most 2^17).
      const std::int64_t at_ns = duration_ns / pieces * k + duration_ns % pieces * k / pieces;
      const double s = static_cast<double>(at_ns) / static_cast<double>(duration_ns);
      ros::Time at;
      at.fromNSec(start.stamp.toNSec() + static_cast<std::uint64_t>(at_ns));
      Point between{at, next_order_++, positions, kBetween};
      for (std::size_t j = 0; j < positions.size(); ++j) {
        between.positions[j] = start.positions[j] + s * (positions[j] - start.positions[j]);
      }
      joints->points.push_back(std::move(between));
    }
  }

  // The earlier plans' points after `start` lose the joints `names` (a point left without
  // joints goes), and a plan under way then gets a point at `start`.
  void Supersede(const std::vector<std::string>& names, const ros::Time& start) {
    const std::size_t count = plans_.size();  // the parts split off below are already cut
    for (std::size_t k = 0; k < count; ++k) {
      if (!(plans_[k].last > start)) continue;
      std::vector<std::size_t> kept;  // the indices of the names that stay
      const std::vector<std::string>& old_names = plans_[k].names;
      for (std::size_t j = 0; j < old_names.size(); ++j) {
        if (std::find(names.begin(), names.end(), old_names[j]) == names.end()) kept.push_back(j);
      }
      if (kept.size() == old_names.size()) continue;
      std::vector<Point>& points = plans_[k].points;
      const auto after = std::stable_partition(points.begin(), points.end(),
                                               [&](const Point& p) { return !(p.stamp > start); });
      // Each point read once: the rest split off an earlier cut was counted then.
      counts_->superseded_points += static_cast<std::uint64_t>(
          std::count_if(after, points.end(),
                        [](const Point& p) { return p.index != kBetween && !p.is_superseded; }));
      // Under way at `start` (a point at or before it, one after): where the controller has
      // its joints then ends the cut plan (a point put there, unless one is) and starts the
      // rest, so that the new plan's first step starts there, not at the point before, and the
      // rest's joints move on from it with the new plan's cycles.
      std::vector<Point> at_start;
      if (after != points.begin() && after != points.end()) {
        const Point& p0 = *(after - 1);
        const double s = static_cast<double>(NsBetween(p0.stamp, start)) /
                         static_cast<double>(NsBetween(p0.stamp, after->stamp));
        // As old as the cut plan: a plan read since (but the new one) keeps its own at `start`.
        at_start.push_back({start, p0.order, p0.positions, kBetween});
        for (std::size_t j = 0; j < p0.positions.size(); ++j) {
          at_start.back().positions[j] += s * (after->positions[j] - p0.positions[j]);
        }
      }
      Joints rest{{}, {}, plans_[k].last, plans_[k].where};
      for (const std::size_t j : kept) rest.names.push_back(old_names[j]);
      auto add_part = [&](const Point& point) {
        Point part{point.stamp, point.order, {}, point.index, true};
        for (const std::size_t j : kept) part.positions.push_back(point.positions[j]);
        rest.points.push_back(std::move(part));
      };
      if (!kept.empty()) {
        for (const Point& point : at_start) add_part(point);
        std::for_each(after, points.end(), add_part);
      }
      const bool is_at_point = after != points.begin() && !((after - 1)->stamp < start);
      points.erase(after, points.end());
      if (!is_at_point) points.insert(points.end(), at_start.begin(), at_start.end());
      plans_[k].last = start;
      if (!rest.points.empty()) plans_.push_back(std::move(rest));
    }
  }

  std::vector<Joints> plans_;
  std::uint64_t next_order_ = 0;
  Input* counts_;
  std::map<std::string, double> turning_;
  std::int64_t between_count_ = 0;  // points put between (AddBetween)
  std::vector<double> under_way_;  // ForEachUnderWayAt's positions
};

}  // namespace replay
}  // namespace arm_collision_monitor
