#include "mesh_file.h"

#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "arm_collision_monitor/core/load_error.h"

namespace arm_collision_monitor {
namespace {

// The extension of `name` in lower case ("" if none), assimp's format hint.
std::string ExtensionHint(const std::string& name) {
  const std::size_t dot = name.find_last_of('.');
  const std::size_t slash = name.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string hint = name.substr(dot + 1);
  std::transform(hint.begin(), hint.end(), hint.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return hint;
}

// assimp calls bytes read from memory "$$$___magic___$$$.<hint>" in its messages: the file
// name of `url` instead.
std::string NameInMessage(std::string message, const std::string& url) {
  const std::string name = url.substr(url.find_last_of('/') + 1);
  const std::string magic = AI_MEMORYIO_MAGIC_FILENAME;
  for (std::size_t at = message.find(magic); at != std::string::npos;
       at = message.find(magic, at + name.size())) {
    std::size_t end = at + magic.size();
    if (end < message.size() && message[end] == '.') ++end;
    while (end < message.size() && std::isalnum(static_cast<unsigned char>(message[end]))) ++end;
    message.replace(at, end - at, name);
  }
  return message;
}

Eigen::Affine3d ToEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d matrix;
  matrix << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2,
      m.d3, m.d4;
  return Eigen::Affine3d(matrix);
}

// The root node's transformation without its rotation (see ReadMeshFileBytes).
Eigen::Affine3d RootWithoutRotation(const aiMatrix4x4& root) {
  aiVector3D scaling, position;
  aiQuaternion rotation;
  root.Decompose(scaling, rotation, position);
  Eigen::Affine3d X = Eigen::Affine3d::Identity();
  X.translation() = Eigen::Vector3d(position.x, position.y, position.z);
  X.linear() = Eigen::Vector3d(scaling.x, scaling.y, scaling.z).asDiagonal();
  return X;
}

// Appends the triangles of `node` and its children, each vertex through the node's transform.
void AppendNode(const aiScene& scene, const aiNode& node, const Eigen::Affine3d& X_MN,
                TriangleMesh* mesh) {
  for (unsigned int j = 0; j < node.mNumMeshes; ++j) {
    const aiMesh& part = *scene.mMeshes[node.mMeshes[j]];
    const auto offset = static_cast<std::uint32_t>(mesh->vertices_L.size());
    for (unsigned int i = 0; i < part.mNumVertices; ++i) {
      const aiVector3D& v = part.mVertices[i];
      mesh->vertices_L.push_back(X_MN * Eigen::Vector3d(v.x, v.y, v.z));
    }
    for (unsigned int f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines bound nothing
      mesh->triangles.push_back(
          {offset + face.mIndices[0], offset + face.mIndices[1], offset + face.mIndices[2]});
    }
  }
  for (unsigned int c = 0; c < node.mNumChildren; ++c) {
    AppendNode(scene, *node.mChildren[c], X_MN * ToEigen(node.mChildren[c]->mTransformation), mesh);
  }
}

// Merges vertices at identical positions and drops the unreferenced ones.
void MergeIdenticalVertices(TriangleMesh* mesh) {
  const std::vector<Eigen::Vector3d>& v = mesh->vertices_L;
  std::vector<std::uint32_t> order(v.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return std::tie(v[a].x(), v[a].y(), v[a].z()) < std::tie(v[b].x(), v[b].y(), v[b].z());
  });
  std::vector<std::uint32_t> new_index(v.size());
  std::vector<Eigen::Vector3d> merged;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || v[order[k]] != merged.back()) merged.push_back(v[order[k]]);
    new_index[order[k]] = static_cast<std::uint32_t>(merged.size() - 1);
  }
  std::vector<bool> is_used(merged.size(), false);
  for (auto& triangle : mesh->triangles) {
    for (std::uint32_t& index : triangle) {
      index = new_index[index];
      is_used[index] = true;
    }
  }
  std::vector<std::uint32_t> compact(merged.size());
  mesh->vertices_L.clear();
  for (std::size_t i = 0; i < merged.size(); ++i) {
    compact[i] = static_cast<std::uint32_t>(mesh->vertices_L.size());
    if (is_used[i]) mesh->vertices_L.push_back(merged[i]);
  }
  for (auto& triangle : mesh->triangles) {
    for (std::uint32_t& index : triangle) index = compact[index];
  }
}

