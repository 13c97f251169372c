// ReadSceneGeometryText: MoveIt's scene geometry text (a `.scene` file), read token by token
// with line numbers for the messages. The grammar, as MoveIt 1's PlanningScene writes and reads
// it (saveGeometryToStream / loadGeometryFromStream, shapes as geometric_shapes' saveAsText):
//
//   NAME                                  the whole first line
//   * ID                                  an object: the rest of the line is its id
//   [X Y Z  QX QY QZ QW]                  its pose (the newer format only)
//   COUNT                                 its shapes, each:
//     TYPE DIMENSIONS                     sphere R | box X Y Z | cylinder R L | cone R L |
//                                         mesh V T, V vertices X Y Z, T triangles I J K
//     X Y Z  QX QY QZ QW                  its pose, in the object's frame (the older format:
//                                         in the planning frame)
//     R G B A                             its colour (read, not used)
//   [COUNT (NAME X Y Z QX QY QZ QW)...]   its subframes (the newer format only; not used)
//   .                                     the end (what follows is not read)
//
// As MoveIt does, the format is told by the line after the first object's marker: a pose (with
// spaces) in the newer format, the shape count in the older one.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/scene/planning_scene_reader.h"
#include "arm_collision_monitor/scene/unit_quaternion.h"
#include "text_trim.h"

namespace arm_collision_monitor {
namespace {

/// What a message says was found: the token, or the end of the file for "".
std::string Found(const std::string& token) {
  return token.empty() ? "the file ends" : "'" + token + "'";
}

/// The text's tokens (whitespace-separated) in order, each with its line.
class TokenReader {
 public:
  TokenReader(const std::string& text, const std::string& path) : text_(text), path_(path) {}

  /// The element messages name until the first object: "scene".
  void SetElement(const std::string& element) { element_ = element; }
  int line() const { return line_; }

  [[noreturn]] void Fail(const std::string& what) const {
    throw LoadError(path_ + ":" + std::to_string(line_) + ": " + element_ + ": " + what);
  }

  /// The rest of the current line (the scene name, an object's id), trimmed; moves past it.
  std::string RestOfLine() {
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    const std::size_t start = pos_;
    pos_ = end;
    return Trimmed(text_.substr(start, end - start));
  }

