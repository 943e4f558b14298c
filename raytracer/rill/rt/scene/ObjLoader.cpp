// The OBJ + MTL loader (tinyobjloader): triangles in file order (polygons fanned), vertex
// normals and colours where the file has them, materials from the MTL files it names.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

// The first line of a parser's message, without trailing blanks.
std::string first_line(const std::string& s) {
  std::string t = s.substr(0, s.find('\n'));
  while (!t.empty() && (t.back() == '\r' || t.back() == ' ')) t.pop_back();
  return t;
}

Material from_mtl(const tinyobj::material_t& m) {
  Material r;
  r.name = m.name;
  r.diffuse = glm::vec3(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
  r.specular = glm::vec3(m.specular[0], m.specular[1], m.specular[2]);
  r.shininess = std::clamp(m.shininess, 0.0f, 10000.0f);
  r.ior = (m.ior > 0.0f && m.ior <= 100.0f) ? m.ior : 1.5f;
  // illum 3, 5, 6 and 7 (the MTL models with ray-traced reflection): reflection of strength
  // max Ks. Transparency comes from d alone (transmit = 1 - d), whatever the model.
  const float ks = std::max({r.specular.x, r.specular.y, r.specular.z});
  if (m.illum == 3 || m.illum == 5 || m.illum == 6 || m.illum == 7)
    r.reflect = std::clamp(ks, 0.0f, 1.0f);
  float transmit = std::clamp(1.0f - m.dissolve, 0.0f, 1.0f);
  if (!(transmit >= 0.0f)) transmit = 0.0f;  // NaN
  r.transmit = transmit;
  if (r.reflect + r.transmit > 1.0f) r.reflect = 1.0f - r.transmit;
  if (!std::isfinite(r.reflect)) r.reflect = 0;
  return r;
}

}  // namespace

Scene load_obj(const std::string& path, const ObjLoadOptions& opt) {
  namespace fs = std::filesystem;
  {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw SceneError(path + ": no such file");
    if (fs::is_directory(path, ec)) throw SceneError(path + ": is a directory, not an OBJ file");
    std::ifstream probe(path);
    if (!probe) throw SceneError(path + ": cannot open for reading");
  }
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> mtls;
  std::string warn, err;
  std::string base = fs::path(path).parent_path().string();
  if (!base.empty()) base += "/";
  // triangulate = false: we fan polygons ourselves (tinyobjloader's triangulation does not).
  bool ok = tinyobj::LoadObj(&attrib, &shapes, &mtls, &warn, &err, path.c_str(), base.c_str(),
                             /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!ok) throw SceneError(path + ": " + (err.empty() ? "cannot parse" : first_line(err)));

  Scene s;
  s.name = fs::path(path).stem().string();
  const size_t nv = attrib.vertices.size() / 3;
  const size_t nn = attrib.normals.size() / 3;
  const bool has_colors = attrib.colors.size() == attrib.vertices.size() && !attrib.colors.empty();

  std::vector<int> mat_index(mtls.size());
  int fallback = -1;
  if (opt.override_material != nullptr) {
    fallback = s.add_material(*opt.override_material);
  } else {
    for (size_t i = 0; i < mtls.size(); ++i) mat_index[i] = s.add_material(from_mtl(mtls[i]));
  }
  auto default_mat = [&] {
    if (fallback < 0) {
      Material grey;
      grey.name = "default";
      fallback = s.add_material(grey);
    }
    return fallback;
  };

  auto vertex = [&](const tinyobj::index_t& ix, size_t face, const std::string& shape) {
    if (ix.vertex_index < 0 || static_cast<size_t>(ix.vertex_index) >= nv)
      throw SceneError(path + ": shape '" + shape + "' face " + std::to_string(face + 1) +
                       " refers to vertex " + std::to_string(ix.vertex_index + 1) +
                       ", but the file has " + std::to_string(nv) + " vertices");
    if (ix.normal_index >= 0 && static_cast<size_t>(ix.normal_index) >= nn)
      throw SceneError(path + ": shape '" + shape + "' face " + std::to_string(face + 1) +
                       " refers to normal " + std::to_string(ix.normal_index + 1) +
                       ", but the file has " + std::to_string(nn) + " normals");
    if (ix.normal_index < -1)
      throw SceneError(path + ": shape '" + shape + "' face " + std::to_string(face + 1) +
                       " has an invalid normal index");
  };

  for (const tinyobj::shape_t& sh : shapes) {
    size_t offset = 0;
    const auto& mesh = sh.mesh;
    for (size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
      const size_t fv = mesh.num_face_vertices[f];
      if (offset + fv > mesh.indices.size()) throw SceneError(path + ": truncated face list");
      for (size_t k = 0; k < fv; ++k) vertex(mesh.indices[offset + k], f, sh.name);
      int mat;
      if (opt.override_material != nullptr) {
        mat = fallback;
      } else {
        int id = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
        mat = (id >= 0 && static_cast<size_t>(id) < mtls.size())
                  ? mat_index[static_cast<size_t>(id)]
                  : default_mat();
      }
      auto pos = [&](size_t k) {
        int vi = mesh.indices[offset + k].vertex_index;
        glm::vec3 p(attrib.vertices[3 * vi], attrib.vertices[3 * vi + 1],
                    attrib.vertices[3 * vi + 2]);
        return opt.transform.apply_point(p);
      };
      auto col = [&](size_t k) {
        int vi = mesh.indices[offset + k].vertex_index;
        return glm::vec3(attrib.colors[3 * vi], attrib.colors[3 * vi + 1],
                         attrib.colors[3 * vi + 2]);
      };
      bool all_normals = true;
      for (size_t k = 0; k < fv; ++k)
        all_normals = all_normals && mesh.indices[offset + k].normal_index >= 0;
      auto nrm = [&](size_t k) {
        int ni = mesh.indices[offset + k].normal_index;
        glm::vec3 n(attrib.normals[3 * ni], attrib.normals[3 * ni + 1], attrib.normals[3 * ni + 2]);
        return opt.transform.apply_normal(n);
      };
      // Fan: (v0, vk, vk+1).
      for (size_t k = 1; k + 1 < fv; ++k) {
        glm::vec3 n[3], c[3];
        if (all_normals) {
          n[0] = nrm(0);
          n[1] = nrm(k);
          n[2] = nrm(k + 1);
        }
        if (has_colors) {
          c[0] = col(0);
          c[1] = col(k);
          c[2] = col(k + 1);
        }
        s.add_triangle(pos(0), pos(k), pos(k + 1), mat, all_normals ? n : nullptr,
                       has_colors ? c : nullptr);
      }
      offset += fv;
    }
  }
  if (s.materials.empty()) default_mat();
  return s;
}

}  // namespace rt