// True iff `text` contains `word` (lower case) in any case.
bool ContainsCaseless(const std::string& text, const std::string& word) {
  return std::search(text.begin(), text.end(), word.begin(), word.end(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) == b;
         }) != text.end();
}

// Refuses a COLLADA file whose <p> (index list) holds anything but integers: assimp 5.2's
// COLLADA parser reads <p> with strtol10 and stops only at the end of the text, so a character
// that is neither a digit, a sign nor a space stops it from advancing, and it appends index 0
// until memory runs out (minimal input: test/fuzz/corpus/scene_mesh_file/oom_dae_letter_in_p).
// Checked on the raw text, before XML decoding: an entity, comment or CDATA section inside <p>
// is refused too (no exporter writes one), so every <p> that reaches assimp is safe.
void CheckColladaIndexLists(const std::string& bytes) {
  for (std::size_t at = bytes.find("<p"); at != std::string::npos; at = bytes.find("<p", at + 2)) {
    const std::size_t tag_end = bytes.find('>', at);
    if (tag_end == std::string::npos) return;  // not a tag: assimp's XML parser refuses it
    const char after = at + 2 < bytes.size() ? bytes[at + 2] : '\0';
    if (after != '>' && after != '/' && !std::isspace(static_cast<unsigned char>(after))) continue;
    if (bytes[tag_end - 1] == '/') continue;  // <p/>: empty
    const std::size_t close = bytes.find("</p", tag_end);
    const std::size_t end = close == std::string::npos ? bytes.size() : close;
    for (std::size_t i = tag_end + 1; i < end; ++i) {
      const char c = bytes[i];
      if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == ' ' ||
          c == '\t' || c == '\r' || c == '\n') {
        continue;
      }
      const auto line = 1 + std::count(bytes.begin(), bytes.begin() + i, '\n');
      throw LoadError("COLLADA <p> element on line " + std::to_string(line) +
                      ": character code " + std::to_string(static_cast<unsigned char>(c)) +
                      " in its index list (expected only integers separated by spaces)");
    }
  }
}

// `text` with the spans from each `open` to its `close` blanked (newlines kept, so that lines
// still count); an unclosed span runs to the end.
void Blank(const std::string& open, const std::string& close, std::string* text) {
  for (std::size_t at = text->find(open); at != std::string::npos; at = text->find(open, at)) {
    const std::size_t found = text->find(close, at + open.size());
    const std::size_t end = found == std::string::npos ? text->size() : found + close.size();
    for (std::size_t k = at; k < end; ++k) (*text)[k] = (*text)[k] == '\n' ? '\n' : ' ';
    at = end;
  }
}

