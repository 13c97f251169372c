#include "arm_collision_monitor/kinematics/urdf_conversions.h"

#include <console_bridge/console.h>
#include <strings.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>
#include <vector>

#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {

Eigen::Isometry3d UrdfPoseToIsometry(const urdf::Pose& pose) {
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
  pose.rotation.getQuaternion(qx, qy, qz, qw);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return X;
}

namespace {

// Attribute `name` of `xml` as a finite number >= 0, else a LoadError naming `where`.
double NonNegativeAttribute(const tinyxml2::XMLElement& xml, const char* name,
                            const std::string& where) {
  double value = 0.0;
  if (xml.QueryDoubleAttribute(name, &value) != tinyxml2::XML_SUCCESS || !std::isfinite(value) ||
      value < 0.0) {
    throw LoadError(where + ": <capsule radius, length> must be finite numbers >= 0");
  }
  return value;
}

// "x y z" to round-trip.
std::string XyzText(const urdf::Vector3& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "%.17g %.17g %.17g", v.x, v.y, v.z);
  return text;
}

// Rewrites each <collision> of `link` whose geometry is Drake's <capsule radius length> (along z
// of its <origin>, `length` between the centres of its end spheres), which urdfdom cannot parse
// (it drops the link's collision elements from there on), as the capsule idiom: a <cylinder> of
// that radius and length, and a <sphere> of the radius on each end face, appended to the link
// (the other elements keep their indices). The scene loader reads the idiom as that capsule.
void RewriteDrakeCapsules(const std::string& urdf_path, tinyxml2::XMLElement* link) {
  const char* link_name = link->Attribute("name");
  int index = 0;
  std::vector<tinyxml2::XMLElement*> caps;
  for (tinyxml2::XMLElement* c = link->FirstChildElement("collision"); c != nullptr;
       c = c->NextSiblingElement("collision"), ++index) {
    tinyxml2::XMLElement* geometry = c->FirstChildElement("geometry");
    tinyxml2::XMLElement* capsule =
        geometry == nullptr ? nullptr : geometry->FirstChildElement("capsule");
    if (capsule == nullptr) continue;
    const std::string where = urdf_path + ": link '" + (link_name ? link_name : "") +
                              "' <collision> " + std::to_string(index) + " (from 0) <capsule>";
    const double radius_m = NonNegativeAttribute(*capsule, "radius", where);
    const double length_m = NonNegativeAttribute(*capsule, "length", where);
    urdf::Pose origin;
    const tinyxml2::XMLElement* origin_xml = c->FirstChildElement("origin");
    try {
      if (origin_xml != nullptr && origin_xml->Attribute("xyz") != nullptr) {
        origin.position.init(origin_xml->Attribute("xyz"));
      }
      if (origin_xml != nullptr && origin_xml->Attribute("rpy") != nullptr) {
        urdf::Vector3 rpy;
        rpy.init(origin_xml->Attribute("rpy"));
        origin.rotation.setFromRPY(rpy.x, rpy.y, rpy.z);
      }
    } catch (const std::exception& e) {
      throw LoadError(where + ": <origin>: " + e.what());
    }
    capsule->SetName("cylinder");
    for (const double side : {-0.5, 0.5}) {
      const urdf::Vector3 offset =
          origin.rotation * urdf::Vector3(0.0, 0.0, side * length_m);
      tinyxml2::XMLElement* cap = link->GetDocument()->NewElement("collision");
      cap->InsertNewChildElement("origin")->SetAttribute(
          "xyz", XyzText(urdf::Vector3(origin.position.x + offset.x,
                                       origin.position.y + offset.y,
                                       origin.position.z + offset.z))
                     .c_str());
      cap->InsertNewChildElement("geometry")->InsertNewChildElement("sphere")->SetAttribute(
          "radius", radius_m);
      caps.push_back(cap);
    }
  }
  for (tinyxml2::XMLElement* cap : caps) link->InsertEndChild(cap);
}

// urdfdom says why it rejects a file only through console_bridge's log. While ParseUrdfFile
// parses, this handler keeps the parsing thread's messages (errors whatever the log level), and
// passes the other threads' on to the handler it replaced. console_bridge keeps a pointer to it
// afterwards (its previous handler, which rosconsole_bridge reinstates at exit), so it lives as
// long as the process and, when not parsing, writes as console_bridge's own handler does.
class UrdfdomLog : public console_bridge::OutputHandlerSTD {
 public:
  struct Entry {
    std::string text;
    console_bridge::LogLevel level;
    const char* file;
    int line;
  };
  /// What one parse logged, and where it would have gone.
  struct Captured {
    std::vector<Entry> entries;
    console_bridge::OutputHandler* before = nullptr;  // the handler then (null: none)
    console_bridge::LogLevel level = console_bridge::CONSOLE_BRIDGE_LOG_WARN;  // the level then

