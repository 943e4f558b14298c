// Shapes (box, quad, sphere, Utah teapot) and the built-in scenes.
#include <cmath>
#include <cstdint>

#include "rill/rt/scene/ClassicMaterial.h"
#include "rill/rt/scene/Scene.h"
#include "rill/rt/scene/TeapotData.h"

namespace rt {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A small deterministic generator (the scenes must be the same on every machine).
struct Lcg {
  uint64_t s;
  explicit Lcg(uint64_t seed) : s(seed) {}
  double next() {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(s >> 11) / 9007199254740992.0;  // [0, 1)
  }
  float uniform(double lo, double hi) { return static_cast<float>(lo + (hi - lo) * next()); }
};

// A classic material (ClassicMaterial.h): phong, or glass where it transmits.
Material mat(const std::string& name, glm::vec3 kd, glm::vec3 ks = glm::vec3(0.0f),
             float ns = 32.0f, float reflect = 0.0f, float transmit = 0.0f, float ior = 1.5f) {
  return ClassicMaterial{kd, ks, ns, reflect, transmit, ior}.material(name);
}

double bernstein(int i, double t) {
  const double s = 1.0 - t;
  switch (i) {
    case 0:
      return s * s * s;
    case 1:
      return 3.0 * t * s * s;
    case 2:
      return 3.0 * t * t * s;
    default:
      return t * t * t;
  }
}
double bernstein_d(int i, double t) {
  const double s = 1.0 - t;
  switch (i) {
    case 0:
      return -3.0 * s * s;
    case 1:
      return 3.0 * s * s - 6.0 * t * s;
    case 2:
      return 6.0 * t * s - 3.0 * t * t;
    default:
      return 3.0 * t * t;
  }
}

// Teapot patch p at (u, v): position and normal, y up.
void teapot_eval(int p, double u, double v, glm::dvec3& pos, glm::dvec3& nrm) {
  glm::dvec3 P(0.0), Pu(0.0), Pv(0.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const float* c = teapot::kControl[p][i * 4 + j];
      glm::dvec3 q(c[0], c[2], -c[1]);  // z up -> y up
      P += q * (bernstein(i, u) * bernstein(j, v));
      Pu += q * (bernstein_d(i, u) * bernstein(j, v));
      Pv += q * (bernstein(i, u) * bernstein_d(j, v));
    }
  pos = P;
  nrm = glm::cross(Pu, Pv);
}

}  // namespace

void add_quad(Scene& s, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
              const glm::vec3& d, int m) {
  const glm::vec2 t1[3] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}};
  const glm::vec2 t2[3] = {{0.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  s.add_triangle(a, b, c, m, nullptr, nullptr, t1);
  s.add_triangle(a, c, d, m, nullptr, nullptr, t2);
}

void add_box(Scene& s, const glm::vec3& lo, const glm::vec3& hi, int m, const Transform& t,
             bool inward) {
  glm::vec3 v[8];
  for (int i = 0; i < 8; ++i)
    v[i] = t.apply_point(
        glm::vec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z));
  // Faces, counter-clockwise seen from outside.
  const int f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : f) {
    if (inward)
      add_quad(s, v[q[0]], v[q[3]], v[q[2]], v[q[1]], m);
    else
      add_quad(s, v[q[0]], v[q[1]], v[q[2]], v[q[3]], m);
  }
}

