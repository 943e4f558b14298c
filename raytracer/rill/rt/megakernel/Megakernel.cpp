// The megakernel (Megakernel.h): its program and its render loop over samples.
#include "rill/rt/megakernel/Megakernel.h"

#include <algorithm>
#include <cstdlib>
#include <future>
#include <optional>
#include <stdexcept>
#include <vector>

#include "rill/Backend.h"
#include "rill/Reduce.h"
#include "rill/Stopwatch.h"

namespace rt {

using namespace rill;

// One loop is captured now, so that a shader's misuse of its parameters is an error of the
// Tracer's constructor (the other loop runs the same shader code); the other at its first use.
Megakernel::Megakernel(DeviceScene& scene) : S_(scene) {
  if (path()) path_ = std::make_unique<PathIntegrator>(S_, S_.path_lights, S_.options);
  for (int k = 0; k < kPathSamplesPerLaunch; ++k)
    sample_offsets_.push_back(std::make_unique<Uniform<Float2>>(
        glm::vec2(0.5f), "path_sample_offset" + std::to_string(k)));
  (void)program(MegakernelLoop::Segment);
}

Megakernel::~Megakernel() = default;

Float2 Megakernel::launch_sample_offset(const Int& i) const {
  Float2 o = *sample_offsets_[0];
  for (size_t k = 1; k < sample_offsets_.size(); ++k)
    o = select(i == static_cast<int>(k), static_cast<const Float2&>(*sample_offsets_[k]), o);
  return o;
}

const Program& Megakernel::program(MegakernelLoop loop, bool packets) const {
  if (loop == MegakernelLoop::Auto)
    throw std::invalid_argument("Megakernel::program: resolve Auto first (megakernel_loop_for)");
  auto it = programs_.find({loop, packets});
  if (it == programs_.end()) {
    // The intersector's walk is chosen at capture (Intersector::set_packets), for this
    // program alone.
    S_.intersector.set_packets(packets);
    Program p = capture(loop);
    S_.intersector.set_packets(false);
    it = programs_.emplace(std::make_pair(loop, packets), std::move(p)).first;
  }
  return it->second;
}

// The loop's state, carried from one iteration to the next: the ray being traced and (Ray
// loop) what it is for, the path (colour, weight, depth), the light loop's position (Ray) and
// the surface it shades, and the ray stack. What a loop does not use, the optimizer removes.
struct Megakernel::PathLoop {
  explicit PathLoop(int stack_size) {
    for (int s = 0; s < stack_size; ++s) {
      stack_ray.push_back(Ray{Float3(0.0f), Float3(0.0f), Float(0.0f)});
      stack_weight.emplace_back(0.0f);
      stack_depth.emplace_back(0);
    }
  }
  Ray ray{Float3(0.0f), Float3(0.0f), Float(kBig)};
  Bool ray_active = true;
  Float3 color{0.0f};
  Float weight = 1.0f;  // eq. 5.1: the product of the reflection coefficients so far
  Int depth = 0;
  Int mode = 0;  // 0: camera or secondary ray, 1: shadow ray towards light li
  Int li = 0;
  Int rays = 0, iter = 0;
  Bool finished = false;
  // Fields the scene has no use for keep these values and are never assigned (set_surface).
  Surface surf{Float3(0.0f), Float3(0.0f), Float3(0.0f), Float3(0.0f), Float3(0.0f),
               Float2(0.0f), Bool(true),   Float3(1.0f), Int(0)};
  Float3 local{0.0f};
  // The ray stack (refraction: the reflected branch waits here); sp entries are used.
  std::vector<Ray> stack_ray;
  std::vector<Float> stack_weight;
  std::vector<Int> stack_depth;
  Int sp = 0;
  // Set within one iteration: the surface is done (local light complete), the path is
  // done (no next ray).
  Bool shade_done = false, path_done = false;
};

// The AOVs of the camera ray: what a miss leaves, until its hit sets them.
struct Megakernel::Aovs {
  Float depth = as_float(Int(0x7f800000));
  Int prim = -1;
  Float3 normal{0.0f};
};

namespace {

// Both programs' last outputs: the ray count and the camera ray's AOVs, written whether or not
// a render reads them back (Megakernel.h says why).
void write_rays_and_aovs(const Int& rays, const Float& depth, const Int& prim,
                         const Float3& normal) {
  Output<Int> out_rays("rays");
  out_rays = rays;
  Output<Float> out_depth("depth");
  Output<Int> out_prim("prim");
  Output<Float3> out_normal("normal");
  out_depth = depth;
  out_prim = prim;
  out_normal = normal;
}

}  // namespace

// The path integrator's kernel: samples path_first_ .. path_first_ + path_samples_ - 1 of
// its pixel, one path after the other (path regeneration, Megakernel.h). Each iteration traces
// the path's ray, shades what it found (PathIntegrator::shade) and traces the light sample's
// shadow ray; the iteration that ends a path adds its radiance to the pixel's sum (film_add,
// the film's operations) and starts the next sample's camera ray. Under path_accumulate_ = 0
// the sum restarts at each sample: a launch of one sample writes that sample's colour, for
// the film to add.
Program Megakernel::capture_path() const {
  return rill::program("rill_path", [&] {
    const Int2 pix = element_coord();
    const PathIntegrator& P = *path_;
    Input<Float3> sum_in("sum_in"), carry_in("carry_in");
    Float3 sum = sum_in, carry = carry_in;
    const Bool accumulate = path_accumulate_ != 0;
    const Int end = path_first_ + path_samples_;
    // The sample being traced, and its offset in the pixel: the camera and the random numbers
    // read these variables where the one-sample kernels read their uniforms.
    Int sample = path_first_;
    Float2 offset = *sample_offsets_[0];
    S_.camera.sample_offset_var = &offset;
    S_.camera.lens_sample_var = &sample;
    path_->sample_var = &sample;
    Int rays = 0;
    auto add = [&](const PathItem& path) {
      const FilmSum next = film_add(sum, carry, path.radiance, !accumulate || sample == 0);
      sum = next.sum;
      carry = next.carry;
      rays += path.rays;
    };
    // A new path, its ray from the eye (aimed by the camera where it is traced).
    auto new_path = [&] {
      return P.start(Ray{S_.camera.eye, Float3(0.0f, 0.0f, 1.0f), Float(kBig)});
    };
    PathItem path = new_path();
    FirstHit first;
    first.depth = as_float(Int(0x7f800000));
    const Bool sees = S_.F.geometry ? S_.camera.may_see_scene(pix, S_.F.dynamic) : Bool(true);
    RILL_IF(max_iter_ > 0 && !sees) {
      // The camera ray would miss: what shading a miss gives, without making the ray.
      RILL_WHILE(sample < end) {
        path = new_path();
        (void)P.shade(path, Hit{Float(0.0f), Float2(0.0f), Int(-1)}, pix);
        add(path);
        sample += 1;
      }
      RILL_ENDWHILE;
    }
    RILL_ELSE_IF(max_iter_ > 0) {
      S_.camera.aim(path.ray, pix);
      const Int2 image_pix = pix + S_.camera.origin;
      Int iter = 0;
      Bool finished = false;
      RILL_DO {
        Hit hit{Float(0.0f), Float2(0.0f), Int(-1)};
        if (S_.F.geometry) hit = S_.intersector.intersect(path.ray, nullptr);
        // The AOVs are the launch's first sample's (sample 0's in the launch that traces it):
        // the later samples' camera rays leave them as they are.
        const Bool launch_first = sample == path_first_;
        first.only_if = &launch_first;
        const ShadowQuery shadow = P.shade(path, hit, image_pix, &first);
        first.only_if = nullptr;
        if (P.shadow_rays()) {
          RILL_IF(shadow.active) {
            const Bool any_hit = true;
            P.shadow_result(path, shadow, S_.intersector.intersect(shadow.ray, &any_hit));
          }
          RILL_ENDIF;
        }
        iter += 1;
        path.done = path.done || iter >= max_iter_;
        // The path ended: the next sample starts here, without waiting for the paths of the
        // pixels that run along with this one (a lockstep group, a GPU's warp).
        RILL_IF(path.done) {
          add(path);
          sample += 1;
          RILL_IF(sample < end) {
            offset = launch_sample_offset(sample - path_first_);
            path = new_path();
            S_.camera.aim(path.ray, pix);
            iter = 0;
          }
          RILL_ELSE {
            finished = true;
          }
          RILL_ENDIF;
        }
        RILL_ENDIF;
      }
      RILL_UNTIL(finished);
    }
    RILL_ENDIF;
    S_.camera.sample_offset_var = nullptr;
    S_.camera.lens_sample_var = nullptr;
    path_->sample_var = nullptr;
    Output<Float3> out_color("color"), out_carry("carry");
    out_color = sum;
    out_carry = carry;
    write_rays_and_aovs(rays, first.depth, first.prim, first.normal);
    Output<Float3> albedo("albedo");
    albedo = first.albedo;
  });
}

Program Megakernel::capture(MegakernelLoop loop) const {
  if (path()) return capture_path();
  return rill::program("rill_trace", [&] {
    Aovs aovs;

    PathLoop L(S_.F.stack);
    L.ray.o = S_.camera.eye;
    const Int2 pix = element_coord();
    // max_iter = 0 skips all tracing: render() uses that for a warm-up launch.
    // (An empty scene's rays all miss anyway: its kernel reads no array.)
    const Bool sees = S_.F.geometry ? S_.camera.may_see_scene(pix, S_.F.dynamic) : Bool(true);
    RILL_IF(max_iter_ > 0 && !sees) {
      // A camera ray outside the scene's box on screen: the miss its first segment would
      // give (the same operations), without making the ray or walking it.
      L.rays += 1;
      miss(L);
    }
    RILL_ELSE_IF(max_iter_ > 0) {
      S_.camera.aim(L.ray, pix);
      RILL_DO {
        L.path_done = false;
        if (loop == MegakernelLoop::Segment) {
          path_segment(L, aovs);
        } else {
          if (S_.F.shadows) L.shade_done = false;
          const Hit hit = trace(L);
          Int cur_mode = L.mode;  // the steps below may change mode for the next iteration
          RILL_IF(cur_mode == 0) {
            camera_or_secondary_ray(L, hit, aovs);
          }
          RILL_ENDIF;
          if (S_.F.shadows) {
            RILL_IF(cur_mode == 1) {
              shadow_ray_back(L, hit);
            }
            RILL_ENDIF;
            // Without shadows, camera_or_secondary_ray went on to the next ray itself.
            RILL_IF(L.shade_done) {
              next_ray(L);
            }
            RILL_ENDIF;
          }
        }
        RILL_IF(L.path_done) {
          pop_or_finish(L);
        }
        RILL_ENDIF;
        L.iter += 1;
        L.finished = L.finished || L.iter >= max_iter_;
      }
      RILL_UNTIL(L.finished);
    }
    RILL_ENDIF;
    Output<Float3> out_color("color");
    out_color = L.color;
    write_rays_and_aovs(L.rays, aovs.depth, aovs.prim, aovs.normal);
  });
}

Hit Megakernel::trace(PathLoop& L) const {
  Hit hit{Float(0.0f), Float2(0.0f), Int(-1)};
  if (!S_.F.geometry) {
    L.rays += 1;
    return hit;
  }
  RILL_IF(L.ray_active) {
    Bool any_hit = L.mode == 1;
    if (S_.F.area_lights) {  // an area light sample's shadow ray has no light buffer
      const Int buffer_light = S_.shading.buffer_light(L.li);
      hit = S_.F.shadows ? S_.intersector.intersect(L.ray, &any_hit, &buffer_light)
                         : S_.intersector.intersect(L.ray, nullptr);
    } else {
      hit = S_.F.shadows ? S_.intersector.intersect(L.ray, &any_hit, &L.li)
                         : S_.intersector.intersect(L.ray, nullptr);
    }
    L.rays += 1;
  }
  RILL_ENDIF;
  return hit;
}

// The loop's surface from a new one: only the fields the scene uses, since on simd every
// assignment under a branch is a masked select per lane.
void Megakernel::set_surface(Surface& to, const Surface& from) const {
  to.P = from.P;
  to.ns = from.ns;
  to.nf = from.nf;
  to.ngf = from.ngf;
  to.V = from.V;
  to.entering = from.entering;
  to.material = from.material;
  if (S_.F.texcoords) to.uv = from.uv;
  if (S_.F.vertex_colors) to.vertex_color = from.vertex_color;
}

// A hit: the surface, the shader's emitted light and the camera ray's AOVs. Returns the
// material's parameters, read once for the lights and the next ray.
MaterialTable::Slots Megakernel::begin_surface(PathLoop& L, const Hit& hit, Aovs& aovs) const {
  const Shading& sh = S_.shading;
  set_surface(L.surf, sh.surface(L.ray, hit));
  const MaterialTable::Slots slots = sh.material(L.surf);
  L.local = sh.emitted(L.surf, &slots);
  // An area light's own emission where a ray meets its front (LightSampler::emission).
  if (S_.F.area_lights) L.local += S_.path_lights.emission(L.surf);
  RILL_IF(L.depth == 0) {
    aovs.depth = hit.t;
    aovs.prim = hit.id;
    aovs.normal = L.surf.ns;
  }
  RILL_ENDIF;
  return slots;
}

// Ray: a hit starts the surface's local light (the shader's emitted light) and its light
// loop; a miss adds the background and ends the path.
void Megakernel::camera_or_secondary_ray(PathLoop& L, const Hit& hit, Aovs& aovs) const {
  const Shading& sh = S_.shading;
  if (!S_.F.geometry) {
    miss(L);
    return;
  }
  Bool hit_something = hit.id >= 0;
  RILL_IF(hit_something) {
    const MaterialTable::Slots slots = begin_surface(L, hit, aovs);
    if (S_.F.shadows) {
      L.mode = 1;
      L.li = 0;
      shadow_ray_to_light(L);
    } else {  // the surface is done in this iteration: its parameters serve the next ray too
      const std::optional<LightKey> key = light_key(L);
      L.local += sh.unshadowed_light(L.surf, &slots, key ? &*key : nullptr);
      next_ray(L, &slots);
    }
  }
  RILL_ELSE {
    miss(L);
  }
  RILL_ENDIF;
}

// Ray: the next ray is the shadow ray towards light L.li.
void Megakernel::shadow_ray_to_light(PathLoop& L) const {
  const std::optional<LightKey> key = light_key(L);
  const ShadowRay shadow = S_.shading.loop_shadow_ray(L.li, L.surf, key ? &*key : nullptr);
  L.ray = shadow.ray;
  L.ray_active = shadow.active;
}

// A shadow ray came back: the light's share if it was not blocked, then the next light's
// shadow ray, or, after the last light, the surface is done.
void Megakernel::shadow_ray_back(PathLoop& L, const Hit& hit) const {
  const Shading& sh = S_.shading;
  Bool hit_something = hit.id >= 0;
  RILL_IF(L.ray_active && !hit_something) {
    const std::optional<LightKey> key = light_key(L);
    L.local += sh.loop_light(L.li, L.surf, key ? &*key : nullptr);
  }
  RILL_ENDIF;
  L.li += 1;
  // (Without area lights, the point lights' count itself: the same kernel as before them.)
  const Bool more = S_.F.area_lights ? Bool(L.li < sh.loop_lights()) : Bool(L.li < S_.lights.count);
  RILL_IF(more) {
    shadow_ray_to_light(L);
  }
  RILL_ELSE {
    L.mode = 0;
    L.shade_done = true;
  }
  RILL_ENDIF;
}

// What keys the area light samples of the loop's surface (Shading.h): the pixel in image
// coordinates and the bounce. Only area lights use it.
std::optional<LightKey> Megakernel::light_key(const PathLoop& L) const {
  if (!S_.F.area_lights) return std::nullopt;
  return LightKey{element_coord() + S_.camera.origin, L.depth};
}

// A camera or secondary ray that hit nothing: the background, and the path ends.
void Megakernel::miss(PathLoop& L) const {
  L.color += L.weight * S_.shading.background;
  L.path_done = true;
}

// Segment: the camera or secondary ray, and on a hit the whole surface: its local light, with
// a shadow ray per light, then eq. 5.1 and the next ray. The same operations in the same
// order as the Ray loop's iterations for this ray and its shadow rays.
void Megakernel::path_segment(PathLoop& L, Aovs& aovs) const {
  const Shading& sh = S_.shading;
  L.rays += 1;
  if (!S_.F.geometry) {  // an empty scene's kernel only writes the background
    miss(L);
    return;
  }
  const Hit hit = S_.intersector.intersect(L.ray, nullptr);
  RILL_IF(hit.id >= 0) {
    const MaterialTable::Slots slots = begin_surface(L, hit, aovs);
    if (S_.F.shadows) {
      shadowed_lights(L, slots);
    } else {
      const std::optional<LightKey> key = light_key(L);
      L.local += sh.unshadowed_light(L.surf, &slots, key ? &*key : nullptr);
    }
    next_ray(L, &slots);
  }
  RILL_ELSE {
    miss(L);
  }
  RILL_ENDIF;
}

// Segment: each light's shadow ray, traced for any hit (the light buffer first); a light
// that is not blocked adds its share.
void Megakernel::shadowed_lights(PathLoop& L, const MaterialTable::Slots& slots) const {
  const Shading& sh = S_.shading;
  if (S_.F.area_lights) {
    area_shadowed_lights(L, slots);
    return;
  }
  RILL_FOR(Int l = 0, l < S_.lights.count, l += 1) {
    const ShadowRay shadow = sh.shadow_ray(l, L.surf);
    RILL_IF(shadow.active) {
      const Bool any_hit = true;
      const Hit blocker = S_.intersector.intersect(shadow.ray, &any_hit, &l);
      L.rays += 1;
      RILL_IF(blocker.id < 0) {
        L.local += sh.light(l, L.surf, &slots);
      }
      RILL_ENDIF;
    }
    RILL_ENDIF;
  }
  RILL_ENDFOR;
}

// Segment with area lights: the same over the point lights and then the area light samples
// (Shading.h), whose shadow rays walk the grid.
void Megakernel::area_shadowed_lights(PathLoop& L, const MaterialTable::Slots& slots) const {
  const Shading& sh = S_.shading;
  const std::optional<LightKey> key = light_key(L);
  RILL_FOR(Int l = 0, l < sh.loop_lights(), l += 1) {
    const ShadowRay shadow = sh.loop_shadow_ray(l, L.surf, &*key);
    RILL_IF(shadow.active) {
      const Bool any_hit = true;
      const Int buffer_light = sh.buffer_light(l);
      const Hit blocker = S_.intersector.intersect(shadow.ray, &any_hit, &buffer_light);
      L.rays += 1;
      RILL_IF(blocker.id < 0) {
        L.local += sh.loop_light(l, L.surf, &*key, &slots);
      }
      RILL_ENDIF;
    }
    RILL_ENDIF;
  }
  RILL_ENDFOR;
}

// Eq. 5.1 for the finished surface, and the path's next ray (a second branch waits on the
// stack).
void Megakernel::next_ray(PathLoop& L, const MaterialTable::Slots* slots) const {
  const int stack = S_.F.stack;
  const Bounce b =
      S_.shading.shade(L.surf, L.local, PathSums{L.color, L.weight, L.depth}, stack > 0, slots);
  L.color = b.path.color;
  L.weight = b.path.weight;
  L.depth = b.path.depth;
  if (stack > 0) {
    RILL_IF(b.second.wanted && L.sp < stack) {  // the reflection waits on the stack
      for (int s = 0; s < stack; ++s) {
        RILL_IF(L.sp == s) {
          L.stack_ray[static_cast<size_t>(s)] = b.second.ray;
          L.stack_weight[static_cast<size_t>(s)] = b.second.weight;
          L.stack_depth[static_cast<size_t>(s)] = L.depth;
        }
        RILL_ENDIF;
      }
      L.sp += 1;
    }
    RILL_ENDIF;
  }
  RILL_IF(b.go) {
    L.ray = b.next;
    L.ray_active = true;
  }
  RILL_ELSE {
    L.path_done = true;
  }
  RILL_ENDIF;
}

// The path ended: the next ray from the stack, or the loop is finished.
void Megakernel::pop_or_finish(PathLoop& L) const {
  const int stack = S_.F.stack;
  if (stack == 0) {
    L.finished = true;
    return;
  }
  RILL_IF(L.sp > 0) {
    for (int s = 0; s < stack; ++s) {
      RILL_IF(L.sp == s + 1) {
        L.ray.o = L.stack_ray[static_cast<size_t>(s)].o;
        L.ray.d = L.stack_ray[static_cast<size_t>(s)].d;
        L.weight = L.stack_weight[static_cast<size_t>(s)];
        L.depth = L.stack_depth[static_cast<size_t>(s)];
      }
      RILL_ENDIF;
    }
    L.sp -= 1;
    L.ray_active = true;
    L.ray.tmax = kBig;
  }
  RILL_ELSE {
    L.finished = true;
  }
  RILL_ENDIF;
}

bool path_regeneration_default(const std::string& backend) {
  return backend != "simd";
}

int path_samples_per_launch(int setting, const std::string& backend, const char* regenerate) {
  if (setting > 0) return std::min(setting, kPathSamplesPerLaunch);
  if (regenerate == nullptr) return path_regeneration_default(backend) ? kPathSamplesPerLaunch : 1;
  if (std::string(regenerate) == "on") return kPathSamplesPerLaunch;
  if (std::string(regenerate) == "off") return 1;
  throw std::invalid_argument("RILL_PATH_REGENERATE='" + std::string(regenerate).substr(0, 40) +
                              "': expected on or off");
}

int path_samples_per_launch(int setting, const std::string& backend) {
  // Read once: a render's setting does not change with the environment mid-run.
  static const char* const regenerate = std::getenv("RILL_PATH_REGENERATE");
  return path_samples_per_launch(setting, backend, regenerate);
}

// "backend/accuracy/loop": a compiled kernel's key, and its warm-up's.
std::string Megakernel::kernel_key(const std::string& backend_name, Accuracy a,
                                   MegakernelLoop loop) {
  return backend_key(backend_name, a) + "/" + megakernel_loop_name(loop);
}

Kernel& Megakernel::kernel(const std::string& backend_name, Accuracy a, MegakernelLoop loop) {
  loop = megakernel_loop_for(loop, backend_name);
  const std::string key = kernel_key(backend_name, a, loop);
  auto it = kernels_.find(key);
  if (it != kernels_.end()) return it->second;
  const bool packets = packets_for(S_.K.packets, backend_name);
  return kernels_.emplace(key, compile_for(program(loop, packets), backend_name, a)).first->second;
}

// One backend's output streams, kept for its next frame of the same size (Film.h says why
// per backend).
struct Megakernel::Buffers {
  Buffers(int w, int h)
      : width(w),
        height(h),
        color(w, h, "color"),
        normal(w, h, "normal"),
        dist(w, h, "depth"),
        prim(w, h, "prim"),
        rays(w, h, "rays"),
        albedo(w, h, "albedo"),
        carry(w, h, "carry") {}
  int width, height;
  Stream<Float3> color, normal;
  Stream<Float> dist;
  Stream<Int> prim, rays;
  Stream<Float3> albedo;  // the path program's
  Stream<Float3> carry;   // the path program's, where it sums no more than one sample
};

// Sample 0's camera rays once more, for their AOVs alone: its first iteration (max_iter_ 1,
// set by the caller), which traces the camera ray and writes the AOVs as the launch that
// traced sample 0 wrote them. The path program's colour, a path cut short, goes to the
// kernel's own streams, never the film's sums; its rays are not counted.
void Megakernel::retrace_aovs(Kernel& k, Buffers& out, const Film::Sums& film_sums,
                              RenderResult& r) {
  S_.camera.offset.set(sample_offset(0));
  S_.camera.lens_sample.set(0);
  if (S_.F.area_lights) S_.shading.sample_index.set(0);
  const bool sums = film_sums.sum != nullptr;
  if (path_) {
    path_first_.set(0);
    path_samples_.set(1);
    path_accumulate_.set(0);
    sample_offsets_[0]->set(sample_offset(0));
    if (sums) {
      k.bind("sum_in", out.color).bind("carry_in", out.carry);
      k.bind("color", out.color).bind("carry", out.carry);
    }
  }
  Stopwatch launch;
  k.execute();
  ++r.launches;
  r.times.launch += launch.ms();
  r.times.add_kernel(k.last_launch().device_ms);
  if (path_ && sums) {
    k.bind("sum_in", *film_sums.sum).bind("carry_in", *film_sums.carry);
    k.bind("color", *film_sums.sum).bind("carry", *film_sums.carry);
  }
}

void Megakernel::render(const Frame& frame, RenderResult& r) {
  const RenderSettings& rs = frame.settings;
  const int width = frame.width, height = frame.height, depth = frame.depth, spp = frame.spp;
  Film& film = frame.film;
  r.backend = rs.backend;
  r.width = width;
  r.height = height;
  const MegakernelLoop loop = megakernel_loop_for(rs.loop, rs.backend);
  r.loop = megakernel_loop_name(loop);
  Stopwatch since_start;
  // A first frame on a backend that compiles off the calling thread (cpu: a C compiler
  // process) compiles the frame's small kernels, the film's and the ray count's, while the
  // megakernel compiles: one after the other, their compiler runs added about 0.3 s to a
  // cold first image (docs/benchmarks/2026-12-07-first-image.md). The program is captured
  // here, on this thread (capture is per thread); only its compile runs on the other.
  const std::string megakernel_key = kernel_key(rs.backend, rs.accuracy, loop);
  std::future<Kernel> building;
  if (!kernels_.count(megakernel_key) && !rill::backend(rs.backend).single_threaded()) {
    // The packets choice as kernel() makes it: with program(loop) alone a first frame ran the
    // walk without packets whatever TracerOptions::packets said.
    const Program& p = program(loop, packets_for(S_.K.packets, rs.backend));
    building = std::async(std::launch::async,
                          [&p, &rs] { return compile_for(p, rs.backend, rs.accuracy); });
  }
  Stopwatch setup;
  Buffers& out = buffers_for(buffers_, backend_key(rs.backend, rs.accuracy), width, height);
  film.begin(rs.backend, rs.accuracy, width, height, spp, rs.resume, frame.summing(),
             rs.outputs.variance);
  r.times.setup = setup.ms();
  if (building.valid()) {
    (void)rill::sum(out.rays);  // its reduction levels, compiled (and run on zeros)
    if (rs.outputs.rgb8) film.prepare_encoder(out.color);
    kernels_.emplace(megakernel_key, building.get());
  }
  Kernel& k = kernel(rs.backend, rs.accuracy, loop);
  r.from_cache = k.info().cache_hit || k.info().from_disk_cache;
  add_stages(r, k.info());

  // The loop's iteration limit: a backstop that must never end a path early. Where it did,
  // the two loops, which take different numbers of iterations for the same path, would give
  // different images. A path has at most depth + 1 segments (camera ray and bounces), or with
  // a ray stack at most 2^(depth + 1) - 1 (each segment spawns two at most). The Ray loop
  // takes one iteration per segment and one per light on a hit; the Segment loop one per
  // segment.
  S_.shading.max_depth.set(depth);
  const int64_t segments = S_.F.stack == 0 ? int64_t{depth} + 1
                           : depth >= 29   ? int64_t{1} << 30
                                           : (int64_t{1} << (depth + 1)) - 1;
  const int64_t loop_lights =
      S_.light_count + (S_.F.area_lights ? int64_t{S_.options.light_samples} : 0);
  const int64_t iters = segments * (loop_lights + 1) + 8;

  // Both loops write the same outputs: they share the backend's buffers, and each warms up.
  setup.lap();
  k.bind("rays", out.rays).bind("color", out.color);
  k.bind("depth", out.dist).bind("prim", out.prim).bind("normal", out.normal);
  // The path program adds its samples into the film's sums where the film keeps them (and no
  // squares) and a launch takes more than one; otherwise it writes one sample's colour (and a
  // carry of zeros) for the film to add.
  const int per_launch =
      path() ? path_samples_per_launch(rs.path_samples_per_launch, rs.backend) : 1;
  const Film::Sums film_sums = per_launch > 1 ? film.sums() : Film::Sums{};
  const bool sums = film_sums.sum != nullptr;
  if (path()) {
    k.bind("albedo", out.albedo);
    Stream<Float3>& sum = sums ? *film_sums.sum : out.color;
    Stream<Float3>& carry = sums ? *film_sums.carry : out.carry;
    k.bind("sum_in", sum).bind("carry_in", carry).bind("color", sum).bind("carry", carry);
  }
  r.times.setup += setup.ms();
  // A first launch at this size that traces nothing (max_iter = 0): drivers that finish
  // compiling at the first launch of a size (PoCL, Mesa) do it here, so that the trace time
  // below is tracing alone. The ray count's reduction kernels compile here too.
  const auto warm_key =
      std::make_pair(kernel_key(rs.backend, rs.accuracy, loop), int64_t{width} * height);
  if (!warmed_.count(warm_key)) {
    Stopwatch first_launch;
    max_iter_.set(0);
    k.execute();
    (void)rill::sum(out.rays);
    warmed_.insert(warm_key);
    r.first_launch_ms = first_launch.ms();
  }
  // A path has at most depth + 1 segments, one iteration each.
  const int32_t max_iter =
      path_ ? depth + 2 : static_cast<int32_t>(std::min<int64_t>(iters, 1 << 30));
  max_iter_.set(max_iter);
  r.compile_ms = since_start.ms() - r.times.setup;

  Stopwatch trace, step;
  const AovStreams aovs{out.dist, out.prim, out.normal, path() ? &out.albedo : nullptr};
  if (frame.retrace_aovs()) {
    max_iter_.set(1);  // the camera ray's iteration alone
    retrace_aovs(k, out, film_sums, r);
    film.read_aovs(aovs, rs.outputs, r);
    max_iter_.set(max_iter);
  }
  for (int s = frame.first_sample; s < spp;) {
    const int n = sums ? std::min(per_launch, spp - s) : 1;  // this launch's samples
    S_.camera.offset.set(sample_offset(s));
    S_.camera.lens_sample.set(s);
    if (path_) {
      path_first_.set(s);
      path_samples_.set(n);
      path_accumulate_.set(sums ? 1 : 0);
      for (int i = 0; i < n; ++i)
        sample_offsets_[static_cast<size_t>(i)]->set(sample_offset(s + i));
    }
    if (S_.F.area_lights) S_.shading.sample_index.set(s);
    step.lap();
    k.execute();
    ++r.launches;
    r.times.launch += step.lap();
    r.times.add_kernel(k.last_launch().device_ms);
    r.rays += rill::sum(out.rays);  // on the device: only the total comes back
    r.times.reduce += step.lap();
    // A launch's AOVs are its first sample's: sample 0's, before the next launch writes over
    // them.
    if (s == 0) film.read_aovs(aovs, rs.outputs, r);
    if (sums)
      film.added_samples(n);
    else
      film.add_sample(out.color, s);
    s += n;
    if (!frame.more_after(s - 1)) break;
  }
  film.finish(rs.outputs, r);
  r.trace_ms = trace.ms();
}

}  // namespace rt