    /// The errors, joined by "; ".
    std::string Errors() const {
      std::string joined;
      for (const Entry& e : entries) {
        if (e.level < console_bridge::CONSOLE_BRIDGE_LOG_ERROR) continue;
        joined += (joined.empty() ? "" : "; ") + e.text;
      }
      return joined;
    }
    /// Hands the entries at the level then to the handler then: all, or those below errors.
    void PassOn(bool with_errors) const {
      if (before == nullptr) return;
      for (const Entry& e : entries) {
        const bool is_error = e.level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR;
        if (e.level >= level && (with_errors || !is_error)) {
          before->log(e.text, e.level, e.file, e.line);
        }
      }
    }
  };

  static UrdfdomLog& Instance() {
    static UrdfdomLog* const log = new UrdfdomLog;  // never destroyed: see above
    return *log;
  }

  /// Keeps the calling thread's messages until End(). Calls must not overlap (ParseUrdfFile's
  /// lock). console_bridge's lock is never taken while holding mutex_ (its log() holds it when
  /// it calls log() below).
  void Begin() {
    const console_bridge::LogLevel level = console_bridge::getLogLevel();
    console_bridge::OutputHandler* const before = console_bridge::getOutputHandler();
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      captured_ = Captured{{}, before, level};
      thread_ = std::this_thread::get_id();
      is_capturing_ = true;
    }
    if (level > console_bridge::CONSOLE_BRIDGE_LOG_ERROR) {
      console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_ERROR);
    }
    console_bridge::useOutputHandler(this);
  }
  /// Puts the handler and the level before Begin() back; returns what was kept.
  Captured End() {
    console_bridge::restorePreviousOutputHandler();
    Captured captured;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      is_capturing_ = false;
      captured = std::move(captured_);
    }
    console_bridge::setLogLevel(captured.level);
    return captured;
  }

  void log(const std::string& text, console_bridge::LogLevel level, const char* file,
           int line) override {
    console_bridge::OutputHandler* before = nullptr;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (is_capturing_) {
        if (std::this_thread::get_id() == thread_) {
          captured_.entries.push_back({text, level, file, line});
          return;
        }
        if (level < captured_.level) return;  // below the level the other thread set
        before = captured_.before;
      }
    }
    // This handler was itself the one before (reinstated as console_bridge's current one).
    if (before != nullptr && before != this) {
      before->log(text, level, file, line);
    } else {
      OutputHandlerSTD::log(text, level, file, line);
    }
  }

 private:
  UrdfdomLog() = default;

  std::mutex mutex_;  // guards the members below: log() runs on any thread
  Captured captured_;
  std::thread::id thread_;
  bool is_capturing_ = false;
};

// Where urdfdom's `errors` point in `robot`: "<line>: joint 'j'" for the first name they give in
// [brackets] or 'quotes' after the word "joint" or "link" that a <joint> or <link> of the file
// has (its last: a name urdfdom finds twice is the later one's fault); empty if none.
std::string ElementNamed(const std::string& errors, const tinyxml2::XMLElement* robot) {
  for (std::size_t open = errors.find_first_of("['"); open != std::string::npos;
       open = errors.find_first_of("['", open + 1)) {
    const char close = errors[open] == '[' ? ']' : '\'';
    const std::size_t end = errors.find(close, open + 1);
    if (end == std::string::npos) break;
    const std::string name = errors.substr(open + 1, end - open - 1);
    const std::size_t word_end =
        open == 0 ? std::string::npos : errors.find_last_not_of(' ', open - 1);
    for (const char* kind : {"joint", "link"}) {
      const std::size_t n = std::strlen(kind);
      if (word_end == std::string::npos || word_end + 1 < n ||
          strncasecmp(errors.c_str() + word_end + 1 - n, kind, n) != 0) {
        continue;
      }
      const tinyxml2::XMLElement* last = nullptr;
      for (const tinyxml2::XMLElement* e = robot->FirstChildElement(kind); e != nullptr;
           e = e->NextSiblingElement(kind)) {
        if (e->Attribute("name") != nullptr && name == e->Attribute("name")) last = e;
      }
      if (last != nullptr) {
        return std::to_string(last->GetLineNum()) + ": " + kind + " '" + name + "'";
      }
    }
    open = end;  // its closing mark opens nothing
  }
  return "";
}

