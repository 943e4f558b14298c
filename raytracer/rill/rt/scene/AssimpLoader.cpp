// PLY and glTF 2.0 files (MeshFile.h), read by assimp (AssimpFile.h): the meshes of the
// node tree in order, each face triangulated by Rill (Triangulate.h: the same triangles and
// primitive ids as the same polygon in an OBJ file), every index and coordinate checked.
#include <assimp/scene.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include "rill/rt/scene/AssimpFile.h"
#include "rill/rt/scene/GltfMaterial.h"
#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/MeshFile.h"
#include "rill/rt/scene/NameList.h"
#include "rill/rt/scene/PlyCheck.h"
#include "rill/rt/scene/Triangulate.h"
#include "rill/rt/scene/VertexNormals.h"

namespace rt {

namespace {

namespace fs = std::filesystem;

struct Tri {
  glm::vec3 p[3];
  glm::vec3 n[3];
  glm::vec2 uv[3];
  int32_t vertex[3];  // over all meshes placed, for computed normals
  bool has_normals, has_uv;
  int mat;
};

struct Walk {
  Walk(const std::string& p, const ObjLoadOptions& o) : path(p), opt(o) {}
  const std::string& path;
  const ObjLoadOptions& opt;
  std::vector<Tri> tris;
  size_t points_lines = 0;  // faces of 1 or 2 vertices: no triangle
  size_t bad_polygons = 0;  // polygons that cannot be cut (fanned)
  std::string first_bad;    // the first of them, for the warning
  int32_t vertex_base = 0;  // the first vertex number of the next mesh placed
};

std::string mesh_name(const aiMesh& m, unsigned index) {
  return "mesh " + std::to_string(index) +
         (m.mName.length > 0 ? " ('" + clipped(m.mName.C_Str()) + "')" : std::string());
}

glm::vec3 vec(const aiVector3D& v) {
  return glm::vec3(v.x, v.y, v.z);
}

// The triangles of one mesh placed by `to_world` (the node's matrix; identity for a PLY
// file), appended to w.tris with material `mat`.
void add_mesh(Walk& w, const aiMesh& m, unsigned index, const aiMatrix4x4& to_world, int mat) {
  const std::string where = w.path + ": " + mesh_name(m, index);
  if (m.mNumVertices > 0 && m.mVertices == nullptr) throw SceneError(where + " has no positions");
  for (unsigned v = 0; v < m.mNumVertices; ++v) {
    const aiVector3D& p = m.mVertices[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw SceneError(where + ": vertex " + std::to_string(v) + " " + vec_str(vec(p)) +
                       ": positions must be finite numbers");
    if (m.mNormals != nullptr) {
      const aiVector3D& n = m.mNormals[v];
      if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z))
        throw SceneError(where + ": vertex " + std::to_string(v) + " normal " + vec_str(vec(n)) +
                         ": normals must be finite numbers");
    }
  }
  const bool identity = to_world.IsIdentity();
  // Normals by the inverse transpose; a mirroring matrix turns the winding, which glTF says
  // to undo (the front face stays the counter-clockwise one in the world).
  aiMatrix3x3 normal_matrix(to_world);
  const float det = normal_matrix.Determinant();
  const bool mirrored = det < 0.0f;
  // A node that scales by 0 flattens its mesh (triangles without area, never hit): its normals
  // have no inverse transpose, and the triangles get none.
  const bool invertible = std::isfinite(det) && det != 0.0f;
  if (invertible) normal_matrix.Inverse().Transpose();
  auto point = [&](unsigned i) {
    const aiVector3D p = identity ? m.mVertices[i] : to_world * m.mVertices[i];
    return w.opt.transform.apply_point(vec(p));
  };
  auto normal = [&](unsigned i) {
    const aiVector3D n = identity ? m.mNormals[i] : normal_matrix * m.mNormals[i];
    return w.opt.transform.apply_normal(vec(n));
  };
  const aiVector3D* uv = m.mTextureCoords[0];
  std::vector<glm::vec3> poly;
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices < 3) {
      ++w.points_lines;
      continue;
    }
    poly.clear();
    for (unsigned k = 0; k < face.mNumIndices; ++k) {
      const unsigned i = face.mIndices[k];
      if (i >= m.mNumVertices)
        throw SceneError(where + ": face " + std::to_string(f) + " refers to vertex " +
                         std::to_string(i) + ", but there are " + std::to_string(m.mNumVertices) +
                         " vertices (counting from 0)");
      poly.push_back(vec(m.mVertices[i]));
    }
    // In the file's own coordinates, as OBJ polygons are cut.
    const Triangulation cut = triangulate(poly);
    if (cut.shape != PolygonShape::Ok && w.bad_polygons++ == 0)
      w.first_bad = mesh_name(m, index) + " face " + std::to_string(f) + " (" +
                    std::to_string(face.mNumIndices) + " vertices)";
    if (w.tris.size() + cut.triangles.size() > kMaxTriangles)
      throw SceneError(w.path + ": more than " + grouped(kMaxTriangles) +
                       " triangles (the most a scene may hold)");
    for (const auto& t : cut.triangles) {
      Tri tri{};
      tri.mat = mat;
      tri.has_normals = m.mNormals != nullptr && invertible;
      tri.has_uv = uv != nullptr;
      for (int k = 0; k < 3; ++k) {
        const unsigned i = face.mIndices[t[mirrored && k > 0 ? 3 - k : k]];
        tri.p[k] = point(i);
        if (tri.has_normals) tri.n[k] = normal(i);
        if (tri.has_uv) tri.uv[k] = glm::vec2(uv[i].x, uv[i].y);
        tri.vertex[k] = w.vertex_base + static_cast<int32_t>(i);
      }
      w.tris.push_back(tri);
    }
  }
  w.vertex_base += static_cast<int32_t>(m.mNumVertices);
}

