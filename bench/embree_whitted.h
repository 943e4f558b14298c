// A plain Whitted renderer on Intel Embree 3, for rill-bench-trace's whitted section: the
// work of Rill's Whitted megakernel (megakernel/Megakernel.cpp, the Segment loop that the CPU
// backends run) done on the host, ray by ray, with Embree finding the hits. Per pixel: the
// same camera ray (rt::camera_ray, docs/camera.md), traced with rtcIntersect1; at a hit the
// shader's ambient term and, per point light, a shadow ray (rtcOccluded1) and the light's
// Phong share if nothing blocks it; then eq. 5.1 and the reflected or refracted ray, the
// second branch of a glass surface on a ray stack of the kernel's size, up to the scene's
// maximum depth, dropping rays below the kernel's minimum weight. The formulas are
// WhittedFormulas.h's. The pixels are spread over the cores by oneTBB in tiles of 16 x 16,
// about 1024 pixels a task (as Rill's CPU backends split a launch), and each tile writes the
// linear colour and the 8-bit sRGB bytes a PNG needs, as `rill-trace render` reads back.
//
// It renders what the thesis scenes and the built-in glass scene use: the phong, mirror and
// glass shaders with constant parameters, point lights without falloff, shadows on or off,
// vertex normals, a pinhole camera. Anything else is refused when it is made, naming it.
//
// Compiled only when CMake found Embree 3 (RILL_BENCH_HAVE_EMBREE).
#pragma once

#ifdef RILL_BENCH_HAVE_EMBREE

#include <cstdint>
#include <vector>

#include "WhittedFormulas.h"
#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/Options.h"
#include "rill/rt/scene/Camera.h"
#include "rill/rt/scene/Scene.h"
#include "trace_embree.h"

namespace bench {

// When a pixel of this renderer's linear image agrees with Rill's (rill-bench-trace's whitted
// section): every channel within kWhittedSame. Where both trace the same ray tree, the two
// differ only by float rounding: Embree's triangle test gives the hit's barycentrics (and so
// the point, which the scaled offset takes from them) a few ulps from Rill's, and the host
// compiler may order or contract a few operations differently; that moves a colour of order 1
// by some 1e-6 per bounce, far below 1e-4. A pixel differs by more only where a ray of its tree
// takes another path: a camera or secondary ray through a shared edge or a silhouette, or a
// shadow ray grazing an occluder's edge, where those few ulps decide. Such rays lie within
// ulps of an edge, a small share of the pixels (measured: docs/benchmarks/
// 2026-12-08-embree-whitted.md), so at least kWhittedMinAgree of the pixels must agree.
constexpr float kWhittedSame = 1e-4f;
constexpr double kWhittedMinAgree = 0.99;

// The rays of a frame, by kind (Rill counts them all in RenderResult::rays).
struct WhittedRays {
  int64_t camera = 0, shadow = 0, secondary = 0;
  int64_t total() const { return camera + shadow + secondary; }
};

// A frame: linear colour per pixel (row 0 at the top) and its sRGB bytes.
struct WhittedImage {
  int width = 0, height = 0;
  std::vector<glm::vec3> color;
  std::vector<unsigned char> rgb8;
  WhittedRays rays;
};

class EmbreeWhitted {
 public:
  // The scene as `rill-trace render` renders it with the tracer's features F and knobs K
  // (Tracer::features, TracerOptions) and maximum depth max_depth. Throws std::invalid_argument
  // naming what the plain renderer does not do.
  EmbreeWhitted(const rt::Scene& scene, const EmbreeScene& embree, const rt::Features& F,
                const rt::TracerOptions& K, int max_depth);
  // Renders a width x height frame into image (its memory reused from frame to frame).
  void render(int width, int height, WhittedImage& image) const;

 private:
  enum class Kind { Phong, Mirror, Glass };
  struct Mat {
    Kind kind = Kind::Phong;
    whitted::Phong phong;
    float reflect = 0, transmit = 0, ior = 1.5f;
  };
  // Per Rill primitive id: what the kernel's triangle arrays hold (kernel/Triangles.cpp).
  struct Tri {
    glm::vec3 v0, e1, e2, ng;
    int32_t material;
  };
  struct Counts;
  glm::vec3 trace_pixel(const rt::CameraFrame& cam, int i, int j, Counts& n) const;
  // The light a surface of material m sends towards the viewer, the shadow rays traced.
  glm::vec3 local_light(const whitted::Surface& s, const Mat& m, Counts& n) const;
  whitted::Scatter scatter(const whitted::Surface& s, const Mat& m, float weight) const;

  const rt::Scene& scene_;
  const EmbreeScene& embree_;
  rt::Features F_;
  bool scaled_;  // TracerOptions::offset is Scaled
  int max_depth_;
  float eps_;
  std::vector<Tri> tris_;
  std::vector<glm::vec3> normals_;  // 3 per triangle where F.vertex_normals
  std::vector<Mat> mats_;
};

}  // namespace bench

#endif  // RILL_BENCH_HAVE_EMBREE
