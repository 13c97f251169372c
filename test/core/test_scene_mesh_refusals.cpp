// LoadWorkcell refusing bad mesh input, each with a LoadError naming the URDF (or scene file),
// the link (or object) and the mesh: unreadable, malformed or empty files, COLLADA files whose
// index lists or references would mislead assimp, meshes without volume, bad scales.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "arm_collision_monitor/scene/workcell.h"
#include "load_error_expect.h"
#include "mesh_file_writers.h"
#include "mesh_robot_files.h"
#include "test_geometry_shapes.h"

namespace arm_collision_monitor {
namespace {

// Loading a robot whose link0 has the mesh `file` (written with `bytes` unless empty) fails
// naming the URDF, the link, the mesh and each of `parts`.
void ExpectBadLinkMesh(const std::string& dir, const std::string& file, const std::string& bytes,
                       const std::vector<std::string>& parts, const std::string& scale = "") {
  if (!bytes.empty()) WriteBytes(dir + file, bytes);
  const Files files = WriteRobot(dir, {MeshCollision(file, "", scale)});
  std::vector<std::string> all = {files.urdf, "link 'link0'", "mesh '" + file + "'"};
  all.insert(all.end(), parts.begin(), parts.end());
  ExpectLoadError([&] { LoadWorkcell(files.urdf, files.scene, CacheIn(dir)); }, all);
  // assimp's own name for bytes read from memory never shows: the file's does.
  try {
    LoadWorkcell(files.urdf, files.scene, CacheIn(dir));
  } catch (const LoadError& e) {
    EXPECT_EQ(std::string(e.what()).find("magic"), std::string::npos) << e.what();
  }
}

// The COLLADA text `dae` of LShapeMesh(0.1, 0.05), written as `file` for link0, loads: its fit
// encloses the mesh.
void ExpectLShapeLoads(const std::string& dir, const std::string& file, const std::string& dae) {
  WriteBytes(dir + file, dae);
  const Files files = WriteRobot(dir, {MeshCollision(file)});
  ExpectEncloses(LoadWorkcell(files.urdf, files.scene, CacheIn(dir)), "link0",
                 LShapeMesh(0.1, 0.05), Eigen::Isometry3d::Identity());
}

TEST(SceneMeshRefusals, BadMeshFilesAreRejectedNamingUrdfLinkAndFile) {
  const std::string dir = FreshDir("bad_files");
  ExpectBadLinkMesh(dir, "missing.stl", "", {"cannot open the file"});
  ExpectBadLinkMesh(dir, "", "", {"an empty file name"});
  ExpectBadLinkMesh(dir, " ", "", {"an empty file name"});
  std::string garbage;
  for (int i = 0; i < 3000; ++i) garbage += static_cast<char>((i * 7919 + 13) % 251);
  for (const std::string& name :
       std::vector<std::string>{"garbage.stl", "garbage.dae", "garbage.obj"}) {
    ExpectBadLinkMesh(dir, name, garbage, {});
  }
  const std::string stl = BinaryStl(LShapeMesh(0.1, 0.05));
  ExpectBadLinkMesh(dir, "truncated.stl", stl.substr(0, stl.size() - 30), {"cannot read the mesh"});
  ExpectBadLinkMesh(dir, "header_only.stl", stl.substr(0, 40), {"cannot read the mesh"});
  ExpectBadLinkMesh(dir, "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n", {});
}

// Inputs the mesh fuzzer (test/fuzz/fuzz_scene_mesh_file.cpp) found: assimp refuses them (and
// leaks on the first, see test/fuzz/lsan.supp); the error still names the URDF, link and file.
TEST(SceneMeshRefusals, MalformedStlFilesAreRejected) {
  const std::string dir = FreshDir("bad_stl");
  const std::string facet_start = "solid a\nfacet normal 0 0 1\nouter loop\n";
  ExpectBadLinkMesh(dir, "two_vertices.stl",
                    facet_start + "vertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid a\n",
                    {"cannot read the mesh"});
  ExpectBadLinkMesh(dir, "no_facet.stl", "solid a\nendsolid a\n", {"cannot read the mesh"});
  // A binary STL whose triangle count needs more bytes than the file has, by 4 triangles or,
  // with 32-bit arithmetic, by 2^31 (84 + 50 (2^31 + 1) wraps to the file's 134 bytes).
  std::string stl = BinaryStl(BoxMesh(Eigen::Vector3d(0.1, 0.1, 0.1))).substr(0, 134);
  for (const std::uint32_t count : {5u, 0x80000001u}) {
    std::memcpy(&stl[80], &count, 4);
    ExpectBadLinkMesh(dir, "count_" + std::to_string(count) + ".stl", stl,
                      {"cannot read the mesh"});
  }
}

// A COLLADA file that places no geometry in its scene (no node instances its geometry) is
// refused: assimp marks the scene incomplete and gives it a stand-in skeleton mesh, whose fit was
// a 0.1 mm capsule for the link (helper-66 trial, a contact missed). So is a reference assimp
// skips with a log line, leaving its part out (helper-68, helper-69): an <instance_geometry> whose
// url names no geometry of the file, alone or beside a good one, one naming the id of a node, one
// whose '>' in an attribute hides its url from a naive reading, and a node in another file.
TEST(SceneMeshRefusals, ColladaPlacingNoGeometryIsRejected) {
  const std::string dir = FreshDir("dae_no_geometry");
  const std::string dae = Dae(LShapeMesh(0.1, 0.05));
  const std::string instance = "<instance_geometry url=\"#g\"/>";
  const std::size_t at = dae.find(instance);
  ASSERT_NE(at, std::string::npos);
  const auto line = std::to_string(1 + std::count(dae.begin(), dae.begin() + at, '\n'));
  auto with = [&](const std::string& in_place_of_instance) {
    std::string edited = dae;
    edited.replace(at, instance.size(), in_place_of_instance);
    return edited;
  };
  const std::string no_geometry = "which is no <geometry> or <controller> of the file";
  for (const std::string& dangling :
       {with("<instance_geometry url=\"#nothere\"/>"),
        with(instance + "<instance_geometry url=\"#nothere\"/>"),
        with(instance + "<instance_geometry name=\"a>b\" url=\"#nothere\"/>")}) {
    ExpectBadLinkMesh(dir, "dangling.dae", dangling,
                      {"COLLADA <instance_geometry> on line " + line, "names '#nothere', " +
                       no_geometry});
  }
  ExpectBadLinkMesh(dir, "node_id.dae", with(instance + "<instance_geometry url=\"#n\"/>"),
                    {"names '#n', " + no_geometry});
  ExpectBadLinkMesh(dir, "external.dae", with("<instance_node url=\"parts.dae#arm\"/>"),
                    {"COLLADA <instance_node>", "names 'parts.dae#arm', which is no <node>"});
  ExpectBadLinkMesh(dir, "unplaced.dae", with(""), {"places no mesh in its scene"});
  // The file as written loads (the edits above are what fails), and so do the forms of a good
  // reference: spaced around '=' in either quote, a character reference (&#103; is 'g'), a
  // node's name (assimp's fallback), and dangling references assimp never reads (in a comment,
  // in an <extra> block).
  ExpectLShapeLoads(dir, "placed.dae", dae);
  std::string spaced = with(
      "<!-- <instance_geometry url=\"#old\"/> --><instance_geometry url = '#&#103;'/>"
      "<extra><technique profile=\"x\"><instance_geometry url=\"#gone\"/></technique></extra>");
  const std::string geometry = "<geometry id=\"g\">";
  spaced.replace(spaced.find(geometry), geometry.size(), "<geometry\n id =\"g\">");
  ExpectLShapeLoads(dir, "spaced.dae", spaced);
  std::string by_name = dae;
  by_name.replace(by_name.find("<node id=\"n\">"), 13, "<node id=\"n\" name=\"Body\">");
  by_name.replace(by_name.find("</node>"), 7,
                  "</node><node id=\"n2\"><instance_node url=\"#Body\"/></node>");
  ExpectLShapeLoads(dir, "by_name.dae", by_name);
}

// A binary STL whose header names COLLADA is no COLLADA: its bytes are not read as XML, though a
// coordinate of 0.15667814 is the bytes "<p >" (helper-69: refused as a bad index list before).
TEST(SceneMeshRefusals, ABinaryStlNamingColladaIsReadAsAnStl) {
  const std::string dir = FreshDir("stl_named_collada");
  const TriangleMesh box = BoxMesh(Eigen::Vector3d(2.0 * 0.15667814, 0.1, 0.1));
  std::string stl = BinaryStl(box);
  stl.replace(0, 24, "exported through COLLADA");
  ASSERT_NE(stl.find("<p >"), std::string::npos);
  WriteBytes(dir + "box.stl", stl);
  const Files files = WriteRobot(dir, {MeshCollision("box.stl")});
  ExpectEncloses(LoadWorkcell(files.urdf, files.scene, CacheIn(dir)), "link0", box,
                 Eigen::Isometry3d::Identity());
}

// assimp 5.2 appends index 0 until memory runs out when a COLLADA <p> holds a non-number: the
// reader refuses it first, naming the element and its line (fuzzer finding), whatever the
// file's extension; a valid file with spaces, signs and attributes in <p> still loads.
TEST(SceneMeshRefusals, ColladaIndexListWithANonNumberIsRejected) {
  const std::string dir = FreshDir("bad_dae");
  const std::string dae = Dae(LShapeMesh(0.1, 0.05));
  const std::size_t p = dae.find("<p>");
  ASSERT_NE(p, std::string::npos);
  const auto line = std::to_string(1 + std::count(dae.begin(), dae.begin() + p, '\n'));
  for (const std::string& name : std::vector<std::string>{"letter.dae", "letter.xml"}) {
    std::string bad = dae;
    bad.insert(p + 3, "0 x ");
    ExpectBadLinkMesh(dir, name, bad,
                      {"COLLADA <p> element on line " + line, "character code 120"});
  }
  std::string entity = dae;
  entity.insert(p + 3, "&#48; ");
  ExpectBadLinkMesh(dir, "entity.dae", entity, {"<p> element", "character code 38"});
  std::string spaced = dae;
  spaced.replace(p, 3, "<p  class=\"x\">\t+");
  ExpectLShapeLoads(dir, "spaced.dae", spaced);
}

TEST(SceneMeshRefusals, MeshesWithoutVolumeAreRejected) {
  const std::string dir = FreshDir("no_volume");
  const std::string one = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nf 1 2 3\n";
  const std::string flat = "v 0 0 0\nv 0.1 0 0\nv 0.1 0.1 0\nv 0 0.1 0\nf 1 2 3\nf 1 3 4\n";
  const std::string collinear = "v 0 0 0\nv 0.1 0.1 0.1\nv 0.2 0.2 0.2\nf 1 2 3\n";
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"one_triangle.obj", one}, {"flat.obj", flat}, {"collinear.obj", collinear}}) {
    ExpectBadLinkMesh(dir, name, text, {"no volume"});
  }
}