  /// The next token; "" at the end of the text.
  std::string Next() {
    while (pos_ < text_.size() && IsSpace(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !IsSpace(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  /// The next token as a finite number; `what` names it in the message.
  double Number(const std::string& what) {
    const std::string token = Next();
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(token.c_str(), &end);
    if (token.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(value)) {
      Fail(Found(token) + " (expected " + what + ", a finite number)");
    }
    return value;
  }

  /// A shape's dimensions, each named in `names` ("the box's size x", ...): numbers > 0, all on
  /// one line as MoveIt writes them (a number short would otherwise take the pose's first).
  std::vector<double> Dimensions(const std::vector<std::string>& names) {
    std::vector<double> values;
    int first_line = 0;
    for (const std::string& name : names) {
      const double value = Number(name);
      if (values.empty()) first_line = line_;
      if (line_ != first_line) {
        Fail("line " + std::to_string(first_line) + " holds " + std::to_string(values.size()) +
             " of the " + std::to_string(names.size()) + " dimensions, and " + name +
             " would be this line's first number (expected a shape's dimensions on one line, "
             "as MoveIt writes them)");
      }
      if (!(value > 0.0)) Fail(name + " " + std::to_string(value) + " (expected a number > 0)");
      values.push_back(value);
    }
    return values;
  }

  /// The next token as a count of at most `most`.
  std::uint32_t Count(const std::string& what, std::uint64_t most) {
    const std::string token = Next();
    char* end = nullptr;
    errno = 0;
    const unsigned long long value = std::strtoull(token.c_str(), &end, 10);
    if (token.empty() || token[0] == '-' || *end != '\0' || errno == ERANGE || value > most) {
      Fail(Found(token) + " (expected " + what + ", an integer from 0 to " +
           std::to_string(most) + ")");
    }
    return static_cast<std::uint32_t>(value);
  }

  /// X Y Z  QX QY QZ QW as a pose (the quaternion policy of planning_scene_reader.h).
  Eigen::Isometry3d Pose(const std::string& what) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 3; ++i) X.translation()[i] = Number(what + " position x y z");
    Eigen::Vector4d xyzw;
    for (int i = 0; i < 4; ++i) xyzw[i] = Number(what + " orientation qx qy qz qw");
    Eigen::Quaterniond q;
    const std::string error = ToUnitQuaternion(xyzw, &q);
    if (!error.empty()) Fail(what + ": " + error);
    X.linear() = q.toRotationMatrix();
    return X;
  }

 private:
  static bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

  const std::string& text_;
  const std::string& path_;
  std::string element_ = "scene";
  std::size_t pos_ = 0;
  int line_ = 1;
};

/// Counts above this are refused rather than read: a mesh of more vertices or triangles, or an
/// object of more shapes or subframes, is a corrupt file (and would only be read token by token).
constexpr std::uint64_t kMostCount = 10'000'000;

/// One shape: its type, dimensions, pose (X_FO * its pose) and colour, into `object`.
void ReadShape(TokenReader* in, const Eigen::Isometry3d& X_FO, SceneCollisionObject* object) {
  const std::string type = in->Next();
  if (type == "mesh") {
    SceneMesh mesh;
    const std::uint32_t vertex_count = in->Count("the mesh's vertex count", kMostCount);
    const std::uint32_t triangle_count = in->Count("the mesh's triangle count", kMostCount);
    if (vertex_count < 3 || triangle_count == 0) {
      in->Fail("a mesh of " + std::to_string(vertex_count) + " vertices and " +
               std::to_string(triangle_count) +
               " triangles (expected at least 3 vertices and 1 triangle)");
    }
    for (std::uint32_t i = 0; i < vertex_count; ++i) {
      Eigen::Vector3d p_M;
      for (int k = 0; k < 3; ++k) p_M[k] = in->Number("a vertex's x y z");
      mesh.vertices_M.push_back(p_M);
    }
    for (std::uint32_t t = 0; t < triangle_count; ++t) {
      std::array<std::uint32_t, 3> triangle{};
      for (auto& index : triangle) index = in->Count("a vertex index", vertex_count - 1);
      mesh.triangles.push_back(triangle);
    }
    mesh.X_FM = X_FO * in->Pose("the mesh's pose");
    object->meshes.push_back(std::move(mesh));
  } else {
    ScenePrimitive primitive;
    if (type == "sphere") {
      primitive.type = SolidPrimitiveType::kSphere;
      primitive.dimensions_m = in->Dimensions({"the sphere's radius"});
    } else if (type == "box") {
      primitive.type = SolidPrimitiveType::kBox;
      primitive.dimensions_m =
          in->Dimensions({"the box's size x", "the box's size y", "the box's size z"});
    } else if (type == "cylinder" || type == "cone") {
      primitive.type =
          type == "cylinder" ? SolidPrimitiveType::kCylinder : SolidPrimitiveType::kCone;
      const std::vector<double> radius_length =
          in->Dimensions({"the " + type + "'s radius", "the " + type + "'s length"});
      // shape_msgs' order: height, radius
      primitive.dimensions_m = {radius_length[1], radius_length[0]};
    } else if (type == "plane") {
      in->Fail("planes are not supported (expected box, sphere, cylinder, cone or mesh)");
    } else {
      in->Fail(std::string(type.empty() ? "" : "unknown shape type ") + Found(type) +
               " (expected box, sphere, cylinder, cone or mesh)");
    }
    primitive.X_FP = X_FO * in->Pose("the " + type + "'s pose");
    object->primitives.push_back(std::move(primitive));
  }
  for (int i = 0; i < 4; ++i) in->Number("the shape's colour r g b a");
}

/// Whether the line after the first object's marker (after the name line) holds a pose (the
/// newer format).
bool IsNewerFormat(const std::string& text) {
  std::size_t start = std::min(text.find('\n'), text.size()) + 1;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::size_t first = text.find_first_not_of(" \t\r", start);
    if (first < end && text[first] == '*') {
      const std::size_t next = end + 1;
      if (next >= text.size()) return false;
      return Trimmed(text.substr(next, text.find('\n', next) - next)).find_first_of(" \t") !=
             std::string::npos;
    }
    start = end + 1;
  }
  return false;
}

}  // namespace

PlanningSceneFile ReadSceneGeometryText(const std::string& text, const std::string& path) {
  TokenReader in(text, path);
  PlanningSceneFile scene;
  scene.name = in.RestOfLine();
  const bool is_newer = IsNewerFormat(text);
  std::set<std::string> ids;
  std::string last_id;
  for (;;) {
    in.SetElement(last_id.empty() ? "scene" : "after object '" + last_id + "'");
    const std::string marker = in.Next();
    if (marker == ".") break;
    if (marker != "*") {
      in.Fail(Found(marker) + " (expected '* ID' for an object or '.' for the end of the scene)");
    }
    SceneCollisionObject object;
    object.line = in.line();
    object.id = in.RestOfLine();
    object.element = "object '" + object.id + "'";
    in.SetElement(object.element);
    if (object.id.empty()) in.Fail("an object without id (expected '* ID')");
    if (!ids.insert(object.id).second) in.Fail("id repeated (expected unique ids)");
    last_id = object.id;
    const Eigen::Isometry3d X_FO =
        is_newer ? in.Pose("the object's pose") : Eigen::Isometry3d::Identity();
    const std::uint32_t shape_count = in.Count("the object's shape count", kMostCount);
    for (std::uint32_t i = 0; i < shape_count; ++i) {
      in.SetElement(object.element + " shape " + std::to_string(i));
      ReadShape(&in, X_FO, &object);
    }
    in.SetElement(object.element);
    if (is_newer) {
      const std::uint32_t subframe_count = in.Count("the object's subframe count", kMostCount);
      for (std::uint32_t i = 0; i < subframe_count; ++i) {
        if (in.Next().empty()) in.Fail("the file ends (expected a subframe's name)");
        in.Pose("a subframe's pose");
      }
    }
    if (shape_count == 0) {
      scene.notices.push_back(ShapelessObjectNotice(object));
      scene.shapeless_ids.push_back(object.id);
    } else {
      scene.objects.push_back(std::move(object));
    }
  }
  return scene;
}

}  // namespace arm_collision_monitor
