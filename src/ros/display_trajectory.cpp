#include "arm_collision_monitor/ros/display_trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <Eigen/Geometry>
#include <ros/message_traits.h>
#include <ros/serialization.h>

#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

// One field of a message definition. Constants are left out: they are not serialized.
struct Field {
  std::string type;  ///< a built-in type or "<package>/<Type>"
  std::string name;
  bool is_array = false;
  bool is_fixed = false;         ///< T[N]: no count in the bytes
  std::uint32_t fixed_count = 0;  ///< N of T[N]
};
using Definitions = std::map<std::string, std::vector<Field>>;

// Deeper nesting than any message needs (CheckNesting refuses more).
constexpr int kMaxDepth = 32;
// A serialized size larger than any message (1 TiB): fixed sizes are clamped to it.
constexpr long kTooLarge = 1L << 40;

std::runtime_error Error(const std::string& path, const std::string& what) {
  return std::runtime_error((path.empty() ? std::string("the message") : path) + ": " + what);
}

// Serialized size of a built-in type, 0 for string (a length, then its bytes), -1 for a message
// type.
int BuiltinSize(const std::string& type) {
  static const std::map<std::string, int> kSizes = {
      {"bool", 1},    {"int8", 1},    {"uint8", 1},   {"byte", 1},    {"char", 1},
      {"int16", 2},   {"uint16", 2},  {"int32", 4},   {"uint32", 4},  {"float32", 4},
      {"int64", 8},   {"uint64", 8},  {"float64", 8}, {"time", 8},    {"duration", 8},
      {"string", 0}};
  const auto it = kSizes.find(type);
  return it == kSizes.end() ? -1 : it->second;
}

// A field's type as written in the definition of `owner`, made "<package>/<Type>".
std::string ResolveType(const std::string& type, const std::string& owner) {
  if (BuiltinSize(type) >= 0 || type.find('/') != std::string::npos) return type;
  if (type == "Header") return "std_msgs/Header";
  return owner.substr(0, owner.find('/') + 1) + type;
}

// The fields of `main_type` and of each type after a line of '=' and "MSG: <package>/<Type>".
Definitions ParseDefinitions(const std::string& main_type, const std::string& text) {
  Definitions definitions;
  std::string owner = main_type;
  definitions[owner];
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream tokens(line);
    std::string type, name;
    if (!(tokens >> type)) continue;
    const std::string where = "message definition line " + std::to_string(number);
    if (type.find_first_not_of('=') == std::string::npos) {
      owner.clear();
      continue;
    }
    if (type == "MSG:") {
      if (!(tokens >> owner) || owner.find('/') == std::string::npos) {
        throw std::runtime_error(where + ": 'MSG:' without a <package>/<Type>");
      }
      definitions[owner];
      continue;
    }
    if (owner.empty()) throw std::runtime_error(where + ": a field before its type's 'MSG:' line");
    if (!(tokens >> name)) throw std::runtime_error(where + ": a field without a name");
    if (line.find('=') != std::string::npos) continue;  // a constant
    Field field;
    field.name = name;
    const std::size_t bracket = type.find('[');
    if (bracket != std::string::npos) {
      const std::string count = type.substr(bracket + 1, type.size() - bracket - 2);
      if (type.back() != ']' || count.size() > 9 ||
          count.find_first_not_of("0123456789") != std::string::npos) {
        throw std::runtime_error(where + ": bad array type '" + type + "'");
      }
      field.is_array = true;
      field.is_fixed = !count.empty();
      field.fixed_count = field.is_fixed ? static_cast<std::uint32_t>(std::stoul(count)) : 0;
    }
    field.type = ResolveType(type.substr(0, bracket), owner);
    definitions[owner].push_back(field);
  }
  return definitions;
}

// Walks serialized bytes by a message definition. The walk recurses only as deep as the types
// nest below `main_type`, which the constructor bounds (CheckNesting).
class Reader {
 public:
  Reader(const Definitions& definitions, const std::string& main_type, const std::uint8_t* data,
         std::size_t size)
      : definitions_(definitions), at_(data), end_(data + size) {
    CheckNesting(main_type);
  }

  std::size_t remaining() const { return static_cast<std::size_t>(end_ - at_); }

