// The OBJ + MTL loader (tinyobjloader): triangles in file order (polygons triangulated by
// Triangulate.h: convex ones fanned), vertex normals (the file's, else computed by
// VertexNormals.h), colours and texture coordinates where the file has them, materials from the MTL
// files it names, with their map_Kd PNGs as bitmap textures.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "rill/rt/scene/ClassicMaterial.h"
#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/NameList.h"
#include "rill/rt/scene/ObjSyntax.h"
#include "rill/rt/scene/Scene.h"
#include "rill/rt/scene/Triangulate.h"
#include "rill/rt/scene/VertexNormals.h"

namespace rt {

namespace {

namespace fs = std::filesystem;

// Turns the line checks' findings (ObjSyntax.h) into errors and warnings naming `file` and the
// line: a bad value is an error; a malformed line is one too under --strict-input, else the
// first few are warnings and the rest a count.
void report_lines(const std::string& file, const std::vector<LineIssue>& all,
                  const InputOptions& input, std::vector<std::string>& warnings) {
  std::vector<LineIssue> issues;
  for (const LineIssue& i : all)
    if (!i.rewrite_only()) issues.push_back(i);
  if (issues.empty()) return;
  auto at = [&](const LineIssue& i) { return file + ":" + std::to_string(i.line) + ": " + i.what; };
  for (const LineIssue& i : issues)
    if (i.value || input.strict)
      throw SceneError(at(i) + (i.value ? "" : " (an error under --strict-input)"));
  constexpr size_t kShown = 3;
  for (size_t k = 0; k < issues.size() && k < kShown; ++k)
    warnings.push_back(at(issues[k]) + "; the line is skipped");
  if (issues.size() > kShown)
    warnings.push_back(file + ": " + std::to_string(issues.size() - kShown) +
                       " more malformed lines skipped (" + std::to_string(issues.size()) +
                       " in all; --strict-input makes them errors)");
}

// The MTL files an OBJ names with `mtllib`: an absolute name as it is, a relative one from
// the OBJ's folder, however the OBJ's own path was spelled (tinyobjloader's reader joins the
// folder to absolute names too). Only regular files within the input limit (InputFile.h);
// a file that is not there is a warning, and the faces keep the default material. Their
// lines are checked like the OBJ's (report_lines).
class MtlReader : public tinyobj::MaterialReader {
 public:
  // `overridden`: every face gets the scene file's material (ObjLoadOptions::override_material),
  // so a missing MTL file changes no face, and its warning must not say that one turns grey.
  MtlReader(const std::string& obj_path, const InputOptions& input,
            std::vector<std::string>& warnings, bool overridden)
      : obj_(obj_path),
        dir_(fs::path(obj_path).parent_path()),
        input_(input),
        warnings_(warnings),
        overridden_(overridden) {}
  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* by_name, std::string* warn,
                  std::string* err) override {
    fs::path file(name);
    if (file.is_relative()) file = dir_ / file;
    std::error_code ec;
    if (!fs::exists(file, ec)) {
      warnings_.push_back(obj_ + ": mtllib " + clipped(file.string()) + ": no such file " +
                          (overridden_ ? "(its materials are missing, but no face uses them: the "
                                         "scene file gives this mesh its material)"
                                       : "(its materials are missing; faces that use them get "
                                         "the default grey)"));
      missing_ = true;
      return false;
    }
    if (fs::equivalent(file, obj_, ec))
      throw SceneError(obj_ + ": mtllib " + clipped(name) +
                       " names this OBJ file itself, not an MTL file");
    const std::string text = read_input_file(file.string(), "an MTL file");
    const MtlLines lines = check_mtl_lines(text);
    report_lines(file.string(), lines.issues, input_, warnings_);
    std::istringstream in(without_lines(text, lines.issues));
    tinyobj::LoadMtl(by_name, materials, &in, warn, err);
    return true;
  }
  bool missing() const { return missing_; }

