// Test and benchmark meshes: closed, outward-oriented triangle meshes (extruded polygons) and
// writers for the mesh file formats the loader reads (binary and ASCII STL, OBJ, COLLADA).
// Every coordinate is rounded to float, the precision of those files, so that a mesh read back
// has exactly the vertices written.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "arm_collision_monitor/geometry/mesh_fit.h"

namespace arm_collision_monitor {

inline double ToFloat(double x) { return static_cast<double>(static_cast<float>(x)); }

/// The prism of a counter-clockwise polygon (seen from +z) between z0 < z1: side quads and two
/// caps fanned from `apex` (a vertex from which the whole polygon is visible).
inline TriangleMesh ExtrudedPolygon(const std::vector<Eigen::Vector2d>& polygon, int apex,
                                    double z0, double z1) {
  TriangleMesh mesh;
  const auto n = static_cast<std::uint32_t>(polygon.size());
  for (const double z : {z0, z1}) {
    for (const Eigen::Vector2d& p : polygon) {
      mesh.vertices_L.emplace_back(ToFloat(p.x()), ToFloat(p.y()), ToFloat(z));
    }
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    mesh.triangles.push_back({i, j, j + n});
    mesh.triangles.push_back({i, j + n, i + n});
    const auto a = static_cast<std::uint32_t>(apex);
    if (i != a && j != a) {
      mesh.triangles.push_back({a + n, i + n, j + n});  // top, facing +z
      mesh.triangles.push_back({a, j, i});              // bottom, facing -z
    }
  }
  return mesh;
}

/// A box of `size_m` centred on the origin.
inline TriangleMesh BoxMesh(const Eigen::Vector3d& size_m) {
  const double x = 0.5 * size_m.x(), y = 0.5 * size_m.y();
  return ExtrudedPolygon({{-x, -y}, {x, -y}, {x, y}, {-x, y}}, 0, -0.5 * size_m.z(),
                         0.5 * size_m.z());
}

/// A regular `sides`-gon prism of circumradius `radius_m` along z, centred on the origin.
inline TriangleMesh PrismMesh(double radius_m, double length_m, int sides) {
  std::vector<Eigen::Vector2d> polygon;
  for (int k = 0; k < sides; ++k) {
    const double angle = 2.0 * M_PI * k / sides;
    polygon.emplace_back(radius_m * std::cos(angle), radius_m * std::sin(angle));
  }
  return ExtrudedPolygon(polygon, 0, -0.5 * length_m, 0.5 * length_m);
}

/// A non-convex L: the square [0, 2a]^2 less [a, 2a]^2, extruded over [0, h].
inline TriangleMesh LShapeMesh(double a_m, double h_m) {
  return ExtrudedPolygon(
      {{0, 0}, {2 * a_m, 0}, {2 * a_m, a_m}, {a_m, a_m}, {a_m, 2 * a_m}, {0, 2 * a_m}}, 3, 0.0,
      h_m);
}

/// A tessellated capsule along z (segment length `length_m`, radius `radius_m`): `segments`
/// around, `rings` latitude rings per hemisphere, each vertex's distance from the axis segment
/// scaled by 1 + noise * u (u uniform in [-1, 1] from `rng`). Closed and outward-oriented;
/// 2 * segments * (2 * rings - 1) triangles.
template <typename Rng>
TriangleMesh TessellatedCapsuleMesh(double radius_m, double length_m, int segments, int rings,
                                    double noise, Rng* rng) {
  TriangleMesh mesh;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto add = [&](const Eigen::Vector3d& centre, const Eigen::Vector3d& direction) {
    const Eigen::Vector3d p = centre + radius_m * (1.0 + noise * u(*rng)) * direction;
    mesh.vertices_L.emplace_back(ToFloat(p.x()), ToFloat(p.y()), ToFloat(p.z()));
    return static_cast<std::uint32_t>(mesh.vertices_L.size() - 1);
  };
  const Eigen::Vector3d bottom(0, 0, -0.5 * length_m), top(0, 0, 0.5 * length_m);
  const std::uint32_t south = add(bottom, -Eigen::Vector3d::UnitZ());
  std::vector<std::uint32_t> previous;
  for (int ring = 1; ring <= 2 * rings; ++ring) {
    // Rings 1..rings: the bottom hemisphere up to its equator; rings+1..2 rings: the top one
    // from its equator.
    const int latitude = ring <= rings ? ring : ring - 1;
    const double theta = M_PI * latitude / (2 * rings);  // from the south pole
    const Eigen::Vector3d& centre = ring <= rings ? bottom : top;
    std::vector<std::uint32_t> current;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * M_PI * j / segments;
      current.push_back(add(centre, Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                    std::sin(theta) * std::sin(phi),
                                                    -std::cos(theta))));
    }
    for (int j = 0; j < segments; ++j) {
      const int k = (j + 1) % segments;
      if (previous.empty()) {
        mesh.triangles.push_back({south, current[k], current[j]});
      } else {
        mesh.triangles.push_back({previous[j], previous[k], current[k]});
        mesh.triangles.push_back({previous[j], current[k], current[j]});
      }
    }
    previous = current;
  }
  const std::uint32_t north = add(top, Eigen::Vector3d::UnitZ());
  for (int j = 0; j < segments; ++j) {
    mesh.triangles.push_back({north, previous[j], previous[(j + 1) % segments]});
  }
  return mesh;
}