// For a file urdfdom rejects: "; it is xacro ..." when `root` or an element below it is
// xacro's (a package's unexpanded robot.urdf.xacro, perhaps one defining macros only), else "".
std::string XacroNote(const tinyxml2::XMLElement* root) {
  int count = 0;
  const tinyxml2::XMLElement* first = nullptr;
  std::vector<const tinyxml2::XMLElement*> pending{root};
  while (!pending.empty()) {
    const tinyxml2::XMLElement* e = pending.back();
    pending.pop_back();
    if (IsXacroElement(e)) {
      ++count;
      if (first == nullptr || e->GetLineNum() < first->GetLineNum()) first = e;
    }
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c != nullptr;
         c = c->NextSiblingElement()) {
      pending.push_back(c);
    }
  }
  if (first == nullptr) return "";
  const char* name = first->Attribute("name");
  const std::string named = name != nullptr ? std::string(" name='") + name + "'" : "";
  return "; it is xacro, not expanded (" + std::to_string(count) + " <xacro:...> element(s), " +
         "the first <" + first->Name() + named + "> at line " +
         std::to_string(first->GetLineNum()) +
         "): expand it with xacro first, on a machine with ROS's xacro";
}

}  // namespace

std::string MalformedXmlError(const std::string& path, const tinyxml2::XMLDocument& doc,
                              const std::string& expected) {
  const int line_number = doc.ErrorLineNum();
  const std::string line = std::to_string(line_number);
  // tinyxml2 ends some errors with the element's name: "...: XMLElement name=group".
  const std::string detail = doc.ErrorStr();
  const std::string::size_type named = detail.find("XMLElement name=");
  const std::string element =
      named == std::string::npos ? "the element" : "<" + detail.substr(named + 16) + ">";
  std::string what = std::string("malformed XML (") + doc.ErrorName() + ")";
  switch (doc.ErrorID()) {
    case tinyxml2::XML_ERROR_PARSING:  // what tinyxml2 reports when the text ends too early
      what += ": the file ends inside the element that begins on line " + line +
              " (its end tag is missing, and maybe those of the elements around it)";
      break;
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      what += ": " + element + ", which begins on line " + line +
              ", is closed by an end tag not its own (an end tag inside it is missing or "
              "misspelt, or one has no start tag)";
      break;
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      what += ": the file holds no element";
      break;
    default:
      what += ": " + detail;
  }
  return path + (line_number > 0 ? ":" + line : std::string()) + ": " + what +
         " (expected a well-formed " + expected + ")";
}

bool IsXacroElement(const tinyxml2::XMLElement* xml) {
  return std::strncmp(xml->Name(), "xacro:", 6) == 0;
}

urdf::ModelInterfaceSharedPtr ParseUrdfFile(const std::string& urdf_path) {
  std::ifstream in(urdf_path);
  if (!in) {
    throw LoadError(urdf_path + ": cannot open the URDF file (expected a readable URDF/XML file" +
                    RelativePathNote(urdf_path) + ")");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string xml = buffer.str();
  // urdfdom reports malformed XML without a line ("Error reading end tag"): tinyxml2 names it.
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw LoadError(MalformedXmlError(urdf_path, doc, "URDF"));
  }
  tinyxml2::XMLElement* robot = doc.RootElement();
  for (tinyxml2::XMLElement* link = robot ? robot->FirstChildElement("link") : nullptr;
       link != nullptr; link = link->NextSiblingElement("link")) {
    RewriteDrakeCapsules(urdf_path, link);
  }
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  urdf::ModelInterfaceSharedPtr model;
  UrdfdomLog::Captured captured;
  {
    static std::mutex parse_mutex;  // one capture at a time
    const std::lock_guard<std::mutex> lock(parse_mutex);
    UrdfdomLog& urdfdom_log = UrdfdomLog::Instance();
    urdfdom_log.Begin();
    try {
      model = urdf::parseURDF(printer.CStr());
    } catch (const std::exception& e) {
      captured = urdfdom_log.End();
      const std::string errors = captured.Errors();
      throw LoadError(urdf_path + ": not a valid URDF: urdfdom failed: " + e.what() +
                      (errors.empty() ? "" : " (after: " + errors + ")"));
    }
    captured = urdfdom_log.End();
  }
  // A file urdfdom takes may still have had errors (a <collision> it dropped): they go out.
  captured.PassOn(model != nullptr);
  const std::string errors = captured.Errors();
  if (!model) {
    const std::string element = robot != nullptr ? ElementNamed(errors, robot) : "";
    throw LoadError(urdf_path + (element.empty() ? "" : ":" + element) +
                    ": not a valid URDF: urdfdom rejected it" +
                    (errors.empty() ? std::string(" without a reason") : ": " + errors) +
                    (robot != nullptr ? XacroNote(robot) : "") +
                    " (expected a <robot> whose links and joints form one tree)");
  }
  return model;
}

}  // namespace arm_collision_monitor