  const std::vector<Field>& FieldsOf(const std::string& type, const std::string& path) const {
    const auto it = definitions_.find(type);
    if (it == definitions_.end()) throw Error(path, "type " + type + " is not in the definition");
    return it->second;
  }

  std::uint32_t ReadCount(const std::string& path) {
    Take(4, path);
    std::uint32_t count = 0;
    std::memcpy(&count, at_ - 4, 4);  // little-endian, as ROS serializes (x86 and ARM alike)
    return count;
  }

  // The number of elements of `field` (read from the bytes unless fixed); at most the bytes
  // left, as every element of a type that is not empty takes at least one.
  std::uint32_t ReadArrayCount(const Field& field, const std::string& path) {
    const std::uint32_t count = field.is_fixed ? field.fixed_count : ReadCount(path);
    if (count > remaining()) {
      throw Error(path, std::to_string(count) + " elements, with " + std::to_string(remaining()) +
                            " bytes left");
    }
    return count;
  }

  void SkipField(const Field& field, const std::string& owner_path) {
    const std::string path = owner_path.empty() ? field.name : owner_path + "." + field.name;
    if (!field.is_array) {
      SkipValue(field.type, path);
      return;
    }
    const std::uint32_t count = ReadArrayCount(field, path);
    const long size = FixedSize(field.type);
    if (size >= 0) {
      if (size > 0 && count > remaining() / static_cast<std::size_t>(size)) {
        throw Error(path, "the message ends early");
      }
      Take(static_cast<std::size_t>(size) * count, path);
      return;
    }
    for (std::uint32_t k = 0; k < count; ++k) {
      SkipValue(field.type, path + "[" + std::to_string(k) + "]");
    }
  }

  // A value of fixed size is taken at once: a definition whose fields fan out over types of
  // fixed (or no) size costs no more than its bytes. Every other value holds a length or a
  // count, so the walk is bounded by the bytes too.
  void SkipValue(const std::string& type, const std::string& path) {
    const long size = FixedSize(type);
    if (size >= 0) {
      Take(static_cast<std::size_t>(size), path);
    } else if (type == "string") {
      Take(ReadCount(path), path);
    } else {
      for (const Field& field : FieldsOf(type, path)) SkipField(field, path);
    }
  }

  // Deserializes a value of `type` into `msg` (this build's type of that name) after checking
  // that the definition lays it out as this build does; the bytes are walked by the definition
  // first, so that no count in them can make the deserializer allocate more than they hold.
  template <typename Msg>
  void ReadTyped(const std::string& type, const std::string& path, Msg* msg) {
    const Definitions own =
        ParseDefinitions(type, ros::message_traits::Definition<Msg>::value());
    CheckSameLayout(own, type, path);
    const std::uint8_t* const start = at_;
    SkipValue(type, path);
    ros::serialization::IStream stream(const_cast<std::uint8_t*>(start),
                                       static_cast<std::uint32_t>(at_ - start));
    ros::serialization::deserialize(stream, *msg);
    if (stream.getData() != at_) throw Error(path, "bytes not as its definition lays them out");
  }

 private:
  /// Refuses, before any byte is read, a definition in which a type contains itself (no ROS
  /// message does) or in which types nest deeper than kMaxDepth below `type`; returns how deep
  /// they nest.
  int CheckNesting(const std::string& type, int depth = 0) {
    if (BuiltinSize(type) >= 0) return 0;
    if (depth > kMaxDepth) throw Error("", "types nested too deep");
    const auto [known, is_new] = nesting_.emplace(type, -1);
    if (!is_new) {
      if (known->second < 0) throw Error("", "type " + type + " contains itself");
      return known->second;
    }
    int height = 0;
    const auto it = definitions_.find(type);
    if (it != definitions_.end()) {
      for (const Field& field : it->second) {
        height = std::max(height, 1 + CheckNesting(field.type, depth + 1));
      }
    }
    if (depth + height > kMaxDepth) throw Error("", "types nested too deep");
    known->second = height;
    return height;
  }

  void Take(std::size_t bytes, const std::string& path) {
    if (bytes > remaining()) throw Error(path, "the message ends early");
    at_ += bytes;
  }