 private:
  std::string obj_;
  fs::path dir_;
  InputOptions input_;
  std::vector<std::string>& warnings_;
  bool overridden_;
  bool missing_ = false;
};

// The first line of a parser's message, without trailing blanks.
std::string first_line(const std::string& s) {
  std::string t = s.substr(0, s.find('\n'));
  while (!t.empty() && (t.back() == '\r' || t.back() == ' ')) t.pop_back();
  return t;
}

// An MTL material as a classic one (ClassicMaterial.h): phong, or glass where d < 1.
Material from_mtl(const tinyobj::material_t& m) {
  ClassicMaterial r;
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
  Material out = r.material(m.name);
  // Ke: emitted radiance (an area light; docs/path-tracing.md). The MTL syntax check already
  // refused a negative or non-finite Ke.
  out.emission = glm::max(glm::vec3(m.emission[0], m.emission[1], m.emission[2]), glm::vec3(0.0f));
  return out;
}

// The line number (1-based) of the face-th face (0-based, over all shapes) that
// tinyobjloader keeps: its lines starting with "f" and at least 3 vertices, in file order.
// tinyobjloader reports only the last line of the file for a bad index, so an error that
// names a face's line scans the file again.
size_t face_line(const std::string& text, size_t face) {
  size_t line = 0, seen = 0, pos = 0;
  while (pos < text.size()) {
    // tinyobjloader's lines end at \n, \r\n or a lone \r.
    size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    ++line;
    std::istringstream words(text.substr(pos, end - pos));
    std::string word;
    size_t count = 0;
    bool is_face = false;
    while (words >> word) is_face = count++ == 0 ? word == "f" : is_face;
    if (is_face && count >= 4 && seen++ == face) return line;
    pos = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
  }
  return 0;
}

}  // namespace