inline std::string Number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", x);  // 9 digits round-trip a float
  return text;
}

/// Binary STL: an 80-byte header (not starting with "solid"), the count, 50 bytes per facet.
inline std::string BinaryStl(const TriangleMesh& mesh) {
  std::string bytes(80, ' ');
  bytes.replace(0, 6, "binary");
  auto put = [&](const void* data, std::size_t size) {
    bytes.append(static_cast<const char*>(data), size);
  };
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  put(&count, 4);
  for (const auto& triangle : mesh.triangles) {
    const float normal[3] = {0, 0, 0};
    put(normal, sizeof normal);
    for (const std::uint32_t index : triangle) {
      for (int k = 0; k < 3; ++k) {
        const auto x = static_cast<float>(mesh.vertices_L[index][k]);
        put(&x, 4);
      }
    }
    const std::uint16_t attribute = 0;
    put(&attribute, 2);
  }
  return bytes;
}

inline std::string AsciiStl(const TriangleMesh& mesh) {
  std::string text = "solid test\n";
  for (const auto& triangle : mesh.triangles) {
    text += " facet normal 0 0 0\n  outer loop\n";
    for (const std::uint32_t index : triangle) {
      const Eigen::Vector3d& v = mesh.vertices_L[index];
      text += "   vertex " + Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()) + "\n";
    }
    text += "  endloop\n endfacet\n";
  }
  return text + "endsolid test\n";
}

inline std::string Obj(const TriangleMesh& mesh) {
  std::string text = "# test mesh\n";
  for (const Eigen::Vector3d& v : mesh.vertices_L) {
    text += "v " + Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()) + "\n";
  }
  for (const auto& t : mesh.triangles) {
    text += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
            std::to_string(t[2] + 1) + "\n";
  }
  return text;
}

/// COLLADA 1.4.1 with the given <unit meter> and <up_axis> (coordinates written as given).
inline std::string Dae(const TriangleMesh& mesh, const std::string& unit_meter = "1",
                       const std::string& up_axis = "Z_UP") {
  std::string positions, indices;
  for (const Eigen::Vector3d& v : mesh.vertices_L) {
    positions += Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z()) + " ";
  }
  for (const auto& t : mesh.triangles) {
    for (const std::uint32_t index : t) indices += std::to_string(index) + " ";
  }
  const std::string n = std::to_string(mesh.vertices_L.size());
  return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
         "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
         "<asset><unit name=\"u\" meter=\"" + unit_meter + "\"/><up_axis>" + up_axis +
         "</up_axis></asset>\n"
         "<library_geometries><geometry id=\"g\"><mesh>\n"
         "<source id=\"p\"><float_array id=\"pa\" count=\"" +
         std::to_string(3 * mesh.vertices_L.size()) + "\">" + positions +
         "</float_array><technique_common><accessor source=\"#pa\" count=\"" + n +
         "\" stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
         "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
         "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"
         "<triangles count=\"" + std::to_string(mesh.triangles.size()) +
         "\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>" + indices +
         "</p></triangles>\n</mesh></geometry></library_geometries>\n"
         "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">"
         "<instance_geometry url=\"#g\"/></node></visual_scene></library_visual_scenes>\n"
         "<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
}

inline void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace arm_collision_monitor