// An attribute value with XML's character references decoded (&#NN;, &#xHH; and the five
// named ones), as assimp's XML parser reads it; other text as it is.
std::string DecodeXmlText(const std::string& value) {
  static const std::map<std::string, char> kNamed = {
      {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
  std::string out;
  for (std::size_t i = 0; i < value.size(); ++i) {
    // A reference is short: the ';' within a few characters (a bounded search, on any input).
    const std::size_t near = value[i] == '&' ? value.substr(i, 12).find(';') : std::string::npos;
    const std::size_t semi = near == std::string::npos ? near : i + near;
    if (semi == std::string::npos) {
      out += value[i];
      continue;
    }
    const std::string ref = value.substr(i + 1, semi - i - 1);
    const auto named = kNamed.find(ref);
    const bool is_hex = ref.size() > 2 && ref[0] == '#' && (ref[1] == 'x' || ref[1] == 'X');
    const std::string digits = ref.size() > 1 && ref[0] == '#' ? ref.substr(is_hex ? 2 : 1) : "";
    char* rest = nullptr;
    const long code = digits.empty() ? -1 : std::strtol(digits.c_str(), &rest, is_hex ? 16 : 10);
    if (named != kNamed.end()) {
      out += named->second;
    } else if (code > 0 && code < 128 && rest != nullptr && *rest == '\0') {
      out += static_cast<char>(code);  // ids and urls are ASCII in every exporter seen
    } else {
      out += value.substr(i, semi - i + 1);
    }
    i = semi;
  }
  return out;
}

// One start tag of XML text: its name, its attributes (values decoded) and where it starts.
struct XmlTag {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::size_t at = 0;
};

// The start tags of `text` (comments and the like blanked), in order; a '>' in a quoted value
// does not end its tag. Scanning stops at a tag left open at the end.
std::vector<XmlTag> StartTags(const std::string& text) {
  std::vector<XmlTag> tags;
  const auto is_space = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
  for (std::size_t at = text.find('<'); at != std::string::npos; at = text.find('<', at + 1)) {
    std::size_t i = at + 1;
    XmlTag tag;
    tag.at = at;
    while (i < text.size() && !is_space(text[i]) && text[i] != '>' && text[i] != '/') {
      tag.name += text[i++];
    }
    if (tag.name.empty() || tag.name[0] == '!' || tag.name[0] == '?') continue;
    for (;;) {
      while (i < text.size() && is_space(text[i])) ++i;
      if (i >= text.size()) return tags;
      if (text[i] == '>' || text[i] == '/') break;
      std::string key;
      while (i < text.size() && !is_space(text[i]) && text[i] != '=' && text[i] != '>') {
        key += text[i++];
      }
      while (i < text.size() && is_space(text[i])) ++i;
      if (i >= text.size() || text[i] != '=') break;  // not XML: assimp's parser refuses it
      ++i;
      while (i < text.size() && is_space(text[i])) ++i;
      if (i >= text.size() || (text[i] != '"' && text[i] != '\'')) break;
      const std::size_t end = text.find(text[i], i + 1);
      if (end == std::string::npos) return tags;
      tag.attributes[key] = DecodeXmlText(text.substr(i + 1, end - i - 1));
      i = end + 1;
    }
    at = i - 1;
    tags.push_back(std::move(tag));
  }
  return tags;
}

// assimp leaves out, with only a log line, a COLLADA <instance_geometry> whose url names no
// <geometry> or <controller> of the file, and an <instance_node> whose url names no <node> (by
// id, or by name: assimp's fallback): the part is missing from the link, its contacts would be
// missed. Refused here, naming the element and its line. Read as assimp reads the file:
// comments, CDATA sections, processing instructions and <extra> blocks (which it skips) are
// blanked first.
void CheckColladaReferences(const std::string& bytes) {
  if (bytes.find("<instance_geometry") == std::string::npos &&
      bytes.find("<instance_node") == std::string::npos) {
    return;
  }
  std::string text = bytes;
  Blank("<!--", "-->", &text);
  Blank("<![CDATA[", "]]>", &text);
  Blank("<?", "?>", &text);
  Blank("<extra>", "</extra>", &text);
  Blank("<extra ", "</extra>", &text);
  const std::vector<XmlTag> tags = StartTags(text);
  std::set<std::string> geometries, nodes;
  for (const XmlTag& tag : tags) {
    const auto id = tag.attributes.find("id");
    if ((tag.name == "geometry" || tag.name == "controller") && id != tag.attributes.end()) {
      geometries.insert(id->second);
    }
    if (tag.name != "node") continue;
    for (const char* key : {"id", "name"}) {
      const auto value = tag.attributes.find(key);
      if (value != tag.attributes.end()) nodes.insert(value->second);
    }
  }
  for (const XmlTag& tag : tags) {
    const bool is_geometry = tag.name == "instance_geometry";
    if (!is_geometry && tag.name != "instance_node") continue;
    const auto url = tag.attributes.find("url");
    if (url == tag.attributes.end()) continue;
    const std::string& value = url->second;
    const std::set<std::string>& targets = is_geometry ? geometries : nodes;
    if (!value.empty() && value[0] == '#' && targets.count(value.substr(1)) != 0) continue;
    const auto line = 1 + std::count(text.begin(), text.begin() + tag.at, '\n');
    throw LoadError("COLLADA <" + tag.name + "> on line " + std::to_string(line) + " names '" +
                    value + "', which is no " +
                    (is_geometry ? "<geometry> or <controller>" : "<node>") +
                    " of the file (expected '#' and its id)");
  }
}

// Whether `bytes` is laid out as a binary STL: an 80-byte header, a triangle count n, then n
// triangles of 50 bytes. No XML text is (its count would be four characters).
bool IsBinaryStl(const std::string& bytes) {
  if (bytes.size() < 84) return false;
  std::uint32_t count = 0;
  for (int k = 3; k >= 0; --k) count = count << 8 | static_cast<unsigned char>(bytes[80 + k]);
  return bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count);
}

}  // namespace