void add_sphere(Scene& s, const glm::vec3& center, float radius, int slices, int stacks, int m,
                bool smooth) {
  // u along the longitude (j / slices, 1 at the seam's second side), v = 1 at the north pole
  // (i = 0) down to 0 at the south; a pole vertex takes the middle of its triangle's span.
  auto tex = [&](int i, int j, int other_j) {
    double u = j;
    if (i == 0 || i == stacks) u = 0.5 * (j + other_j);
    return glm::vec2(static_cast<float>(u / slices), static_cast<float>(1.0 - double(i) / stacks));
  };
  auto point = [&](int i, int j, glm::vec3& n) {
    double th = kPi * i / stacks, ph = 2.0 * kPi * (j % slices) / slices;
    glm::dvec3 d(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph));
    if (i == 0) d = glm::dvec3(0, 1, 0);
    if (i == stacks) d = glm::dvec3(0, -1, 0);
    n = glm::vec3(d);
    return glm::vec3(glm::dvec3(center) + d * static_cast<double>(radius));
  };
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      glm::vec3 n00, n10, n11, n01;
      glm::vec3 p00 = point(i, j, n00), p10 = point(i + 1, j, n10), p11 = point(i + 1, j + 1, n11),
                p01 = point(i, j + 1, n01);
      if (i != 0) {
        glm::vec3 n[3] = {n00, n10, n01};
        glm::vec2 uv[3] = {tex(i, j, j + 1), tex(i + 1, j, j + 1), tex(i, j + 1, j)};
        s.add_triangle(p00, p10, p01, m, smooth ? n : nullptr, nullptr, uv);
      }
      if (i != stacks - 1) {
        glm::vec3 n[3] = {n01, n10, n11};
        glm::vec2 uv[3] = {tex(i, j + 1, j), tex(i + 1, j, j + 1), tex(i + 1, j + 1, j)};
        s.add_triangle(p01, p10, p11, m, smooth ? n : nullptr, nullptr, uv);
      }
    }
}

void add_teapot(Scene& s, int n, int m, const Transform& t, bool smooth) {
  for (int p = 0; p < teapot::kPatches; ++p) {
    std::vector<glm::vec3> pos((n + 1) * (n + 1)), nrm((n + 1) * (n + 1));
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
        glm::dvec3 P, N;
        teapot_eval(p, u, v, P, N);
        if (glm::length(N) < 1e-9) {  // a collapsed patch edge (lid top, bottom centre)
          glm::dvec3 P2;
          teapot_eval(p, u < 0.5 ? u + 1e-4 : u - 1e-4, v, P2, N);
          if (glm::length(N) < 1e-12) N = glm::dvec3(0, 1, 0);
        }
        // The patches' (u, v) orientation makes cross(Pu, Pv) point inwards: flip, and wind
        // the triangles to match (counter-clockwise seen from outside).
        pos[i * (n + 1) + j] = t.apply_point(glm::vec3(P));
        nrm[i * (n + 1) + j] = t.apply_normal(glm::vec3(-glm::normalize(N)));
      }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        int a = i * (n + 1) + j, b = (i + 1) * (n + 1) + j, c = (i + 1) * (n + 1) + j + 1,
            d = i * (n + 1) + j + 1;
        glm::vec3 n1[3] = {nrm[a], nrm[c], nrm[b]}, n2[3] = {nrm[a], nrm[d], nrm[c]};
        // The patch's (u, v) = (i / n, j / n).
        auto uv = [&](int di, int dj) {
          return glm::vec2(static_cast<float>(i + di) / static_cast<float>(n),
                           static_cast<float>(j + dj) / static_cast<float>(n));
        };
        glm::vec2 t1[3] = {uv(0, 0), uv(1, 1), uv(1, 0)}, t2[3] = {uv(0, 0), uv(0, 1), uv(1, 1)};
        s.add_triangle(pos[a], pos[c], pos[b], m, smooth ? n1 : nullptr, nullptr, t1);
        s.add_triangle(pos[a], pos[d], pos[c], m, smooth ? n2 : nullptr, nullptr, t2);
      }
  }
}

// ---- built-in scenes -----------------------------------------------------------------------

