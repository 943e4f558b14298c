// The multipass strategy's shading passes (Multipass.h): the ray generator, the surface,
// the shadow rays and their light, and combine (eq. 5.1 and the next bounce). Each calls
// the same Shading functions (kernel/Shading.h), and so the same shaders, as the megakernel.
#include "rill/rt/multipass/Multipass.h"
#include "rill/rt/multipass/States.h"

namespace rt {

using namespace rill;
using namespace mp;

Program Multipass::capture_raygen() const {
  return rill::program("mp_raygen", [&] {
    Output<Ray> ray("ray");
    Output<PathState> path("path");
    Output<Aov> aov("aov");
    Output<Int> ts("tr.state");
    Float3 eye = S_.camera.eye;
    if (S_.camera.kind == CameraKind::Pinhole) {
      ray = Ray{eye, S_.camera.direction(element_coord()), Float(kBig)};
    } else {
      Ray r{eye, Float3(0.0f, 0.0f, 1.0f), Float(kBig)};
      S_.camera.aim(r, element_coord());
      ray = r;
    }
    path = PathState{Int(kPathAlive), Int(0), Int(1), Float(1.0f), Float3(0.0f)};
    aov = Aov{as_float(Int(0x7f800000)), Int(-1), Float3(0.0f)};
    ts = kPending;
  });
}

// ---- shading ---------------------------------------------------------------------------
Program Multipass::capture_surface() const {
  const Features& F = S_.F;
  const Shading& sh = S_.shading;
  return rill::program("mp_surface", [&] {
    Input<Float3> o("ray.o");
    Input<Float3> d("ray.d");
    Input<Hit> hit("hit");
    Input<Int> state("path.state");
    Input<Int> depth("path.depth");
    Input<Float> w("path.weight");
    Input<Float3> color("path.color");
    Output<Float3> local("local");
    Output<Float3> color_out("path.color");
    Output<Int> state_out("path.state");
    Output<Aov> aov("aov");
    skip_where(state == kPathEnded);
    Int hid = -1;
    if (F.geometry) hid = hit.id;
    RILL_IF(hid >= 0) {
      Surface s = sh.surface(Ray{o, d, Float(kBig)}, Hit{hit.t, hit.uv, hid});
      const MaterialTable::Slots slots = sh.material(s);
      Float3 loc = sh.emitted(s, &slots);
      RILL_IF(depth == 0) {  // AOVs of the camera ray
        aov = Aov{hit.t, hid, s.ns};
      }
      RILL_ENDIF;
      if (!F.shadows) loc += sh.unshadowed_light(s, &slots);
      local = loc;
      state_out = kPathSurface;
    }
    RILL_ELSE {
      color_out = color + w * sh.background;
      state_out = kPathEnded;
    }
    RILL_ENDIF;
  });
}

Program Multipass::capture_shadow_gen() const {
  const Shading& sh = S_.shading;
  return rill::program("mp_shadow_rays", [&] {
    Input<Float3> o("ray.o");
    Input<Float3> d("ray.d");
    Input<Hit> hit("hit");
    Input<Int> state("path.state");
    Input<Int> rays("path.rays");
    Output<Ray> shadow("shadow");
    Output<Int> ts("tr.state");
    Output<Int> rays_out("path.rays");
    skip_where(state != kPathSurface);
    Surface s = sh.surface(Ray{o, d, Float(kBig)}, hit);
    const ShadowRay ray = sh.shadow_ray(light_, s);
    shadow = ray.ray;
    ts = select(ray.active, Int(kPending), Int(kNone));
    rays_out = rays + select(ray.active, Int(1), Int(0));
  });
}

Program Multipass::capture_shadow_acc() const {
  const Shading& sh = S_.shading;
  return rill::program("mp_shadow_light", [&] {
    Input<Float3> o("ray.o");
    Input<Float3> d("ray.d");
    Input<Hit> hit("hit");
    Input<Int> state("path.state");
    Input<Int> ts("tr.state");
    Input<Int> sid("shadow_hit.id");
    Input<Float3> local("local");
    Output<Float3> local_out("local");
    skip_where(state != kPathSurface || ts != kFinished || sid >= 0);
    Surface s = sh.surface(Ray{o, d, Float(kBig)}, hit);
    local_out = local + sh.light(light_, s);
  });
}

// The path's ray keeps tmax = kBig from the ray generator: combine writes o and d only.
Program Multipass::capture_combine() const {
  const Shading& sh = S_.shading;
  return rill::program("mp_combine", [&] {
    Input<Float3> o("ray.o");
    Input<Float3> d("ray.d");
    Input<Hit> hit("hit");
    Input<PathState> path("path");
    Input<Float3> local("local");
    Output<PathState> path_out("path");
    Output<Float3> o_out("ray.o");
    Output<Float3> d_out("ray.d");
    Output<Int> ts("tr.state");
    skip_where(path.state != kPathSurface);
    Surface s = sh.surface(Ray{o, d, Float(kBig)}, hit);
    const Bounce b = sh.shade(s, local, PathSums{path.color, path.weight, path.depth}, false);
    RILL_IF(b.go) {
      o_out = b.next.o;
      d_out = b.next.d;
      ts = kPending;
    }
    RILL_ENDIF;
    path_out = PathState{select(b.go, Int(kPathAlive), Int(kPathEnded)), b.path.depth,
                         path.rays + select(b.go, Int(1), Int(0)), b.path.weight, b.path.color};
  });
}

}  // namespace rt