TriangleMesh ReadMeshFileBytes(const std::string& bytes, const std::string& name,
                               const Eigen::Vector3d& scale) {
  if (bytes.empty()) throw LoadError("the file is empty (expected a mesh: STL, DAE, OBJ, ...)");
  Assimp::Importer importer;
  const std::string hint = ExtensionHint(name);
  // Whatever the extension, assimp takes a file that names COLLADA near its start for one; not
  // a binary STL whose header names it (its coordinates could read as a "<p >").
  if ((hint == "dae" || ContainsCaseless(bytes, "collada")) && !IsBinaryStl(bytes)) {
    CheckColladaIndexLists(bytes);
    CheckColladaReferences(bytes);
  }
  const aiScene* scene =
      importer.ReadFileFromMemory(bytes.data(), bytes.size(),
                                  aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                      aiProcess_SortByPType | aiProcess_ValidateDataStructure,
                                  hint.c_str());
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw LoadError("cannot read the mesh: " + NameInMessage(importer.GetErrorString(), name) +
                    " (expected a mesh file: STL, DAE, OBJ, ...)");
  }
  // assimp marks a scene incomplete when the file placed no mesh in it (a COLLADA
  // <instance_geometry> naming no geometry, a geometry never instanced), and some of its
  // readers then add a stand-in skeleton mesh: fitting that would give the link a speck.
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    throw LoadError("the file places no mesh in its scene (assimp reads it as incomplete: a "
                    "COLLADA <instance_geometry> naming no geometry, or a geometry no node "
                    "instances?); expected a surface of triangles or polygons");
  }
  TriangleMesh mesh;
  const Eigen::Affine3d X_scale(Eigen::Scaling(scale));
  AppendNode(*scene, *scene->mRootNode,
             X_scale * RootWithoutRotation(scene->mRootNode->mTransformation), &mesh);
  if (mesh.triangles.empty()) {
    throw LoadError("the mesh file holds no triangle (" + std::to_string(scene->mNumMeshes) +
                    " meshes; expected a surface of triangles or polygons)");
  }
  for (std::size_t i = 0; i < mesh.vertices_L.size(); ++i) {
    if (!mesh.vertices_L[i].allFinite()) {  // merging sorts positions: NaN has no order
      throw LoadError("vertex " + std::to_string(i) + " is not finite (after scale)");
    }
  }
  MergeIdenticalVertices(&mesh);
  return mesh;
}

}  // namespace arm_collision_monitor