TEST(SceneMeshRefusals, AbsurdScalesAreRejected) {
  const std::string dir = FreshDir("scales");
  const std::string stl = BinaryStl(LShapeMesh(0.1, 0.05));
  for (const std::string& scale : std::vector<std::string>{"0 1 1", "1 0 1", "1 1 0"}) {
    ExpectBadLinkMesh(dir, "l.stl", stl, {"scale", "finite, non-zero numbers"}, scale);
  }
  ExpectBadLinkMesh(dir, "l.stl", stl, {"too large"}, "1e6 1e6 1e6");
  ExpectBadLinkMesh(dir, "l.stl", stl, {"too small"}, "1e-6 1e-6 1e-6");
}

TEST(SceneMeshRefusals, NanScaleIsRejected) {
  const std::string dir = FreshDir("nan_scale");
  WriteBytes(dir + "l.stl", BinaryStl(LShapeMesh(0.1, 0.05)));
  const Files files = WriteRobot(dir, {MeshCollision("l.stl", "", "nan 1 1")});
  // urdfdom drops a collision element it cannot parse (and says so on its console only).
  ExpectLoadError([&] { LoadWorkcell(files.urdf, files.scene, CacheIn(dir)); },
                  {files.urdf, "link 'link0'", "1 <collision>", "urdfdom read 0"});
}