  // Serialized size of every value of `type`, or -1 when it varies (strings, arrays). Each
  // type's is computed once.
  long FixedSize(const std::string& type) const {
    const int builtin = BuiltinSize(type);
    if (builtin >= 0) return builtin > 0 ? builtin : -1;
    const auto known = fixed_size_.find(type);
    if (known != fixed_size_.end()) return known->second;
    const auto it = definitions_.find(type);
    if (it == definitions_.end()) return -1;
    long size = 0;
    for (const Field& field : it->second) {
      const long element = field.is_array && !field.is_fixed ? -1 : FixedSize(field.type);
      if (element < 0) return fixed_size_[type] = -1;
      const long count = field.is_array ? field.fixed_count : 1;
      // Past kTooLarge the bytes run out anyway: no overflow on the way there.
      size += count > 0 && element > kTooLarge / count ? kTooLarge : element * count;
      if (size > kTooLarge) size = kTooLarge;
    }
    fixed_size_[type] = size;
    return size;
  }

  void CheckSameLayout(const Definitions& own, const std::string& type,
                       const std::string& path) const {
    const std::vector<Field>& fields = FieldsOf(type, path);
    const std::vector<Field>& expected = own.at(type);
    auto text = [](const std::vector<Field>& list) {
      std::string out;
      for (const Field& f : list) {
        out += (out.empty() ? "" : "; ") + f.type +
               (f.is_array ? "[" + (f.is_fixed ? std::to_string(f.fixed_count) : "") + "]" : "") +
               " " + f.name;
      }
      return out;
    };
    if (text(fields) != text(expected)) {
      throw Error(path, type + " is '" + text(fields) + "' in the bag, '" + text(expected) +
                            "' in this build");
    }
    for (const Field& field : fields) {
      if (BuiltinSize(field.type) < 0) CheckSameLayout(own, field.type, path);
    }
  }

  const Definitions& definitions_;
  mutable std::map<std::string, long> fixed_size_;  ///< FixedSize's, per message type
  std::map<std::string, int> nesting_;  ///< CheckNesting's heights (-1: being checked)
  const std::uint8_t* at_;
  const std::uint8_t* const end_;
};

// Whether `type` has the field `name` of `field_type` (an array or not, as `is_array`).
bool HasField(const Reader& reader, const std::string& type, const std::string& name,
              const std::string& field_type, bool is_array, const std::string& path) {
  for (const Field& field : reader.FieldsOf(type, path)) {
    if (field.name == name && field.type == field_type && field.is_array == is_array) return true;
  }
  return false;
}

// The fields from an action goal down to its trajectory_msgs/JointTrajectory.
const std::vector<std::string>& GoalFields(const std::string& type) {
  static const std::map<std::string, std::vector<std::string>> kFields = {
      {kFollowJointTrajectoryGoalType, {"goal", "trajectory"}},
      {kExecuteTrajectoryGoalType, {"goal", "trajectory", "joint_trajectory"}}};
  const auto it = kFields.find(type);
  if (it == kFields.end()) throw std::invalid_argument("no joint trajectory read from " + type);
  return it->second;
}

// Checks, before any byte is read, that `fields` lead from `type` to a JointTrajectory.
void CheckGoalFields(const Reader& reader, std::string type,
                     const std::vector<std::string>& fields) {
  std::string path;
  for (const std::string& name : fields) {
    const std::vector<Field>& own = reader.FieldsOf(type, path);
    const auto field = std::find_if(own.begin(), own.end(), [&](const Field& f) {
      return f.name == name && !f.is_array;
    });
    if (field == own.end()) throw Error(path, type + " has no field '" + name + "'");
    path += (path.empty() ? "" : ".") + name;
    type = field->type;
  }
  if (type != "trajectory_msgs/JointTrajectory") {
    throw Error(path, "is " + type + ", not trajectory_msgs/JointTrajectory");
  }
}