// The triangles into the scene: the file's normals, else (compute) normals computed as for an
// OBJ file without `vn`, keeping flat the triangles they leave flat (ObjLoader.cpp does the
// same, so that the same mesh renders with the same bits from either file).
void add_triangles(Scene& s, const std::vector<Tri>& tris, bool compute,
                   const ObjLoadOptions& opt) {
  std::vector<glm::vec3> computed;
  if (compute && !tris.empty()) {
    std::vector<glm::vec3> pos;
    std::vector<int32_t> ids;
    for (const Tri& t : tris)
      for (int k = 0; k < 3; ++k) {
        pos.push_back(t.p[k]);
        ids.push_back(t.vertex[k]);
      }
    computed = vertex_normals({pos, ids, {}}, opt.crease_degrees, opt.normal_weighting);
  }
  for (size_t i = 0; i < tris.size(); ++i) {
    const Tri& t = tris[i];
    glm::vec3 n[3] = {t.n[0], t.n[1], t.n[2]};
    bool normals = t.has_normals;
    if (!normals && !computed.empty()) normals = !keeps_flat(t.p, &computed[3 * i], n);
    s.add_triangle(t.p[0], t.p[1], t.p[2], t.mat, normals ? n : nullptr, nullptr,
                   t.has_uv ? t.uv : nullptr);
  }
}

// The warnings about faces that PLY and glTF loads share, one line each.
void warn_common(Scene& s, const Walk& w) {
  if (w.points_lines > 0)
    s.warnings.push_back(w.path + ": " + grouped(w.points_lines) +
                         " points and lines skipped (Rill renders triangles)");
  if (w.bad_polygons > 0)
    s.warnings.push_back(w.path + ": " + grouped(w.bad_polygons) +
                         " polygons that cannot be cut into triangles as drawn (crossing edges, "
                         "no area) are fanned from their first vertex; the first is " +
                         w.first_bad);
}

// assimp's log of the read: faces it dropped for out-of-range indices are an error (as an OBJ
// file's are), anything else a warning naming the file (the first 3, then a count).
void check_log(Scene& s, const AssimpFile& file, const std::string& path) {
  size_t shown = 0;
  for (const std::string& line : file.log()) {
    if (line.find("out-of-range indices") != std::string::npos)
      throw SceneError(path + ": faces refer to vertices that are not there (assimp: " +
                       clipped(line, 200) + ")");
    if (++shown <= 3) s.warnings.push_back(path + ": assimp: " + clipped(line, 200));
  }
  if (shown > 3)
    s.warnings.push_back(path + ": " + grouped(shown - 3) + " more warnings from assimp");
}

