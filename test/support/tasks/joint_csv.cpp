#include "arm_collision_monitor/tasks/joint_csv.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "arm_collision_monitor/core/constants.h"
#include "arm_collision_monitor/core/load_error.h"
#include "arm_collision_monitor/safety/joint_merger.h"

namespace arm_collision_monitor {
namespace {

constexpr const char* kTimeColumn = "time_s";
constexpr const char* kUtf8ByteOrderMark = "\xEF\xBB\xBF";
// Columns of no model joint named in the error for a missing joint (JointCsvInModelOrder).
constexpr std::size_t kNotedColumns = 8;

std::string Trim(const std::string& s) {
  const std::size_t begin = s.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const std::size_t end = s.find_last_not_of(" \t\r");
  return s.substr(begin, end - begin + 1);
}

std::vector<std::string> SplitFields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(Trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string Where(const std::string& path, int line) {
  return path + ":" + std::to_string(line) + ": ";
}

// The joint names of a header row from column `first` on; `where` prefixes its errors.
std::vector<std::string> HeaderJoints(const std::vector<std::string>& fields, std::size_t first,
                                      const std::string& where) {
  // A first row of numbers alone is a file without its header row.
  if (std::all_of(fields.begin(), fields.end(), [](const std::string& field) {
        char* end = nullptr;
        std::strtod(field.c_str(), &end);
        return !field.empty() && *end == '\0';
      })) {
    throw LoadError(where + "the first row holds numbers only: expected a header row of joint "
                    "names first (optionally time_s, then one name a column)");
  }
  std::vector<std::string> names;
  std::unordered_map<std::string, int> seen;
  for (std::size_t c = first; c < fields.size(); ++c) {
    if (fields[c].empty()) {
      throw LoadError(where + "header column " + std::to_string(c + 1) +
                      " is empty: expected a joint name");
    }
    if (fields[c].find_first_of(";\t") != std::string::npos) {
      throw LoadError(where + "header column " + std::to_string(c + 1) + " '" + fields[c] +
                      "' holds a ';' or a tab: expected columns separated by commas");
    }
    if (!seen.emplace(fields[c], static_cast<int>(c)).second) {
      throw LoadError(where + "joint '" + fields[c] + "' appears twice in the header");
    }
    names.push_back(fields[c]);
  }
  if (names.empty()) throw LoadError(where + "the header names no joint");
  return names;
}

}  // namespace

JointCsv ReadJointCsv(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw LoadError(path + ": cannot open the joint CSV file");
  JointCsv csv;
  csv.path = path;
  bool has_time = false;
  bool has_header = false;
  std::string line;
  int line_number = 0;
  int header_line = 0;
  while (std::getline(file, line)) {
    ++line_number;
    // A UTF-8 byte order mark (spreadsheet exports) is not part of the first name.
    if (line_number == 1 && line.rfind(kUtf8ByteOrderMark, 0) == 0) {
      line.erase(0, std::char_traits<char>::length(kUtf8ByteOrderMark));
    }
    const std::string trimmed = Trim(line);
    if (trimmed.empty() || trimmed[0] == '#') continue;
    std::vector<std::string> fields = SplitFields(trimmed);
    if (!has_header) {
      has_header = true;
      header_line = line_number;
      has_time = fields.front() == kTimeColumn;
      csv.joint_names = HeaderJoints(fields, has_time ? 1 : 0, Where(path, line_number));
      continue;
    }
    const std::size_t expected = csv.joint_names.size() + (has_time ? 1 : 0);
    if (fields.size() != expected) {
      throw LoadError(Where(path, line_number) + std::to_string(fields.size()) +
                      " fields, expected " + std::to_string(expected) + " (one per header column)");
    }
    Eigen::VectorXd row(static_cast<Eigen::Index>(csv.joint_names.size()));
    double time_s = 0.0;
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const std::string column = has_time && c == 0 ? kTimeColumn
                                                    : csv.joint_names[c - (has_time ? 1 : 0)];
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(fields[c].c_str(), &end);
      // A position may be nan or inf, as a driver may publish: the monitor refuses that cycle
      // (as the node refuses such a message); the time must be a finite number.
      const bool is_time = has_time && c == 0;
      const bool is_number = !fields[c].empty() && *end == '\0' &&
                             (std::isfinite(value) ? errno != ERANGE : !is_time);
      if (!is_number) {
        throw LoadError(Where(path, line_number) + "column '" + column + "': '" + fields[c] +
                        (is_time ? "' is not a finite number" : "' is not a number"));
      }
      if (has_time && c == 0) {
        time_s = value;
      } else {
        row[static_cast<Eigen::Index>(c - (has_time ? 1 : 0))] = value;
      }
    }
    if (!has_time) time_s = static_cast<double>(csv.rows.size()) * kTaskCyclePeriod_s;
    if (!csv.time_s.empty() && time_s <= csv.time_s.back()) {
      throw LoadError(Where(path, line_number) + "time_s " + fields[0] +
                      " does not increase over the previous row");
    }
    csv.time_s.push_back(time_s);
    csv.rows.push_back(row);
  }
  if (!has_header) throw LoadError(path + ": empty: expected a header row of joint names");
  if (csv.rows.empty()) {
    throw LoadError(Where(path, header_line) + "no row after the header: expected one row of " +
                    "joint positions per cycle");
  }
  return csv;
}

std::vector<Eigen::VectorXd> JointCsvInModelOrder(
    const JointCsv& csv, const std::vector<std::string>& model_joint_names,
    const std::vector<std::pair<int, double>>& defaults,
    const std::vector<std::string>& derived_joint_names, std::vector<std::string>* ignored,
    std::vector<std::string>* derived) {
  std::unordered_map<std::string, int> model_index;
  for (std::size_t j = 0; j < model_joint_names.size(); ++j) {
    model_index.emplace(model_joint_names[j], static_cast<int>(j));
  }
  std::vector<int> column_of(model_joint_names.size(), -1);
  std::vector<std::string> unknown;  // columns that are no joints of the model, nor mimic ones
  for (std::size_t c = 0; c < csv.joint_names.size(); ++c) {
    const auto it = model_index.find(csv.joint_names[c]);
    if (it == model_index.end()) {
      // A mimic joint's position follows from the others; any other name is no joint of the
      // model (a gripper the driver publishes beside the arms): ignored, as the node ignores it.
      const bool is_derived = std::find(derived_joint_names.begin(), derived_joint_names.end(),
                                        csv.joint_names[c]) != derived_joint_names.end();
      std::vector<std::string>* list = is_derived ? derived : ignored;
      if (list != nullptr) list->push_back(csv.joint_names[c]);
      if (!is_derived) unknown.push_back(csv.joint_names[c]);
      continue;
    }
    column_of[it->second] = static_cast<int>(c);
  }
  Eigen::VectorXd q_default = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(column_of.size()));
  std::vector<bool> has_default(column_of.size(), false);
  for (const auto& [q_index, position] : defaults) {
    q_default[q_index] = position;
    has_default[static_cast<std::size_t>(q_index)] = true;
  }
  std::vector<std::string> missing;
  for (std::size_t j = 0; j < model_joint_names.size(); ++j) {
    if (column_of[j] < 0 && !has_default[j]) missing.push_back(model_joint_names[j]);
  }
  if (!missing.empty()) {
    // A misspelt or prefixed name is among the columns the model does not know.
    const std::size_t more = unknown.size() - std::min(unknown.size(), kNotedColumns);
    unknown.resize(unknown.size() - more);
    const std::string others =
        unknown.empty() ? ""
                        : "; the header's columns that are no joints of the model: " +
                              QuotedNames(unknown) +
                              (more > 0 ? " and " + std::to_string(more) + " more" : "") +
                              PrefixedNamesHint(model_joint_names, unknown, "the model");
    throw LoadError(csv.path + ": header: no column for " + ModelJointsText(missing) + " (" +
                    JointDefaultsHint(missing.size()) + ")" + others);
  }
  std::vector<Eigen::VectorXd> rows;
  rows.reserve(csv.rows.size());
  for (const Eigen::VectorXd& row : csv.rows) {
    Eigen::VectorXd q(static_cast<Eigen::Index>(model_joint_names.size()));
    for (std::size_t j = 0; j < model_joint_names.size(); ++j) {
      q[j] = column_of[j] >= 0 ? row[column_of[j]] : q_default[j];
    }
    rows.push_back(q);
  }
  return rows;
}

}  // namespace arm_collision_monitor