Scene load_obj(const std::string& path, const ObjLoadOptions& opt) {
  const std::string text = read_input_file(path, "an OBJ file");
  Scene s;
  const ObjLines lines = check_obj_lines(text);
  report_lines(path, lines.issues, opt.input, s.warnings);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> mtls;
  std::string warn, err;
  MtlReader mtl_reader(path, opt.input, s.warnings, opt.override_material != nullptr);
  // What tinyobjloader reads: malformed lines emptied (line numbers kept). face_line scans
  // this text, so that it counts the faces tinyobjloader kept.
  const std::string parsed = without_lines(text, lines.issues);
  std::istringstream in(parsed);
  // triangulate = false: we triangulate polygons ourselves (Triangulate.h), fanning convex ones
  // as Rill always did; tinyobjloader's triangulation does not fan (docs/primitive-ids.md).
  bool ok = tinyobj::LoadObj(&attrib, &shapes, &mtls, &warn, &err, &in, &mtl_reader,
                             /*triangulate=*/false, /*default_vcols_fallback=*/false);
  if (!ok)
    throw SceneError(path + ": tinyobjloader cannot read it: " +
                     (err.empty() ? "no reason given" : clipped(first_line(err), 200)));
  // Files that give nothing to render: an error (a mistyped path, a file of another kind),
  // unless the user says an empty mesh is what they mean.
  if (!opt.input.allow_empty) {
    if (text.empty())
      throw SceneError(path + ": the file is empty (--allow-empty loads it as no triangles)");
    if (lines.faces == 0)
      throw SceneError(
          path + ": no faces in " + std::to_string(lines.lines) + " lines (" +
          std::to_string(lines.vertices) + " vertices, " +
          std::to_string(std::count_if(lines.issues.begin(), lines.issues.end(),
                                       [](const LineIssue& i) { return !i.rewrite_only(); })) +
          " malformed lines): is it an OBJ file? (--allow-empty loads it as no "
          "triangles)");
  }
  // usemtl names that no MTL file defines (unless an MTL file was missing, which has its own
  // warning): their faces get the default grey. The first 3 are named, the rest counted.
  if (opt.override_material == nullptr && !mtl_reader.missing()) {
    constexpr size_t kShown = 3;
    std::set<std::string> defined, reported;
    for (const tinyobj::material_t& m : mtls) defined.insert(m.name);
    for (const auto& [line, name] : lines.usemtl)
      if (!defined.count(name) && reported.insert(name).second && reported.size() <= kShown)
        s.warnings.push_back(
            path + ":" + std::to_string(line) + ": usemtl '" + clipped(name) +
            "': no material of that name in " +
            (mtls.empty() ? "any MTL file (the OBJ loads none)" : "its MTL files") +
            "; its faces get the default grey");
    if (reported.size() > kShown)
      s.warnings.push_back(path + ": " + grouped(reported.size() - kShown) +
                           " more usemtl names with no material (" + grouped(reported.size()) +
                           " in all); their faces get the default grey too");
  }
  const fs::path dir = fs::path(path).parent_path();  // relative names start here

  s.name = fs::path(path).stem().string();
  const size_t nv = attrib.vertices.size() / 3;
  const size_t nn = attrib.normals.size() / 3;
  const size_t nt = attrib.texcoords.size() / 2;
  const bool has_colors = attrib.colors.size() == attrib.vertices.size() && !attrib.colors.empty();

  std::vector<int> mat_index(mtls.size());
  int fallback = -1;
  if (opt.override_material != nullptr) {
    fallback = s.add_material(*opt.override_material);
  } else {
    // map_Kd and map_Ke: the PNG (relative to the OBJ's directory, where the MTL files are
    // read from) becomes a bitmap texture, loaded once however many materials name it. map_Kd
    // is bound to the diffuse colour (in place of Kd); map_Ke is the emission texture, scaled by
    // Ke where Ke is given (else by 1).
    std::map<std::string, int> texture_of_file;
    auto texture = [&](const std::string& map, const char* key, const Material& m) {
      fs::path file(map);
      if (file.is_relative()) file = dir / file;
      auto [it, added] = texture_of_file.emplace(file.string(), 0);
      if (added) {
        try {
          s.textures.push_back(load_png_texture(file.string()));
        } catch (const SceneError& e) {
          throw SceneError(path + ": material '" + clipped(m.name) + "': " + key + " " + e.what());
        }
        s.textures.back().name = map;
        it->second = static_cast<int>(s.textures.size()) - 1;
      }
      return it->second;
    };
    for (size_t i = 0; i < mtls.size(); ++i) {
      Material m = from_mtl(mtls[i]);
      if (const std::string& map = mtls[i].diffuse_texname; !map.empty())
        m.params["diffuse"] = ParamValue::of_texture(texture(map, "map_Kd", m));
      if (const std::string& map = mtls[i].emissive_texname; !map.empty()) {
        m.emission_texture = texture(map, "map_Ke", m);
        if (!m.emits()) m.emission = glm::vec3(1.0f);
      }
      mat_index[i] = s.add_material(m);
    }
  }
  auto default_mat = [&] {
    if (fallback < 0) {
      Material grey;
      grey.name = "default";
      fallback = s.add_material(grey);
    }
    return fallback;
  };

  size_t faces_before = 0;  // faces of the earlier shapes, for face_line
  auto vertex = [&](const tinyobj::index_t& ix, size_t face, const std::string& shape) {
    // tinyobjloader does not check vt indices: a positive one past the end stays as it is,
    // a relative one before the first becomes < -1 (-1 is "none").
    if (ix.texcoord_index < -1 ||
        (ix.texcoord_index >= 0 && static_cast<size_t>(ix.texcoord_index) >= nt)) {
      const long long written = ix.texcoord_index >= 0 ? ix.texcoord_index + 1LL
                                                       : static_cast<long long>(ix.texcoord_index) -
                                                             static_cast<long long>(nt);
      throw SceneError(path + ":" + std::to_string(face_line(parsed, faces_before + face)) +
                       ": vt index " + std::to_string(written) + " out of range (the file has " +
                       std::to_string(nt) + ")");
    }
    // file:line of the face, and which shape's face it is (tinyobjloader's shapes may be
    // unnamed).
    auto where = [&] {
      return path + ":" + std::to_string(face_line(parsed, faces_before + face)) + ": " +
             (shape.empty()
                  ? "face " + std::to_string(face + 1) + " of an unnamed shape"
                  : "face " + std::to_string(face + 1) + " of shape '" + clipped(shape) + "'");
    };
    if (ix.vertex_index < 0 || static_cast<size_t>(ix.vertex_index) >= nv)
      throw SceneError(where() + " refers to vertex " + std::to_string(ix.vertex_index + 1) +
                       ", but the file has " + std::to_string(nv) + " vertices");
    if (ix.normal_index >= 0 && static_cast<size_t>(ix.normal_index) >= nn)
      throw SceneError(where() + " refers to normal " + std::to_string(ix.normal_index + 1) +
                       ", but the file has " + std::to_string(nn) + " normals");
    if (ix.normal_index < -1) throw SceneError(where() + " has an invalid normal index");
  };

  // Triangles first (each polygon triangulated, Triangulate.h), then vertex normals for a file
  // without `vn` (they need every triangle at a vertex), then the scene's triangles in order.
  struct Tri {
    tinyobj::index_t ix[3];
    int mat;
    uint32_t group;  // smoothing group
    size_t face;     // the face it comes from, counted over the file (for face_line)
  };
  std::vector<Tri> tris;
  std::vector<std::string> bad_polygons;  // warnings, one per polygon
  size_t bad_polygon_count = 0;
  std::vector<glm::vec3> poly;
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
      const uint32_t group = f < mesh.smoothing_group_ids.size() ? mesh.smoothing_group_ids[f] : 0;
      poly.clear();
      for (size_t k = 0; k < fv; ++k) {
        const int vi = mesh.indices[offset + k].vertex_index;
        poly.emplace_back(attrib.vertices[3 * vi], attrib.vertices[3 * vi + 1],
                          attrib.vertices[3 * vi + 2]);
      }
      // In the file's own coordinates: the transform cannot make a polygon convex or not.
      const Triangulation cut = fv >= 3 ? triangulate(poly) : Triangulation{};
      if (cut.shape != PolygonShape::Ok && ++bad_polygon_count <= 3) {
        const char* why = cut.shape == PolygonShape::SelfIntersecting ? "its edges cross"
                          : cut.shape == PolygonShape::TooLarge
                              ? "it is concave with more than 4096 vertices"
                              : "it has no area (or no ear left to cut)";
        bad_polygons.push_back(path + ":" + std::to_string(face_line(parsed, faces_before + f)) +
                               ": a polygon of " + std::to_string(fv) + " vertices that " +
                               "cannot be cut into triangles as drawn (" + why +
                               "); it is fanned from its first vertex");
      }
      for (const auto& t : cut.triangles)
        tris.push_back(Tri{
            {mesh.indices[offset + t[0]], mesh.indices[offset + t[1]], mesh.indices[offset + t[2]]},
            mat,
            group,
            faces_before + f});
      offset += fv;
    }
    faces_before += mesh.num_face_vertices.size();
  }
  for (std::string& w : bad_polygons) s.warnings.push_back(std::move(w));
  if (bad_polygon_count > 3)
    s.warnings.push_back(path + ": " + grouped(bad_polygon_count - 3) +
                         " more polygons fanned because they cannot be cut (" +
                         grouped(bad_polygon_count) + " in all)");

  auto pos = [&](const tinyobj::index_t& ix) {
    const int vi = ix.vertex_index;
    glm::vec3 p(attrib.vertices[3 * vi], attrib.vertices[3 * vi + 1], attrib.vertices[3 * vi + 2]);
    return opt.transform.apply_point(p);
  };
  auto has_normals = [](const Tri& t) {
    return t.ix[0].normal_index >= 0 && t.ix[1].normal_index >= 0 && t.ix[2].normal_index >= 0;
  };
  // Computed normals (VertexNormals.h), in world space, for the triangles whose face gives no
  // `vn` (all of a file without any), smoothing on. Faces with `vn` share in them too: a
  // face's normal is geometry whatever the file says at its corners.
  std::vector<glm::vec3> computed;
  if (opt.smooth && !std::all_of(tris.begin(), tris.end(), has_normals)) {
    std::vector<glm::vec3> corner_pos;
    std::vector<int32_t> corner_vertex;
    std::vector<uint32_t> groups;
    corner_pos.reserve(3 * tris.size());
    corner_vertex.reserve(3 * tris.size());
    for (const Tri& t : tris) {
      for (const tinyobj::index_t& ix : t.ix) {
        corner_pos.push_back(pos(ix));
        corner_vertex.push_back(ix.vertex_index);
      }
      // Without any `s` line every face is in one group; with them, `s off` (0) is flat.
      groups.push_back(lines.smoothing_groups ? t.group : 1u);
    }
    computed = vertex_normals({corner_pos, corner_vertex, groups}, opt.crease_degrees,
                              opt.normal_weighting);
  }

  for (size_t i = 0; i < tris.size(); ++i) {
    const Tri& tri = tris[i];
    bool all_normals = true, all_uv = true;
    for (const tinyobj::index_t& ix : tri.ix) {
      all_normals = all_normals && ix.normal_index >= 0;
      all_uv = all_uv && ix.texcoord_index >= 0;
    }
    glm::vec3 p[3], n[3], c[3];
    glm::vec2 t[3];
    for (int k = 0; k < 3; ++k) {
      const tinyobj::index_t& ix = tri.ix[k];
      p[k] = pos(ix);
      if (all_normals)
        n[k] = opt.transform.apply_normal(glm::vec3(attrib.normals[3 * ix.normal_index],
                                                    attrib.normals[3 * ix.normal_index + 1],
                                                    attrib.normals[3 * ix.normal_index + 2]));
      if (has_colors)
        c[k] = glm::vec3(attrib.colors[3 * ix.vertex_index], attrib.colors[3 * ix.vertex_index + 1],
                         attrib.colors[3 * ix.vertex_index + 2]);
      if (all_uv)
        t[k] = glm::vec2(attrib.texcoords[2 * ix.texcoord_index],
                         attrib.texcoords[2 * ix.texcoord_index + 1]);
    }
    if (!computed.empty() && !all_normals) all_normals = !keeps_flat(p, &computed[3 * i], n);
    s.add_triangle(p[0], p[1], p[2], tri.mat, all_normals ? n : nullptr, has_colors ? c : nullptr,
                   all_uv ? t : nullptr);
    if (opt.corners != nullptr)
      for (const tinyobj::index_t& ix : tri.ix) opt.corners->push_back(ix.vertex_index);
  }
  if (s.materials.empty()) default_mat();
  // A face without `vt` on a material that reads texture coordinates shows the texture at
  // (0, 0), one flat colour (docs/scene-format.md): a warning per material, naming the first
  // such face's line and counting the faces.
  const Material* const shared = opt.override_material;
  const std::vector<Texture>* textures = shared != nullptr ? opt.override_textures : &s.textures;
  auto uv_texture = [&](const Material& m) -> const Texture* {
    if (textures == nullptr) return nullptr;
    auto read = [&](int i) {
      return i >= 0 && static_cast<size_t>(i) < textures->size() &&
             reads_texture_coordinates((*textures)[static_cast<size_t>(i)]);
    };
    for (const auto& [param, value] : m.params)
      if (value.kind == ParamValue::Kind::Texture && read(value.texture))
        return &(*textures)[static_cast<size_t>(value.texture)];
    return read(m.emission_texture) ? &(*textures)[static_cast<size_t>(m.emission_texture)]
                                    : nullptr;
  };
  struct Uvless {
    size_t first_face, faces = 0, last_face;
  };
  std::map<int, Uvless> uvless;  // by material
  for (const Tri& t : tris) {
    if (t.ix[0].texcoord_index >= 0 && t.ix[1].texcoord_index >= 0 && t.ix[2].texcoord_index >= 0)
      continue;
    auto [it, first] = uvless.try_emplace(t.mat, Uvless{t.face, 0, t.face});
    if (first || it->second.last_face != t.face) ++it->second.faces;
    it->second.last_face = t.face;
  }
  for (const auto& [mat, u] : uvless) {
    const Material& m = shared != nullptr ? *shared : s.materials[static_cast<size_t>(mat)];
    const Texture* tex = uv_texture(m);
    if (tex == nullptr) continue;
    s.warnings.push_back(path + ":" + std::to_string(face_line(parsed, u.first_face)) + ": " +
                         grouped(u.faces) + (u.faces == 1 ? " face" : " faces") + " of material '" +
                         clipped(m.name) + "' give no texture coordinates " +
                         "(vt), so its texture '" + clipped(tex->name) +
                         "' shows one flat colour on them (its value at (0, 0))");
  }
  return s;
}

}  // namespace rt