void check_not_empty(const Scene& s, const std::string& path, const ObjLoadOptions& opt) {
  if (s.triangle_count() == 0 && !opt.input.allow_empty)
    throw SceneError(path + ": no triangles in the file (--allow-empty loads it as no triangles)");
}

Material default_grey() {
  Material grey;
  grey.name = "default";
  return grey;
}

// How deeply a glTF file's JSON may nest objects and arrays (real files nest under 10):
// assimp's JSON parser recurses once per level, so a small file of brackets would overflow
// its stack.
constexpr int kMaxGltfJsonDepth = 256;

// The deepest nesting of objects and arrays in JSON text (strings skipped).
int json_depth(const std::string& t) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (size_t i = 0; i < t.size(); ++i) {
    const char c = t[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

// The glTF JSON of a .gltf file, or of a .glb's first chunk, checked before assimp reads the
// file: an object with an "asset" of version 2.x. assimp would otherwise try its other
// importers on a file its glTF reader refuses (a .gltf that is an MD5 or X file loads as one).
nlohmann::json gltf_json(const std::string& bytes, const std::string& path, bool binary) {
  auto fail = [&](const std::string& why) { throw SceneError(path + ": " + why); };
  std::string text = bytes;
  if (binary) {
    uint32_t header[5] = {0, 0, 0, 0, 0};  // magic, version, length, chunk length, chunk type
    if (bytes.size() < sizeof header || bytes.compare(0, 4, "glTF") != 0)
      fail("not a .glb file (it does not start with the magic \"glTF\")");
    std::memcpy(header, bytes.data(), sizeof header);  // little-endian, as x86 and ARM are
    if (header[1] != 2)
      fail("a .glb of version " + std::to_string(header[1]) + ": Rill reads glTF 2.0");
    if (bytes.compare(16, 4, "JSON") != 0 || header[3] > bytes.size() - sizeof header)
      fail("its first chunk is not a JSON chunk within the file: truncated, or not a .glb");
    text = bytes.substr(sizeof header, header[3]);
  }
  if (json_depth(text) > kMaxGltfJsonDepth)
    fail("JSON nested deeper than " + std::to_string(kMaxGltfJsonDepth) +
         " levels (objects and arrays): not a glTF file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    fail("not a glTF file: invalid JSON: " + clipped(e.what(), 200));
  }
  if (!j.is_object() || !j.contains("asset") || !j["asset"].is_object())
    fail("not a glTF file: no \"asset\" object");
  const nlohmann::json& version = j["asset"].contains("version") ? j["asset"]["version"] : j;
  if (!version.is_string() || version.get<std::string>().rfind("2.", 0) != 0)
    fail("glTF version " +
         (version.is_string() ? "'" + clipped(version.get<std::string>()) + "'"
                              : std::string("missing")) +
         ": Rill reads glTF 2.0");
  return j;
}

}  // namespace

Scene load_ply(const std::string& path, const ObjLoadOptions& opt) {
  // The structure first: assimp reads a PLY's counts and indices on trust (PlyCheck.h).
  const PlyLayout layout = check_ply(read_input_file(path, "a PLY file"), path);
  AssimpFile file(path, "PLY");
  const aiScene& as = file.scene();
  Scene s;
  check_log(s, file, path);
  s.name = fs::path(path).stem().string();
  const int mat = s.add_material(opt.override_material ? *opt.override_material : default_grey());
  Walk w(path, opt);
  // assimp's PLY reader gives one mesh at the root; a file without faces may give none.
  for (unsigned i = 0; i < as.mNumMeshes; ++i)
    if (as.mMeshes[i] != nullptr) add_mesh(w, *as.mMeshes[i], i, aiMatrix4x4(), mat);
  add_triangles(s, w.tris, !layout.normals && opt.smooth, opt);
  warn_common(s, w);
  if (layout.colors)
    s.warnings.push_back(path +
                         ": vertex colours ignored (Rill's PLY reading takes positions, "
                         "normals and faces)");
  check_not_empty(s, path, opt);
  return s;
}

Scene load_gltf(const std::string& path, const ObjLoadOptions& opt) {
  const std::string bytes = read_input_file(path, "a glTF file");
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool binary = ext == ".glb";
  const nlohmann::json j = gltf_json(bytes, path, binary);
  AssimpFile file(path, "glTF 2.0");
  const aiScene& as = file.scene();
  Scene s;
  check_log(s, file, path);
  s.name = fs::path(path).stem().string();
  std::vector<std::string> ignored;
  // What the file has that Rill does not map, counted from the JSON (assimp drops some).
  {
    for (const char* key : {"animations", "skins", "cameras"})
      if (j.contains(key) && j[key].is_array() && !j[key].empty())
        ignored.push_back(std::to_string(j[key].size()) + " " + key);
    if (j.contains("extensionsUsed") && j["extensionsUsed"].is_array())
      for (const auto& e : j["extensionsUsed"])
        // assimp decodes these two into plain geometry; Rill maps the emissive strength.
        if (e.is_string() && e != "KHR_draco_mesh_compression" && e != "KHR_mesh_quantization" &&
            e != "KHR_materials_emissive_strength")
          ignored.push_back("extension " + clipped(e.get<std::string>()));
  }
  // Materials as meshes use them (an unused one adds nothing to the scene).
  std::map<unsigned, int> material_of;
  int fallback = -1;
  auto material = [&](unsigned index) {
    if (opt.override_material != nullptr || index >= as.mNumMaterials ||
        as.mMaterials[index] == nullptr) {
      if (fallback < 0)
        fallback = s.add_material(opt.override_material ? *opt.override_material : default_grey());
      return fallback;
    }
    auto [it, added] = material_of.emplace(index, 0);
    if (added) it->second = add_gltf_material(s, as, *as.mMaterials[index], path, ignored);
    return it->second;
  };
  Walk w(path, opt);
  bool colours = false;
  // The node tree depth first, each node's meshes in order, with its matrix times its
  // parent's. An explicit stack: a file's tree may be deep.
  struct Visit {
    const aiNode* node;
    aiMatrix4x4 to_world;
  };
  std::vector<Visit> stack;
  if (as.mRootNode != nullptr) stack.push_back({as.mRootNode, as.mRootNode->mTransformation});
  while (!stack.empty()) {
    const Visit v = stack.back();
    stack.pop_back();
    for (unsigned k = 0; k < v.node->mNumMeshes; ++k) {
      const unsigned i = v.node->mMeshes[k];
      if (i >= as.mNumMeshes || as.mMeshes[i] == nullptr)
        throw SceneError(path + ": node '" + clipped(v.node->mName.C_Str()) + "' names mesh " +
                         std::to_string(i) + ", which is not there");
      const aiMesh& m = *as.mMeshes[i];
      colours = colours || m.mColors[0] != nullptr;
      add_mesh(w, m, i, v.to_world, material(m.mMaterialIndex));
    }
    // Children pushed last first, so that they are visited in order.
    for (unsigned c = v.node->mNumChildren; c-- > 0;)
      if (v.node->mChildren[c] != nullptr)
        stack.push_back({v.node->mChildren[c], v.to_world * v.node->mChildren[c]->mTransformation});
  }
  // glTF: a primitive without normals is flat shaded (the specification says so).
  add_triangles(s, w.tris, /*compute=*/false, opt);
  if (s.materials.empty()) material(as.mNumMaterials);
  warn_common(s, w);
  if (colours) ignored.push_back("vertex colours (COLOR_0)");
  if (!ignored.empty()) {
    std::sort(ignored.begin(), ignored.end());
    ignored.erase(std::unique(ignored.begin(), ignored.end()), ignored.end());
    std::string list;
    for (const std::string& x : ignored) list += (list.empty() ? "" : ", ") + x;
    s.warnings.push_back(path + ": ignored: " + list +
                         " (Rill reads meshes, node transforms and metallic-roughness "
                         "materials: docs/scene-format.md)");
  }
  check_not_empty(s, path, opt);
  return s;
}

}  // namespace rt