// Reads the value of `type` at the reader, taking the value at the end of `fields` (from
// `depth` on; none when that field is not of type Msg) into *msg and skipping every other field;
// `multi_dof` (unless null) takes the sibling "multi_dof_<last field>" of type MultiDof (a
// RobotTrajectory's multi_dof_joint_trajectory, a RobotState's multi_dof_joint_state).
template <typename Msg, typename MultiDof = trajectory_msgs::MultiDOFJointTrajectory>
void ReadAlong(Reader* reader, const std::string& type, const std::string& path,
               const std::vector<std::string>& fields, std::size_t depth, Msg* msg,
               MultiDof* multi_dof = nullptr) {
  const bool is_last = depth + 1 == fields.size();
  for (const Field& field : reader->FieldsOf(type, path)) {
    const std::string field_path = path.empty() ? field.name : path + "." + field.name;
    if (is_last && multi_dof != nullptr && !field.is_array &&
        field.name == "multi_dof_" + fields[depth] &&
        field.type == ros::message_traits::DataType<MultiDof>::value()) {
      reader->ReadTyped(field.type, field_path, multi_dof);
      continue;
    }
    if (field.is_array || field.name != fields[depth] ||
        (is_last && field.type != ros::message_traits::DataType<Msg>::value())) {
      reader->SkipField(field, path);
      continue;
    }
    if (is_last) {
      reader->ReadTyped(field.type, field_path, msg);
    } else {
      ReadAlong(reader, field.type, field_path, fields, depth + 1, msg, multi_dof);
    }
  }
}

// Whether the 7 numbers of `pose` are finite and its quaternion not zero.
bool IsValidPose(const geometry_msgs::Transform& pose) {
  const geometry_msgs::Vector3& t = pose.translation;
  const geometry_msgs::Quaternion& q = pose.rotation;
  const double norm2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
  return std::isfinite(t.x + t.y + t.z) && std::isfinite(norm2) && norm2 > 0.0;
}

// Each name's transform, as far as both lists go.
MultiDofPoses PosesByName(const std::vector<std::string>& names,
                          const std::vector<geometry_msgs::Transform>& transforms) {
  MultiDofPoses at;
  for (std::size_t j = 0; j < names.size() && j < transforms.size(); ++j) {
    at[names[j]] = transforms[j];
  }
  return at;
}

// The distance (m) and the rotation angle (rad) from valid pose `a` to valid pose `b`. Eigen's
// angular distance is 2 atan2(|v|, |w|) of their quotient (w, v): exact for small turns too
// (acos of the dot product reads a turn below ~2e-8 rad as none), for quaternions of any norm.
std::pair<double, double> PoseChange(const geometry_msgs::Transform& a,
                                     const geometry_msgs::Transform& b) {
  const auto point = [](const geometry_msgs::Vector3& t) {
    return Eigen::Vector3d(t.x, t.y, t.z);
  };
  const auto rotation = [](const geometry_msgs::Quaternion& q) {
    return Eigen::Quaterniond(q.w, q.x, q.y, q.z);
  };
  return {(point(b.translation) - point(a.translation)).norm(),
          rotation(a.rotation).angularDistance(rotation(b.rotation))};
}

}  // namespace

trajectory_msgs::JointTrajectory ReadGoalTrajectory(
    const std::string& type, const std::string& definition, const std::uint8_t* data,
    std::size_t size, trajectory_msgs::MultiDOFJointTrajectory* multi_dof) {
  const std::vector<std::string>& fields = GoalFields(type);
  const Definitions definitions = ParseDefinitions(type, definition);
  Reader reader(definitions, type, data, size);
  CheckGoalFields(reader, type, fields);
  trajectory_msgs::JointTrajectory trajectory;
  ReadAlong(&reader, type, "", fields, 0, &trajectory, multi_dof);
  if (reader.remaining() != 0) {
    throw Error("", std::to_string(reader.remaining()) + " bytes left after the last field");
  }
  return trajectory;
}

