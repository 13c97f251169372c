#include "arm_collision_monitor/scene/mesh_fit_cache.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "arm_collision_monitor/core/constants.h"

namespace arm_collision_monitor {
namespace {

constexpr const char* kFormatLine = "arm_collision_monitor mesh fit v1";

std::string HexFloat(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%a", x);
  return text;
}

// Reads the next token of `in` as a C hexfloat (or decimal); false unless all of it parses.
bool ReadDouble(std::istream& in, double* x) {
  std::string token;
  if (!(in >> token)) return false;
  char* end = nullptr;
  *x = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();
}

bool ReadVector(std::istream& in, Eigen::Vector3d* v) {
  return ReadDouble(in, &v->x()) && ReadDouble(in, &v->y()) && ReadDouble(in, &v->z());
}

bool ExpectWord(std::istream& in, const char* word) {
  std::string token;
  return (in >> token) && token == word;
}

std::optional<Shape> ReadShape(std::istream& in) {
  std::string kind;
  if (!(in >> kind)) return std::nullopt;
  if (kind == "capsule") {
    Capsule c;
    if (!ReadVector(in, &c.p0_W) || !ReadVector(in, &c.p1_W) || !ReadDouble(in, &c.radius_m) ||
        !(c.p0_W.allFinite() && c.p1_W.allFinite() && std::isfinite(c.radius_m) &&
          c.radius_m >= 0.0)) {
      return std::nullopt;
    }
    return Shape(c);
  }
  if (kind == "box") {
    Box b;
    Eigen::Vector3d t;
    Eigen::Matrix3d R;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d row;
      if (!ReadVector(in, &row)) return std::nullopt;
      R.row(k) = row.transpose();
    }
    if (!ReadVector(in, &t) || !ReadVector(in, &b.half_extents_m)) return std::nullopt;
    // Contains() inverts the rotation by its transpose: it must be orthonormal.
    const bool is_rotation =
        R.allFinite() && R.determinant() > 0.0 &&
        (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <=
            kUnitAxisNormTolerance;
    if (!is_rotation || !t.allFinite() || !b.half_extents_m.allFinite() ||
        (b.half_extents_m.array() < 0.0).any()) {
      return std::nullopt;
    }
    b.X_WB.linear() = R;
    b.X_WB.translation() = t;
    return Shape(b);
  }
  return std::nullopt;
}

void WriteShape(std::ostream& out, const Shape& shape) {
  auto vector = [&](const Eigen::Vector3d& v) {
    out << ' ' << HexFloat(v.x()) << ' ' << HexFloat(v.y()) << ' ' << HexFloat(v.z());
  };
  if (const auto* c = std::get_if<Capsule>(&shape)) {
    out << "capsule";
    vector(c->p0_W);
    vector(c->p1_W);
    out << ' ' << HexFloat(c->radius_m) << '\n';
    return;
  }
  const Box& b = std::get<Box>(shape);
  out << "box";
  for (int k = 0; k < 3; ++k) vector(b.X_WB.linear().row(k).transpose());
  vector(b.X_WB.translation());
  vector(b.half_extents_m);
  out << '\n';
}

bool Contains(const Shape& shape_L, const Eigen::Vector3d& p_L) {
  if (const auto* c = std::get_if<Capsule>(&shape_L)) {
    const Eigen::Vector3d d = c->p1_W - c->p0_W;
    const double length2 = d.squaredNorm();
    const double s = length2 > 0.0 ? std::clamp((p_L - c->p0_W).dot(d) / length2, 0.0, 1.0) : 0.0;
    return (p_L - (c->p0_W + s * d)).squaredNorm() <= c->radius_m * c->radius_m;
  }
  const Box& b = std::get<Box>(shape_L);
  const Eigen::Vector3d p_B = b.X_WB.linear().transpose() * (p_L - b.X_WB.translation());
  return (p_B.cwiseAbs().array() <= b.half_extents_m.array()).all();
}

}  // namespace

std::string DefaultMeshFitCacheDir() {
  if (const char* dir = std::getenv("ACM_MESH_FIT_CACHE")) return dir;
  std::filesystem::path ros_home;
  if (const char* env = std::getenv("ROS_HOME"); env != nullptr && *env != '\0') {
    ros_home = env;
  } else if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
    ros_home = std::filesystem::path(home) / ".ros";
  } else {
    return "";
  }
  return (ros_home / "arm_collision_monitor" / "mesh_fit_cache").string();
}

bool ContainsAllVertices(const std::vector<Shape>& shapes_L, const TriangleMesh& mesh) {
  for (const Eigen::Vector3d& p_L : mesh.vertices_L) {
    bool is_inside = false;
    for (const Shape& shape_L : shapes_L) {
      if (Contains(shape_L, p_L)) {
        is_inside = true;
        break;
      }
    }
    if (!is_inside) return false;
  }
  return true;
}

std::string MeshFitCache::PathOf(std::uint64_t key) const {
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.fit", static_cast<unsigned long long>(key));
  return (std::filesystem::path(dir_) / name).string();
}

std::optional<MeshFit> MeshFitCache::Find(std::uint64_t key, const TriangleMesh& mesh) const {
  if (!is_enabled()) return std::nullopt;
  std::ifstream in(PathOf(key));
  std::string format;
  if (!in || !std::getline(in, format) || format != kFormatLine) return std::nullopt;
  MeshFit fit;
  int closed = -1;
  std::size_t count = 0;
  if (!ExpectWord(in, "closed") || !(in >> closed) || (closed != 0 && closed != 1) ||
      !ExpectWord(in, "mesh_volume_m3") || !ReadDouble(in, &fit.mesh_volume_m3) ||
      !ExpectWord(in, "fitted_volume_m3") || !ReadDouble(in, &fit.fitted_volume_m3) ||
      !ExpectWord(in, "shapes") || !(in >> count) || count == 0 ||
      count > static_cast<std::size_t>(kMeshFitMaxCapsules)) {
    return std::nullopt;
  }
  fit.is_mesh_closed = closed == 1;
  for (std::size_t k = 0; k < count; ++k) {
    const std::optional<Shape> shape = ReadShape(in);
    if (!shape) return std::nullopt;
    fit.shapes_L.push_back(*shape);
  }
  std::string rest;
  if (!ExpectWord(in, "end") || (in >> rest)) return std::nullopt;
  if (!(fit.fitted_volume_m3 > 0.0) || fit.is_mesh_closed != std::isfinite(fit.mesh_volume_m3) ||
      !ContainsAllVertices(fit.shapes_L, mesh)) {
    return std::nullopt;
  }
  fit.excess_ratio = fit.fitted_volume_m3 / fit.mesh_volume_m3;
  return fit;
}

std::string MeshFitCache::Store(std::uint64_t key, const MeshFit& fit) const {
  if (!is_enabled()) return "";
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) return "cannot create " + dir_ + ": " + error.message();
  const std::string path = PathOf(key);
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << kFormatLine << "\nclosed " << (fit.is_mesh_closed ? 1 : 0) << "\nmesh_volume_m3 "
        << HexFloat(fit.mesh_volume_m3) << "\nfitted_volume_m3 " << HexFloat(fit.fitted_volume_m3)
        << "\nshapes " << fit.shapes_L.size() << '\n';
    for (const Shape& shape : fit.shapes_L) WriteShape(out, shape);
    out << "end\n";
    out.flush();
    if (!out) {
      std::filesystem::remove(temporary, error);
      return "cannot write " + temporary;
    }
  }
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    return "cannot rename " + temporary + " to " + path + ": " + error.message();
  }
  return "";
}

}  // namespace arm_collision_monitor