TEST(SceneMeshRefusals, BadMeshObjectsAreRejectedNamingSceneObjectAndFile) {
  const std::string dir = FreshDir("bad_objects");
  WriteBytes(dir + "l.obj", Obj(LShapeMesh(0.1, 0.05)));
  WriteBytes(dir + "flat.obj", "v 0 0 0\nv 0.1 0 0\nv 0.1 0.1 0\nv 0 0.1 0\nf 1 2 3\nf 1 3 4\n");
  const std::string pose = ", pose: {xyz_m: [0, 0, 1]}}\n";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"{name: a, type: mesh" + pose, {"objects[0] 'a'", "a mesh needs mesh"}},
      {"{name: a, type: mesh, mesh: nowhere.obj" + pose,
       {"objects[0] 'a'", "mesh 'nowhere.obj'", "cannot open the file"}},
      {"{name: a, type: mesh, mesh: flat.obj" + pose, {"objects[0] 'a'", "flat.obj", "no volume"}},
      {"{name: a, type: mesh, mesh: l.obj, scale: [1, 0, 1]" + pose,
       {"objects[0] 'a'", "l.obj", "scale"}},
      {"{name: a, type: mesh, mesh: l.obj, scale: [1, .nan, 1]" + pose,
       {"objects[0] 'a'", "scale"}},
      {"{name: a, type: box, size_m: [1, 1, 1], mesh: l.obj" + pose,
       {"objects[0] 'a'", "mesh is not a key of a box"}},
      {"{name: a, type: mesh, mesh: package://nowhere/l.obj" + pose,
       {"objects[0] 'a'", "package://nowhere/l.obj", "give a file path"}},
  };
  for (const auto& [entry, parts] : cases) {
    const Files files = WriteRobot(dir, {}, "objects:\n  - " + entry);
    std::vector<std::string> all = parts;
    all.push_back(files.scene);
    ExpectLoadError([&] { LoadWorkcell(files.urdf, files.scene, CacheIn(dir)); }, all);
  }
}

}  // namespace
}  // namespace arm_collision_monitor