DisplayedPlan ReadDisplayTrajectory(const std::string& definition, const std::uint8_t* data,
                                    std::size_t size) {
  const Definitions definitions = ParseDefinitions(kDisplayTrajectoryType, definition);
  Reader reader(definitions, kDisplayTrajectoryType, data, size);
  // What is read must be there before any byte is.
  if (!HasField(reader, kDisplayTrajectoryType, "trajectory", "moveit_msgs/RobotTrajectory", true,
                "")) {
    throw Error("", "no field 'moveit_msgs/RobotTrajectory[] trajectory' in its definition");
  }
  if (!HasField(reader, "moveit_msgs/RobotTrajectory", "joint_trajectory",
                "trajectory_msgs/JointTrajectory", false, "trajectory")) {
    throw Error("trajectory", "moveit_msgs/RobotTrajectory has no field "
                              "'trajectory_msgs/JointTrajectory joint_trajectory'");
  }
  DisplayedPlan plan;
  for (const Field& field : reader.FieldsOf(kDisplayTrajectoryType, "")) {
    if (field.name == "trajectory" && field.type == "moveit_msgs/RobotTrajectory" &&
        field.is_array) {
      const std::uint32_t count = reader.ReadArrayCount(field, field.name);
      for (std::uint32_t k = 0; k < count; ++k) {
        plan.trajectories.emplace_back();
        plan.multi_dof_trajectories.emplace_back();
        ReadAlong(&reader, field.type, "trajectory[" + std::to_string(k) + "]",
                  {"joint_trajectory"}, 0, &plan.trajectories.back(),
                  &plan.multi_dof_trajectories.back());
      }
    } else if (field.name == "trajectory_start" && field.type == "moveit_msgs/RobotState" &&
               !field.is_array) {
      ReadAlong(&reader, field.type, field.name, {"joint_state"}, 0, &plan.start_state,
                &plan.start_multi_dof);
    } else {
      reader.SkipField(field, "");
    }
  }
  if (reader.remaining() != 0) {
    throw Error("", std::to_string(reader.remaining()) + " bytes left after the last field");
  }
  return plan;
}

MultiDofPoses StartMultiDofPoses(const sensor_msgs::MultiDOFJointState& state) {
  return PosesByName(state.joint_names, state.transforms);
}

MultiDofPoses FirstMultiDofPoses(const trajectory_msgs::MultiDOFJointTrajectory& trajectory) {
  if (trajectory.points.empty()) return {};
  return PosesByName(trajectory.joint_names, trajectory.points.front().transforms);
}

std::string DescribeMultiDofAway(const MultiDofPoses& expected, const MultiDofPoses& at,
                                 std::string* joint) {
  for (const auto& [name, pose] : expected) {
    const auto given = at.find(name);
    if (given == at.end()) continue;
    *joint = name;
    if (!IsValidPose(given->second) || !IsValidPose(pose)) {
      return "puts '" + name + "' at a pose not finite, or of a zero quaternion, not where";
    }
    const auto [m, rad] = PoseChange(pose, given->second);
    if (m <= kSceneBaseAgreement_m && rad <= kSceneBaseAgreement_rad) continue;
    char amount[96];
    std::snprintf(amount, sizeof(amount), " %.6g m and %.6g rad from where", m, rad);
    return "puts '" + name + "'" + amount;
  }
  return "";
}

std::string DescribeMultiDofMotion(const trajectory_msgs::MultiDOFJointTrajectory& trajectory,
                                   MultiDofPoses* at) {
  const std::vector<std::string>& names = trajectory.joint_names;
  double largest_m = 0.0, largest_rad = 0.0;
  bool is_invalid = false;
  std::set<std::string> moving;
  for (const trajectory_msgs::MultiDOFJointTrajectoryPoint& point : trajectory.points) {
    if (point.transforms.size() != names.size()) {
      return "its multi_dof_joint_trajectory has a point of " +
             std::to_string(point.transforms.size()) + " transforms for " +
             std::to_string(names.size()) + " joints";
    }
    for (std::size_t j = 0; j < names.size(); ++j) {
      const geometry_msgs::Transform& pose = point.transforms[j];
      const auto [before, is_new] = at->emplace(names[j], pose);  // new: its first point's
      if (!IsValidPose(pose) || !IsValidPose(before->second)) {
        is_invalid = true;
        moving.insert(names[j]);
        continue;
      }
      const auto [m, rad] = PoseChange(before->second, pose);
      if (m > kMultiDofStill_m || rad > kMultiDofStill_rad) moving.insert(names[j]);
      largest_m = std::max(largest_m, m);
      largest_rad = std::max(largest_rad, rad);
    }
  }
  for (std::size_t j = 0; j < names.size() && !trajectory.points.empty(); ++j) {
    (*at)[names[j]] = trajectory.points.back().transforms[j];
  }
  if (moving.empty()) return "";
  std::string text = "its multi_dof_joint_trajectory moves";
  const char* separator = " '";
  for (const std::string& name : moving) {
    text += separator + name + "'";
    separator = ", '";
  }
  char amount[96];
  std::snprintf(amount, sizeof(amount), " by up to %.6g m and %.6g rad", largest_m, largest_rad);
  return text + amount + (is_invalid ? " (and to a pose not finite, or a zero quaternion)" : "");
}

}  // namespace arm_collision_monitor