namespace {

// Thesis scene A: three boxes (36 triangles), two lights, no reflections.
Scene scene_a() {
  Scene s;
  s.name = "thesis-a";
  int red = s.add_material(mat("red", {0.8f, 0.15f, 0.1f}, glm::vec3(0.4f), 40.0f));
  int green = s.add_material(mat("green", {0.2f, 0.7f, 0.25f}, glm::vec3(0.3f), 20.0f));
  int blue = s.add_material(mat("blue", {0.15f, 0.3f, 0.85f}, glm::vec3(0.5f), 60.0f));
  add_box(s, {-2.2f, 0.0f, -0.8f}, {-0.6f, 1.6f, 0.8f}, red);
  Transform t;
  t.rotate_deg.y = 30.0f;
  t.translate = glm::vec3(0.4f, 0.0f, -0.6f);
  add_box(s, {-0.5f, 0.0f, -0.5f}, {0.5f, 2.6f, 0.5f}, green, t);
  t.rotate_deg.y = -20.0f;
  t.translate = glm::vec3(1.9f, 0.0f, 0.6f);
  add_box(s, {-0.6f, 0.0f, -0.6f}, {0.6f, 1.0f, 0.6f}, blue, t);
  s.camera = Camera{{1.0f, 3.5f, 7.5f}, {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  s.has_camera = true;
  s.lights = {Light{{-4.0f, 6.0f, 5.0f}, {0.8f, 0.8f, 0.8f}},
              Light{{5.0f, 4.0f, 3.0f}, {0.4f, 0.4f, 0.5f}}};
  s.background = {0.1f, 0.1f, 0.15f};
  s.width = s.height = 256;
  return s;
}

// Thesis scene B: 171 cubes distributed in a room (12 + 171 * 12 = 2064 triangles).
Scene scene_b() {
  Scene s;
  s.name = "thesis-b";
  int room = s.add_material(mat("room", {0.75f, 0.72f, 0.65f}, glm::vec3(0.0f), 1.0f, 0.15f));
  int cols[6];
  const glm::vec3 kd[6] = {{0.85f, 0.2f, 0.15f}, {0.2f, 0.7f, 0.3f}, {0.2f, 0.35f, 0.9f},
                           {0.9f, 0.8f, 0.2f},   {0.7f, 0.3f, 0.8f}, {0.9f, 0.9f, 0.9f}};
  for (int i = 0; i < 6; ++i)
    cols[i] = s.add_material(
        mat("cube" + std::to_string(i), kd[i], glm::vec3(0.4f), 30.0f, i == 5 ? 0.6f : 0.0f));
  add_box(s, {-10.0f, 0.0f, -10.0f}, {10.0f, 8.0f, 10.0f}, room, {}, true);
  Lcg r(2005);
  for (int i = 0; i < 171; ++i) {
    float size = r.uniform(0.3, 1.2);
    glm::vec3 c(r.uniform(-8.5, 8.5), 0.0f, r.uniform(-8.5, 8.5));
    c.y = r.next() < 0.5 ? size * 0.5f : r.uniform(0.8, 6.5);
    Transform t;
    t.rotate_deg = glm::vec3(r.uniform(0, 90), r.uniform(0, 90), 0.0f);
    if (c.y == size * 0.5f) t.rotate_deg = glm::vec3(0.0f, r.uniform(0, 90), 0.0f);
    t.translate = c;
    add_box(s, glm::vec3(-size * 0.5f), glm::vec3(size * 0.5f), cols[i % 6], t);
  }
  s.camera = Camera{{0.0f, 4.5f, 9.5f}, {0.0f, 2.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 60.0f};
  s.has_camera = true;
  s.lights = {Light{{0.0f, 7.5f, 0.0f}, {0.7f, 0.7f, 0.65f}},
              Light{{-6.0f, 5.0f, 6.0f}, {0.35f, 0.35f, 0.4f}}};
  s.width = s.height = 256;
  return s;
}

// Thesis scene C: a Utah teapot (21 x 21 per patch: 28224 triangles), two fine spheres
// (16128 each), 90 cubes (1080) and a floor (2): 61562 triangles.
Scene scene_c() {
  Scene s;
  s.name = "thesis-c";
  int floor = s.add_material(mat("floor", {0.6f, 0.6f, 0.6f}, glm::vec3(0.0f), 1.0f, 0.25f));
  int pot = s.add_material(mat("teapot", {0.8f, 0.25f, 0.15f}, glm::vec3(0.6f), 60.0f, 0.1f));
  int mirror = s.add_material(mat("mirror", {0.9f, 0.9f, 0.9f}, glm::vec3(0.8f), 200.0f, 0.8f));
  int matte = s.add_material(mat("matte", {0.25f, 0.45f, 0.85f}, glm::vec3(0.3f), 30.0f));
  int cube_mats[3] = {s.add_material(mat("yellow", {0.9f, 0.75f, 0.2f}, glm::vec3(0.2f), 20.0f)),
                      s.add_material(mat("green", {0.2f, 0.7f, 0.3f}, glm::vec3(0.2f), 20.0f)),
                      s.add_material(mat("purple", {0.6f, 0.3f, 0.75f}, glm::vec3(0.2f), 20.0f))};
  add_quad(s, {-12.0f, 0.0f, -12.0f}, {-12.0f, 0.0f, 12.0f}, {12.0f, 0.0f, 12.0f},
           {12.0f, 0.0f, -12.0f}, floor);
  Transform t;
  t.translate = glm::vec3(0.0f, 0.0f, 0.0f);
  t.rotate_deg.y = -30.0f;
  add_teapot(s, 21, pot, t);
  add_sphere(s, {-4.2f, 1.6f, -1.5f}, 1.6f, 128, 64, mirror);
  add_sphere(s, {4.0f, 1.3f, -2.5f}, 1.3f, 128, 64, matte);
  Lcg r(61562);
  for (int i = 0; i < 90; ++i) {
    float a = static_cast<float>(2.0 * kPi * i / 90.0);
    float rad = 7.0f + r.uniform(0.0, 3.5);
    float size = r.uniform(0.3, 0.8);
    Transform bt;
    bt.rotate_deg.y = r.uniform(0, 90);
    bt.translate = glm::vec3(rad * std::cos(a), size * 0.5f, rad * std::sin(a));
    add_box(s, glm::vec3(-size * 0.5f), glm::vec3(size * 0.5f), cube_mats[i % 3], bt);
  }
  s.camera = Camera{{0.0f, 5.0f, 11.0f}, {0.0f, 1.2f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f};
  s.has_camera = true;
  s.lights = {Light{{-5.0f, 9.0f, 6.0f}, {0.75f, 0.75f, 0.7f}},
              Light{{6.0f, 6.0f, 4.0f}, {0.35f, 0.35f, 0.4f}}};
  s.background = {0.35f, 0.45f, 0.6f};
  s.width = s.height = 256;
  return s;
}

// The Cornell box (the measured geometry, in metres), lit by a point light under the lamp.
Scene scene_cornell() {
  Scene s;
  s.name = "cornell";
  int white = s.add_material(mat("white", {0.75f, 0.75f, 0.75f}));
  int red = s.add_material(mat("red", {0.75f, 0.12f, 0.1f}));
  int green = s.add_material(mat("green", {0.15f, 0.6f, 0.12f}));
  auto v = [](float x, float y, float z) { return glm::vec3(x, y, z) * 0.001f; };
  add_quad(s, v(552.8f, 0, 0), v(0, 0, 0), v(0, 0, 559.2f), v(549.6f, 0, 559.2f), white);  // floor
  add_quad(s, v(556, 548.8f, 0), v(556, 548.8f, 559.2f), v(0, 548.8f, 559.2f), v(0, 548.8f, 0),
           white);  // ceiling
  add_quad(s, v(549.6f, 0, 559.2f), v(0, 0, 559.2f), v(0, 548.8f, 559.2f), v(556, 548.8f, 559.2f),
           white);                                                                         // back
  add_quad(s, v(0, 0, 559.2f), v(0, 0, 0), v(0, 548.8f, 0), v(0, 548.8f, 559.2f), green);  // right
  add_quad(s, v(552.8f, 0, 0), v(549.6f, 0, 559.2f), v(556, 548.8f, 559.2f), v(556, 548.8f, 0),
           red);  // left
  // Short block.
  const glm::vec3 sb[20] = {v(130, 165, 65), v(82, 165, 225),  v(240, 165, 272), v(290, 165, 114),
                            v(290, 0, 114),  v(290, 165, 114), v(240, 165, 272), v(240, 0, 272),
                            v(130, 0, 65),   v(130, 165, 65),  v(290, 165, 114), v(290, 0, 114),
                            v(82, 0, 225),   v(82, 165, 225),  v(130, 165, 65),  v(130, 0, 65),
                            v(240, 0, 272),  v(240, 165, 272), v(82, 165, 225),  v(82, 0, 225)};
  for (int q = 0; q < 5; ++q)
    add_quad(s, sb[4 * q], sb[4 * q + 1], sb[4 * q + 2], sb[4 * q + 3], white);
  // Tall block.
  const glm::vec3 tb[20] = {v(423, 330, 247), v(265, 330, 296), v(314, 330, 456), v(472, 330, 406),
                            v(423, 0, 247),   v(423, 330, 247), v(472, 330, 406), v(472, 0, 406),
                            v(472, 0, 406),   v(472, 330, 406), v(314, 330, 456), v(314, 0, 456),
                            v(314, 0, 456),   v(314, 330, 456), v(265, 330, 296), v(265, 0, 296),
                            v(265, 0, 296),   v(265, 330, 296), v(423, 330, 247), v(423, 0, 247)};
  for (int q = 0; q < 5; ++q)
    add_quad(s, tb[4 * q], tb[4 * q + 1], tb[4 * q + 2], tb[4 * q + 3], white);
  s.camera = Camera{v(278, 273, -800), v(278, 273, 0), {0.0f, 1.0f, 0.0f}, 39.3f};
  s.has_camera = true;
  s.lights = {Light{v(278, 540, 279.5f), {0.9f, 0.85f, 0.75f}}};
  s.background = glm::vec3(0.0f);
  s.options.ambient = 0.15f;
  s.width = s.height = 256;
  return s;
}

// The Cornell box for the path integrator: diffuse walls of the same colours, lit by the
// original data's 130 x 105 mm area light 1 mm below the ceiling (emission (17, 12, 4), facing
// down) instead of the point light.
Scene scene_cornell_path() {
  Scene s = scene_cornell();
  s.name = "cornell-path";
  for (Material& m : s.materials) {
    const glm::vec3 diffuse = m.params.at("diffuse").color;
    m.shader = "diffuse";
    m.params.clear();
    m.set("diffuse", diffuse);
  }
  Material light;
  light.name = "light";
  light.shader = "diffuse";
  light.set("diffuse", glm::vec3(0.78f));
  light.emission = glm::vec3(17.0f, 12.0f, 4.0f);
  const int l = s.add_material(light);
  auto v = [](float x, float y, float z) { return glm::vec3(x, y, z) * 0.001f; };
  add_quad(s, v(343, 547.8f, 227), v(343, 547.8f, 332), v(213, 547.8f, 332), v(213, 547.8f, 227),
           l);
  s.lights.clear();
  s.options.integrator = Integrator::Path;
  s.options.max_depth = 5;
  s.options.spp = 16;
  return s;
}

// Glass and mirrors: a glass sphere and a glass teapot in front of a mirror, on a
// checkerboard, with a mirror sphere.
Scene scene_glass() {
  Scene s;
  s.name = "glass";
  int light_tile =
      s.add_material(mat("tile-light", {0.85f, 0.85f, 0.8f}, glm::vec3(0.0f), 1.0f, 0.1f));
  int dark_tile =
      s.add_material(mat("tile-dark", {0.15f, 0.15f, 0.2f}, glm::vec3(0.0f), 1.0f, 0.1f));
  int glass =
      s.add_material(mat("glass", {0.9f, 0.95f, 1.0f}, glm::vec3(0.8f), 150.0f, 0.0f, 0.92f, 1.5f));
  int mirror = s.add_material(mat("mirror", {0.9f, 0.9f, 0.9f}, glm::vec3(0.9f), 300.0f, 0.9f));
  int frame = s.add_material(mat("frame", {0.5f, 0.3f, 0.15f}, glm::vec3(0.3f), 30.0f));
  int red = s.add_material(mat("red", {0.85f, 0.15f, 0.1f}, glm::vec3(0.5f), 50.0f));
  for (int i = -6; i < 6; ++i)
    for (int j = -6; j < 4; ++j) {
      float x = static_cast<float>(i), z = static_cast<float>(j);
      add_quad(s, {x, 0.0f, z}, {x, 0.0f, z + 1.0f}, {x + 1.0f, 0.0f, z + 1.0f},
               {x + 1.0f, 0.0f, z}, ((i + j) & 1) ? dark_tile : light_tile);
    }
  // A mirror on the back wall, in a frame.
  add_box(s, {-4.3f, 0.0f, -6.3f}, {4.3f, 4.3f, -6.0f}, frame);
  add_quad(s, {-4.0f, 0.3f, -5.99f}, {4.0f, 0.3f, -5.99f}, {4.0f, 4.0f, -5.99f},
           {-4.0f, 4.0f, -5.99f}, mirror);
  add_sphere(s, {-1.6f, 1.0f, 0.5f}, 1.0f, 48, 24, glass);
  add_sphere(s, {2.3f, 0.8f, -1.8f}, 0.8f, 48, 24, mirror);
  Transform t;
  t.scale = glm::vec3(0.45f);
  t.translate = glm::vec3(1.4f, 0.0f, 1.2f);
  t.rotate_deg.y = 20.0f;
  add_teapot(s, 6, glass, t);
  add_box(s, {-0.4f, 0.0f, -2.6f}, {0.4f, 1.6f, -1.8f}, red);
  s.camera = Camera{{0.0f, 2.6f, 7.5f}, {0.0f, 1.0f, -0.5f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  s.has_camera = true;
  s.lights = {Light{{-3.0f, 6.0f, 5.0f}, {0.8f, 0.8f, 0.75f}},
              Light{{4.0f, 5.0f, 2.0f}, {0.3f, 0.3f, 0.35f}}};
  s.background = {0.5f, 0.65f, 0.85f};
  s.options.max_depth = 6;
  s.width = s.height = 256;
  return s;
}

Texture procedural(const std::string& type, glm::vec3 c1, glm::vec3 c2, float scale) {
  Texture t;
  t.name = t.type = type;
  t.color1 = c1, t.color2 = c2, t.scale = scale;
  return t;
}

// A bitmap made in memory (no file needed): 64 x 64 diagonal stripes in two colours with a
// soft edge, so that bilinear filtering and the wrap mode show.
Texture stripes() {
  Texture t;
  t.name = "stripes";
  t.type = "bitmap";
  t.file = "(generated)";
  t.width = t.height = 64;
  t.texels.resize(64 * 64);
  const glm::vec3 a(0.9f, 0.75f, 0.2f), b(0.15f, 0.25f, 0.6f);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const int d = (x + y) % 16;  // the period along the diagonal: 16 texels
      const float w = d < 7 ? 0.0f : d == 7 ? 0.5f : d < 15 ? 1.0f : 0.5f;
      t.texels[static_cast<size_t>(y * 64 + x)] = a + (b - a) * w;
    }
  return t;
}

// Textures: a checker floor, a marble sphere, a wood box, a box with a bitmap made in memory,
// and a sphere with the mirror shader; 2 lights. 1946 triangles.
Scene scene_textured() {
  Scene s;
  s.name = "textured";
  auto textured = [&](const std::string& name, const Texture& t, glm::vec3 ks, float ns) {
    s.textures.push_back(t);
    Material m = mat(name, glm::vec3(0.8f), ks, ns);
    m.params["diffuse"] = ParamValue::of_texture(static_cast<int>(s.textures.size()) - 1);
    return s.add_material(m);
  };
  // The floor quad's uv spans [0, 1] over 12 units: scale 12 gives checks of one unit.
  int floor = textured("floor", procedural("checker", glm::vec3(0.85f), glm::vec3(0.15f), 12.0f),
                       glm::vec3(0.0f), 1.0f);
  int marble =
      textured("marble", procedural("marble", {0.92f, 0.9f, 0.85f}, {0.25f, 0.3f, 0.35f}, 1.5f),
               glm::vec3(0.5f), 80.0f);
  int wood = textured("wood", procedural("wood", {0.75f, 0.5f, 0.25f}, {0.45f, 0.25f, 0.1f}, 2.0f),
                      glm::vec3(0.2f), 20.0f);
  int striped = textured("striped", stripes(), glm::vec3(0.3f), 40.0f);
  Material chrome;
  chrome.name = "chrome";
  chrome.shader = "mirror";
  chrome.set("reflect", 0.85f);
  int mirror = s.add_material(chrome);

  add_quad(s, {-6.0f, 0.0f, 6.0f}, {6.0f, 0.0f, 6.0f}, {6.0f, 0.0f, -6.0f}, {-6.0f, 0.0f, -6.0f},
           floor);
  add_sphere(s, {-1.7f, 1.0f, 0.3f}, 1.0f, 32, 16, marble);
  Transform t;
  t.rotate_deg.y = 25.0f;
  t.translate = glm::vec3(0.3f, 0.0f, -1.8f);
  add_box(s, {-0.7f, 0.0f, -0.7f}, {0.7f, 1.4f, 0.7f}, wood, t);
  t.rotate_deg.y = -15.0f;
  t.translate = glm::vec3(1.9f, 0.0f, 0.8f);
  add_box(s, {-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, striped, t);
  add_sphere(s, {1.6f, 0.6f, -3.5f}, 0.6f, 32, 16, mirror);
  s.camera = Camera{{0.0f, 2.8f, 7.0f}, {0.0f, 0.8f, -0.5f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  s.has_camera = true;
  s.lights = {Light{{-4.0f, 6.0f, 5.0f}, {0.8f, 0.8f, 0.75f}},
              Light{{5.0f, 4.0f, 2.0f}, {0.35f, 0.35f, 0.4f}}};
  s.background = {0.45f, 0.55f, 0.7f};
  s.width = s.height = 256;
  return s;
}

// "bounce": thesis scene A's three boxes on a floor before a wall, static, with six balls
// bouncing in front of them (one sphere mesh placed six times) and three cubes spinning around
// the tall box; 4 seconds at 24 frames per second, the camera swinging round. The motion is
// sampled into keys 12 times a second (linear in between): a parabola per bounce, a fraction
// of a turn per key.
Scene scene_bounce() {
  Scene s = scene_a();
  s.name = "bounce";
  const int floor = s.add_material(mat("floor", {0.7f, 0.7f, 0.68f}, glm::vec3(0.0f), 1.0f, 0.2f));
  const int wall = s.add_material(mat("wall", {0.55f, 0.6f, 0.7f}));
  add_quad(s, {-14.0f, 0.0f, -6.0f}, {-14.0f, 0.0f, 9.0f}, {14.0f, 0.0f, 9.0f},
           {14.0f, 0.0f, -6.0f}, floor);
  add_quad(s, {-14.0f, 0.0f, -3.0f}, {14.0f, 0.0f, -3.0f}, {14.0f, 8.0f, -3.0f},
           {-14.0f, 8.0f, -3.0f}, wall);
  const int ball_mats[3] = {
      s.add_material(mat("ball-red", {0.9f, 0.2f, 0.15f}, glm::vec3(0.5f), 60.0f)),
      s.add_material(mat("ball-mirror", {0.2f, 0.2f, 0.2f}, glm::vec3(0.8f), 200.0f, 0.7f)),
      s.add_material(mat("ball-teal", {0.1f, 0.7f, 0.7f}, glm::vec3(0.5f), 60.0f))};
  const int spin_mat = s.add_material(mat("spinner", {0.95f, 0.6f, 0.1f}, glm::vec3(0.4f), 40.0f));
  constexpr double kSeconds = 4.0, kKeysPerSecond = 12.0;
  const int keys = static_cast<int>(kSeconds * kKeysPerSecond) + 1;
  auto object = [&](const std::string& name, size_t first, size_t end, auto pose_at) {
    AnimatedObject o;
    o.name = name;
    o.first = first;
    o.count = end - first;
    for (int k = 0; k < keys; ++k) {
      PoseKey key;
      key.time = k / kKeysPerSecond;
      key.pose = pose_at(key.time);
      o.track.keys.push_back(key);
    }
    s.animation.objects.push_back(o);
  };
  const size_t ball = s.triangle_count();
  add_sphere(s, glm::vec3(0.0f), 1.0f, 24, 12, ball_mats[0]);
  const size_t ball_tris = s.triangle_count() - ball;
  for (int i = 0; i < 6; ++i) {
    const double radius = 0.25 + 0.05 * (i % 3);
    size_t first = ball;
    if (i > 0) {  // another placement of the same mesh, in its own material
      first = s.triangle_count();
      for (size_t t = ball; t < ball + ball_tris; ++t) {
        // Copies: add_triangle grows the vectors these would point into.
        const glm::vec3 p[3] = {s.positions[3 * t], s.positions[3 * t + 1], s.positions[3 * t + 2]};
        const glm::vec3 n[3] = {s.normals[3 * t], s.normals[3 * t + 1], s.normals[3 * t + 2]};
        const glm::vec2 uv[3] = {s.texcoords[3 * t], s.texcoords[3 * t + 1],
                                 s.texcoords[3 * t + 2]};
        s.add_triangle(p[0], p[1], p[2], ball_mats[i % 3], n, nullptr, uv);
      }
    }
    const double x = -2.5 + 1.0 * i, z = 1.4 + 0.5 * std::sin(i * 1.7);
    const double period = 0.8 + 0.12 * i, height = 1.2 + 0.4 * (i % 2);
    object("ball " + std::to_string(i), first, first + ball_tris, [=](double t) {
      const double u = std::fmod(t / period + i * 0.37, 1.0);  // 0..1 per bounce
      Pose p;
      p.translate = glm::dvec3(x, radius + height * 4.0 * u * (1.0 - u), z);
      p.scale = glm::dvec3(radius);
      return p;
    });
  }
  for (int i = 0; i < 3; ++i) {
    const size_t first = s.triangle_count();
    add_box(s, glm::vec3(-0.2f), glm::vec3(0.2f), spin_mat);
    object("spinner " + std::to_string(i), first, s.triangle_count(), [=](double t) {
      const double a = 2.0 * kPi * (t / kSeconds + i / 3.0);  // one orbit in the clip
      Pose p;  // around the tall green box (at x 0.4, z -0.6)
      p.translate = glm::dvec3(0.4 + 1.1 * std::cos(a), 1.6 + 0.6 * std::sin(2.0 * a),
                               -0.6 + 1.1 * std::sin(a));
      p.rotation = glm::angleAxis(2.0 * kPi * t * 0.5, glm::normalize(glm::dvec3(1.0, 2.0, 0.5)));
      return p;
    });
  }
  s.animation.time = TimeRange{0.0, kSeconds, 24.0};
  CameraKey from, to;
  from.time = 0.0;
  from.camera = CameraPose{s.camera.eye, s.camera.look_at, s.camera.up, s.camera.fov_y};
  to = from;
  to.time = kSeconds;
  to.camera.eye = glm::vec3(-4.5f, 3.0f, 6.5f);
  s.animation.camera.keys = {from, to};
  s.animation.camera.interpolation = Interpolation::Smooth;
  return s;
}

}  // namespace

std::vector<std::string> builtin_scene_names() {
  return {"thesis-a", "thesis-b", "thesis-c", "cornell", "cornell-path",
          "glass",    "textured", "bounce",   "empty"};
}

Scene builtin_scene(const std::string& name) {
  if (name == "thesis-a" || name == "a") return scene_a();
  if (name == "thesis-b" || name == "b") return scene_b();
  if (name == "thesis-c" || name == "c") return scene_c();
  if (name == "cornell") return scene_cornell();
  if (name == "cornell-path") return scene_cornell_path();
  if (name == "glass") return scene_glass();
  if (name == "textured") return scene_textured();
  if (name == "bounce") return scene_bounce();
  if (name == "empty") {
    Scene s;
    s.name = "empty";
    s.has_camera = true;
    s.width = s.height = 64;
    return s;
  }
  std::string all;
  for (const auto& n : builtin_scene_names()) all += (all.empty() ? "" : ", ") + n;
  throw SceneError("unknown built-in scene '" + name + "' (known: " + all + ")");
}

}  // namespace rt
